"""Robot abstraction (seed 003 §6.3.2, App. C.1.3, C.3.5): the per-robot description nervous runs on,
generated from the robot's model, not written by hand.

§6.3.2: one nervous program serves many robots through per-robot files — "ロボットの持つアクチュエータ数・
制御パラメータ (PID ゲインなど) の種類と数・搭載されたセンサの種類と数などが定義された C 言語のヘッダファイル。
EusLisp の幾何モデルから変換できるようにした" — generated from the EusLisp model by ``robot2c.l``
(C.1.3); C.3.5: ``${ROBOT}.c`` holds "センサの変換パラメータやサーボの初期値等". Here the model is MuJoCo's:
:func:`describe_servos` reads the position servos, their joints' types, ranges and initial values and the
named sensors of any ``MjModel``; :func:`describe_spine` reads a muscle-driven spine's tendons, reels,
accelerometers and its drive's conversions. ``shintai nervous describe ROBOT`` prints the result.

Units on the wire are the thesis's EusLisp conventions: rotational DOF in degrees, linear ones (slide
joints, muscle wire) in millimetres; sensors in SI units (their ``unit``), each with its conversion.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field

import mujoco
import numpy as np

UNIT_SCALE = {"deg": math.pi / 180.0, "mm": 1e-3}  # wire unit → SI (rad, m)
SENSOR_UNITS = {  # MuJoCo sensor type → SI unit of its reading
    "ACCELEROMETER": "m/s^2", "VELOCIMETER": "m/s", "GYRO": "rad/s", "FORCE": "N", "TORQUE": "N m",
    "JOINTPOS": "rad", "JOINTVEL": "rad/s", "FRAMEPOS": "m", "FRAMEQUAT": "quaternion", "TOUCH": "N",
    "TENDONPOS": "m", "ACTUATORFRC": "N or N m",
}


@dataclass(frozen=True)
class Dof:
    """One commanded degree of freedom: a servo's joint or a muscle's wire."""

    name: str
    unit: str  # "deg" or "mm"
    lower: float  # in unit
    upper: float
    initial: float
    drives: str  # what it moves: "hinge joint j1", "slide joint x", "muscle CLA-RF (reel + tendon)"

    @property
    def scale(self) -> float:
        return UNIT_SCALE[self.unit]


@dataclass(frozen=True)
class Sensor:
    """One sensor in the state: its size, unit and how the raw reading becomes that unit."""

    name: str
    size: int
    unit: str
    conversion: str


@dataclass(frozen=True)
class Description:
    """What ``robot2c`` generated for one robot: DOF, sensors, servo parameters, the packet period."""

    robot: str
    source: str
    packet_period_s: float
    dofs: tuple[Dof, ...]
    sensors: tuple[Sensor, ...]
    servo: dict = field(default_factory=dict)  # gain name → value (one value for all DOF)
    notes: tuple[str, ...] = ()

    @property
    def n(self) -> int:
        return len(self.dofs)

    @property
    def names(self) -> list[str]:
        return [d.name for d in self.dofs]

    @property
    def lower(self) -> np.ndarray:
        return np.array([d.lower for d in self.dofs])

    @property
    def upper(self) -> np.ndarray:
        return np.array([d.upper for d in self.dofs])

    @property
    def initial(self) -> np.ndarray:
        return np.array([d.initial for d in self.dofs])

    @property
    def scale(self) -> np.ndarray:
        """Per DOF: wire unit → SI."""
        return np.array([d.scale for d in self.dofs])

    def sensor(self, name: str) -> Sensor | None:
        return next((s for s in self.sensors if s.name == name), None)

    def to_json(self) -> str:
        return json.dumps(asdict(self), separators=(",", ":"))

    def text(self) -> str:
        """The description as a person reads it (``shintai nervous describe``)."""
        lines = [f"robot {self.robot} ({self.source})",
                 f"packet period {1e3 * self.packet_period_s:g} ms, {self.n} DOF, {len(self.sensors)} sensors"]
        lines.append("DOF:")
        for i, d in enumerate(self.dofs):
            lines.append(f"  {i:3d} {d.name:22s} [{d.lower:9.4g}, {d.upper:9.4g}] {d.unit:3s} "
                         f"initial {d.initial:8.4g}  {d.drives}")
        lines.append("sensors:")
        for s in self.sensors:
            lines.append(f"  {s.name:22s} x{s.size:<3d} {s.unit:12s} {s.conversion}")
        if self.servo:
            lines.append("servo: " + ", ".join(f"{k}={v:g}" for k, v in self.servo.items()))
        lines += [f"note: {note}" for note in self.notes]
        return "\n".join(lines)


def _name(model: mujoco.MjModel, kind: mujoco.mjtObj, i: int) -> str:
    return mujoco.mj_id2name(model, kind, i) or f"{kind.name[6:].lower()}{i}"


def position_servos(model: mujoco.MjModel) -> list[int]:
    """The actuators that are position servos on a hinge or slide joint: MuJoCo's ``<position>``
    (fixed gain kp, affine bias −kp q − kv q̇), in actuator order."""
    out = []
    for i in range(model.nu):
        if int(model.actuator_trntype[i]) != int(mujoco.mjtTrn.mjTRN_JOINT):
            continue
        kp = model.actuator_gainprm[i, 0]
        servo = (int(model.actuator_gaintype[i]) == int(mujoco.mjtGain.mjGAIN_FIXED)
                 and int(model.actuator_biastype[i]) == int(mujoco.mjtBias.mjBIAS_AFFINE)
                 and kp > 0 and math.isclose(model.actuator_biasprm[i, 1], -kp))
        joint = model.actuator_trnid[i, 0]
        if servo and int(model.jnt_type[joint]) in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)):
            out.append(i)
    return out


def model_sensors(model: mujoco.MjModel, skip=()) -> list[Sensor]:
    """Every named MuJoCo sensor, SI units (its type's), read as simulated (conversion: none)."""
    out = []
    for i in range(model.nsensor):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SENSOR, i)
        if not name or name in skip:
            continue
        kind = mujoco.mjtSensor(model.sensor_type[i]).name.removeprefix("mjSENS_")
        out.append(Sensor(name, int(model.sensor_dim[i]), SENSOR_UNITS.get(kind, "SI"), f"MuJoCo {kind.lower()}"))
    return out


def describe_servos(model: mujoco.MjModel, robot: str, source: str, packet_period_s: float,
                    qpos=None, notes: tuple[str, ...] = ()) -> Description:
    """The description of a robot driven by position servos, read from its ``MjModel``: one DOF per
    position actuator (name = the actuator's), hinge → deg, slide → mm, limits = the actuator's control
    range if limited, else its joint's range, initial = the joint's value in ``qpos`` (default
    ``qpos0``); the servo gains kp, kv (shared when all actuators agree, else their mean)."""
    qpos = model.qpos0 if qpos is None else np.asarray(qpos)
    dofs, kp, kv = [], [], []
    for i in position_servos(model):
        j = model.actuator_trnid[i, 0]
        hinge = int(model.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_HINGE)
        unit = "deg" if hinge else "mm"
        scale = UNIT_SCALE[unit]
        if model.actuator_ctrllimited[i]:
            lo, hi = model.actuator_ctrlrange[i]
        elif model.jnt_limited[j]:
            lo, hi = model.jnt_range[j]
        else:
            lo, hi = (-math.pi, math.pi) if hinge else (-1.0, 1.0)  # chosen: a turn, or a metre, each way
        dofs.append(Dof(_name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, i), unit, float(lo / scale), float(hi / scale),
                        float(qpos[model.jnt_qposadr[j]] / scale),
                        f"{'hinge' if hinge else 'slide'} joint {_name(model, mujoco.mjtObj.mjOBJ_JOINT, j)}"))
        kp.append(model.actuator_gainprm[i, 0])
        kv.append(-model.actuator_biasprm[i, 2])
    if not dofs:
        raise ValueError(f"robot {robot}: the model has no position servo on a hinge or slide joint")
    sensors = [Sensor("angle-vector", len(dofs), "deg|mm", "the servoed joints' positions (joint encoders)")]
    sensors += model_sensors(model)
    servo = {"kp": float(np.mean(kp)), "kv": float(np.mean(kv))}
    return Description(robot, source, float(packet_period_s), tuple(dofs), tuple(sensors), servo, notes)


def describe_spine(body, robot: str, source: str, packet_period_s: float, servo: dict,
                   notes: tuple[str, ...] = ()) -> Description:
    """The description of a muscle-driven spine (:class:`~shintai.spine.bodies_mujoco.SpineBody`): one
    DOF per muscle — the encoder length l (mm of wire wound in since the encoder zero, §4.6.1), limits
    from the reel's travel in the model, initial 0 (the zeroed encoders); sensors as §3.6.2 lists them,
    with the drive's conversions (Table 3.2, eq. 3.6, §3.6.1)."""
    model = body.model
    rob = body.robot
    dofs = []
    for name in rob.muscle_names:
        j = body.id("joint", f"{name}:reel")
        lo, hi = model.jnt_range[j]
        dofs.append(Dof(name, "mm", float(1e3 * lo), float(1e3 * hi), 0.0,
                        f"muscle {name} (reel {name}:reel, tendon {name})"))
    motor = rob.motors[0]
    m = len(dofs)
    sensors = [
        Sensor("angle-vector", m, "mm", f"the encoders: {motor.encoder_cpr} counts per motor turn, gear "
               f"{motor.gear_ratio}, pulley {1e3 * motor.pulley_diameter_m:g} mm → "
               f"{1e6 * motor.encoder_step_m:.2f} µm of wire per count (Table 3.2)"),
        Sensor("tension", m, "N", f"{rob.sensor.adc_bits}-bit ADC of the FSR tension sensor read back through its "
               "calibration table (§3.6.1, Fig. 3.34)"),
        Sensor("current", m, "A", "shunt voltage / 0.1 Ω (eq. 3.6)"),
    ]
    sensors += model_sensors(model)
    sensors += [Sensor("posture", 2, "rad", "(roll, pitch) of the shoulder seen from the waist, eq. 3.4"),
                Sensor("theta", 3 * rob.n, "rad", "the true joint angles (simulation only; no such sensor on Cla)")]
    return Description(robot, source, float(packet_period_s), tuple(dofs), tuple(sensors), dict(servo), notes)
