"""The door of seed 001 §3.4.3 (Figs. 3.12–3.17): the scene, the robot's start and shift control [8].

30 links (n = 15) and a spring-hinged door in MuJoCo. The thesis gives no door geometry, spring, hook or
trajectory numbers (A18: an operator chose targets and phases with a gamepad); constants.DoorSetup holds
the choices and why. The operator's phases are in door_operator.py.
"""

from __future__ import annotations

import numpy as np

from shintai.core.geometry import rot_z
from shintai.snake.constants import CH3_ROBOT, DOOR, MUJOCO_SNAKE, SnakeGeometry
from shintai.snake.model3d import chain_from_wheel
from shintai.snake.mujoco_plant import Scene


def knob_point(beta: float, door=DOOR) -> np.ndarray:
    """World (x, y) of the knob with the door open by β (counter-clockwise about the hinge at the origin)."""
    local = np.array([-door.knob_offset, door.width - door.knob_from_edge])
    c, s = np.cos(beta), np.sin(beta)
    return np.array([c * local[0] - s * local[1], s * local[0] + c * local[1]])


def door_scene(door=DOOR, spring: float | None = None, knob_height: float | None = None) -> Scene:
    """Walls with a doorway y ∈ [0, width] at x ∈ [0, thickness]; the leaf on a spring hinge (joint ``hinge``,
    sensor ``door_angle``); a knob (site ``knob``, free to slide vertically so that the hook holds it in
    the plane only); the hook: a ``connect`` equality ``hook`` between the head tip and the knob, off, switched
    through the body's set channel ``hook``."""
    t, w, h = door.thickness, door.width, door.height
    k = door.spring if spring is None else spring
    wall = door.wall_length
    head = MUJOCO_SNAKE.wheel_radius if knob_height is None else knob_height  # the hooked head tip's height
    z_knob = head - door.floor_gap  # above the leaf's base
    y_knob = w - door.knob_from_edge
    return Scene(
        worldbody=f"""
    <geom name="wall_right" class="object" type="box" pos="{t / 2} {-wall / 2} {h / 2}" size="{t / 2} {wall / 2} {h / 2}"
          rgba=".7 .7 .75 1"/>
    <geom name="wall_left" class="object" type="box" pos="{t / 2} {w + wall / 2} {h / 2}" size="{t / 2} {wall / 2} {h / 2}"
          rgba=".7 .7 .75 1"/>
    <body name="leaf" pos="0 0 {door.floor_gap}">
      <joint name="hinge" type="hinge" axis="0 0 1" range="0 {door.open_limit}" stiffness="{k}"
             damping="{door.damping}"/>
      <geom name="leaf" class="object" type="box" pos="{t / 2} {w / 2} {h / 2}" size="{t / 2} {w / 2 - 0.005} {h / 2}"
            mass="{door.leaf_mass}" rgba=".75 .55 .35 1"/>
      <geom type="capsule" fromto="0 {y_knob} {z_knob} {-door.knob_offset} {y_knob} {z_knob}"
            size="{door.knob_stem_radius}" contype="0" conaffinity="0" mass="{door.knob_mass}" rgba=".8 .7 .2 1"/>
      <body name="knob" pos="{-door.knob_offset} {y_knob} {z_knob}" gravcomp="1">
        <joint name="knob_z" type="slide" axis="0 0 1" range="{door.knob_slide[0]} {door.knob_slide[1]}"/>
        <geom type="sphere" size="{door.knob_radius}" contype="0" conaffinity="0" mass="{door.knob_mass}"
              rgba=".9 .8 .2 1"/>
        <site name="knob" size="0.005"/>
      </body>
    </body>""",
        equality='<connect name="hook" site1="head" site2="knob" active="false"/>',
        sensor='<jointpos name="door_angle" joint="hinge"/>',
        switches=("hook",),
    )


class ShiftControl:
    """Shift control [8], tail-first (§3.4.3 phase 3): the body is fitted to a continuous curve that travels
    from the tail toward the head, so the robot moves tail-first.

    The curve is given by the yaw angles along the body, a_k for joint index k: the current joint angles
    for k = 1..n ([62]: the initial curve is made from the current angles) and, beyond the tail, a
    serpenoid a_{n+j} = A sin(2π j / N_w + φ_0) with A sin φ_0 = φ_n (continuous at the tail). After s
    joint spacings of travel (s = t / shift_period) joint i takes a(i + s), linearly interpolated.

    These are the yaw angles only: the curve is planar and every wheel is on the floor. §3.4.3 has the robot
    snake (蛇行) through pushing the leaf with its tail (Fig. 3.14c) and describes no lifted wheels in this
    phase: lifting is two-point control's mode selection (§3.2.4), which phase 3 does not use; that the
    raised head part comes down too is this scenario's reading (the whole body passes). The shift phase
    (door_operator.Shift) therefore sends the rates as a planar command (``phi_dot``, every wheel grounded):
    the pitch joints put down the wheels phase 2's modes had lifted and lower the raised head part.
    """

    def __init__(self, phi_now, door=DOOR):
        phi_now = np.asarray(phi_now, dtype=float)
        n = len(phi_now)
        self.door = door
        horizon = int(door.t_shift / door.shift_period) + 2
        start = np.arcsin(np.clip(phi_now[-1] / door.shift_amplitude, -1.0, 1.0))
        j = np.arange(1, horizon + 1)
        self.curve = np.concatenate((phi_now, door.shift_amplitude * np.sin(2 * np.pi * j / door.shift_wave + start)))
        self.index = np.arange(n, dtype=float)
        self.command = phi_now.copy()

    @property
    def duration(self) -> float:
        """Time after which the curve is used up (the head joint has reached its end): nothing moves after it."""
        return (len(self.curve) - 1) * self.door.shift_period

    def angles(self, t: float) -> np.ndarray:
        """Joint angles after ``t`` s of shifting."""
        return np.interp(self.index + t / self.door.shift_period, np.arange(len(self.curve)), self.curve)

    def rates(self, t: float, dt: float) -> np.ndarray:
        """φ̇ that brings the integrated command to the curve at t + dt."""
        target = self.angles(t + dt)
        rate = (target - self.command) / dt
        self.command = target
        return rate


def door_geometry() -> SnakeGeometry:
    return SnakeGeometry(n=DOOR.n, l=CH3_ROBOT.l)


def door_start(offset=np.zeros(3), door=DOOR) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(p_h, R_h, ψ0): the door's φ(0) with the head part raised as an arm (raise_n_h, raise_pitch, as in
    door_operator.pull_rig), wheel raise_n_h on the floor, heading π, the head tip approach_gap short of the
    closed knob; ``offset`` = (dx, dy, dθ) moves and turns the whole body about the head tip."""
    geometry = door_geometry()
    n_h = door.raise_n_h
    psi = np.zeros(geometry.joints)
    psi[::2] = door.phi0
    psi[2 * n_h - 1] -= door.raise_pitch
    psi[1] += door.raise_pitch
    R = rot_z(offset[2]) @ np.diag([-1.0, -1.0, 1.0])
    start = np.array([0.0, 0.0, MUJOCO_SNAKE.wheel_radius])
    tip = chain_from_wheel(psi, geometry.l, n_h, start, R).P[0]
    start[:2] += knob_point(0.0, door) - np.array([door.approach_gap, 0.0]) + offset[:2] - tip[:2]
    ch = chain_from_wheel(psi, geometry.l, n_h, start, R)
    return ch.P[0], ch.R[0], psi
