"""Kinematic plant of the two-plane world of seed 001 ch. 4 — the thesis's models as the motion law (spec §5.2).

The contact code of every wheel (front plane, lifted, rear plane) is a command, as the mode σ is in ch. 2;
the motion follows (2.21) while the head is raised and (4.9) once wheel 1 is on the front plane
(two_plane.py has the models).
"""

from __future__ import annotations

import numpy as np

from shintai.core.geometry import rot_z
from shintai.core.integrators import rk4_constant_rate
from shintai.core.runtime import SET, Body, SimulationDiverged, declare
from shintai.snake.constants import CH4_ROBOT, TWO_PLANE, TWO_PLANE_SCENE, SnakeGeometry, TwoPlaneSettings
from shintai.snake.model3d import (
    base_matrices,
    chain_from_wheel,
    contact_relation,
    forward_kinematics,
    planar_pose,
    yaw_joints,
)
from shintai.snake.two_plane import FRONT, LIFTED, REAR, Partition, TwoPlaneWorld, edge_clearance, straddle_model


class TwoPlaneSnake(Body):
    """Kinematic plant of the two-plane world: the thesis's models as the motion law (spec §5.2).

    State: head pose (p_h, R_h) and all joints ψ. Commands: ``psi_dot`` (2n−1) and ``contact`` (n codes,
    :data:`FRONT`/:data:`LIFTED`/:data:`REAR`; which wheels touch is a command, as σ in ch. 2), held over δt.

    * Wheel 1 lifted (head raised, §2.5.1): the grounded base n_h..n moves as (2.21) by least squares,
      ẇ̃_{n_h} = A_b^† B_b φ̇_b (RK4); the head part follows by forward kinematics from wheel n_h.
    * Wheel 1 on the front plane: ^f w̃_h moves as (4.9) by least squares, ^f ẇ̃_h = A_p^† B_p ψ̇ (RK4); the
      front part lies in the front plane by construction, everything else follows by forward kinematics.
      On entering this mode the head is projected onto the front plane (``snap_m``: largest point shift).

    The snapshot reports ``slip`` = max |A ẇ − B ψ̇| of the constraints used, and for every wheel its contact
    relation [d, κ, λ] (2.36)–(2.38) to the front (``r_front``) and rear (``r_rear``) planes, plus the
    clearance of the lifted part (:meth:`lifted_clearance`) to the front edge.
    """

    channels = {**declare("psi_dot"), **declare("contact", kind=SET)}  # contact: one code per wheel

    def __init__(self, world: TwoPlaneWorld, p_h, R_h, psi, contact, geometry: SnakeGeometry = CH4_ROBOT,
                 settings: TwoPlaneSettings = TWO_PLANE, link_radius: float = TWO_PLANE_SCENE.link_radius):
        self.world, self.geometry, self.settings, self.link_radius = world, geometry, settings, link_radius
        self.dt = float(settings.dt)
        self.t, self.steps = 0.0, 0
        self.ch = forward_kinematics(p_h, R_h, psi, geometry.l)
        if len(self.ch.psi) != geometry.joints:
            raise ValueError(f"psi must hold 2n−1 = {geometry.joints} joint angles, got {len(self.ch.psi)}")
        self.contact = np.asarray(contact).round().astype(int)
        self.psi_dot = np.zeros(geometry.joints)
        self.slip, self.snap_m = 0.0, 0.0

    def snapshot(self) -> dict:
        ch, w = self.ch, self.world
        r_front = np.array([contact_relation(ch.wheel_position(i), ch.wheel_frame(i), w.front)
                            for i in range(1, self.geometry.n + 1)])
        r_rear = np.array([contact_relation(ch.wheel_position(i), ch.wheel_frame(i), w.rear)
                           for i in range(1, self.geometry.n + 1)])
        return {"t": self.t, "p_h": ch.P[0].copy(), "R_h": ch.R[0].copy(), "psi": ch.psi.copy(),
                "contact": self.contact.copy(), "slip": self.slip, "snap_m": self.snap_m,
                "r_front": r_front, "r_rear": r_rear, "edge_clearance": self.lifted_clearance(),
                "wheels": np.array([ch.wheel_position(i) for i in range(1, self.geometry.n + 1)])}

    def lifted_clearance(self) -> float:
        """:func:`edge_clearance` of the body between the last front-plane wheel (or the head tip) and the first
        rear-plane wheel (or the tail tip): the lifted part, the connection part once wheel 1 is on the front."""
        c = self.contact
        if (c == FRONT).all():
            return float("inf")
        first = 2 * int(np.argmax(c != FRONT)) if c[0] == FRONT else 0
        rear = np.flatnonzero(c == REAR)
        last = 2 * (int(rear[0]) + 1) if len(rear) else 2 * self.geometry.n
        return edge_clearance(self.world, self.ch, first, last, self.link_radius)

    def apply(self, command: dict) -> None:
        if "contact" in command:
            contact = np.asarray(command["contact"]).round().astype(int)
            if contact.shape != (self.geometry.n,) or not np.isin(contact, (LIFTED, FRONT, REAR)).all():
                raise ValueError(f"contact must give n = {self.geometry.n} codes 0/1/2, got {contact.tolist()}")
            self.contact = contact
        psi_dot = np.asarray(command.get("psi_dot", np.zeros(self.geometry.joints)), dtype=float)
        if psi_dot.shape != (self.geometry.joints,):
            raise ValueError(f"psi_dot must have 2n−1 = {self.geometry.joints} entries, got shape {psi_dot.shape}")
        self.psi_dot = psi_dot

    def step(self) -> None:
        if self.contact[0] == FRONT:
            self._step_front()
        else:
            self._step_base()
        if not np.all(np.isfinite(self.ch.P)):
            raise SimulationDiverged(f"two-plane snake: non-finite state at t = {self.t + self.dt:.3f} s")
        self.steps += 1
        self.t = self.steps * self.dt

    def _rk4(self, f, x, psi):
        """RK4 of ẋ = f(x, ψ)[0] with ψ̇ constant over δt; returns (x, ψ) at t + δt and f's first residual."""
        k1, residual = f(x, psi)
        steps = self.settings.rk4_steps
        x, psi = rk4_constant_rate(lambda x_, psi_: f(x_, psi_)[0], x, psi, self.psi_dot, self.dt / steps, steps, k1)
        return x, psi, residual

    def _step_front(self) -> None:
        part, l = Partition.from_contact(self.contact), self.geometry.l
        w = self.world.planar(self.ch.P[0], self.ch.R[0])
        snapped = forward_kinematics(*self.world.embed(w), self.ch.psi, l)
        self.snap_m = max(self.snap_m, float(np.abs(snapped.P - self.ch.P).max()))

        def f(w_, psi_):
            m = straddle_model(self.world, part, w_, psi_, l)
            A, b = m.A_p(), m.B_p() @ self.psi_dot
            w_dot = np.linalg.lstsq(A, b, rcond=None)[0]
            return w_dot, A @ w_dot - b

        w, psi, residual = self._rk4(f, w, self.ch.psi)
        self.slip = float(np.abs(residual).max(initial=0.0))
        self.ch = forward_kinematics(*self.world.embed(w), psi, l)

    def _step_base(self) -> None:
        rear = np.flatnonzero(self.contact == REAR)
        if len(rear) < 2 or rear[-1] != self.geometry.n - 1 or np.ptp(rear) != len(rear) - 1 \
                or (self.contact[: rear[0]] != LIFTED).any():
            raise ValueError(f"with wheel 1 off the front plane the contact must read LIFTED…, REAR… (wheels "
                             f"n_h..n on the rear plane), got {self.contact.tolist()}")
        k, n, l = int(rear[0]) + 1, self.geometry.n, self.geometry.l
        base_yaw = yaw_joints(2 * k + 1, 2 * n - 1)
        p_a, R_a = self.ch.wheel_position(k), self.ch.wheel_frame(k)
        w_a = planar_pose(self.ch, 2 * k, self.ch.wheel_link(k))

        def f(w_, psi_):
            A, B = base_matrices(w_, psi_[base_yaw], l)
            b = B @ self.psi_dot[base_yaw]
            w_dot = np.linalg.lstsq(A, b, rcond=None)[0]
            return w_dot, A @ w_dot - b

        w, psi, residual = self._rk4(f, w_a, self.ch.psi)
        self.slip = float(np.abs(residual).max(initial=0.0))
        shift = np.r_[w[:2] - w_a[:2], 0.0]
        self.ch = chain_from_wheel(psi, l, k, p_a + shift, rot_z(w[2] - w_a[2]) @ R_a)
