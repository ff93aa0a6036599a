"""The V-BOARD of seed 000 App. A.1.2 (Figs. A.4–A.7, Eqs. A.1–A.4), a self-balancing two-wheeled
scooter ("hoverboard"), built in code with MjSpec.

What the thesis gives (§A.1.2): two boards, one per foot, each tilting in pitch; no force plate and
no CoP sensing, only a binary contact sensor per board that switches its wheel's drive on or off;
each wheel turns at a speed proportional to its board's tilt,

* Eq. A.1  Ω_s = K_s (θ_s − θ_sO), K_R = 4.6203, K_L = 4.3356 rad/s per degree, θ_RO = −1.7871°,
  θ_LO = −1.9972° (the regression of Fig. A.6; θ in degrees),
* Eq. A.2  V_s = r Ω_s, r = 0.080 m (no slip),
* Eq. A.3  v = (V_R + V_L)/2, ω = (V_R − V_L)/W, W = 0.515 m,
* Eq. A.4  (v, ω) from (θ_R, θ_L): A.3 ∘ A.2 ∘ A.1,

and calls this "an inverted-pendulum control that balances by commanding the wheel speed from the
body's tilt" (after Eq. A.4, [196]). It gives no dynamic model of the scooter itself.

The model (chosen). A real hoverboard is two rigid halves on one axle line, joined by a centre
pivot: each half carries a foot pad, a gyro/IMU board, and its hub motor's stator; the wheel
(tyre + outer rotor) turns on it. So here: a level frame ``vboard`` on the axle line (3 slides,
yaw, roll: it never pitches, so it carries only the axisymmetric pivot tube), each half
``vboard_s`` hinged on it about the axle (joint ``board_s``: its angle *is* the half's pitch θ_s
in the world, what the half's gyro measures), each wheel hinged on its half (joint ``wheel_s``,
the motor's shaft). The halves' only coupling is the pivot's friction (tendon ``vboard_pivot``).

The firmware (:class:`VboardFirmware`, run before every physics step) is Eq. A.1 as a speed servo
of each hub motor: τ_s = k_v (K_s (θ_s − θ_sO) − Ω_s) while the side's contact switch is on,
τ_s = 0 (the wheel coasts) while it is off; Ω_s is the motor speed (wheel relative to half, the
hall sensors'), |τ_s| ≤ 15 N m. At steady speed τ only meets the bearing's drag, so Eq. A.1 holds
to 0.5 % (k_v / (k_v + bearing damping)).
What keeps a loaded board near θ_O is this same law: a tilt drives the wheel, and the motor's
reaction torque turns the half back — for a free half I θ̈ + k_v (1 + I/(M r²)) θ̇ + k_v K (θ − θ_O)
= 0, a stiff, damped levelling loop. A load whose mass centre is over the axle at θ_O stays put;
one ahead of (behind) the axle tips the board and drives the scooter forward (back), as a rider
leaning does. A rigid load is thus an inverted pendulum on a speed-commanded cart, slowly unstable
(pole ≈ g/(r K) ≈ 0.5 s⁻¹): the rider balances, as §6.2.1's behaviour level 1 shows (the robot
holding a fixed posture moved off, accelerating; Fig. 6.3). A scenario wanting the real board's
inexact θ_O (§6.2.1: level 2 drifted back with θ_R > θ_RO) builds the scooter from a
``dataclasses.replace(VBOARD, theta_o_deg=...)`` while its controllers keep :data:`VBOARD`. An unloaded half (drive off) hangs level under its own weight
(mass centre below the axle). Mass, sizes and motor are a 6.5-inch board's (:class:`VboardSpec`).

Frames: vehicle origin on the ground under the axle's midpoint, x forward, y left, z up. θ_s turns
about +y: positive tips the toes down, and θ_s > θ_sO turns the wheel forward (§6.2.1).

Names (``s`` is ``r`` or ``l``):

==========  ====================================================================================
joints      ``vboard_x``, ``vboard_y``, ``vboard_z`` (slides), ``vboard_yaw``, ``vboard_roll`` (the
            level frame), ``board_s`` (θ_s), ``wheel_s`` (motor angle, wheel relative to half)
bodies      ``vboard`` (level frame, origin on the axle midpoint), ``vboard_s`` (half), ``wheel_s``
sites       ``board_s_top`` (foot-pad top centre, half frame; a sole stands here; the contact
            switch's region), ``vboard_centre`` (axle midpoint)
sensors     ``board_s_pitch``, ``board_s_rate`` (θ_s, θ̇_s), ``wheel_s_speed`` (Ω_s, motor speed),
            ``board_s_touch`` (normal force on the pad; the switch is on above ``switch_force``),
            ``vboard_vel``, ``vboard_angvel``, ``vboard_heading`` (world-frame velocity, angular
            velocity and x axis of the level frame: the true v and ω, :func:`scooter_velocity`)
actuators   ``wheel_s_motor`` (the firmware's Eq. A.1 term), ``wheel_s_damper`` (its −k_v Ω term,
            gain × switch); with ``hold=True`` also ``board_s_hold``, a test fixture holding θ_s
==========  ====================================================================================

The V-BOARD itself has no v/ω sensors (§6.2.2: the robot must estimate them); ``vboard_vel`` etc.
are the simulator's truth for evaluation; :func:`wheel_odometry` is Eqs. A.2–A.3 on wheel speeds.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from shintai.humanoid.constants import SCENE, SOLE, SUBSTEPS, VBOARD, VBOARD_HOLD_SERVO, WHEEL, VboardSpec
from shintai.humanoid.vboard.constants import (FIRMWARE_LAW, FIRMWARE_LAWS, HOUSING, METAL, RUBBER, SWITCH_MARGIN,
                                             TORQUE_TILT_TD, TYRE)
from shintai.sim.body import MujocoBody
from shintai.sim.spec import add_hinge, add_visual, box_inertia, fill_keyframe, scene_spec, set_joints

SIDES = {"r": -1.0, "l": 1.0}  # y sign of each half
ROOT = ("vboard_x", "vboard_y", "vboard_z", "vboard_yaw", "vboard_roll")
BOARD = {s: f"board_{s}" for s in SIDES}  # joints θ_s
WHEEL_JOINT = {s: f"wheel_{s}" for s in SIDES}
PAD = {s: f"board_{s}_top" for s in SIDES}  # pad-top sites
TOUCH = {s: f"board_{s}_touch" for s in SIDES}
CAPSULE, BOX = mujoco.mjtGeom.mjGEOM_CAPSULE, mujoco.mjtGeom.mjGEOM_BOX


# --- Eqs. A.1–A.4 ------------------------------------------------------------------------------


def wheel_speed(theta: float, side: str, v: VboardSpec = VBOARD) -> float:
    """Eq. A.1: Ω_s = K_s (θ_s − θ_sO) [rad/s] for board pitch ``theta`` [rad]."""
    return v.gain(side) * (theta - v.theta_o(side))


def wheel_odometry(omega_r: float, omega_l: float, v: VboardSpec = VBOARD) -> tuple[float, float]:
    """Eqs. A.2–A.3: (v [m/s], ω [rad/s]) of the scooter from its wheel speeds Ω_R, Ω_L [rad/s]."""
    v_r, v_l = v.wheel_radius * omega_r, v.wheel_radius * omega_l  # Eq. A.2
    return (v_r + v_l) / 2, (v_r - v_l) / v.track  # Eq. A.3


def tilt_velocity(theta_r: float, theta_l: float, v: VboardSpec = VBOARD) -> tuple[float, float]:
    """Eq. A.4: (v, ω) of the scooter at board pitches θ_R, θ_L [rad] (steady state)."""
    return wheel_odometry(wheel_speed(theta_r, "r", v), wheel_speed(theta_l, "l", v), v)


def tilts_for(speed: float, yaw_rate: float, v: VboardSpec = VBOARD) -> tuple[float, float]:
    """Eq. A.4 inverted: the board pitches (θ_R, θ_L) [rad] that make the scooter go at ``speed``
    [m/s] turning at ``yaw_rate`` [rad/s]."""
    v_r, v_l = speed + yaw_rate * v.track / 2, speed - yaw_rate * v.track / 2
    return (v_r / v.wheel_radius / v.gain("r") + v.theta_o("r"),
            v_l / v.wheel_radius / v.gain("l") + v.theta_o("l"))


# --- the model ---------------------------------------------------------------------------------


def _add_half(spec: mujoco.MjSpec, frame, side: str, v: VboardSpec, hold: bool) -> None:
    """Half ``side``: housing, pad (with the contact switch's site), hub motor and wheel."""
    s = SIDES[side]
    half = frame.add_body(name=f"vboard_{side}")
    add_hinge(half, BOARD[side], [0, 1, 0])
    r = v.wheel_radius
    inner, outer = v.housing_gap, v.housing_outer
    y_mid, width = s * (inner + outer) / 2, outer - inner
    top = v.deck_height - v.pad_thickness - r  # housing top, axle frame
    bottom = v.housing_bottom - r
    half.add_geom(name=f"vboard_{side}_housing", type=BOX, size=[v.housing_depth / 2, width / 2, (top - bottom) / 2],
                  pos=[0, y_mid, (top + bottom) / 2], rgba=HOUSING, mass=0, contype=WHEEL, conaffinity=SOLE)
    pad_z = v.deck_height - r - v.pad_thickness / 2
    half.add_geom(name=f"board_{side}_pad", type=BOX, size=[v.pad_size[0] / 2, v.pad_size[1] / 2, v.pad_thickness / 2],
                  pos=[0, s * v.pad_y, pad_z], rgba=RUBBER, mass=0, contype=0, conaffinity=SOLE)
    add_visual(half, BOX, [0.05, 0.02, 0.04], HOUSING, pos=[0, s * (outer + 0.005), 0.05])  # fender stay
    # the switch's region: the pad and a margin, so that contacts on the pad's edges (a sole longer
    # than the pad touches it there) fall inside the touch sensor's volume
    half.add_site(name=PAD[side], type=mujoco.mjtGeom.mjGEOM_BOX, pos=[0, s * v.pad_y, v.deck_height - r],
                  size=[v.pad_size[0] / 2 + SWITCH_MARGIN, v.pad_size[1] / 2 + SWITCH_MARGIN, SWITCH_MARGIN],
                  rgba=[0, 0, 0, 0])
    half.explicitinertial = True
    half.mass, half.ipos = v.half_mass, [0, y_mid, -v.half_com_drop]
    half.inertia = box_inertia(v.half_mass, (v.housing_depth, width, top - bottom))
    wheel = half.add_body(name=WHEEL_JOINT[side], pos=[0, s * v.track / 2, 0])
    joint = add_hinge(wheel, WHEEL_JOINT[side], [0, 1, 0], damping=v.wheel_damping)
    joint.actfrclimited = mujoco.mjtLimited.mjLIMITED_TRUE  # the motor's torque limit, both terms together
    joint.actfrcrange = [-v.max_torque, v.max_torque]
    wheel.add_geom(name=WHEEL_JOINT[side], type=mujoco.mjtGeom.mjGEOM_ELLIPSOID, size=[r, v.tyre_width / 2, r],
                   rgba=TYRE, mass=v.wheel_mass, contype=WHEEL, conaffinity=0,
                   friction=[v.tyre_friction, 0.005, 0.0001])  # ellipsoid: one smooth rolling contact (tricycle)
    add_visual(wheel, BOX, [r * 0.6, v.tyre_width / 2 + 0.002, 0.012], METAL)  # hub spoke, shows the turning
    motor = spec.add_actuator(name=f"wheel_{side}_motor", target=WHEEL_JOINT[side], trntype=mujoco.mjtTrn.mjTRN_JOINT)
    motor.set_to_motor()
    damper = spec.add_actuator(name=f"wheel_{side}_damper", target=WHEEL_JOINT[side],
                               trntype=mujoco.mjtTrn.mjTRN_JOINT)  # force = ctrl · (−k_v Ω), ctrl = switch
    damper.gaintype = mujoco.mjtGain.mjGAIN_AFFINE
    damper.gainprm = [0.0, 0.0, -v.speed_gain] + [0.0] * 7
    damper.biastype = mujoco.mjtBias.mjBIAS_NONE
    damper.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
    damper.ctrlrange = [0.0, 1.0]
    joint_sensors = ((f"board_{side}_pitch", mujoco.mjtSensor.mjSENS_JOINTPOS, BOARD[side]),
                     (f"board_{side}_rate", mujoco.mjtSensor.mjSENS_JOINTVEL, BOARD[side]),
                     (f"wheel_{side}_speed", mujoco.mjtSensor.mjSENS_JOINTVEL, WHEEL_JOINT[side]))
    for name, kind, joint_name in joint_sensors:
        spec.add_sensor(name=name, type=kind, objtype=mujoco.mjtObj.mjOBJ_JOINT, objname=joint_name)
    spec.add_sensor(name=TOUCH[side], type=mujoco.mjtSensor.mjSENS_TOUCH, objtype=mujoco.mjtObj.mjOBJ_SITE,
                    objname=PAD[side])
    if hold:
        kp, kv = VBOARD_HOLD_SERVO
        act = spec.add_actuator(name=f"board_{side}_hold", target=BOARD[side], trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=kp, kv=kv)


def add_vboard(spec: mujoco.MjSpec, parent, pos=(0.0, 0.0, 0.0), yaw: float = 0.0, v: VboardSpec = VBOARD, *,
               hold: bool = False, fixed: bool = False):
    """Add the V-BOARD with its vehicle origin (ground under the axle midpoint) at ``pos``, heading
    ``yaw`` [rad] (the slides ``vboard_x``/``vboard_y`` move along the initial heading's axes).

    ``hold`` adds the pitch-holding fixture ``board_s_hold`` (it reacts on the level frame, hence on
    the world: a hand holding the board, not a part of the scooter); ``fixed`` mounts the scooter on a
    stand, its wheels 50 mm clear of the ground (the measurement of Fig. A.5), without root joints.
    Returns the level-frame body ``vboard``. Run :class:`VboardFirmware` on the compiled model.
    """
    lift = 0.05 if fixed else 0.0
    frame = parent.add_body(name="vboard", pos=[pos[0], pos[1], pos[2] + v.wheel_radius + lift],
                            quat=[math.cos(yaw / 2), 0, 0, math.sin(yaw / 2)])
    if not fixed:
        for name, axis in zip(ROOT[:3], ([1, 0, 0], [0, 1, 0], [0, 0, 1])):
            frame.add_joint(name=name, type=mujoco.mjtJoint.mjJNT_SLIDE, axis=axis)
        add_hinge(frame, "vboard_yaw", [0, 0, 1])
        add_hinge(frame, "vboard_roll", [1, 0, 0])
    add_visual(frame, CAPSULE, [0.02], METAL, v.pivot_mass, fromto=[0, -0.03, 0, 0, 0.03, 0])  # centre pivot tube
    frame.add_site(name="vboard_centre")
    for side in SIDES:
        _add_half(spec, frame, side, v, hold)
    pivot = spec.add_tendon(name="vboard_pivot", damping=v.pivot_damping)  # θ_R − θ_L: the pivot's friction
    pivot.wrap_joint(BOARD["r"], 1.0)
    pivot.wrap_joint(BOARD["l"], -1.0)
    for name, kind in (("vboard_vel", mujoco.mjtSensor.mjSENS_FRAMELINVEL),
                       ("vboard_angvel", mujoco.mjtSensor.mjSENS_FRAMEANGVEL),
                       ("vboard_heading", mujoco.mjtSensor.mjSENS_FRAMEXAXIS)):
        spec.add_sensor(name=name, type=kind, objtype=mujoco.mjtObj.mjOBJ_SITE, objname="vboard_centre")
    return frame


def vboard_state(model: mujoco.MjModel, qpos: np.ndarray, theta: dict | None = None,
                 v: VboardSpec = VBOARD) -> None:
    """Set the boards' pitch in ``qpos``: ``theta`` {side: rad}, by default θ_O (a loaded scooter at rest)."""
    theta = {s: v.theta_o(s) for s in SIDES} if theta is None else theta
    set_joints(model, qpos, {BOARD[s]: value for s, value in theta.items()})


# --- the firmware and the sensors ---------------------------------------------------------------


class VboardFirmware:
    """The V-BOARD's controller (§A.1.2), one per model; call it before every physics step
    (:func:`install_firmware` puts it in a body's ``before_physics``).

    Each side: the contact switch is on while its pad's normal force exceeds ``switch_force`` (or
    always, for sides in ``strapped``: Fig. A.5's belt pressing the sensor). While on, the hub motor
    is speed-servoed to Eq. A.1: ``wheel_s_motor`` gets k_v K_s (θ_s − θ_sO) and ``wheel_s_damper``
    gain 1 (its force −k_v Ω_s, integrated implicitly by MuJoCo); while off, both get 0. θ_s is read
    from ``qpos`` (current), the pad force from ``sensordata`` (one physics step old: MuJoCo computes
    sensors at the start of a step), a 1 ms switch latency.

    ``law="torque"`` (issue 26's candidate; default :data:`~shintai.humanoid.vboard.constants.FIRMWARE_LAW`,
    the speed servo): the hub motor is current (torque) driven from the tilt, τ_s = k_τ,s (θ_s − θ_sO) +
    d_τ,s θ̇_s, ``wheel_s_damper`` gain 0. Its reaction −τ_s on the half is the levelling torque, −d_τ θ̇_s its
    damping (a gyro's D term). k_τ from Eq. A.1 as Fig. A.5 measured it, the wheel in the air: the half held
    (θ̇_s = 0), the wheel's only load its bearing's drag b (``VboardSpec.wheel_damping``), so at steady speed
    k_τ (θ_s − θ_sO) = b Ω_s, i.e. Ω_s = (k_τ/b)(θ_s − θ_sO): Eq. A.1 exactly iff k_τ,s = K_s b (K_s in rad/s per
    rad; 2.647 N·m/rad right, 2.484 left with b = 0.01 N·m·s/rad). The stand cannot tell this law from the
    speed servo (whose steady Ω is k_v/(k_v + b) of Eq. A.1's). d_τ,s = k_τ,s T_d,
    T_d = :data:`~shintai.humanoid.vboard.constants.TORQUE_TILT_TD` (chosen: Eq. A.1, measured at rest, cannot fix it).
    """

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, v: VboardSpec = VBOARD, strapped=(),
                 law: str = FIRMWARE_LAW):
        unknown = set(strapped) - set(SIDES)
        if unknown:
            raise ValueError(f"strapped sides must be among {sorted(SIDES)}, got {sorted(unknown)}")
        if law not in FIRMWARE_LAWS:
            raise ValueError(f"law must be one of {FIRMWARE_LAWS}, got {law!r}")
        self.data, self.v, self.strapped, self.law = data, v, frozenset(strapped), law
        torque = law == "torque"
        self._sides = []
        for s in SIDES:
            j = model.joint(BOARD[s]).id
            gain = (v.wheel_damping if torque else v.speed_gain) * v.gain(s)  # k_τ = K b, or k_v K
            self._sides.append((s, int(model.jnt_qposadr[j]), int(model.jnt_dofadr[j]),
                                int(model.sensor_adr[model.sensor(TOUCH[s]).id]),
                                model.actuator(f"wheel_{s}_motor").id, model.actuator(f"wheel_{s}_damper").id,
                                gain, gain * TORQUE_TILT_TD if torque else 0.0, v.theta_o(s)))
        self._damper_on = 0.0 if torque else 1.0
        self.on = dict.fromkeys(SIDES, False)

    def __call__(self) -> None:
        d = self.data
        qpos, qvel, touch, ctrl = d.qpos, d.qvel, d.sensordata, d.ctrl
        for side, qadr, dadr, tadr, motor, damper, gain, rate_gain, theta_o in self._sides:
            on = side in self.strapped or bool(touch[tadr] > self.v.switch_force)
            self.on[side] = on
            ctrl[motor] = gain * (qpos[qadr] - theta_o) + rate_gain * qvel[dadr] if on else 0.0
            ctrl[damper] = self._damper_on if on else 0.0


def install_firmware(body: MujocoBody, v: VboardSpec = VBOARD, strapped=(), law: str = FIRMWARE_LAW) -> VboardFirmware:
    """Run the V-BOARD's firmware (``law``: :class:`VboardFirmware`) before every physics step of ``body``; returns it
    (``.on``: switches)."""
    firmware = VboardFirmware(body.model, body.data, v, strapped, law)
    body.before_physics.append(firmware)
    return firmware


def board_pitch(snapshot) -> dict[str, float]:
    """θ_s [rad] per side (the halves' gyros)."""
    return {s: float(snapshot[f"board_{s}_pitch"][0]) for s in SIDES}


def wheel_speeds(snapshot) -> dict[str, float]:
    """Ω_s [rad/s] per side (motor speed, wheel relative to its half)."""
    return {s: float(snapshot[f"wheel_{s}_speed"][0]) for s in SIDES}


def contact_switches(snapshot, v: VboardSpec = VBOARD) -> dict[str, bool]:
    """Each side's contact switch from its pad force (the firmware's rule, without ``strapped``)."""
    return {s: bool(snapshot[TOUCH[s]][0] > v.switch_force) for s in SIDES}


def scooter_velocity(snapshot) -> tuple[float, float]:
    """The true (v, ω): the axle midpoint's velocity along the heading [m/s] and the yaw rate [rad/s]."""
    return float(snapshot["vboard_vel"] @ snapshot["vboard_heading"]), float(snapshot["vboard_angvel"][2])


def build_vboard(theta: dict | None = None, v: VboardSpec = VBOARD, *, hold: bool = False, fixed: bool = False,
                 strapped=(), substeps: int = SUBSTEPS, law: str = FIRMWARE_LAW) -> MujocoBody:
    """The V-BOARD alone (keyframe ``park``: boards at ``theta``, default θ_O), its firmware installed.

    ``hold``/``fixed``: see :func:`add_vboard` (the fixture then holds ``theta``); ``strapped``: see
    :class:`VboardFirmware`, as ``law``. ``body.firmware`` is the firmware.
    """
    spec = scene_spec("vboard", *SCENE)
    add_vboard(spec, spec.worldbody, v=v, hold=hold, fixed=fixed)
    spec.add_key(name="park")
    model = spec.compile()
    qpos = model.qpos0.copy()
    vboard_state(model, qpos, theta, v)
    fill_keyframe(model, "park", qpos)
    body = MujocoBody(model, substeps=substeps, keyframe="park", spec=spec)
    body.firmware = install_firmware(body, v, strapped, law)
    return body
