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

import numpy as np

import math

from shintai.core.integrators import rk4_constant_rate_floats
from shintai.core.runtime import SET, Body, SimulationDiverged, declare
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, PLANT, PlantSettings, SnakeGeometry
from shintai.snake.linalg import lstsq
from shintai.snake.model import check_mode, configuration, constraint_rows, rate_sums


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
        self._held = self._plain_command()
        self.slip = 0.0

    def _plain_command(self) -> tuple[list, list]:
        """The held command as the O(n) pass reads it: Φ (``rate_sums`` of φ̇) and σ, as plain lists."""
        return rate_sums(self.phi_dot), self.grounded.tolist()

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
        self._held = self._plain_command()

    def head_velocity(self, w_h, phi) -> tuple[np.ndarray, np.ndarray]:
        """ẇ̃_h = A_σ^† B_σ φ̇ (2.10) and the grounded wheels' residual lateral speeds A_σ ẇ̃_h − B_σ φ̇."""
        A_s, rhs = self._grounded_terms(float(w_h[2]), list(phi))
        w_dot = lstsq(A_s, rhs)
        return w_dot, A_s @ w_dot - rhs

    def _grounded_terms(self, theta_h: float, phi: list) -> tuple[np.ndarray, np.ndarray]:
        """A_σ and B_σ φ̇ (2.10)–(2.11) at heading θ_{y,h} and yaw angles φ (floats) for the held command."""
        rates, grounded = self._held
        rows = constraint_rows(theta_h, phi, self.geometry.l, rates, grounded)
        return rows[:, :3], rows[:, 3]

    def _head_rate(self, w_h: list, phi: list) -> list:
        """ẇ̃_h of :meth:`head_velocity` alone, on floats (RK4's later stages do not need the residual)."""
        return lstsq(*self._grounded_terms(w_h[2], phi)).tolist()

    def step(self) -> None:
        """Advance by δt with RK4 (``settings.rk4_steps`` steps); φ(t) = φ + φ̇ t is exact."""
        k1, residual = self.head_velocity(self.w_h, self.phi)
        self.slip = float(np.max(np.abs(residual), initial=0.0))
        steps = self.settings.rk4_steps
        w, phi = rk4_constant_rate_floats(self._head_rate, self.w_h.tolist(), self.phi.tolist(),
                                          self.phi_dot.tolist(), self.dt / steps, steps, k1.tolist())
        if not all(map(math.isfinite, w + phi)):
            raise SimulationDiverged(f"kinematic snake: non-finite state at t = {self.t + self.dt:.3f} s")
        self.w_h, self.phi = np.array(w), np.array(phi)
        self.steps += 1
        self.t = self.steps * self.dt
