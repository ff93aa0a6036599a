"""The two-point law on the 3D models of seed 001 §2.5, as the applications of §3.4 use it.

The thesis applies two-point control (3.3)–(3.6), (3.19)–(3.20) to the double-arm model for the handcart
((3.24)–(3.25), §3.4.2) and to the head-raised model for the door (§3.4.3) without writing the 3D law out
(A17, A18). Here: a 3D model as the controller sees it (:class:`SpatialModel`: A_σ ċ = B_σ u with its
inputs, base wheels and candidate base modes), the candidate base modes (§3.2.4 on the base), the three
models used (:func:`double_arm_model`, :func:`head_raised_model`, :func:`head_raised_two_point_model`), a
kinematic plant of such a model (:class:`KinematicSpatial`) and the law (:class:`SpatialTwoPoint`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from shintai.core.geometry import wrap
from shintai.core.runtime import SET, Body, Module, SimulationDiverged, declare, whole_multiple
from shintai.snake.constants import CH3_GAINS, MUJOCO_SNAKE, SnakeGeometry
from shintai.snake.model3d import (
    PLANAR,
    DoubleArm,
    chain_from_pose,
    euler_zyx,
    head_euler_map,
    head_raised,
    pose_jacobian,
    yaw_joints,
)
from shintai.snake.mujoco_plant import lift_profile
from shintai.snake.two_point import joint_limit_objective

ANGLES_6 = (3, 4, 5, 9, 10, 11)  # Euler angles in c_d = [w_h; w_t] (2.34)


@dataclass(frozen=True)
class SpatialModel:
    """A 3D model of §2.5 as the controller uses it: ``matrices(w_h, ψ, σ) -> (A, B, c)`` with A ċ = B u,
    ``inputs`` (0-based ψ indices of u), the base wheels ``base`` = (first, last) (1-based) lying on the
    floor, the candidate base modes (rows of grounded flags for the base wheels, §3.2.4) and the indices
    of Euler angles in c (their errors are wrapped)."""

    matrices: Callable[[np.ndarray, np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
    inputs: np.ndarray
    base: tuple[int, int]
    candidates: np.ndarray
    angles: tuple[int, ...] = ANGLES_6


def base_candidates(n_base: int, n_c: int, n_g: int, min_lifted: int, fixed: int = 1,
                    tail_lifted: bool = False) -> np.ndarray:
    """Base modes (rows of grounded flags for the base wheels): the ``fixed`` wheels at each end of the base
    grounded, runs of lifted wheels <= n_c, >= n_g grounded, >= ``min_lifted`` lifted (rules (iii) and (ii')
    of §3.2.4 on the base).

    The end wheels (n_h, n_t) must stay on the plane: (2.16) and (2.29) assume it. ``fixed = 2`` also keeps
    their neighbours down, a stage-1 exclusion of §3.2.4 (modes the hardware cannot realise as the model
    assumes): a wheel is lifted by pitching the links beside it (§2.3, Fig. 2.5), and the link beside wheel
    n_h + 1 on the head side is the frame of wheel n_h (Σ_{w,n_h}, §2.1), whose pitch (2.16) holds at 0; the
    yaw joint between cannot level it again. Lifting wheel n_h + 1 therefore tips the whole raised head part
    (on MuJoCo: the head 9 mm and 23 mrad off at each such switch). ``tail_lifted``: the base's last wheel
    is the second control point instead (the tail wheel, rule (i) of §3.2.4): it is lifted and only the
    front end is fixed.
    """
    modes = ((np.arange(2 ** n_base)[:, None] >> np.arange(n_base)) & 1).astype(bool)
    ends = np.r_[0:fixed] if tail_lifted else np.r_[0:fixed, n_base - fixed:n_base]
    keep = modes[:, ends].all(1) & (modes.sum(1) >= n_g) & ((~modes).sum(1) >= min_lifted)
    if tail_lifted:
        keep &= ~modes[:, -1]
    run = np.zeros(len(modes), int)
    longest = np.zeros(len(modes), int)
    for i in range(n_base):
        run = np.where(modes[:, i], 0, run + 1)
        longest = np.maximum(longest, run)
    return modes[keep & (longest <= n_c)]


def double_arm_model(geometry: SnakeGeometry, n_h: int, n_t: int, candidates: np.ndarray) -> SpatialModel:
    """Double-arm model (2.32)–(2.35) of model3d: c_d = [w_h; w_t], u = ψ_d = [ψ_h; φ'_b; ψ_t]."""
    arm = DoubleArm(geometry.n, geometry.l, n_h, n_t)

    def matrices(w_h, psi, grounded):
        m = arm.matrices(w_h, psi, grounded)
        return m.A_d, m.B_d, m.c_d

    return SpatialModel(matrices, arm.input_joints, (n_h, n_t), candidates)


def head_raised_model(geometry: SnakeGeometry, n_h: int, candidates: np.ndarray) -> SpatialModel:
    """Head-raised model (2.16)–(2.26) of model3d (the head-raising control [12] of §3.4.3 phase 1): c = w_h
    (6D), u = ψ̄ = [ψ_h; φ_b] (2.26), base wheels n_h..n."""
    n = geometry.n
    inputs = np.concatenate((np.arange(2 * n_h), yaw_joints(2 * n_h + 1, 2 * n - 1)))
    n_b = n - n_h + 1

    def matrices(w_h, psi, grounded):
        hr = head_raised(chain_from_pose(w_h, psi, geometry.l), n_h)
        rows = np.concatenate((np.flatnonzero(grounded), n_b + np.arange(3)))
        return hr.A_h[rows], hr.B_h[rows], np.asarray(w_h, dtype=float).copy()

    return SpatialModel(matrices, inputs, (n_h, n), candidates, (3, 4, 5))


def head_raised_two_point_model(geometry: SnakeGeometry, n_h: int, candidates: np.ndarray) -> SpatialModel:
    """Two-point control with the head raised (§3.4.3 phase 2, A18): the head-raised model (2.25) and the tail
    wheel's planar pose w̃_t as second control point, stacked as (2.14)–(2.15) and (2.32)–(2.33) are:
    A = [[A_h, O], [J_{t,1}, −I_3]], B = [[B_h], [−J_{t,2}]] with ẇ̃_t = J_{t,1} ẇ_h + J_{t,2} ψ̄̇ (the planar
    rows of the tail wheel's pose Jacobian, as (2.30)); c = [w_h; w̃_t] (9), u = ψ̄ = [ψ_h; φ_b]. The tail
    wheel must be lifted in every candidate (rule (i) of §3.2.4)."""
    n = geometry.n
    inputs = np.concatenate((np.arange(2 * n_h), yaw_joints(2 * n_h + 1, 2 * n - 1)))
    n_b = n - n_h + 1

    def matrices(w_h, psi, grounded):
        ch = chain_from_pose(w_h, psi, geometry.l)
        hr = head_raised(ch, n_h)
        rows = np.concatenate((np.flatnonzero(grounded), n_b + np.arange(3)))
        J_twist, J_psi = pose_jacobian(ch, 2 * n, 2 * n - 1)
        J1 = J_twist[PLANAR] @ head_euler_map(euler_zyx(ch.R[0]))
        J2 = J_psi[PLANAR][:, inputs]
        A = np.block([[hr.A_h[rows], np.zeros((len(rows), 3))], [J1, -np.eye(3)]])
        B = np.vstack((hr.B_h[rows], -J2))
        c = np.concatenate((np.asarray(w_h, dtype=float), ch.wheel_pose(n)[PLANAR]))
        return A, B, c

    return SpatialModel(matrices, inputs, (n_h, n), candidates, (3, 4, 5, 8))


class KinematicSpatial(Body):
    """A 3D model of §2.5 (a :class:`SpatialModel`) as a kinematic plant (spec §5.2): the input joints move as
    commanded and the head pose by ċ = A_σ^† B_σ u (explicit Euler per δt); the base pitch joints stay 0 (the
    model's flat base; lifting is the deletion of rows, §2.3). Snapshot ``t, head_pose, psi, phi, grounded``;
    command ``psi_dot``, ``grounded``."""

    channels = {**declare("psi_dot"), **declare("grounded", kind=SET)}  # σ: on the floor (1) / lifted (0)

    def __init__(self, w_h, psi, geometry: SnakeGeometry, model: SpatialModel, dt: float = CH3_GAINS.dt):
        self.geometry, self.model, self.dt = geometry, model, float(dt)
        self.w_h, self.psi = np.array(w_h, float), np.array(psi, float)
        self.grounded = np.ones(geometry.n, bool)
        self.psi_dot = np.zeros(geometry.joints)
        self.t, self.steps = 0.0, 0

    def snapshot(self) -> dict:
        return {"t": self.t, "head_pose": self.w_h.copy(), "psi": self.psi.copy(), "phi": self.psi[::2].copy(),
                "grounded": self.grounded.copy()}

    def apply(self, command: dict) -> None:
        if "grounded" in command:
            self.grounded = np.asarray(command["grounded"], dtype=bool)
        self.psi_dot = np.asarray(command.get("psi_dot", np.zeros(self.geometry.joints)), dtype=float)

    def step(self) -> None:
        first, last = self.model.base
        A, B, _ = self.model.matrices(self.w_h, self.psi, self.grounded[first - 1:last])
        u = self.psi_dot[self.model.inputs]
        c_dot = np.linalg.lstsq(A, B @ u, rcond=None)[0]
        self.w_h = self.w_h + self.dt * c_dot[:6]
        self.psi = self.psi.copy()
        self.psi[self.model.inputs] += self.dt * u
        if not (np.all(np.isfinite(self.w_h)) and np.all(np.isfinite(self.psi))):
            raise SimulationDiverged(f"kinematic 3D snake: non-finite state at t = {self.t + self.dt:.3f} s")
        self.steps += 1
        self.t = self.steps * self.dt


class SpatialTwoPoint(Module):
    """The two-point law (3.3)–(3.6), (3.19)–(3.20) on a 3D model of §2.5 (the thesis uses the double-arm
    model for the handcart, (3.24)–(3.25), and states that the law carries over; A17, A18):

    u = B_σ^† A_σ (ċ_d + K_p (c_d − c)) + k_v (I − B_σ^† B_σ) η, η = ∂V_{u,1}/∂u (joint limits, (3.13));
    u = 0 if ‖u‖ > u_lim. Every t_σ the base mode maximising V_m = σ_min(B_σ) is chosen (k_m = (0, 1) as
    §3.3). c and the matrices come from the measured 6D head pose (``head_pose``, mocap) and the encoders.
    The lifted base wheels are raised by the base's pitch joints (mujoco_plant.lift_profile on the base,
    anchored at its first wheel, at most at settings.lift_rate as on the planar plant); everything else is
    in u. Sends ``psi_dot`` and ``grounded``.

    ``pose``: the snapshot key of the 6D head pose it controls from (``head_pose``, the mocap; the door's
    operator gives an internal-model estimate); ``clock``: the key of the time the target is read at
    (``t``, the body's; the door's targets run on the operator's clock).
    """

    def __init__(self, model: SpatialModel, target, geometry: SnakeGeometry, gains=CH3_GAINS,
                 settings=MUJOCO_SNAKE, k_sigma: float = 0.0, name: str = "spatial", pose: str = "head_pose",
                 clock: str = "t"):
        super().__init__(name, period=gains.dt)
        self.k_sigma, self.pose, self.clock = k_sigma, pose, clock
        self.model, self.target, self.geometry, self.gains, self.settings = model, target, geometry, gains, settings
        first, last = model.base
        self.lift_joints = 2 * np.arange(first + 1, last) - 1  # pitch joints of the inner base wheels (0-based)
        self.select_every = whole_multiple(gains.t_sigma, gains.dt, "t_sigma")
        self.mode, self.calls = 0, 0
        self.lift_cmd = np.zeros(len(self.lift_joints))

    def reset(self, snapshot) -> None:
        self.calls = 0
        self.lift_cmd = snapshot["psi"][self.lift_joints].copy()

    def grounded(self) -> np.ndarray:
        g = np.zeros(self.geometry.n, bool)
        first, last = self.model.base
        g[first - 1:last] = self.model.candidates[self.mode]
        return g

    def select(self, w_h, psi) -> None:
        """(3.19) with k_m = (0, 1): the base mode with the largest σ_min(B_σ). B_σ of every mode is B of the
        all-grounded base with the lifted wheels' rows deleted (T_σ, (2.11), (2.35)), so B is built once."""
        n_b = self.model.candidates.shape[1]
        B = self.model.matrices(w_h, psi, np.ones(n_b, bool))[1]
        rest = np.ones(B.shape[0] - n_b, bool)
        V = [np.linalg.svd(B[np.r_[g, rest]], compute_uv=False)[-1] for g in self.model.candidates]
        self.mode = int(np.argmax(V))

    def update(self, snapshot):
        t, w_h, psi = float(snapshot["t"]), snapshot[self.pose], snapshot["psi"]
        if len(self.model.candidates) > 1 and self.calls % self.select_every == 0:
            self.select(w_h, psi)
        self.calls += 1
        g = self.model.candidates[self.mode]
        A, B, c = self.model.matrices(w_h, psi, g)
        c_d, c_d_dot = self.target(float(snapshot[self.clock]))
        error = np.asarray(c_d, float) - c
        angles = list(self.model.angles)
        error[angles] = wrap(error[angles])
        eta = self.gains.k_u[0] * joint_limit_objective(psi[self.model.inputs], self.gains.phi_th)[1]
        if self.k_sigma:
            eta = eta + self.k_sigma * self.sigma_gradient(w_h, psi, g, B)
        u, stopped, u_norm = self.law(A, B, c_d_dot + self.gains.k_p * error, eta)
        psi_dot = np.zeros(self.geometry.joints)
        psi_dot[self.model.inputs] = u
        first, last = self.model.base
        lift = lift_profile(snapshot["phi"][first - 1:last], g, self.geometry.l, self.settings)[1:]
        rate = np.clip((lift - self.lift_cmd) / self.period, -self.settings.lift_rate, self.settings.lift_rate)
        psi_dot[self.lift_joints] = rate
        self.lift_cmd = self.lift_cmd + rate * self.period
        p = self.name
        V_m = float(np.linalg.svd(B, compute_uv=False)[-1])  # σ_min(B_σ) of the mode in use, (3.19)
        self.log(t, **{f"{p}.c": c, f"{p}.c_d": c_d, f"{p}.error": error, f"{p}.stopped": stopped,
                       f"{p}.u_norm": u_norm, f"{p}.mode": self.mode, f"{p}.psi": psi, f"{p}.V_m": V_m})
        return {"psi_dot": psi_dot, "grounded": self.grounded()}

    def sigma_gradient(self, w_h, psi, grounded, B, step: float = 1e-4) -> np.ndarray:
        """∂σ_min(B_σ)/∂u by forward differences: sub-task (c) of §3.2.3, avoid singular configuration II.
        The thesis's V_{u,3} = det(B B^T) (3.15) is a product of 19+ squared singular values here, numerically
        flat; its smallest factor carries the same information."""
        base = np.linalg.svd(B, compute_uv=False)[-1]
        grad = np.empty(len(self.model.inputs))
        for k, j in enumerate(self.model.inputs):
            moved = psi.copy()
            moved[j] += step
            grad[k] = np.linalg.svd(self.model.matrices(w_h, moved, grounded)[1], compute_uv=False)[-1] - base
        return grad / step

    def law(self, A, B, xi, eta) -> tuple[np.ndarray, bool, float]:
        """(3.3)–(3.5) with the pseudo-inverse by SVD, then (3.20)."""
        U, s, Vt = np.linalg.svd(B, full_matrices=False)
        keep = s > max(B.shape) * np.finfo(float).eps * s[0]
        U, s, Vt = U[:, keep], s[keep], Vt[keep]
        u_c = Vt.T @ ((U.T @ (A @ xi)) / s)
        u = u_c + self.gains.k_v * (eta - Vt.T @ (Vt @ eta))
        norm = float(np.linalg.norm(u))
        return (np.zeros_like(u), True, norm) if norm > self.gains.u_lim else (u, False, norm)
