"""The electric unicycle "Ninebot One S2" of seed 000 App. A.1.3 (Figs. A.8–A.9, Eqs. A.5–A.9), built in code
with MjSpec, with optional passive training wheels (Fig. A.8 (II)).

What the thesis gives (§A.1.3): one motor-driven wheel and two footboards; "ボード単体には傾斜検知の用途のセンサ類は
搭載されておらず,車体内部に1輪の車輪を制御して Pitch 方向の傾斜を立て直す働きをもつ制御系" — no sensor in the
boards, an internal controller that rights the pitch by driving the wheel; "Roll 方向の傾きに関しては制御する機能を
備えてなく" — roll is not controlled (training wheels under the footboards, or the rider, hold it). The model of
Fig. A.9, for a static rider of weight W whose ZMP is p^{d**}:

* Eq. A.5  M_y⁰ = W (p^{d**} − p⁰)      the pitch moment about the moment reference point p⁰,
* Eq. A.6  Ω = k M_y⁰                    the wheel turns in proportion to it,
* Eq. A.7  v_traj = r Ω                  rolling without slip,
* Eq. A.8  v_traj = r k W (p^{d**} − p⁰),
* Eq. A.9  v_traj = K₀ p^{d**}, K₀ = r k W (differentiated and Laplace-transformed, p⁰ constant).

The thesis gives no number for r, k, W, p⁰, K₀ (chosen in :class:`NinebotSpec`, each with its reason).

The model (chosen). The internal pitch controller is taken as ideal: the vehicle frame ``ninebot`` (shell,
footboards, motor stator) never pitches — it has slides x, y, z, a yaw and a roll hinge, no pitch joint, so the
world carries the pitch moment the real controller's balance would. What the firmware does with that moment is the
thesis's model: :class:`NinebotFirmware` (run before every physics step) measures M_y⁰ of Eq. A.5 from the
footboards' normal contact loads about p⁰ (``NinebotSpec.p0`` from the axle along the heading: M_y⁰ =
Σ f_n (x_c − p⁰), i.e. W (p − p⁰) with p the rider's measured ZMP on the boards), lags it by the firmware's ``lag``, and
speed-servoes the hub motor to Ω = k M_y⁰ (Eq. A.6; τ = k_v (Ω_ref − Ω), |τ| ≤ ``max_torque``). The
training wheels (``training_wheels=True``) are two free-spinning wheels on the frame under the footboards' outer
ends, touching the ground: they hold the roll; without them the roll hinge is free (an inverted pendulum the rider
must balance, §7.3.3's run without training wheels).

Frames: vehicle origin on the ground under the axle, x forward, y left, z up; Ω > 0 rolls forward.

Names: joints ``ninebot_x``, ``ninebot_y``, ``ninebot_z``, ``ninebot_yaw``, ``ninebot_roll``, ``ninebot_wheel``
(and ``ninebot_tw_s`` for the training wheels); sites ``ninebot_board_s_top`` (footboard top centre, where a
sole stands), ``ninebot_centre`` (on the ground under the axle, p⁰); sensors ``ninebot_vel``,
``ninebot_angvel``, ``ninebot_heading`` (the truth for evaluation), ``ninebot_wheel_speed``, ``ninebot_roll``;
actuator ``ninebot_motor`` (velocity servo, ctrl = Ω_ref).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.core.constants import GRAVITY
from shintai.humanoid.constants import HRP2_MASS, SCENE, SOLE, SUBSTEPS, WHEEL
from shintai.humanoid.unicycle.constants import METAL, RUBBER, SHELL, TYRE
from shintai.sim.body import MujocoBody
from shintai.sim.spec import add_hinge, add_visual, box_inertia, fill_keyframe, scene_spec

SIDES = {"r": -1.0, "l": 1.0}
ROOT = ("ninebot_x", "ninebot_y", "ninebot_z", "ninebot_yaw", "ninebot_roll")
PAD = {s: f"ninebot_board_{s}_top" for s in SIDES}
BOX = mujoco.mjtGeom.mjGEOM_BOX


@dataclass(frozen=True)
class NinebotSpec:
    """Sizes, masses and firmware of the Ninebot One S2 model (all chosen: App. A.1.3 gives no numbers)."""

    # r: the S2 rolls on a 14-inch tyre (maker's page, the thesis's ref. [191], ninebot.jp/ones2): 14 in = 0.356 m
    # outer diameter → r = 0.178 m
    wheel_radius: float = 0.178
    tyre_width: float = 0.06
    # footboards: fold-out pedals either side of the shell, their top 0.14 m above the ground (below the axle,
    # as on the S2); pads 0.22 × 0.12 m, longer than the S2's ≈0.15 m pedals so that HRP2's 0.23 m soles rest on
    # them (the V-BOARD's pads were enlarged for the same reason)
    board_height: float = 0.14
    board_y: float = 0.105  # pad centre, |y|
    pad_size: tuple[float, float] = (0.22, 0.12)
    pad_thickness: float = 0.01
    # masses: the S2 weighs ≈11 kg: frame (shell, battery, stator, pedals) 7 kg, wheel (tyre, rim, rotor) 4 kg
    frame_mass: float = 7.0
    wheel_mass: float = 4.0
    # W: the rider's weight, HRP2-JSK's 56.5 kg (Table A.1) × g
    rider_weight: float = HRP2_MASS * GRAVITY
    # K₀ = r k W: chosen 5 s⁻¹ — a rider's ZMP 60 mm ahead of the axle (a clear lean on the 0.22 m pad) rides at
    # 0.3 m/s, the thesis's v^d of Fig. 7.13; k then follows from r and W (:meth:`k`)
    K0: float = 5.0
    # p⁰: the firmware's moment zero point, x from the axle [m]. The thesis gives none, and says the relation of the
    # boards to the wheel is unknown to the rider ('足部ボードの傾斜量と駆動輪の関係が未知', §7.3.3); 0 here, the
    # scenarios set their own (``p0_m``) against a rider whose mass centre was placed over the axle
    p0: float = 0.0
    # the firmware's speed servo: k_v makes the loaded wheel (≈68 kg at r: m r² ≈ 2.2 kg m²) reach its speed in
    # ≈0.1 s; torque limit 60 N m (a 500 W hub motor at low speed); the measured moment is lagged by 0.05 s
    # (the internal pitch loop's response: the firmware reads the tilt, not the moment)
    speed_gain: float = 25.0
    max_torque: float = 60.0
    lag: float = 0.05
    # training wheels (Fig. A.8 (II)): radius 50 mm, under the footboards' outer ends
    tw_radius: float = 0.05
    tw_y: float = 0.22
    tyre_friction: float = 1.2
    wheel_damping: float = 0.01
    roll_damping: float = 0.5  # N m s/rad on the roll hinge: the tyre's footprint scrubbing (chosen)

    def __post_init__(self):
        for name in ("wheel_radius", "tyre_width", "board_height", "board_y", "pad_thickness", "frame_mass",
                     "wheel_mass", "rider_weight", "K0", "speed_gain", "max_torque", "lag", "tw_radius", "tw_y",
                     "tyre_friction"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"NinebotSpec.{name} must be a finite positive number, got {value!r}")
        if not (math.isfinite(self.p0) and abs(self.p0) < self.pad_size[0] / 2):
            raise ValueError(f"NinebotSpec.p0 must be a finite x on the footboards (|p0| < {self.pad_size[0] / 2} m), "
                             f"got {self.p0!r}")

    @property
    def k(self) -> float:
        """k of Eq. A.6 [rad/s per N m]: K₀ / (r W) (Eq. A.9)."""
        return self.K0 / (self.wheel_radius * self.rider_weight)


NINEBOT = NinebotSpec()


# --- Eqs. A.5–A.9 --------------------------------------------------------------------------------------


def pitch_moment(zmp_x: float, p0: float = 0.0, n: NinebotSpec = NINEBOT, weight: float | None = None) -> float:
    """Eq. A.5: M_y⁰ = W (p^{d**} − p⁰) [N m]."""
    return (n.rider_weight if weight is None else weight) * (zmp_x - p0)


def wheel_rate(moment: float, n: NinebotSpec = NINEBOT) -> float:
    """Eq. A.6: Ω = k M_y⁰ [rad/s]."""
    return n.k * moment


def wheel_velocity(omega: float, n: NinebotSpec = NINEBOT) -> float:
    """Eq. A.7: v_traj = r Ω [m/s]."""
    return n.wheel_radius * omega


def zmp_velocity(zmp_x: float, p0: float = 0.0, n: NinebotSpec = NINEBOT) -> float:
    """Eq. A.8: v_traj = r k W (p^{d**} − p⁰) = K₀ (p^{d**} − p⁰) (Eq. A.9) [m/s]."""
    return wheel_velocity(wheel_rate(pitch_moment(zmp_x, p0, n), n), n)


# --- the model -----------------------------------------------------------------------------------------


def add_ninebot(spec: mujoco.MjSpec, parent, pos=(0.0, 0.0, 0.0), n: NinebotSpec = NINEBOT, *,
                training_wheels: bool = True):
    """Add the unicycle with its origin (ground under the axle) at ``pos``; returns the frame body ``ninebot``."""
    r = n.wheel_radius
    frame = parent.add_body(name="ninebot", pos=[pos[0], pos[1], pos[2] + r])
    for name, axis in zip(ROOT[:3], ([1, 0, 0], [0, 1, 0], [0, 0, 1])):
        frame.add_joint(name=name, type=mujoco.mjtJoint.mjJNT_SLIDE, axis=axis)
    add_hinge(frame, "ninebot_yaw", [0, 0, 1])
    add_hinge(frame, "ninebot_roll", [1, 0, 0], damping=n.roll_damping)
    shell_w = n.tyre_width + 0.04
    add_visual(frame, BOX, [r * 0.75, shell_w / 2, r * 0.9], SHELL, pos=[0, 0, 0.03])  # the shell around the wheel
    top = n.board_height - r  # pad top in the frame (axle) coordinates
    for side, s in SIDES.items():
        frame.add_geom(name=f"ninebot_board_{side}", type=BOX,
                       size=[n.pad_size[0] / 2, n.pad_size[1] / 2, n.pad_thickness / 2],
                       pos=[0, s * n.board_y, top - n.pad_thickness / 2], rgba=RUBBER, mass=0, contype=0,
                       conaffinity=SOLE)
        frame.add_site(name=PAD[side], pos=[0, s * n.board_y, top])
        if training_wheels:
            tw = frame.add_body(name=f"ninebot_tw_{side}", pos=[0, s * n.tw_y, n.tw_radius - r])
            add_hinge(tw, f"ninebot_tw_{side}", [0, 1, 0], damping=n.wheel_damping)
            tw.add_geom(type=mujoco.mjtGeom.mjGEOM_ELLIPSOID, size=[n.tw_radius, 0.015, n.tw_radius], rgba=TYRE,
                        mass=0.3, contype=WHEEL, conaffinity=0, friction=[n.tyre_friction, 0.005, 0.0001])
            add_visual(frame, BOX, [0.01, (n.tw_y - n.board_y) / 2, (top - n.tw_radius + r) / 2], METAL,
                       pos=[0, s * (n.tw_y + n.board_y) / 2, (top + n.tw_radius - r) / 2])  # the stay
    frame.explicitinertial = True
    frame.mass, frame.ipos = n.frame_mass, [0, 0, 0]
    frame.inertia = box_inertia(n.frame_mass, (1.5 * r, shell_w, 1.8 * r))
    frame.add_site(name="ninebot_centre", pos=[0, 0, -r])
    wheel = frame.add_body(name="ninebot_wheel")
    add_hinge(wheel, "ninebot_wheel", [0, 1, 0], damping=n.wheel_damping)
    wheel.add_geom(name="ninebot_tyre", type=mujoco.mjtGeom.mjGEOM_ELLIPSOID, size=[r, n.tyre_width / 2, r],
                   rgba=TYRE, mass=n.wheel_mass, contype=WHEEL, conaffinity=0,
                   friction=[n.tyre_friction, 0.005, 0.0001])
    add_visual(wheel, BOX, [r * 0.6, n.tyre_width / 2 + 0.002, 0.02], METAL)  # hub spoke, shows the turning
    motor = spec.add_actuator(name="ninebot_motor", target="ninebot_wheel", trntype=mujoco.mjtTrn.mjTRN_JOINT)
    motor.set_to_velocity(kv=n.speed_gain)
    motor.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
    motor.forcerange = [-n.max_torque, n.max_torque]
    for name, kind, obj, objname in (
            ("ninebot_vel", mujoco.mjtSensor.mjSENS_FRAMELINVEL, mujoco.mjtObj.mjOBJ_SITE, "ninebot_centre"),
            ("ninebot_angvel", mujoco.mjtSensor.mjSENS_FRAMEANGVEL, mujoco.mjtObj.mjOBJ_SITE, "ninebot_centre"),
            ("ninebot_heading", mujoco.mjtSensor.mjSENS_FRAMEXAXIS, mujoco.mjtObj.mjOBJ_SITE, "ninebot_centre"),
            ("ninebot_wheel_speed", mujoco.mjtSensor.mjSENS_JOINTVEL, mujoco.mjtObj.mjOBJ_JOINT, "ninebot_wheel"),
            ("ninebot_roll", mujoco.mjtSensor.mjSENS_JOINTPOS, mujoco.mjtObj.mjOBJ_JOINT, "ninebot_roll")):
        spec.add_sensor(name=name, type=kind, objtype=obj, objname=objname)
    return frame


class NinebotFirmware:
    """The internal controller (module docstring): Eq. A.5 from the footboards' contact loads, lagged, then
    Eq. A.6 as the hub motor's speed reference. Call before every physics step (contacts one step old).
    ``moment`` [N m], ``omega_ref`` [rad/s] are its latest values."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, n: NinebotSpec = NINEBOT, dt: float | None = None):
        self.model, self.data, self.n = model, data, n
        self.pads = {model.geom(f"ninebot_board_{s}").id for s in SIDES}
        self.frame = model.body("ninebot").id
        self.motor = model.actuator("ninebot_motor").id
        self.dt = model.opt.timestep if dt is None else dt
        self._a = math.exp(-self.dt / n.lag)
        self.moment, self.omega_ref = 0.0, 0.0
        self._f = np.zeros(6)

    def measured_moment(self) -> float:
        """M_y⁰ = Σ f_n ((x_c − x_axle)·heading − p⁰) over the contacts on the footboards (Eq. A.5)."""
        m, d = self.model, self.data
        origin = d.xpos[self.frame]
        heading = d.xmat[self.frame].reshape(3, 3)[:, 0]
        total = 0.0
        for i in range(d.ncon):
            c = d.contact[i]
            if c.geom1 in self.pads or c.geom2 in self.pads:
                mujoco.mj_contactForce(m, d, i, self._f)
                total += self._f[0] * (float((c.pos - origin) @ heading) - self.n.p0)
        return total

    def __call__(self) -> None:
        m = self.measured_moment()
        self.moment = m + (self.moment - m) * self._a  # the firmware's lag
        self.omega_ref = wheel_rate(self.moment, self.n)  # Eq. A.6
        self.data.ctrl[self.motor] = self.omega_ref


def install_firmware(body: MujocoBody, n: NinebotSpec = NINEBOT) -> NinebotFirmware:
    """Run the Ninebot's firmware before every physics step of ``body``; returns it."""
    firmware = NinebotFirmware(body.model, body.data, n)
    body.before_physics.append(firmware)
    return firmware


def ninebot_velocity(snapshot) -> tuple[float, float]:
    """The true (v, ω): the vehicle origin's velocity along the heading [m/s] and its yaw rate [rad/s]."""
    return float(snapshot["ninebot_vel"] @ snapshot["ninebot_heading"]), float(snapshot["ninebot_angvel"][2])


def build_ninebot(n: NinebotSpec = NINEBOT, *, training_wheels: bool = True, substeps: int = SUBSTEPS) -> MujocoBody:
    """The unicycle alone (keyframe ``park``), its firmware installed (``body.firmware``)."""
    spec = scene_spec("ninebot", *SCENE)
    add_ninebot(spec, spec.worldbody, n=n, training_wheels=training_wheels)
    spec.add_key(name="park")
    model = spec.compile()
    fill_keyframe(model, "park", model.qpos0.copy())
    body = MujocoBody(model, substeps=substeps, keyframe="park", spec=spec)
    body.firmware = install_firmware(body, n)
    return body
