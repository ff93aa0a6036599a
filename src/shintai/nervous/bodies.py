"""The on-body side of nervous's ``sim`` interface: what a simulated robot's processors do with the targets
nervous sends (seed 003 §6.4.1–6.4.2, App. C.3.7 ``nervelib/jsim`` "シミュレーションとの通信").

nervous sends actuator targets once per sensor packet; the robot's on-body processors close the servo loops
("即応性 (1[ms] の制御周期毎に実行可能)", §6.4.2). Two kinds here:

* :class:`ServoRobot` — joints with position servos (MuJoCo ``<position>`` actuators): a target is the
  servo's set-point (the HRP2 humanoid, the snake, the 3-DOF test arm);
* :class:`MuscleRobot` — a muscle-driven spine (Cla): a target is each muscle's encoder length, and the
  on-body controller runs the muscle laws of §4.6 (L mode by default, eq. 4.37) every 1 ms on
  :class:`~shintai.spine.bodies_mujoco.SpineBody`; at power-up the encoders are zeroed in LL mode with the
  spine held at its basic posture (§4.6.4).

Both also take the world's actions a scenario plays (a human hand holding Cla's spine, a tilting seat) and
the faults the diagnosis plugins of §6.1.2 are tested on (a stretched wire, a blocked reel, a stuck sensor).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import fields

import mujoco
import numpy as np

from shintai.core.runtime import Body, FunctionModule, Loop, whole_multiple
from shintai.nervous.robot import Description, position_servos
from shintai.sim.body import MujocoBody
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.control import Gains, Mode, MuscleControl
from shintai.spine.geometry import uniform_posture
from shintai.spine.teaching import zero_encoders

CALIBRATION_N = 0.3 * 9.80665  # chosen: "just taut" limit for the LL encoder zeroing (§4.6.4), 0.3 kgf
SENSOR_FAULTS = ("tension-stuck", "encoder-stuck")
BODY_FAULTS = ("slack", "stall")


class ServoError(ValueError):
    """A servo command the robot cannot take (unknown gain, mode or DOF)."""


class SimRobot(ABC):
    """A simulated robot behind the ``sim`` interface."""

    description: Description
    body: MujocoBody

    @property
    def t(self) -> float:
        return float(self.body.t)

    @abstractmethod
    def command(self, target: np.ndarray) -> None:
        """Take the target vector (wire units: deg, mm)."""

    @abstractmethod
    def advance(self, seconds: float) -> None:
        """Run the body and its on-body servo loops for ``seconds``."""

    @abstractmethod
    def read(self) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """The measured DOF positions (wire units) and the sensors (SI)."""

    @abstractmethod
    def servo_state(self) -> dict:
        """The servo parameters now (one line's worth)."""

    @abstractmethod
    def set_servo(self, key: str, value: str, dofs: list[int]) -> None:
        """Change a servo parameter for the given DOF indices (all if empty)."""


class ServoRobot(SimRobot):
    """Position servos on joints: target → ``data.ctrl`` of each DOF's actuator (SI)."""

    def __init__(self, body: MujocoBody, description: Description):
        self.body, self.description = body, description
        m = body.model
        self.actuators = np.array(position_servos(m))
        joints = m.actuator_trnid[self.actuators, 0]
        self.qadr = m.jnt_qposadr[joints]
        self.scale = description.scale
        self.sensor_names = [s.name for s in description.sensors if s.name != "angle-vector"]
        self._gains = {"kp": m.actuator_gainprm[self.actuators, 0].copy(), "kv": -m.actuator_biasprm[self.actuators, 2]}
        self._on = np.ones(len(self.actuators), dtype=bool)
        self.command(description.initial)

    def command(self, target: np.ndarray) -> None:
        self.body.data.ctrl[self.actuators] = np.asarray(target) * self.scale

    def advance(self, seconds: float) -> None:
        for _ in range(whole_multiple(seconds, self.body.dt, "packet period")):
            self.body.step()

    def read(self):
        snap = self.body.snapshot()
        return self.body.data.qpos[self.qadr] / self.scale, {k: np.array(snap[k]) for k in self.sensor_names}

    def servo_state(self) -> dict:
        return {"kp": float(np.mean(self._gains["kp"])), "kv": float(np.mean(self._gains["kv"])),
                "off": int((~self._on).sum())}

    def set_servo(self, key: str, value: str, dofs: list[int]) -> None:
        idx = np.array(dofs if dofs else range(len(self.actuators)), dtype=int)
        if key in ("on", "off"):
            self._on[idx] = key == "on"
        elif key in self._gains:
            self._gains[key][idx] = float(value)
        else:
            raise ServoError(f"servo: unknown parameter {key!r} (kp, kv, on, off)")
        m, act = self.body.model, self.actuators
        kp = np.where(self._on, self._gains["kp"], 0.0)
        kv = np.where(self._on, self._gains["kv"], 0.0)
        m.actuator_gainprm[act, 0], m.actuator_biasprm[act, 1], m.actuator_biasprm[act, 2] = kp, -kp, -kv


class FaultyBody(Body):
    """A spine whose sensors may lie: the readings the on-body controller and nervous see, with stuck
    tension sensors or encoders (§6.1.2's sensor faults) substituted."""

    def __init__(self, body: SpineBody):
        self.body = body
        self.channels = body.channels
        self.stuck: dict[tuple[str, int], float] = {}

    @property
    def dt(self) -> float:
        return self.body.dt

    @property
    def t(self) -> float:
        return self.body.t

    def snapshot(self):
        snap = self.body.snapshot()
        for (key, i), value in self.stuck.items():
            snap[key] = snap[key].copy()
            snap[key][i] = value
        return snap

    def apply(self, command) -> None:
        self.body.apply(command)

    def step(self) -> None:
        self.body.step()


class MuscleRobot(SimRobot):
    """Cla's spine with its on-body muscle controller (§4.6) at the body's 1 ms control period.

    The targets are the muscles' encoder lengths l_r in mm (eq. 4.37's l: wire wound in since the zero);
    :meth:`set_servo` switches the per-muscle mode (L, LL, T, S, §4.6.5) and the Table 4.6 gains."""

    def __init__(self, body: SpineBody, description: Description, gains: Gains):
        self.spine, self.description = body, description
        self.body = body
        self.control = MuscleControl(body.robot.m, gains)
        zero_encoders(body, self.control, CALIBRATION_N)
        self.control.set_modes(Mode.L)
        self.faulty = FaultyBody(body)
        self.hand: np.ndarray | None = None  # the posture a human hand holds the spine at (the body's channel)
        hand = FunctionModule(lambda snap: None if self.hand is None else {"hand": self.hand}, name="hand")
        self.loop = Loop(self.faulty, [self.control, hand])
        self.loop.start()
        self._base_quat = body.model.body_quat[body.id("body", "link0")].copy()

    def command(self, target: np.ndarray) -> None:
        self.control.set_targets(l_r=1e-3 * np.asarray(target, dtype=float))

    def advance(self, seconds: float) -> None:
        self.loop.run(seconds)

    def read(self):
        s = self.faulty.snapshot()
        sensors = {"tension": s["tension"], "current": s["current"], "acc_waist": s["acc_waist"],
                   "acc_chest": s["acc_chest"], "posture": s["posture"], "theta": s["theta"]}
        return 1e3 * np.asarray(s["encoder"]), {k: np.array(v) for k, v in sensors.items()}

    def servo_state(self) -> dict:
        modes = self.control.modes
        out = {m.name: int((modes == int(m)).sum()) for m in Mode}
        g = self.control.gains
        out.update({f.name: float(np.mean(getattr(g, f.name))) for f in fields(g)})
        return out

    def set_servo(self, key: str, value: str, dofs: list[int]) -> None:
        m = self.control.m
        idx = np.array(dofs if dofs else range(m), dtype=int)
        if key == "mode":
            names = [mode.name for mode in Mode]
            if value.upper() not in names:
                raise ServoError(f"servo mode: {value!r} is not a muscle mode ({', '.join(names)}, §4.6)")
            modes = self.control.modes.copy()
            modes[idx] = int(Mode[value.upper()])
            if int(Mode.L) in modes[idx] or int(Mode.LL) in modes[idx]:
                # entering length control holds the length the muscle has now (no jump)
                l_r = self.control.l_r.copy()
                l_r[idx] = np.asarray(self.faulty.snapshot()["encoder"])[idx]
                self.control.set_targets(l_r=l_r)
            self.control.set_modes(modes)
            return
        if key in ("off", "on"):
            self.set_servo("mode", "T" if key == "off" else "L", dofs)
            if key == "off":  # a stopped motor: zero duty by a zero tension gain
                self._gain("K_Pt", np.zeros(len(idx)), idx)
                self._gain("K_Dt", np.zeros(len(idx)), idx)
            return
        names = [f.name for f in fields(Gains)]
        if key not in names:
            raise ServoError(f"servo: unknown parameter {key!r} (mode, on, off, {', '.join(names)})")
        self._gain(key, np.full(len(idx), float(value)), idx)

    def _gain(self, key: str, values: np.ndarray, idx: np.ndarray) -> None:
        if key == "T_r":
            T_r = self.control.T_r.copy()
            T_r[idx] = values
            self.control.set_targets(T_r=T_r)
            return
        current = np.broadcast_to(np.asarray(getattr(self.control.gains, key), dtype=float), (self.control.m,)).copy()
        current[idx] = values
        self.control.set_gains(**{key: current})

    # -- the world (a scenario's human, the seat) and faults --------------------------------------

    def hold(self, whole_deg=None) -> None:
        """A human hand holds the top link at the uniform bend ``whole_deg`` (roll, pitch, yaw of the whole
        spine), or lets go (None)."""
        self.hand = None if whole_deg is None else uniform_posture(np.radians(whole_deg), self.spine.robot.n)

    def tilt(self, roll_deg: float, pitch_deg: float = 0.0) -> None:
        """The seat under the pelvis tilts by (roll, pitch) from level (the pelvis is fixed to it)."""
        q = np.zeros(4)
        mujoco.mju_euler2Quat(q, np.radians([roll_deg, pitch_deg, 0.0]), "xyz")
        out = np.zeros(4)
        mujoco.mju_mulQuat(out, q, self._base_quat)
        self.spine.model.body_quat[self.spine.id("body", "link0")] = out

    def fault(self, kind: str, dof: int, value: float = 0.0) -> None:
        """Inject a fault on muscle ``dof``: ``slack`` (the wire stretched by ``value`` mm), ``stall`` (the
        reel blocked), ``tension-stuck`` (the sensor reads ``value`` N), ``encoder-stuck`` (frozen)."""
        b = self.spine
        if kind == "slack":
            t = b.tendon_ids[dof]
            b.model.tendon_lengthspring[t, 1] += 1e-3 * value
            b._free_length[dof] += 1e-3 * value
        elif kind == "stall":
            j = b.id("joint", f"{b.robot.muscle_names[dof]}:reel")
            b.model.dof_frictionloss[b.model.jnt_dofadr[j]] = 1e4  # N: far beyond the stall force
        elif kind == "tension-stuck":
            self.faulty.stuck[("tension", dof)] = float(value)
        elif kind == "encoder-stuck":
            self.faulty.stuck[("encoder", dof)] = float(self.faulty.snapshot()["encoder"][dof])
        else:
            raise ValueError(f"unknown fault {kind!r} ({', '.join(BODY_FAULTS + SENSOR_FAULTS)})")

