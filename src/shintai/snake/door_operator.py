"""The operator of the door experiment, seed 001 §3.4.3 (Fig. 3.15), as a Switcher of phase modules.

The thesis's operator chose the targets and the phases with a gamepad (A18). Here each phase is a module
and the operator's decisions are the guarded transitions of a :class:`~shintai.core.runtime.Switcher`
(switching processing, seed 000 §7.4: exactly one phase runs; a transition log):

    approach ─hooked→ pull ─done→ tail ─done→ release ─settled→ shift ─inside→ passed
    approach, pull, tail ─stalled (give_up s without moving)→ gave_up;   shift ─curve used up→ gave_up

Phase 1, head-raising control [12]: the head part (wheels 1..raise_n_h − 1, joints 1..2·raise_n_h) is raised
as an arm and the head's 6D pose is controlled through the head-raised model (2.16)–(2.26) under the
two-point law with base modes (spatial.SpatialTwoPoint): ``approach`` the knob, the hook engages, ``pull``
the knob along its arc about the hinge to open_angle, the hook's yaw turning with the leaf. Phase 2,
two-point control with the head held: ``tail`` (head-raised model plus the tail wheel's planar pose): the
head holds the door open while the tail goes to the doorway, close to the leaf, and inside; ``release`` the
hook and hold while the door closes onto the body. Phase 3: ``shift`` control [8] tail-first until every
link is inside (``passed``), every wheel on the floor (door.ShiftControl).

Like the thesis's operator, the guards watch the simulation (hook distance, where the body is); the
controllers get the snapshot only. The hook is the body's set channel ``hook`` (an equality in MuJoCo).

The rig runs in two stages with these loop channels:

1. :class:`HeadEstimate` writes ``head_estimate``, the head pose the controllers use: ``model``, as the
   thesis's simulation (Fig. 3.15), from the internal model with the measured joint motion; ``mocap``, the
   simulator's. :class:`OperatorClock` writes ``clock`` (the targets' time) and ``moved_at``.
2. The Switcher writes the body's command, ``hook``, and two channels seen one tick later (declared delays):
   ``moved`` (the time, when the law moved the robot: the operator advances the targets' clock after a
   period in which the robot followed, and stops it while the input limit (3.20) has the robot stopped) and
   ``phase`` (the estimate over a period uses the model of the phase that moved the body in it).
   :func:`door_watch` logs what the simulator shows.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from shintai.core.runtime import SET, Channel, Module, Switcher
from shintai.scenarios.experiment import Rig, Run
from shintai.snake.constants import CH3_GAINS, DOOR, MUJOCO_SNAKE, SnakeGeometry
from shintai.snake.door import ShiftControl, door_geometry, door_scene, door_start, knob_point
from shintai.snake.model3d import chain_from_wheel
from shintai.snake.mujoco_plant import MujocoSnake
from shintai.snake.probe import Probe
from shintai.snake.spatial import (
    KinematicSpatial,
    SpatialModel,
    SpatialTwoPoint,
    base_candidates,
    head_raised_model,
    head_raised_two_point_model,
)
from shintai.snake.targets import PiecewiseLinear

PHASES = ("approach", "pull", "tail", "release", "shift", "passed", "gave_up")  # thesis phase 1 = approach + pull
LOG = "door"  # the operator's signals are logged as door.*
HEAD_ANGLES = (3, 4, 5)  # roll, pitch, yaw in the 6D head pose w_h


def loop_channels() -> list[Channel]:
    """The door rig's own channels (see the module docstring)."""
    return [Channel("head_estimate", SET), Channel("clock", SET), Channel("moved_at", SET),
            # Both delays are causal, and they are the order the thesis's operator (and this code before the
            # Switcher) works in: the clock read at a period's start counts the periods that moved before it,
            # and the head estimate over the last period uses the model of the phase that ran in it.
            Channel("moved", SET, delay=1, doc="the operator's clock advances after a period the robot moved in"),
            Channel("phase", SET, delay=1, default=0.0, doc="the estimate over a period uses that period's model")]


def remembering(model: SpatialModel) -> SpatialModel:
    """``model`` whose ``matrices`` returns its last result again (copies) when called with the same arguments.
    The head estimate needs A, B at the previous period's estimate, joint angles and mode, which the
    controller has just computed: the same numbers, computed once."""
    last = {}

    def matrices(w_h, psi, grounded):
        key = tuple(np.asarray(a, dtype=float).tobytes() for a in (w_h, psi, grounded))
        if key not in last:
            last.clear()
            last[key] = model.matrices(w_h, psi, grounded)
        return tuple(np.array(a, copy=True) for a in last[key])

    return replace(model, matrices=matrices)


class HeadEstimate(Module):
    """Stage 1: ``head_estimate``. ``model``: ẇ_h = (A^† B ψ̇)_head of the model of the last period's phase
    (head-raised, or head-raised plus tail in ``tail``) with the measured joint motion over δt, explicit Euler
    from the measured pose at the start; ``mocap``: the snapshot's ``head_pose``."""

    def __init__(self, raise_model: SpatialModel, tail_model: SpatialModel, head_pose: str = "model",
                 period: float = CH3_GAINS.dt):
        super().__init__("head_estimate", period)
        if head_pose not in ("model", "mocap"):
            raise ValueError(f"head_pose must be 'model' or 'mocap', got {head_pose!r}")
        self.raise_model, self.tail_model, self.head_pose = raise_model, tail_model, head_pose

    def reset(self, snapshot) -> None:
        self.estimate, self.psi_prev = snapshot["head_pose"].copy(), snapshot["psi"].copy()

    def update(self, snapshot):
        if self.head_pose == "mocap":
            return {"head_estimate": snapshot["head_pose"]}
        model = self.tail_model if int(snapshot["phase"]) == PHASES.index("tail") else self.raise_model
        first, last = model.base
        psi = snapshot["psi"]
        A, B, _ = model.matrices(self.estimate, self.psi_prev, snapshot["grounded"][first - 1:last])
        u = (psi - self.psi_prev)[model.inputs] / self.period
        self.estimate = self.estimate + self.period * np.linalg.lstsq(A, B @ u, rcond=None)[0][:6]
        self.psi_prev = psi.copy()
        return {"head_estimate": self.estimate}


class OperatorClock(Module):
    """Stage 1: the operator's clock (``clock``), advanced by δt for each period in which the robot moved
    (``moved``, seen one tick later), and the time it last moved (``moved_at``); logs ``door.clock``."""

    def __init__(self, period: float = CH3_GAINS.dt):
        super().__init__("operator_clock", period)

    def reset(self, snapshot) -> None:
        self.clock, self.moved_at = 0.0, 0.0

    def update(self, snapshot):
        if "moved" in snapshot:
            self.clock += self.period
            self.moved_at = float(snapshot["moved"])
        self.log(snapshot["t"], **{f"{LOG}.clock": self.clock})
        return {"clock": self.clock, "moved_at": self.moved_at}


class DoorPhase(Module):
    """One phase of the operator: :meth:`command` is its command to the body; :meth:`update` adds ``phase``
    and logs ``door.phase`` and ``door.grounded`` (the wheels' mode in force after this command)."""

    def __init__(self, name: str, geometry: SnakeGeometry, period: float = CH3_GAINS.dt):
        super().__init__(name, period)
        self.geometry, self.index = geometry, PHASES.index(name)

    def reset(self, snapshot) -> None:
        self.start = float(snapshot["t"])

    def command(self, snapshot) -> dict:
        return {"psi_dot": np.zeros(self.geometry.joints)}  # hold every joint

    def update(self, snapshot):
        command = self.command(snapshot)
        grounded = np.asarray(command.get("grounded", snapshot["grounded"]), dtype=bool)
        self.log(snapshot["t"], **{f"{LOG}.phase": self.index, f"{LOG}.grounded": grounded})
        return {**command, "phase": self.index}


class TwoPointPhase(DoorPhase):
    """A phase run by the two-point law on a 3D model (spatial.SpatialTwoPoint, logged as ``<law>.*``) toward
    targets set when the phase begins (``targets(snapshot) -> PiecewiseLinear`` on the operator's clock), from
    ``head_estimate``. Writes ``moved`` when the law moved the robot, and holds the hook if ``hooked``."""

    def __init__(self, name: str, model: SpatialModel, targets, geometry: SnakeGeometry, law: str,
                 hooked: bool = False, gains=CH3_GAINS):
        super().__init__(name, geometry, gains.dt)
        self.model, self.targets, self.law_name, self.hooked, self.gains = model, targets, law, hooked, gains

    def reset(self, snapshot) -> None:
        super().reset(snapshot)
        self.waypoints = self.targets(snapshot)
        self.law = SpatialTwoPoint(self.model, self.waypoints, self.geometry, self.gains, name=self.law_name,
                                   pose="head_estimate", clock="clock")
        self.law.attach(self.recorder)
        self.law.reset(snapshot)

    def done(self, snapshot) -> bool:
        """The targets' clock has reached the last waypoint."""
        return float(snapshot["clock"]) >= self.waypoints.times[-1]

    def command(self, snapshot) -> dict:
        command = self.law.update(snapshot)
        if np.any(command["psi_dot"][self.model.inputs]):  # not stopped by (3.20): the targets move on
            command["moved"] = snapshot["t"]
        if self.hooked:
            command["hook"] = 1.0
        return command


class Release(DoorPhase):
    """Release the hook and hold while the door closes onto the body (``settled`` after t_settle)."""

    def command(self, snapshot) -> dict:
        return {**super().command(snapshot), "hook": 0.0}

    def settled(self, snapshot) -> bool:
        return float(snapshot["t"]) - self.start >= DOOR.t_settle


class Shift(DoorPhase):
    """Phase 3, shift control [8] tail-first from the joint angles at its start, as a planar command with
    every wheel grounded (door.ShiftControl)."""

    def reset(self, snapshot) -> None:
        super().reset(snapshot)
        self.control = ShiftControl(snapshot["phi"], DOOR)

    def command(self, snapshot) -> dict:
        rates = self.control.rates(float(snapshot["t"]) - self.start, self.period)
        return {"phi_dot": rates, "grounded": np.ones(self.geometry.n)}

    def used_up(self, snapshot) -> bool:
        """The curve is used up: the joints no longer move, the run cannot change."""
        return float(snapshot["t"]) - self.start >= self.control.duration


class Passed(DoorPhase):
    """Through the door: stand still, every wheel on the floor."""

    def command(self, snapshot) -> dict:
        return {"phi_dot": np.zeros(self.geometry.n), "grounded": np.ones(self.geometry.n)}


def approach_targets(snapshot, door=DOOR) -> PiecewiseLinear:
    """Head tip to the closed knob over t_approach, its height and orientation held, from the pose at the start."""
    w0 = snapshot["head_pose"]
    goal = w0.copy()
    goal[:2] = knob_point(0.0, door)
    return PiecewiseLinear.through((0.0, door.t_approach), (w0, goal), angles=HEAD_ANGLES)


def pull_targets(snapshot, door=DOOR) -> PiecewiseLinear:
    """Head tip along the knob's arc about the hinge (β: 0 → open_angle), its yaw turning with the leaf, height,
    roll and pitch held."""
    w0 = snapshot["head_estimate"]
    betas = np.linspace(0.0, door.open_angle, door.pull_waypoints)
    poses = np.repeat(w0[None], len(betas), axis=0)
    poses[:, :2] = [knob_point(b, door) for b in betas]
    poses[:, 5] = w0[5] + betas
    times = float(snapshot["clock"]) + np.linspace(0.0, door.t_pull, len(betas))
    return PiecewiseLinear.through(times, poses, angles=HEAD_ANGLES)


def tail_targets(model: SpatialModel, snapshot, door=DOOR) -> PiecewiseLinear:
    """Head held; tail wheel to the doorway, then inside, heading +x (e_x tail-ward, so the tail leads)."""
    c0 = model.matrices(snapshot["head_estimate"], snapshot["psi"], model.candidates[0])[2]
    doorway, inside = c0.copy(), c0.copy()
    doorway[6:] = (*door.tail_doorway, 0.0)
    inside[6:] = (*door.tail_inside, 0.0)
    times = float(snapshot["clock"]) + np.array([0.0, door.t_tail[0], sum(door.t_tail)])
    return PiecewiseLinear.through(times, (c0, doorway, inside), angles=(*HEAD_ANGLES, 8))


def hook_distance(body: MujocoSnake) -> float:
    return float(np.linalg.norm(body.mj.site_pos("head")[:2] - body.mj.site_pos("knob")[:2]))


def inside(body: MujocoSnake, door=DOOR) -> bool:
    """Every link origin beyond the wall's inner face by pass_margin."""
    x_min = min(body.mj.body_pos(f"link{j}")[0] for j in range(1, 2 * body.geometry.n + 1))
    return x_min > door.thickness + door.pass_margin


def door_models(geometry: SnakeGeometry, door=DOOR, gains=CH3_GAINS) -> tuple[SpatialModel, SpatialModel]:
    """The head-raised model (phase 1) and the head-raised two-point model (phase 2), with the base modes of
    §3.3's n_c, n_g keeping the base's two front wheels down (spatial.base_candidates, fixed = 2)."""
    n, n_h = geometry.n, door.raise_n_h
    raise_modes = base_candidates(n - n_h + 1, gains.n_c, gains.n_g, 0, fixed=2)
    tail_modes = base_candidates(n - n_h + 1, gains.n_c, gains.n_g, 0, fixed=2, tail_lifted=True)
    return (remembering(head_raised_model(geometry, n_h, raise_modes)),
            remembering(head_raised_two_point_model(geometry, n_h, tail_modes)))


def door_phases(body: MujocoSnake, geometry: SnakeGeometry, raise_model, tail_model, door=DOOR) -> Switcher:
    """The phases and the operator's decisions (module docstring) as a Switcher named ``operator``."""
    approach = TwoPointPhase("approach", raise_model, approach_targets, geometry, "raise")
    pull = TwoPointPhase("pull", raise_model, pull_targets, geometry, "raise", hooked=True)
    tail = TwoPointPhase("tail", tail_model, lambda s: tail_targets(tail_model, s, door), geometry, "tail",
                         hooked=True)
    release, shift = Release("release", geometry), Shift("shift", geometry)
    stalled = lambda s: float(s["t"]) - float(s["moved_at"]) > door.give_up  # noqa: E731
    transitions = [
        *[(phase, "gave_up", stalled) for phase in ("approach", "pull", "tail")],
        ("approach", "pull", lambda s: hook_distance(body) < door.hook_capture),
        ("pull", "tail", pull.done),
        ("tail", "release", tail.done),
        ("release", "shift", release.settled),
        ("shift", "passed", lambda s: inside(body, door)),
        ("shift", "gave_up", shift.used_up),
    ]
    phases = [approach, pull, tail, release, shift, Passed("passed", geometry), DoorPhase("gave_up", geometry)]
    return Switcher(phases, transitions, name="operator", period=CH3_GAINS.dt)


def door_watch(body: MujocoSnake) -> Probe:
    """Logs what the operator sees: the door angle, the simulator's head pose, the controllers' head estimate,
    the tail wheel and the body's polyline (``door.*``)."""
    n = body.geometry.n
    return Probe(LOG, lambda s: {"angle": body.mj.joint_qpos("hinge"), "head": body.snapshot()["head_pose"],
                                 "estimate": s["head_estimate"], "tail": body.mj.site_pos(f"axle{n}"),
                                 "body": body.link_points()})


def door_rig(seed: int = 0, perturbed: bool = False, head_pose: str = "model", duration: float | None = None) -> Rig:
    """One §3.4.3 run, until the body passed or the operator gave up (at most t_budget, or ``duration``).
    ``perturbed``: the start pose and the door spring are drawn off (DoorSetup.perturb_*, from ``seed``), as two
    runs of an operator differ."""
    d = DOOR
    rng = np.random.default_rng(seed)
    offset = rng.uniform(-1, 1, 3) * d.perturb_pose if perturbed else np.zeros(3)
    spring = d.spring * (1 + d.perturb_spring * rng.uniform(-1, 1)) if perturbed else d.spring
    geometry = door_geometry()
    p_h, R_h, psi = door_start(offset, d)
    knob_height = door_start(np.zeros(3), d)[0][2] - d.knob_drop
    body = MujocoSnake([p_h[0], p_h[1], np.pi], d.phi0, geometry, CH3_GAINS.dt,
                       scene=door_scene(d, spring, knob_height), head_pose="mocap", rng=rng)
    body.place(p_h, R_h, psi)
    body.settle(d.settle)
    raise_model, tail_model = door_models(geometry, d)
    switcher = door_phases(body, geometry, raise_model, tail_model, d)
    stages = [[HeadEstimate(raise_model, tail_model, head_pose), OperatorClock()], [switcher, door_watch(body)]]
    return Rig(body, stages=stages, channels=loop_channels(), duration=d.t_budget if duration is None else duration,
               until=lambda s: switcher.active in ("passed", "gave_up"),
               view=body.view(distance=2.2, elevation=-70.0, azimuth=180.0), state={"switcher": switcher})


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

    @classmethod
    def of(cls, run: Run, door=DOOR) -> DoorRun:
        log, switcher = run.log, run.state["switcher"]
        events = [(t, phase) for t, _, phase in switcher.transitions_log]
        angle, times = log.values(f"{LOG}.angle"), log.times(f"{LOG}.angle")
        at = {phase: t for t, phase in events}
        opened = "tail" in at and angle[times <= at["tail"]].max() >= 0.8 * door.open_angle
        tail = log.values(f"{LOG}.tail")
        tail_in = "release" in at and tail[np.searchsorted(times, at["release"]) - 1, 0] > door.thickness
        passed = switcher.active == "passed"
        reached = 3 if passed else 2 if opened and tail_in else 1 if opened else 0
        return cls(passed, reached, events, float(angle.max()), run.body.t)


def pull_rig(duration: float = DOOR.t_pull, door=DOOR) -> Rig:
    """Phase 1's pull on the kinematic plant (no door): the head-raising control [12] through the head-raised
    model (spatial.head_raised_model, SpatialTwoPoint ``raise``, §3.3's mode constants), the hooked head tip
    following the knob's arc about the hinge to open_angle over ``duration``, its yaw turning with the leaf,
    height, roll and pitch held; the base (wheels raise_n_h..n, the door's φ(0)) free."""
    geometry = door_geometry()
    n, n_h = geometry.n, door.raise_n_h
    psi = np.zeros(geometry.joints)
    psi[::2] = door.phi0
    psi[2 * n_h - 1] -= door.raise_pitch
    psi[1] += door.raise_pitch
    start = np.array([0.0, 0.0, MUJOCO_SNAKE.wheel_radius])
    tip = chain_from_wheel(psi, geometry.l, n_h, start, np.diag([-1.0, -1.0, 1.0])).P[0]
    start[:2] += knob_point(0.0, door) - tip[:2]
    w_h = chain_from_wheel(psi, geometry.l, n_h, start, np.diag([-1.0, -1.0, 1.0])).head_pose()
    model = head_raised_model(geometry, n_h, base_candidates(n - n_h + 1, CH3_GAINS.n_c, CH3_GAINS.n_g, 0, fixed=2))
    betas = np.linspace(0.0, door.open_angle, door.pull_waypoints)
    poses = np.repeat(w_h[None], len(betas), axis=0)
    poses[:, :2] = [knob_point(b, door) for b in betas]
    poses[:, 5] += betas
    target = PiecewiseLinear.through(np.linspace(0.0, duration, len(betas)), poses, angles=HEAD_ANGLES)
    body = KinematicSpatial(w_h, psi, geometry, model, CH3_GAINS.dt)
    return Rig(body, [SpatialTwoPoint(model, target, geometry, CH3_GAINS, name="raise")], duration=duration)


def pull_metrics(run: Run) -> dict:
    """The kinematic pull: largest |ψ|, largest head position error and the share of periods stopped by (3.20)."""
    error = run.log.values("raise.error")
    return {"max_joint_rad": float(np.abs(run.log.values("raise.psi")).max()),
            "max_pos_error_m": float(np.linalg.norm(error[:, :3], axis=1).max()),
            "stopped_fraction": float(run.log.values("raise.stopped").mean())}
