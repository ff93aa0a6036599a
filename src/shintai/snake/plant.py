"""Kinematic plant of the wheeled snake — the thesis's own planar model (seed 001 §2.2–§2.3) as a Body.

State q = [w̃_h; φ]. The command is the joint rates φ̇ (``"phi_dot"``, n yaw joints) and the grounded
pattern σ (``"grounded"``, n entries 0/1; lifting a wheel is a command, §2.3). Both are held over one
step δt. The head moves as the least-squares solution of the grounded wheels' constraints (2.10),
ẇ̃_h = A_σ^† B_σ φ̇ (spec §5.2), integrated with RK4; φ̇ is integrated exactly.

Slip: the no-side-slip constraint (2.7) holds exactly only if B_σ φ̇ lies in the range of A_σ. The
residual v = A_σ ẇ̃_h − B_σ φ̇ is the axle-direction speed the grounded wheels would have to slide with;
the snapshot reports its largest magnitude (m/s) for the step just taken as ``"slip"``. It is ≈ 0 when
φ̇ comes from the two-point law with B_{c,σ} of full row rank.

Pitch joints are 0 in the plane (§2.3), so ``"psi"`` (all 2n−1 joints, the 3D models' input) carries the
yaw angles at the odd joints and zeros at the pitch joints.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from shintai.core.integrators import rk4_constant_rate_floats
from shintai.core.runtime import SET, Body, SimulationDiverged, declare
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, PLANT, PlantSettings, SnakeGeometry
from shintai.snake.linalg import DGELSD, least_squares_workspace, lstsq, solve_rows
from shintai.snake.model import check_mode, configuration, constraint_rows, rate_sums

_DIVERGED, _SOLVE_FAILED = 1, 2  # statuses of _advance (0: stepped)


class KinematicSnake(Body):
    """Planar kinematic snake: snapshot ``t, w_h, phi, psi, grounded, slip``; command ``phi_dot, grounded``."""

    channels = {**declare("phi_dot"), **declare("grounded", kind=SET)}  # σ: wheels on the floor (1) or lifted (0)

    def __init__(self, w_h0, phi0, geometry: SnakeGeometry = CH3_ROBOT, dt: float = CH3_GAINS.dt,
                 settings: PlantSettings = PLANT):
        if not dt > 0:
            raise ValueError(f"dt must be > 0 s, got {dt!r}")
        self.geometry = geometry
        self.dt = float(dt)
        self.settings = settings
        self.t = 0.0
        self.steps = 0
        cfg = configuration(w_h0, phi0, geometry.l)  # validates shapes
        if cfg.n != geometry.n:
            raise ValueError(f"phi0 must have n = {geometry.n} yaw angles, got {cfg.n}")
        self.w_h = cfg.w_h.copy()
        self.phi = cfg.phi.copy()
        self.grounded = np.ones(geometry.n, dtype=bool)  # all wheels on the ground until commanded
        self.phi_dot = np.zeros(geometry.n)
        self._rates = rate_sums(self.phi_dot)  # Φ of the held φ̇, as the O(n) pass reads it
        self.slip = 0.0
        n = geometry.n
        self._rows = np.empty((n, 4))  # [A_σ, B_σ φ̇] of one RK4 stage
        self._lapack = least_squares_workspace(n, 3) if DGELSD is not None else None
        self._stages = np.empty((6, max(n, 3)))  # _advance's scratch: k1..k4, the stage's w̃_h and φ

    def snapshot(self) -> dict:
        psi = np.zeros(self.geometry.joints)
        psi[::2] = self.phi
        return {"t": self.t, "w_h": self.w_h.copy(), "phi": self.phi.copy(), "psi": psi,
                "grounded": self.grounded.copy(), "slip": self.slip}

    def apply(self, command: dict) -> None:
        if "grounded" in command:
            self.grounded = check_mode(command["grounded"], self.geometry.n)
        phi_dot = np.asarray(command.get("phi_dot", np.zeros(self.geometry.n)), dtype=float)
        if phi_dot.shape != (self.geometry.n,):
            raise ValueError(f"phi_dot must have n = {self.geometry.n} entries, got shape {phi_dot.shape}")
        self.phi_dot = phi_dot
        self._rates = rate_sums(phi_dot)

    def head_velocity(self, w_h, phi) -> tuple[np.ndarray, np.ndarray]:
        """ẇ̃_h = A_σ^† B_σ φ̇ (2.10) and the grounded wheels' residual lateral speeds A_σ ẇ̃_h − B_σ φ̇."""
        rows, w_dot = self._rows, np.empty(3)
        m = constraint_rows(float(w_h[2]), np.asarray(phi, dtype=float), self.geometry.l, self._rates, self.grounded,
                            rows)
        if DGELSD is None:  # NumPy's LAPACK not reachable from compiled code: the same solve through its gufunc
            w_dot = lstsq(rows[:m, :3], rows[:m, 3]) if m else np.zeros(3)
        elif not solve_rows(DGELSD, rows, m, w_dot, *self._lapack):
            raise np.linalg.LinAlgError("least squares did not converge")
        return w_dot, rows[:m, :3] @ w_dot - rows[:m, 3]

    def step(self) -> None:
        """Advance by δt with RK4 (``settings.rk4_steps`` steps); φ(t) = φ + φ̇ t is exact."""
        k1, residual = self.head_velocity(self.w_h, self.phi)
        self.slip = float(np.abs(residual).max(initial=0.0))
        steps = self.settings.rk4_steps
        if DGELSD is None:  # the same RK4 in Python (what _advance compiles), the rate by NumPy's lstsq
            w, phi = rk4_constant_rate_floats(lambda x, q: self.head_velocity(x, q)[0].tolist(), self.w_h.tolist(),
                                              self.phi.tolist(), self.phi_dot.tolist(), self.dt / steps, steps,
                                              k1.tolist())
            w, phi = np.array(w), np.array(phi)
            status = 0 if np.isfinite(w).all() and np.isfinite(phi).all() else _DIVERGED
        else:
            w, phi = self.w_h.copy(), self.phi.copy()
            status = _advance(DGELSD, w, phi, self.phi_dot, self.dt / steps, steps, k1, self.geometry.l, self._rates,
                              self.grounded, self._rows, *self._lapack, self._stages)
        if status == _SOLVE_FAILED:
            raise np.linalg.LinAlgError("least squares did not converge")
        if status == _DIVERGED:
            raise SimulationDiverged(f"kinematic snake: non-finite state at t = {self.t + self.dt:.3f} s")
        self.w_h, self.phi = w, phi
        self.steps += 1
        self.t = self.steps * self.dt


@njit(cache=True)
def _advance(lapack, w, phi, u, h, steps, k1, l, rates, grounded, rows, ints, reals, stages) -> int:
    """RK4 of ẇ̃_h = A_σ^† B_σ φ̇ (2.10) over ``steps`` steps of ``h`` with φ(t) = φ + u t exact, in place on
    ``w`` (w̃_h) and ``phi``; ``k1`` is the rate at the start. The operations, element by element and in order,
    of :func:`shintai.core.integrators.rk4_constant_rate_floats` with :func:`constraint_rows` and dgelsd
    (:func:`solve_rows`) as the rate, so the bits of the plant written with them; compiled because its eight
    stages per δt are sequential and each is a few dozen flops, where Python's and NumPy's per-call cost was
    the plant's time. Returns 0, or _SOLVE_FAILED (dgelsd failed) or _DIVERGED (a non-finite state)."""
    n = phi.shape[0]
    k, k2, k3, k4, x, mid = stages[0, :3], stages[1, :3], stages[2, :3], stages[3, :3], stages[4, :3], stages[5, :n]
    k[:] = k1
    half, sixth = 0.5 * h, h / 6.0
    for i in range(steps):
        if i and not _head_rate(lapack, w, phi, l, rates, grounded, rows, ints, reals, k):
            return _SOLVE_FAILED
        for j in range(n):
            mid[j] = phi[j] + half * u[j]
        for j in range(3):
            x[j] = w[j] + half * k[j]
        if not _head_rate(lapack, x, mid, l, rates, grounded, rows, ints, reals, k2):
            return _SOLVE_FAILED
        for j in range(3):
            x[j] = w[j] + half * k2[j]
        if not _head_rate(lapack, x, mid, l, rates, grounded, rows, ints, reals, k3):
            return _SOLVE_FAILED
        for j in range(n):
            phi[j] = phi[j] + h * u[j]  # the step's end, φ + h u
        for j in range(3):
            x[j] = w[j] + h * k3[j]
        if not _head_rate(lapack, x, phi, l, rates, grounded, rows, ints, reals, k4):
            return _SOLVE_FAILED
        for j in range(3):
            w[j] = w[j] + sixth * (k[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
    for j in range(3):
        if not math.isfinite(w[j]):
            return _DIVERGED
    for j in range(n):
        if not math.isfinite(phi[j]):
            return _DIVERGED
    return 0


@njit(cache=True)
def _head_rate(lapack, w, phi, l, rates, grounded, rows, ints, reals, out) -> bool:
    """ẇ̃_h = A_σ^† B_σ φ̇ (2.10) at head pose ``w`` and yaw angles ``phi`` into ``out``; False if dgelsd failed."""
    return solve_rows(lapack, rows, constraint_rows(w[2], phi, l, rates, grounded, rows), out, ints, reals)
