"""The DLS IK of :mod:`shintai.sim.ik` for one serial chain of hinge joints and one site, compiled (issue 30).

:func:`shintai.sim.ik.solve` iterates in Python around MuJoCo's ``mj_kinematics``, ``mj_comPos`` and ``mj_jacSite``
on the whole model; the tricycle's hands solve it twice every 4 ms control tick, half of the steering tick's control
time. :class:`ChainIK` runs the same search — the same damped least-squares step Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e, the same
step limit, joint clamping and active set, the same errors, tolerances and best-iterate rule — in one numba kernel
that walks only the chain: its forward kinematics from the chain's parent body as MuJoCo composes it (body offset
and rotation, then the hinge about its anchor), the site's pose and the Jacobian columns a × (site − anchor) and a.
One ``mj_kinematics`` on a scratch ``MjData`` places the parent (the rest of the body as in ``q0``).

It agrees with :func:`shintai.sim.ik.solve` to rounding, not bit for bit (rotation matrices composed here, MuJoCo's
quaternions there; a Cholesky factorisation for LAPACK's LU): tested on the HRP2 arms' targets, joint angles within
1e-9 rad. Targets: a position and, optionally, one site axis made parallel to a world direction (a hand on a bar).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import mujoco
import numpy as np
from numba import njit

from shintai.sim import ik
from shintai.sim.ik import IKResult

_HINGE = int(mujoco.mjtJoint.mjJNT_HINGE)


class ChainIK:
    """The IK of ``joints`` (hinges, each on its own body, each body the child of the previous one) for ``site``
    (on the last joint's body or one of its fixed descendants) of ``model``. :meth:`solve` is
    ``ik.solve(model, {site: Target(pos, axis=(local, world))}, q0, joints)`` with its defaults."""

    def __init__(self, model: mujoco.MjModel, site: str, joints: Sequence[str]):
        ids = [model.joint(j).id for j in joints]
        if not ids:
            raise ValueError("ChainIK: give at least one joint")
        bodies = [int(model.jnt_bodyid[j]) for j in ids]
        for name, j in zip(joints, ids):
            if int(model.jnt_type[j]) != _HINGE:
                raise ValueError(f"ChainIK moves hinge joints only; {name!r} is not one")
        for prev, body, name in zip(bodies, bodies[1:], joints[1:]):
            if int(model.body_parentid[body]) != prev:
                raise ValueError(f"ChainIK: joint {name!r} is not on the child body of the previous joint's")
        if any(int(model.body_jntnum[b]) != 1 for b in bodies):
            raise ValueError("ChainIK: one joint per body of the chain")
        # sim.ik's problem for these joints: its scratch data, the joints' qpos addresses and limits
        problem = ik.cached_problem(model, joints)
        self.model, self.data = model, problem.data
        s = model.site(site).id
        tail, b = [], int(model.site_bodyid[s])
        while b != bodies[-1]:  # fixed bodies between the last joint's body and the site's
            if b == 0 or int(model.body_jntnum[b]) != 0:
                raise ValueError(f"ChainIK: site {site!r} does not hang rigidly from the last joint's body")
            tail.append(b)
            b = int(model.body_parentid[b])
        self.parent = int(model.body_parentid[bodies[0]])
        chain = bodies + tail[::-1]
        # one row per chain body (GEOMETRY's columns): its offset and rotation in its parent, and its hinge's axis and
        # anchor (in the body) and qpos0 (zeros for the fixed bodies after the last joint)
        self.geometry = np.zeros((len(chain), GEOMETRY))
        for row, b in zip(self.geometry, chain):
            row[0:3], row[3:12] = model.body_pos[b], _quat_mat(model.body_quat[b]).ravel()
        for row, j in zip(self.geometry, ids):
            row[12:15], row[15:18], row[18] = model.jnt_axis[j], model.jnt_pos[j], model.qpos0[model.jnt_qposadr[j]]
        self.site = np.concatenate([model.site_pos[s], _quat_mat(model.site_quat[s]).ravel()])
        self.coords, self.limits = problem.qadr, np.stack([problem.lo, problem.hi], axis=1)
        self.n = len(ids)
        self._parent_xpos, self._parent_xmat = self.data.xpos[self.parent], self.data.xmat[self.parent]

    def solve(self, q0: np.ndarray, pos, axis: tuple | None = None, *, tol: float = 1e-4, rot_tol: float = 1e-3,
              max_iter: int = 300, damping: float = 1e-2, max_step: float = 0.2) -> IKResult:
        """Joint values putting the site at ``pos`` (world) with, if given, its axis ``axis[0]`` (site frame)
        parallel to ``axis[1]`` (world); the rest of the body as in the full ``q0``. As :func:`shintai.sim.ik.solve`:
        ``ok`` when within ``tol`` (m) and ``rot_tol`` (rad), else the best iterate; ``residual`` (m, rad)."""
        if damping <= 0:
            raise ValueError("ChainIK: damping > 0 (the Cholesky step needs J Jᵀ + λ² I positive definite)")
        q0 = np.asarray(q0, dtype=float)
        self.data.qpos[:] = q0
        mujoco.mj_kinematics(self.model, self.data)  # the chain's parent, the rest of the body as in q0
        local, world = (_NO_AXIS, _NO_AXIS) if axis is None else (np.asarray(v, dtype=float) for v in axis)
        if not local.shape == world.shape == (3,):  # (their norms are checked where they are normalised)
            raise ValueError(f"ChainIK: the axis target is two non-zero finite 3-vectors (site, world), got {axis!r}")
        q, ok, pos_err, rot_err = chain_dls(self._parent_xpos, self._parent_xmat, self.geometry, self.site,
                                            self.coords, self.limits, q0, np.asarray(pos, dtype=float), local, world,
                                            axis is not None, tol, rot_tol, max_iter, damping, max_step)
        return IKResult(q, ok, (pos_err, rot_err))


GEOMETRY = 19  # a chain body's row: offset (3), rotation (9, row-major), hinge axis (3), anchor (3), qpos0


_NO_AXIS = np.zeros(3)


def _quat_mat(quat) -> np.ndarray:
    m = np.zeros(9)
    mujoco.mju_quat2Mat(m, np.asarray(quat, dtype=float))
    return m.reshape(3, 3)


@njit(cache=True)
def _mat_vec(r, v, out):
    for i in range(3):
        out[i] = r[i, 0] * v[0] + r[i, 1] * v[1] + r[i, 2] * v[2]


@njit(cache=True)
def _mat_mat(a, b, out):
    for i in range(3):
        for j in range(3):
            out[i, j] = a[i, 0] * b[0, j] + a[i, 1] * b[1, j] + a[i, 2] * b[2, j]


@njit(cache=True)
def chain_fk(parent_pos, parent_rot, geometry, n, site, q, joint_pos, joint_axis, site_p, site_r):
    """The chain's forward kinematics (MuJoCo's composition: a body at its parent's pose times its offset, then its
    hinge turning it about the anchor), ``geometry`` as :class:`ChainIK` packs it, the first ``n`` bodies jointed:
    the site's world position and rotation into ``site_p``, ``site_r``; each joint's world anchor and axis into
    ``joint_pos`` and ``joint_axis`` (n × 3)."""
    p, r = parent_pos.copy(), parent_rot.copy()
    v, m, turn = np.empty(3), np.empty((3, 3)), np.empty((3, 3))
    for b in range(geometry.shape[0]):
        g = geometry[b]
        _mat_vec(r, g[0:3], v)
        p += v
        _mat_mat(r, g[3:12].reshape(3, 3), m)
        r[:, :] = m
        if b < n:
            x, y, z = g[12], g[13], g[14]
            _mat_vec(r, g[15:18], v)
            anc = p + v
            joint_pos[b] = anc
            _mat_vec(r, g[12:15], joint_axis[b])
            angle = q[b] - g[18]
            c, s = math.cos(angle), math.sin(angle)
            t = 1.0 - c  # Rodrigues: the hinge's rotation about its unit axis
            turn[0, 0], turn[0, 1], turn[0, 2] = c + t * x * x, t * x * y - s * z, t * x * z + s * y
            turn[1, 0], turn[1, 1], turn[1, 2] = t * x * y + s * z, c + t * y * y, t * y * z - s * x
            turn[2, 0], turn[2, 1], turn[2, 2] = t * x * z - s * y, t * y * z + s * x, c + t * z * z
            _mat_mat(r, turn, m)
            r[:, :] = m
            _mat_vec(r, g[15:18], v)
            p = anc - v
    _mat_vec(r, site[0:3], v)
    site_p[:] = p + v
    _mat_mat(r, site[3:12].reshape(3, 3), site_r)


@njit(cache=True)
def _errors(site_p, site_r, target, local, world, has_axis, e, a):
    """The error rows (position, then the axis error a × w) into ``e``, the site's axis into ``a``; (position
    error, rotation error)."""
    for i in range(3):
        e[i] = target[i] - site_p[i]
    pos_err = math.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
    rot_err = 0.0
    if has_axis:
        _mat_vec(site_r, local, a)
        e[3] = a[1] * world[2] - a[2] * world[1]
        e[4] = a[2] * world[0] - a[0] * world[2]
        e[5] = a[0] * world[1] - a[1] * world[0]
        rot_err = math.atan2(math.sqrt(e[3] * e[3] + e[4] * e[4] + e[5] * e[5]),
                             a[0] * world[0] + a[1] * world[1] + a[2] * world[2])
    return pos_err, rot_err


@njit(cache=True)
def _dls_step(jac, e, rows, damping, free, system, y, step):
    """Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e on the ``free`` columns (the others 0) into ``step``, by an in-place Cholesky
    factorisation (J Jᵀ + λ² I is symmetric positive definite for λ > 0)."""
    n = jac.shape[1]
    for i in range(rows):  # the system's lower triangle
        for j in range(i + 1):
            acc = 0.0
            for k in range(n):
                if free[k]:
                    acc += jac[i, k] * jac[j, k]
            system[i, j] = acc + (damping * damping if i == j else 0.0)
    for j in range(rows):  # L Lᵀ, L in the lower triangle
        acc = system[j, j]
        for k in range(j):
            acc -= system[j, k] * system[j, k]
        d = math.sqrt(acc)
        system[j, j] = d
        for i in range(j + 1, rows):
            acc = system[i, j]
            for k in range(j):
                acc -= system[i, k] * system[j, k]
            system[i, j] = acc / d
    for i in range(rows):  # L z = e
        acc = e[i]
        for k in range(i):
            acc -= system[i, k] * y[k]
        y[i] = acc / system[i, i]
    for i in range(rows - 1, -1, -1):  # Lᵀ x = z
        acc = y[i]
        for k in range(i + 1, rows):
            acc -= system[k, i] * y[k]
        y[i] = acc / system[i, i]
    for k in range(n):
        acc = 0.0
        if free[k]:
            for i in range(rows):
                acc += jac[i, k] * y[i]
        step[k] = acc


@njit(cache=True)
def chain_dls(parent_pos, parent_xmat, geometry, site, coords, limits, q0, target, local_axis, world_axis, has_axis,
              tol, rot_tol, max_iter, damping, max_step):
    """:func:`shintai.sim.ik.solve`'s search (no posture) on the chain of :class:`ChainIK` (its packed ``geometry``,
    ``site``, ``coords`` in qpos, ``limits``), from ``q0`` (the full qpos) clamped to the limits, for the site at
    ``target`` with (``has_axis``) its ``local_axis`` along ``world_axis`` (both normalised here). Returns (the full
    qpos of the answer, converged, position error, rotation error)."""
    n = len(coords)
    rows = 6 if has_axis else 3
    local, world = np.zeros(3), np.zeros(3)
    if has_axis:
        norm_local = math.sqrt(local_axis[0] ** 2 + local_axis[1] ** 2 + local_axis[2] ** 2)
        norm_world = math.sqrt(world_axis[0] ** 2 + world_axis[1] ** 2 + world_axis[2] ** 2)
        if not (0.0 < norm_local < np.inf and 0.0 < norm_world < np.inf):
            raise ValueError("ChainIK: the axis target is two non-zero finite 3-vectors (site, world)")
        local[:] = local_axis / norm_local
        world[:] = world_axis / norm_world
    parent_rot = parent_xmat.reshape(3, 3)
    lo, hi = limits[:, 0], limits[:, 1]
    q = np.empty(n)
    for k in range(n):
        q[k] = min(max(q0[coords[k]], lo[k]), hi[k])
    e, a, site_p, site_r = np.zeros(6), np.zeros(3), np.zeros(3), np.zeros((3, 3))
    jac, system, y, step = np.zeros((rows, n)), np.zeros((rows, rows)), np.zeros(rows), np.zeros(n)
    joint_pos, joint_axis = np.zeros((n, 3)), np.zeros((n, 3))
    free = np.ones(n, dtype=np.bool_)
    best = q.copy()
    best_score, best_pos, best_rot = np.inf, np.inf, np.inf
    converged = False
    for _ in range(max_iter):
        chain_fk(parent_pos, parent_rot, geometry, n, site, q, joint_pos, joint_axis, site_p, site_r)
        pos_err, rot_err = _errors(site_p, site_r, target, local, world, has_axis, e, a)
        score = max(pos_err / tol, rot_err / rot_tol)
        if score <= 1.0:
            best[:], best_pos, best_rot, converged = q, pos_err, rot_err, True
            break
        if score < best_score:
            best[:], best_score, best_pos, best_rot = q, score, pos_err, rot_err
        for k in range(n):  # the Jacobian: a_k × (site − anchor_k), and the axis rows (I − a aᵀ) a_k
            x, yy, z = joint_axis[k, 0], joint_axis[k, 1], joint_axis[k, 2]
            d0, d1, d2 = site_p[0] - joint_pos[k, 0], site_p[1] - joint_pos[k, 1], site_p[2] - joint_pos[k, 2]
            jac[0, k], jac[1, k], jac[2, k] = yy * d2 - z * d1, z * d0 - x * d2, x * d1 - yy * d0
            if has_axis:
                along = a[0] * x + a[1] * yy + a[2] * z
                jac[3, k], jac[4, k], jac[5, k] = x - a[0] * along, yy - a[1] * along, z - a[2] * along
        free[:] = True
        for _ in range(n):  # a joint at a limit that the step pushes further is frozen, the step recomputed
            _dls_step(jac, e, rows, damping, free, system, y, step)
            biggest = np.max(np.abs(step))
            if biggest > max_step:
                step *= max_step / biggest
            blocked = False
            for k in range(n):
                if free[k] and ((q[k] <= lo[k] and step[k] < 0) or (q[k] >= hi[k] and step[k] > 0)):
                    free[k] = False
                    blocked = True
            if not blocked:
                break
        for k in range(n):
            q[k] = min(max(q[k] + step[k], lo[k]), hi[k])
    full = q0.copy()
    for k in range(n):
        full[coords[k]] = best[k]
    return full, converged, best_pos, best_rot
