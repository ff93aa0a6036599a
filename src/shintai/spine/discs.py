"""Pre-compressed silicone discs on a MuJoCo spine whose balls are captured (seed 003 §3.6.1, §3.5.3).

§3.6.1: "シリコンゴムの椎間板は，プリコンプレッションがかかるように節間の隙間より大きい" — Cla's ball sits in a socket
deeper than a hemisphere (Fig. 3.30), so the faces stay ``gap_m`` apart and the disc is pre-compressed by
t_free − gap "筋に張力をかけなくても". §3.5.3: "シリコンゴムの非線形性のため…弾性係数は…大きい…硬くなる". The disc
is Rabbit's ring law (:class:`~shintai.spine.robots.RingDiscSpec`, the same f(c) = k1 c + k3 c³ that
:class:`~shintai.spine.bodies.QuasiStaticSpine` uses): ``n_ring`` compression-only springs between the face
points (x, y, −gap/2) of link i−1 and R (x, y, gap/2) of link i about the ball centre, R = Rz(ψ) Ry(θ) Rx(φ) the
joint's hinges. Its generalised forces are Q_j = Σ_k f(c_k) ∂d_k/∂q_j (c = t_free − d), with
∂d/∂q_j = u · (a_j × R p). :class:`HardeningDiscs` puts them on a :class:`~shintai.spine.bodies_mujoco.SpineBody`:
the tangent at rest stays MuJoCo's joint stiffness (implicit), the rest is applied before every physics step.

**The criterion that sizes a disc** (§7.1.1 "椎間板による基本姿勢と復元力 (重力を前提)": "直立した姿勢を基本姿勢とすると、
基本姿勢は重力のポテンシャルエネルギーが高い状態になり、姿勢を変形した状態から基本姿勢に向かう場合にアクチュエータに必要と
される力を補助する形で復元力が生じる"; §4.6.2, every muscle at one tension: "シリコンゴムから成る椎間板のばね成分で初期
姿勢に戻ろうとする力が生じているだけの状態になる"): upright must be a stable equilibrium under gravity with every muscle at
one tension. :func:`upright_stiffness` is the stiffness about it, :func:`upright_margin` its smallest eigenvalue,
:func:`critical_disc_stiffness` k*, the smallest linear disc for which it is stable (Kenta's discs are 2 × k*,
``robots.KENTA_DISC_NM_RAD``; Cla's hardening disc has 2 × k* as its tangent at rest, ``cla.constants.CLA_RING_DISC``).
"""

from __future__ import annotations

import math
from functools import lru_cache

import mujoco
import numpy as np
from numba import njit

from shintai.spine.geometry import fma
from shintai.spine.robots import RingDiscSpec


@lru_cache(maxsize=None)
def ring_points(disc: RingDiscSpec) -> tuple[np.ndarray, np.ndarray]:
    """(upper, lower) face points (n_ring, 3) about the ball centre: upper on link i, lower on link i−1 (computed
    once per disc, read-only: the law runs before every physics step)."""
    a = 2 * np.pi * np.arange(disc.n_ring) / disc.n_ring
    xy = disc.ring_radius_m * np.stack([np.cos(a), np.sin(a)], axis=1)
    h = np.full((disc.n_ring, 1), disc.gap_m / 2)
    up, low = np.hstack([xy, h]), np.hstack([xy, -h])
    up.flags.writeable = low.flags.writeable = False
    return up, low


def ring_forces(disc: RingDiscSpec, q) -> np.ndarray:
    """The disc's generalised forces (n, 3) [N m] on each joint's (roll, pitch, yaw) hinges at q (n, 3) [rad]
    (the order of eq. 4.1's θ; module docstring)."""
    q = np.ascontiguousarray(np.atleast_2d(np.asarray(q, dtype=float))).reshape(-1)
    law, index = RingLaw(disc, len(q) // 3), np.arange(len(q))
    out = np.empty(len(q))
    law(q, index, np.zeros(len(q)), out, index)
    return out.reshape(-1, 3)


class RingLaw:
    """The ring law of the module docstring for ``n`` joints, in two compiled loops over the joints and the ring
    (:func:`_faces`, :func:`_generalised`) on buffers allocated once: it runs before every physics step, where
    NumPy's per-call cost on (n, 3, k) arrays would be several MuJoCo steps. The loops keep NumPy's arithmetic
    (R p as OpenBLAS's fma chain, the einsums' orders of summation), so they give the bits of the law written
    with NumPy arrays; c³ between them is NumPy's ``power``, as :meth:`RingDiscSpec.force` computes it (a
    product c·c·c differs in the last place)."""

    def __init__(self, disc: RingDiscSpec, n: int):
        up, low = ring_points(disc)
        self.disc, self.up, self.low = disc, np.ascontiguousarray(up), np.ascontiguousarray(low)
        k = disc.n_ring
        self.trig = np.empty((n, 2, 3))  # cos, sin of (roll, pitch, yaw)
        self.x, self.u = np.empty((n, k, 3)), np.empty((n, k, 3))
        self.d, self.c, self.c3 = np.empty((n, k)), np.empty((n, k)), np.empty((n, k))

    def __call__(self, qpos, index, k0, out, dofs) -> None:
        """out[dofs] = Q(q) + k0 q at q = qpos[index] (3n,), in eq. 4.1's order per joint."""
        disc = self.disc
        _faces(qpos, index, self.up, self.low, disc.t_free_m, self.trig, self.x, self.u, self.d, self.c)
        np.power(self.c, 3, out=self.c3)
        _generalised(qpos, index, k0, disc.k1_n_m, disc.k3_n_m3, self.trig, self.x, self.u, self.d, self.c,
                     self.c3, out, dofs)


@njit(cache=True)
def _faces(qpos, index, up, low, t_free, trig, x, u, d, c):
    """The ring's geometry at posture q = qpos[index] (n joints × (roll, pitch, yaw)): each joint's cos and
    sin ``trig``, R = Rz(ψ) Ry(θ) Rx(φ), the upper face points x = R p about the centre (n, k, 3), the spring
    vectors u = x − p_low, their lengths d = |u| and compressions c = max(t_free − d, 0) (n, k)."""
    for i in range(trig.shape[0]):
        for a in range(3):
            trig[i, 0, a] = math.cos(qpos[index[3 * i + a]])
            trig[i, 1, a] = math.sin(qpos[index[3 * i + a]])
        cr, cp, cy = trig[i, 0, 0], trig[i, 0, 1], trig[i, 0, 2]
        sr, sp, sy = trig[i, 1, 0], trig[i, 1, 1], trig[i, 1, 2]
        R = ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
             (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
             (-sp, cp * sr, cp * cr))
        for k in range(up.shape[0]):
            uu = 0.0
            for a in range(3):
                x[i, k, a] = fma(R[a][2], up[k, 2], fma(R[a][1], up[k, 1], R[a][0] * up[k, 0]))
                u[i, k, a] = x[i, k, a] - low[k, a]
                uu += u[i, k, a] * u[i, k, a]
            d[i, k] = math.sqrt(uu)
            c[i, k] = max(t_free - d[i, k], 0.0)


@njit(cache=True)
def _generalised(qpos, index, k0, k1, k3, trig, x, u, d, c, c3, out, dofs):
    """out[dofs] = Q + K₀ q: Q_j = Σ_k f(c_k) ∂d_k/∂q_j, f(c) = k1 c + k3 c³ (:meth:`RingDiscSpec.force`),
    ∂d/∂q_j = a_j · (x × u) / d with the hinge axes a in the parent frame (roll Rz Ry e_x, pitch Rz e_y, yaw
    e_z). One running sum, over the axes' components inside the ring (the NumPy law's einsum order, so the
    same bits)."""
    for i in range(trig.shape[0]):
        cp, cy, sp, sy = trig[i, 0, 1], trig[i, 0, 2], trig[i, 1, 1], trig[i, 1, 2]
        axes = ((cy * cp, sy * cp, -sp), (-sy, cy, 0.0), (0.0, 0.0, 1.0))
        for j in range(3):
            total = 0.0
            for k in range(c.shape[1]):
                f = k1 * c[i, k] + k3 * c3[i, k]
                for a in range(3):
                    b, e = (a + 1) % 3, (a + 2) % 3
                    total += f * axes[j][a] * ((x[i, k, b] * u[i, k, e] - x[i, k, e] * u[i, k, b]) / d[i, k])
            out[dofs[3 * i + j]] = total + k0[3 * i + j] * qpos[index[3 * i + j]]


def rest_tangent(disc: RingDiscSpec, step_rad: float = 1e-6) -> np.ndarray:
    """The disc's tangent stiffness at rest (3,) [N m/rad] per axis (roll, pitch, yaw): −∂Q_j/∂q_j at q = 0."""
    e = step_rad * np.eye(3)
    return -np.diagonal(ring_forces(disc, e) - ring_forces(disc, -e)) / (2 * step_rad)


class HardeningDiscs:
    """``disc`` on every joint of ``body`` (hinge joints, a straight chain): MuJoCo's joint stiffness becomes the
    tangent at rest (plus ``k_twist_nm_rad`` on yaw, the linear twist spring of Rabbit's law), and this hook,
    in ``body.before_physics``, adds the remainder Q(q) + K₀ q to ``qfrc_applied`` of the spine's hinges
    (which it owns) before every physics step."""

    def __init__(self, body, disc: RingDiscSpec):
        if body.joint_type != "hinge":
            raise ValueError("HardeningDiscs needs the hinge spine (three hinges per joint)")
        m = body.model
        self.disc, self.data = disc, body.data
        self.qpos = body.spine_qpos.astype(np.intp)  # the kernels' one index type (compiled once)
        joints = [m.jnt_qposadr.tolist().index(a) for a in self.qpos]
        self.dofs = m.jnt_dofadr[joints].astype(np.intp)
        self.k0 = np.tile(np.maximum(rest_tangent(disc), 0.0), body.robot.n)
        m.jnt_stiffness[joints] = self.k0 + np.tile([0.0, 0.0, disc.k_twist_nm_rad], body.robot.n)
        self.law = RingLaw(disc, body.robot.n)
        body.before_physics.append(self)

    def __call__(self) -> None:
        self.law(self.data.qpos, self.qpos, self.k0, self.data.qfrc_applied, self.dofs)


def upright_stiffness(body, tension_n: float, disc_nm_rad: float, step_rad: float = 1e-5) -> tuple[np.ndarray, list]:
    """The stiffness matrix K = −∂Q/∂q of ``body`` (a :class:`~shintai.spine.bodies_mujoco.SpineBody`) about the
    basic posture (every joint at 0: upright, §3.6.1, §3.7.1) under gravity, every muscle in T mode at the same
    ``tension_n`` (§4.2.1, §3.4.1: "筋の張力はつりあって…椎間板のばね成分で初期姿勢に戻ろうとする力が生じているだけ"),
    the discs at ``disc_nm_rad`` on every spine axis. Q = joint springs (discs, neck spacers) + ligaments +
    servos (arms, neck, eyes at their targets) − gravity − J_mᵀ t with t constant (a tension-controlled wire adds
    only its geometric stiffness). Central differences over every joint except the reels (the reels are where
    the tension is held). Returns (symmetric K, DOF names); upright is stable iff its smallest eigenvalue > 0.
    Any hand lets go (and Kenta's teacher, ``let_go``, where the body has one)."""
    m, d = body.model, body.data
    stiffness, ctrl = m.jnt_stiffness.copy(), d.ctrl.copy()  # restored at the end: the caller's model is unchanged
    body.reset()
    body.hold(None)
    getattr(body, "let_go", lambda: None)()
    body.set_disc(disc_nm_rad)
    muscles = np.asarray(body.tendon_ids)
    k_wire = m.tendon_stiffness[muscles].copy()
    m.tendon_stiffness[muscles] = 0.0  # the wires' own spring is replaced by the held tension
    d.ctrl[:] = 0.0
    dofs = [j for j in range(m.njnt) if not (mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) or "").endswith(":reel")
            and int(m.jnt_type[j]) in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))]
    qadr, vadr = m.jnt_qposadr[dofs], m.jnt_dofadr[dofs]
    q0 = d.qpos.copy()
    moment = np.zeros((m.ntendon, m.nv))

    def force(q):
        d.qpos[:], d.qvel[:] = q, 0.0
        mujoco.mj_forward(m, d)
        mujoco.mju_sparse2dense(moment, d.ten_J, m.ten_J_rownnz, m.ten_J_rowadr, m.ten_J_colind)
        f = d.qfrc_passive + d.qfrc_actuator - d.qfrc_bias - moment[muscles].T @ np.full(len(muscles), tension_n)
        return f[vadr]

    K = np.zeros((len(dofs), len(dofs)))
    for c, a in enumerate(qadr):
        plus, minus = q0.copy(), q0.copy()
        plus[a] += step_rad
        minus[a] -= step_rad
        K[:, c] = -(force(plus) - force(minus)) / (2 * step_rad)
    m.tendon_stiffness[muscles] = k_wire
    m.jnt_stiffness[:] = stiffness
    body.reset()
    d.ctrl[:] = ctrl
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) for j in dofs]
    return 0.5 * (K + K.T), names


def upright_margin(body, tension_n: float, disc_nm_rad: float) -> float:
    """The smallest eigenvalue of :func:`upright_stiffness` [N m/rad]: > 0 iff upright is a stable equilibrium."""
    return float(np.linalg.eigvalsh(upright_stiffness(body, tension_n, disc_nm_rad)[0])[0])


def critical_disc_stiffness(body, tension_n: float, hi_nm_rad: float = 1000.0, tol_nm_rad: float = 0.1) -> float:
    """k*: the smallest per-axis disc stiffness for which upright is stable (:func:`upright_margin` crosses 0),
    by bisection on [0, ``hi_nm_rad``]."""
    lo, hi = 0.0, hi_nm_rad
    if upright_margin(body, tension_n, hi) <= 0:
        raise ValueError(f"upright is unstable even with {hi} N m/rad discs")
    while hi - lo > tol_nm_rad:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if upright_margin(body, tension_n, mid) > 0 else (mid, hi)
    return hi
