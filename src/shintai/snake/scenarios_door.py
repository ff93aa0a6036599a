"""Door opening — seed 001 §3.4.3 (Figs. 3.12–3.17), scenario ``snake.door``.

30 links (n = 15) and a spring-hinged door in MuJoCo, the three phases of Fig. 3.14 run by an operator
module in place of the thesis's gamepad operator (A18, :class:`DoorOperator`):

1. head-raising control [12]: the head part raised as an arm, its hook brought to the knob and the knob
   pulled along its arc about the hinge (head-raised model (2.16)–(2.26));
2. two-point control: the head holds the door open while the tail wheel goes around the leaf into the
   doorway and inside (head-raised model plus the tail's planar pose, A18); then the hook is released;
3. shift control [8] tail-first until the whole body is inside, every wheel on the floor (:class:`ShiftControl`).

As in the thesis's simulation (Fig. 3.15) the controller reads the joint angles from the simulator and
estimates the head pose from its internal model (``head_pose=model``). The thesis reports failures in
phase 3 (wheels caught on the door, Fig. 3.17): the scenario also runs perturbed starts and reports the
success rate. :func:`head_raising_pull` runs phase 1's pull on the kinematic plant (no door).

The thesis gives no door geometry, spring, hook or trajectories (A18): constants.DoorSetup holds the
choices and why.
"""

from __future__ import annotations

from contextlib import nullcontext
from dataclasses import dataclass, replace

import numpy as np
from matplotlib.patches import Rectangle

from shintai.core import Loop, Recorder
from shintai.core.runtime import Module
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, DOOR, MUJOCO_SNAKE, SnakeGeometry
from shintai.snake.mujoco_plant import MujocoSnake, Scene
from shintai.snake.model3d import chain_from_wheel
from shintai.snake.scenarios import draw_link_points, draw_track, shade_stopped, wheel_legend
from shintai.snake.scenarios_physical import (
    KinematicSpatial,
    SpatialTwoPoint,
    Waypoints,
    base_candidates,
    head_raised_model,
    head_raised_two_point_model,
    link_points,
)


def knob_point(beta: float, door=DOOR) -> np.ndarray:
    """World (x, y) of the knob with the door open by β (counter-clockwise about the hinge at the origin)."""
    local = np.array([-door.knob_offset, door.width - door.knob_from_edge])
    c, s = np.cos(beta), np.sin(beta)
    return np.array([c * local[0] - s * local[1], s * local[0] + c * local[1]])


def door_scene(door=DOOR, spring: float | None = None, knob_height: float | None = None) -> Scene:
    """Walls with a doorway y ∈ [0, width] at x ∈ [0, thickness]; the leaf on a spring hinge (joint ``hinge``,
    sensor ``door_angle``); a knob (site ``knob``, free to slide vertically so that the hook holds it in
    the plane only); the hook: a ``connect`` equality ``hook`` between the head tip and the knob, off."""
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
    raised head part comes down too is this scenario's reading (the whole body passes). :class:`DoorOperator`
    therefore sends them as a planar command (``phi_dot``, all wheels grounded), so the pitch joints put down the
    wheels that phase 2's modes had lifted and lower the raised head part. Sending the yaw rates with the
    pitch joints held where phase 2's last mode left them (as this scenario first did) kept 10 of the 15
    wheels in the air (the raised head part's three and the tail wheel among them): with 5 wheels on the
    floor the shifted shape had few side constraints to push against, and in the nominal run the body swung
    about the doorway and drifted head-first (the tail from x = 0.25 back to 0.08 m, the head 1 m away).
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


def remembering(model):
    """``model`` whose ``matrices`` returns its last result again (copies) when called with the same arguments.
    The operator's head estimate (``observed``) needs A, B at the previous period's estimate, joint angles
    and mode, which the controller has just computed: the same numbers, computed once."""
    last = {}

    def matrices(w_h, psi, grounded):
        key = tuple(np.asarray(a, dtype=float).tobytes() for a in (w_h, psi, grounded))
        if key not in last:
            last.clear()
            last[key] = model.matrices(w_h, psi, grounded)
        return tuple(np.array(a, copy=True) for a in last[key])

    return replace(model, matrices=matrices)


DOOR_PHASES = ("approach", "pull", "tail", "release", "shift", "passed", "gave_up")  # thesis phase 1 = approach + pull


class DoorOperator(Module):
    """The operator of §3.4.3 (Fig. 3.15) as a module: chooses the targets and the phase, runs the controller
    of each phase and works the hook. Like the thesis's operator it watches the simulation (hook distance,
    door angle, where the body is); the controllers get only the snapshot.

    Phase 1, head-raising control [12]: the head part (wheels 1..raise_n_h − 1, joints 1..2·raise_n_h) is
    raised as an arm and the head's 6D pose is controlled through the head-raised model (2.16)–(2.26)
    (scenarios_physical.head_raised_model) under the law (3.3)–(3.6), (3.19)–(3.20) with base modes
    (SpatialTwoPoint): ``approach`` the knob, engage the hook, ``pull`` the knob along its arc about the
    hinge to open_angle, the hook's yaw turning with the leaf ("considering the door's rotation centre").
    Phase 2, two-point control with the head held: ``tail`` — the head-raised model plus the tail wheel's
    planar pose (head_raised_two_point_model); the head holds its pose (the door stays open) while the
    tail goes to the doorway, close to the leaf, and inside; ``release`` the hook and hold while the door
    closes onto the body. Phase 3: ``shift`` control [8] tail-first until every link is inside (``passed``),
    every wheel on the floor (planar command, see :class:`ShiftControl`).
    The operator gives up (``gave_up``) when the robot has not followed for ``give_up`` s, or in phase 3 when
    the shift curve is used up (ShiftControl.duration).

    Head pose for the controllers (``head_pose``): ``"model"`` — the thesis's simulation does not read it
    from the simulator but estimates it from the internal model (Fig. 3.15): ẇ_h = (A^† B ψ̇)_head of the
    phase's model with the measured joint motion, from the pose at the start; ``"mocap"`` — the simulator's.

    Targets run on the operator's clock, which stops while the input limit (3.20) has the robot stopped:
    an operator does not push the stick further while the robot does not follow.
    """

    def __init__(self, body: MujocoSnake, geometry: SnakeGeometry, door=DOOR, head_pose: str = "model",
                 gains=CH3_GAINS, name: str = "door"):
        super().__init__(name, period=gains.dt)
        if head_pose not in ("model", "mocap"):
            raise ValueError(f"head_pose must be 'model' or 'mocap', got {head_pose!r}")
        self.body, self.geometry, self.door, self.head_pose, self.gains = body, geometry, door, head_pose, gains
        n, n_h = geometry.n, door.raise_n_h
        self.raise_model = remembering(head_raised_model(
            geometry, n_h, base_candidates(n - n_h + 1, gains.n_c, gains.n_g, 0, fixed=2)))
        self.tail_model = remembering(head_raised_two_point_model(
            geometry, n_h, base_candidates(n - n_h + 1, gains.n_c, gains.n_g, 0, fixed=2, tail_lifted=True)))
        self.phase, self.phase_start, self.clock, self.moved_at = "approach", 0.0, 0.0, 0.0
        self.waypoints: Waypoints | None = None
        self.controller: SpatialTwoPoint | None = None
        self.shift: ShiftControl | None = None
        self.events: list[tuple[float, str]] = []
        self.grounded = np.ones(geometry.n, bool)  # the wheels' mode last sent to the body
        self.estimate: np.ndarray | None = None
        self.psi_prev: np.ndarray | None = None

    def target(self, t: float):
        """(c_d, ċ_d) at the operator's clock (``t`` is the body time, not used)."""
        return self.waypoints(self.clock)

    def use(self, model, waypoints: Waypoints, snapshot, name: str) -> None:
        self.waypoints = waypoints
        self.controller = SpatialTwoPoint(model, self.target, self.geometry, self.gains, name=name)
        if self.recorder is not None:
            self.controller.attach(self.recorder)
        self.controller.reset(snapshot)

    def reset(self, snapshot) -> None:
        self.estimate, self.psi_prev = snapshot["head_pose"].copy(), snapshot["psi"].copy()
        w0 = snapshot["head_pose"]
        goal = w0.copy()
        goal[:2] = knob_point(0.0, self.door)
        self.use(self.raise_model, Waypoints.through((0.0, self.door.t_approach), (w0, goal), angles=(3, 4, 5)),
                 snapshot, "raise")

    def observed(self, snapshot) -> dict:
        """The snapshot the controllers see: the head pose from the internal model or the mocap."""
        if self.head_pose == "mocap":
            return snapshot
        model = self.tail_model if self.phase == "tail" else self.raise_model
        first, last = model.base
        psi = snapshot["psi"]
        A, B, _ = model.matrices(self.estimate, self.psi_prev, snapshot["grounded"][first - 1:last])
        u = (psi - self.psi_prev)[model.inputs] / self.period
        self.estimate = self.estimate + self.period * np.linalg.lstsq(A, B @ u, rcond=None)[0][:6]
        self.psi_prev = psi.copy()
        return {**snapshot, "head_pose": self.estimate.copy()}

    def hook_distance(self) -> float:
        return float(np.linalg.norm(self.body.mj.site_pos("head")[:2] - self.body.mj.site_pos("knob")[:2]))

    def inside(self) -> bool:
        x_min = min(self.body.mj.body_pos(f"link{j}")[0] for j in range(1, 2 * self.geometry.n + 1))
        return x_min > self.door.thickness + self.door.pass_margin

    def enter(self, phase: str, t: float) -> None:
        self.phase, self.phase_start = phase, t
        self.events.append((t, phase))

    def update(self, snapshot):
        t = float(snapshot["t"])
        seen = self.observed(snapshot)
        self.advance(t, seen)
        command = self.command(t, seen)
        if "grounded" in command:
            self.grounded = np.asarray(command["grounded"], dtype=bool)
        self.log(t, **{f"{self.name}.phase": DOOR_PHASES.index(self.phase),
                       f"{self.name}.angle": self.body.mj.joint_qpos("hinge"),
                       f"{self.name}.head": self.body.snapshot()["head_pose"], f"{self.name}.estimate": seen["head_pose"],
                       f"{self.name}.tail": self.body.mj.site_pos(f"axle{self.geometry.n}"),
                       f"{self.name}.clock": self.clock, f"{self.name}.body": link_points(self.body),
                       f"{self.name}.grounded": self.grounded.copy()})
        return command

    def command(self, t: float, seen) -> dict:
        """The phase's command: shift control, hold, or the phase's two-point controller."""
        joints = self.geometry.joints
        if self.phase in ("shift", "passed"):  # planar command: the pitch joints put every wheel on the floor
            phi_dot = np.zeros(self.geometry.n)
            if self.phase == "shift":
                phi_dot = self.shift.rates(t - self.phase_start, self.period)
            return {"phi_dot": phi_dot, "grounded": np.ones(self.geometry.n)}
        if self.phase in ("release", "gave_up"):
            return {"psi_dot": np.zeros(joints)}
        command = self.controller.update(seen)
        if np.any(command["psi_dot"][self.controller.model.inputs]):  # not stopped by (3.20): targets move on
            self.clock += self.period
            self.moved_at = t
        return command

    def advance(self, t: float, snapshot) -> None:
        """Phase transitions (the operator's decisions)."""
        d = self.door
        done = self.clock >= self.waypoints.times[-1]
        if self.phase in ("approach", "pull", "tail") and t - self.moved_at > d.give_up:
            self.enter("gave_up", t)
        elif self.phase == "approach" and self.hook_distance() < d.hook_capture:
            self.body.mj.set_equality("hook", True)
            self.enter("pull", t)
            self.use(self.raise_model, self.pull_targets(snapshot), snapshot, "raise")
        elif self.phase == "pull" and done:
            self.enter("tail", t)
            self.use(self.tail_model, self.tail_targets(snapshot), snapshot, "tail")
        elif self.phase == "tail" and done:
            self.body.mj.set_equality("hook", False)
            self.enter("release", t)
        elif self.phase == "release" and t - self.phase_start >= d.t_settle:
            self.enter("shift", t)
            self.shift = ShiftControl(snapshot["phi"], d)
        elif self.phase == "shift" and self.inside():
            self.enter("passed", t)
        elif self.phase == "shift" and t - self.phase_start >= self.shift.duration:
            self.enter("gave_up", t)  # the curve is used up: the joints no longer move, the run cannot change

    def pull_targets(self, snapshot) -> Waypoints:
        """Head tip along the knob's arc about the hinge (β: 0 → open_angle), its yaw turning with the leaf,
        height, roll and pitch held."""
        w0 = snapshot["head_pose"]
        betas = np.linspace(0.0, self.door.open_angle, 19)
        poses = np.repeat(w0[None], len(betas), axis=0)
        poses[:, :2] = [knob_point(b, self.door) for b in betas]
        poses[:, 5] = w0[5] + betas
        return Waypoints.through(self.clock + np.linspace(0.0, self.door.t_pull, len(betas)), poses, angles=(3, 4, 5))

    def tail_targets(self, snapshot) -> Waypoints:
        """Head held; tail wheel to the doorway, then inside, heading +x (e_x tail-ward, so the tail leads)."""
        d = self.door
        first, last = self.tail_model.base
        c0 = self.tail_model.matrices(snapshot["head_pose"], snapshot["psi"], self.tail_model.candidates[0])[2]
        doorway, inside = c0.copy(), c0.copy()
        doorway[6:] = (*d.tail_doorway, 0.0)
        inside[6:] = (*d.tail_inside, 0.0)
        times = self.clock + np.array([0.0, d.t_tail[0], sum(d.t_tail)])
        return Waypoints.through(times, (c0, doorway, inside), angles=(3, 4, 5, 8))



@dataclass
class DoorRun:
    """Outcome of one door run: ``phase_reached`` = last phase completed (1 door opened to ≥ 80 % of
    open_angle, 2 also the tail inside when the hook was released, 3 the whole body through), the
    operator's events (t, phase) and the largest door angle."""

    passed: bool
    phase_reached: int
    events: list
    max_door_angle: float
    duration: float


def door_geometry() -> SnakeGeometry:
    return SnakeGeometry(n=DOOR.n, l=CH3_ROBOT.l)


def door_start(offset=np.zeros(3), door=DOOR) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(p_h, R_h, ψ0): the door's φ(0) with the head part raised as an arm (raise_n_h, raise_pitch, as in
    :func:`head_raising_pull`), wheel raise_n_h on the floor, heading π, the head tip approach_gap short of the
    closed knob; ``offset`` = (dx, dy, dθ) moves and turns the whole body about the head tip."""
    geometry = door_geometry()
    n_h = door.raise_n_h
    psi = np.zeros(geometry.joints)
    psi[::2] = door.phi0
    psi[2 * n_h - 1] -= door.raise_pitch
    psi[1] += door.raise_pitch
    c, s = np.cos(offset[2]), np.sin(offset[2])
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]) @ np.diag([-1.0, -1.0, 1.0])
    start = np.array([0.0, 0.0, MUJOCO_SNAKE.wheel_radius])
    tip = chain_from_wheel(psi, geometry.l, n_h, start, R).P[0]
    start[:2] += knob_point(0.0, door) - np.array([door.approach_gap, 0.0]) + offset[:2] - tip[:2]
    ch = chain_from_wheel(psi, geometry.l, n_h, start, R)
    return ch.P[0], ch.R[0], psi


def simulate_door(seed: int = 0, perturbed: bool = False, head_pose: str = "model", recorder=None, progress=None,
                  video_path=None) -> DoorRun:
    """One §3.4.3 run. ``perturbed``: the body starts up to ±1 cm / ±0.03 rad off and the door spring is
    ±20 % off (drawn from ``seed``), as two runs of an operator differ. ``head_pose="model"``: the head pose
    is estimated from the internal model as in the thesis's simulation (Fig. 3.15)."""
    d = DOOR
    rng = np.random.default_rng(seed)
    offset = rng.uniform(-1, 1, 3) * (0.01, 0.01, 0.03) if perturbed else np.zeros(3)
    spring = d.spring * (1 + 0.2 * rng.uniform(-1, 1)) if perturbed else d.spring
    geometry = door_geometry()
    p_h, R_h, psi = door_start(offset, d)
    knob_height = door_start(np.zeros(3), d)[0][2] - d.knob_drop
    body = MujocoSnake([p_h[0], p_h[1], np.pi], d.phi0, geometry, CH3_GAINS.dt,
                       scene=door_scene(d, spring, knob_height), head_pose="mocap", rng=rng)
    body.place(p_h, R_h, psi)
    body.settle(d.settle)
    operator = DoorOperator(body, geometry, d, head_pose)
    recorder = recorder if recorder is not None else Recorder()
    view = {"distance": 2.2, "elevation": -70.0, "azimuth": 180.0}
    with body.video(video_path, **view) if video_path is not None else nullcontext():
        Loop(body, [operator], recorder).run(d.t_budget, until=lambda s: operator.phase in ("passed", "gave_up"),
                                             progress=progress)
    angle, times = recorder.values("door.angle"), recorder.times("door.angle")
    events = {phase: t for t, phase in operator.events}
    opened = "tail" in events and angle[times <= events["tail"]].max() >= 0.8 * d.open_angle
    tail = recorder.values("door.tail")
    tail_in = "release" in events and tail[np.searchsorted(times, events["release"]) - 1, 0] > d.thickness
    reached = 3 if operator.phase == "passed" else 2 if opened and tail_in else 1 if opened else 0
    return DoorRun(operator.phase == "passed", reached, operator.events, float(angle.max()), body.t)



def head_raising_pull(duration: float = DOOR.t_pull) -> dict:
    """Phase 1 as the thesis does it, on the kinematic plant: the head-raising control [12] of §3.4.3 through
    the head-raised model (2.16)–(2.26) (scenarios_physical.head_raised_model, SpatialTwoPoint, §3.3's mode
    constants), the hooked head tip following the knob's arc about the hinge to open_angle over ``duration``,
    its yaw turning with the leaf, height, roll and pitch held; the base (wheels raise_n_h..n, the door's
    φ(0)) free. No door physics: the kinematic check of the motion (``plant=kinematic`` has no door); an
    earlier planar substitute (the head on the floor, planar two-point control) wound the yaw joints past π/2
    within a quarter of this pull. Returns the largest |ψ|, position error and stopped fraction."""
    d = DOOR
    geometry = door_geometry()
    n, n_h = geometry.n, d.raise_n_h
    psi = np.zeros(geometry.joints)
    psi[::2] = d.phi0
    psi[2 * n_h - 1] -= d.raise_pitch
    psi[1] += d.raise_pitch
    start = np.array([0.0, 0.0, MUJOCO_SNAKE.wheel_radius])
    tip = chain_from_wheel(psi, geometry.l, n_h, start, np.diag([-1.0, -1.0, 1.0])).P[0]
    start[:2] += knob_point(0.0, d) - tip[:2]
    ch = chain_from_wheel(psi, geometry.l, n_h, start, np.diag([-1.0, -1.0, 1.0]))
    w_h = ch.head_pose()
    model = head_raised_model(geometry, n_h, base_candidates(n - n_h + 1, CH3_GAINS.n_c, CH3_GAINS.n_g, 0, fixed=2))
    betas = np.linspace(0.0, d.open_angle, 19)
    poses = np.repeat(w_h[None], len(betas), axis=0)
    poses[:, :2] = [knob_point(b, d) for b in betas]
    poses[:, 5] += betas
    target = Waypoints.through(np.linspace(0.0, duration, len(betas)), poses, angles=(3, 4, 5))
    body = KinematicSpatial(w_h, psi, geometry, model, CH3_GAINS.dt)
    controller = SpatialTwoPoint(model, target, geometry, CH3_GAINS, name="raise")
    recorder = Recorder()
    Loop(body, [controller], recorder).run(duration)
    error = recorder.values("raise.error")
    return {"max_joint_rad": float(np.abs(recorder.values("raise.psi")).max()),
            "max_pos_error_m": float(np.linalg.norm(error[:, :3], axis=1).max()),
            "stopped_fraction": float(recorder.values("raise.stopped").mean())}


def door_series(recorder: Recorder, key: str) -> tuple[np.ndarray, np.ndarray]:
    """(times, values) of ``<controller>.<key>`` over phases 1 and 2 (controllers ``raise`` then ``tail``), the
    values cut to their common columns (the head's 6D pose first in both)."""
    parts = [(recorder.times(f"{name}.{key}"), np.atleast_2d(recorder.values(f"{name}.{key}").T).T)
             for name in ("raise", "tail") if f"{name}.{key}" in recorder.names()]
    if not parts:
        return np.zeros(0), np.zeros((0, 6))
    width = min(v.shape[1] for _, v in parts)
    t = np.concatenate([tt for tt, _ in parts])
    order = np.argsort(t, kind="stable")
    return t[order], np.concatenate([v[:, :width] for _, v in parts])[order]


def plot_door(ctx, recorder: Recorder, run: DoorRun) -> None:
    """Top view (bodies at the phase changes with wheels by mode, the leaf, head and tail-wheel paths against
    their targets), the errors / V_m / door angle over time with the phases marked, and the mode timeline."""
    d = DOOR
    t = recorder.times("door.phase")
    body, angle = recorder.values("door.body"), recorder.values("door.angle")
    grounded, phase = recorder.values("door.grounded").astype(bool), recorder.values("door.phase").astype(int)
    head, tail = recorder.values("door.head"), recorder.values("door.tail")
    tc, c_d = door_series(recorder, "c_d")
    has_tail = "tail.c_d" in recorder.names()
    with ctx.figure("top_view", figsize=(8.5, 7.0)) as (fig, ax):
        for x0, y0, y1 in ((0.0, -0.8, 0.0), (0.0, d.width, d.width + 0.8)):
            ax.add_patch(Rectangle((x0, y0), d.thickness, y1 - y0, color="0.6"))
        picks = np.unique(np.r_[0, np.searchsorted(t, [e for e, _ in run.events]), len(t) - 1].clip(0, len(t) - 1))
        labels = []
        for j, k in enumerate(picks):
            alpha = 0.25 + 0.75 * j / max(len(picks) - 1, 1)
            draw_link_points(ax, body[k], grounded[k], alpha)
            leaf = d.width * np.array([-np.sin(angle[k]), np.cos(angle[k])])
            ax.plot([0, leaf[0]], [0, leaf[1]], "-", color="tab:brown", lw=3, alpha=alpha)
            text = f"{t[k]:.0f} s {DOOR_PHASES[phase[k]]}"
            near = [label for label in labels if np.hypot(*(label[0] - body[k, -1])) < 0.05]
            if near:  # bodies that barely moved between phase changes share one label
                near[0][1] += f", {text}"
            else:
                labels.append([body[k, -1], text])
        for point, text in labels:
            ax.annotate(text, point, fontsize=7, xytext=(3, -8), textcoords="offset points")
        draw_track(ax, head[:, :2], c_d[:, :2], "tab:orange", "head tip", "head target (phases 1–2)")
        held = phase <= DOOR_PHASES.index("tail")  # the estimate is used (and meaningful) in phases 1–2 only
        ax.plot(*recorder.values("door.estimate")[held, :2].T, ":", color="tab:red", lw=1,
                label="head: internal-model estimate (phases 1–2)")
        tail_target = recorder.values("tail.c_d")[:, 6:8] if has_tail else np.zeros((0, 2))
        draw_track(ax, tail[:, :2], tail_target, "tab:green", "tail wheel", "tail-wheel target (phase 2)")
        wheel_legend(ax, 22)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m] (wall at x = 0; inside: x > 0)")
        ax.set_ylabel("y [m]")
        ax.legend(fontsize=7, loc="best")
        ax.set_title(f"door: phase reached {run.phase_reached}, passed = {int(run.passed)} "
                     "(leaf brown, head ▲, bodies at the start and the phase changes)", fontsize=9)
    events = [(e, name) for e, name in run.events]
    with ctx.figure("phases", nrows=4, ncols=1, figsize=(7.5, 9.0), sharex=True) as (fig, ax):
        ax[0].step(t, phase, where="post")
        ax[0].set_yticks(range(len(DOOR_PHASES)), DOOR_PHASES, fontsize=7)
        ax[0].set_title("phases (operator); red bands: stopped by the input limit (3.20)", fontsize=9)
        ax[1].plot(t, np.degrees(angle), label="door angle")
        ax[1].set_ylabel("door angle [deg]")
        if len(tc):
            _, error = door_series(recorder, "error")
            ax[2].plot(tc, 1e3 * np.linalg.norm(error[:, :3], axis=1), lw=1,
                       label="head: target − internal-model estimate (controller's e)")
            k = np.searchsorted(t, tc).clip(0, len(t) - 1)
            ax[2].plot(tc, 1e3 * np.linalg.norm(c_d[:, :3] - head[k, :3], axis=1), lw=1, label="head: target − true")
        if has_tail:
            e = recorder.values("tail.error")
            ax[2].plot(recorder.times("tail.error"), 1e3 * np.hypot(e[:, 6], e[:, 7]), lw=1,
                       label="tail wheel: target − true")
        ax[2].set_ylabel("position error [mm]")
        ts, V_m = door_series(recorder, "V_m")
        if len(ts):
            ax[3].semilogy(ts, V_m[:, 0], lw=1, label="V_m = σ_min(B_σ) of the mode in use (3.19)")
        ax[3].set_ylabel("singular value")
        ax[3].set_xlabel("t [s]")
        ts, stopped = door_series(recorder, "stopped")
        for a in ax:
            shade_stopped(a, ts, stopped[:, 0].astype(bool))
            for e, _ in events:
                a.axvline(e, color="0.5", ls=":", lw=0.8)
        for a in ax[1:]:
            if a.get_legend_handles_labels()[0]:
                a.legend(fontsize=7, loc="best")
    with ctx.figure("modes", figsize=(7.5, 4.0)) as (fig, ax):
        n = grounded.shape[1]
        ax.imshow(grounded.T, aspect="auto", cmap="Reds", vmin=0, vmax=1.4, interpolation="nearest",
                  extent=(t[0], t[-1] + CH3_GAINS.dt, n + 0.5, 0.5))
        for e, name in events:
            ax.axvline(e, color="k", ls=":", lw=0.8)
            ax.annotate(name, (e, 0.5), fontsize=7, rotation=90, va="top", xytext=(2, -2), textcoords="offset points")
        ax.set_ylabel("wheel (1 = head)")
        ax.set_xlabel("t [s]")
        ax.set_title("grounded wheels (red) / lifted (white): the raised head part, base modes, the lifted tail "
                     "wheel in phase 2", fontsize=8)


@scenario(
    "snake.door",
    source="seed 001 §3.4.3",
    summary="30-link snake opens a spring-hinged door (hook, pull), slips its tail in (two-point control) and "
            "passes tail-first (shift control), in MuJoCo; plus a success rate over perturbed runs",
    params=(
        Param("runs", 3, "perturbed runs for the success rate (head ±1 cm/±0.03 rad, spring ±20 %)", lo=0, hi=20),
        Param("head_pose", "model", "head pose for the controller: internal-model estimate (thesis Fig. 3.15) "
              "or mocap", choices=("model", "mocap")),
    ),
    checks=(
        Check("phase_reached", ">=", 2, "thesis Fig. 3.16 blocks 3–4 / spec §5.4 #20: after phase 2 the tail is "
              "inside and the head holds the door open"),
        Check("passed", "==", 1, "thesis §3.4.3 / Fig. 3.16: the robot passed through the door"),
        Check("success_rate", ">", 0.0, "thesis §3.4.3: passing succeeded, with failures in phase 3 "
              "(Fig. 3.17); no rate is given, so only 'some runs pass'"),
    ),
    thesis={
        "result": ThesisValue("passed (Fig. 3.16); failures seen in phase 3, wheels caught on the door (Fig. 3.17)",
                              "seed 001 §3.4.3", "passed"),
        "simulator": ThesisValue("V-REP + Bullet, 30 links, δt = 0.05 s, operator with a gamepad",
                                 "seed 001 §3.4.3"),
    },
    video=True,
)
def door(ctx) -> dict:
    p = ctx.params
    total = 1 + p["runs"]
    main = simulate_door(seed=ctx.seed, head_pose=p["head_pose"], recorder=ctx.recorder,
                         progress=lambda f: ctx.progress(f / total, "nominal run"),
                         video_path=ctx.video_path if ctx.video else None)
    ctx.sim_time_s = main.duration
    plot_door(ctx, ctx.recorder, main)
    perturbed = []
    for k in range(p["runs"]):
        progress = lambda f, k=k: ctx.progress((1 + k + f) / total, f"perturbed run {k + 1}")  # noqa: E731
        perturbed.append(simulate_door(seed=ctx.seed + 1 + k, perturbed=True, head_pose=p["head_pose"],
                                       progress=progress))
        ctx.sim_time_s += perturbed[-1].duration
    ctx.extra["door_runs"] = [{"seed": ctx.seed + i, "perturbed": i > 0, "passed": r.passed,
                               "phase_reached": r.phase_reached, "events": r.events}
                              for i, r in enumerate([main, *perturbed])]
    raised = head_raising_pull()
    ctx.extra["notes"] = DOOR_NOTES
    return {
        "passed": int(main.passed),
        "phase_reached": main.phase_reached,
        "max_door_angle_rad": main.max_door_angle,
        "success_rate": float(np.mean([r.passed for r in perturbed])) if perturbed else float(main.passed),
        "phase_reached_mean": float(np.mean([r.phase_reached for r in perturbed])) if perturbed else main.phase_reached,
        "runs": len(perturbed),
        **{f"pull_head_raising_kinematic_{key}": value for key, value in raised.items()},
    }


DOOR_NOTES = (
    "Phase 1 used to fail: this scenario had replaced the thesis's head-raising control [12] by planar "
    "two-point control with the knob at floor-head height; hooked, the head had to go 0.37 m back and 0.44 m "
    "sideways along the knob's arc with every wheel on the floor, and the yaw joints passed π/2 within a "
    "quarter of the pull (0/3). With the head part raised as an arm (head-raised model (2.16)–(2.26)) the "
    "pull tracks to 90° and phase 2 (head held, tail around the leaf, head-raised model plus the tail's "
    "planar pose) brings the tail inside in every run. Phase 3 (shift control [8]) then failed in the nominal "
    "run and 2 of 3 perturbed runs, the body swinging about the doorway: an implementation fault, not the "
    "thesis's Fig. 3.17 failure. Shift control's yaw rates were sent with the pitch joints held where phase "
    "2's last mode left them, so 10 of 15 wheels stayed lifted (the raised head part and the tail wheel among "
    "them); the thesis's robot snakes through pushing the leaf with its tail (Fig. 3.14c) and lifts no wheels "
    "in this phase. Sent as a planar command (every wheel grounded; the raised head part comes down) the body "
    "crawls tail-first along the tail's track (nominal top view) and passes in 4 of 4 runs (seed 0 nominal "
    "and perturbed seeds 1–3, ≈ 51 s of shifting each). The thesis's phase-3 failure (wheels caught on the "
    "door because the body does not follow the tail's path exactly) is not reproduced in these runs; the "
    "body still swings wide outside the doorway for the first ≈ 15 s, while the raised part's large yaw "
    "angles leave through the head."
)
