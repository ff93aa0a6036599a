"""The seated HRP2 of ch. 4 (seed 000 §4.3–4.4, §7.3–7.4): the riding assembly with a hip–saddle
contact, environment obstacles, an optional crank motor, and the whole-body *rider* module that the
ch. 4 corrections feed.

Model (:func:`build_ch4`, on top of :func:`shintai.humanoid.tricycle.riding.riding_spec`):

* **hip–saddle contact** (Table 4.2: unilateral): two sit bones (capsules along x) under the
  waist on a saddle crowned across y (:func:`add_seat`) — free to roll about x and to slide in y
  against friction, because the saddle "is thin in y" and y translation and x rotation dominate
  the seat displacement (§4.3.1, Fig. 4.4); on the crown a sideways slide drops the outer sit
  bone, so the translation shows as a roll (the assumption of §4.3.2's detection).
  ``hip="weld"`` keeps :mod:`~shintai.humanoid.tricycle.riding`'s hip weld switched on (the §3.3.2
  assumption), ``hip="contact"`` switches it off so the robot only sits.
* **obstacles**: static boxes in geom group :data:`~shintai.humanoid.tricycle.constants.OBSTACLE_GROUP`,
  touching wheels and soles, seen by the depth sensor.
* **crank motor** (``drive=motor``): a velocity servo on the crank standing in for the legs — NOT the
  thesis's method; scenarios label it. The feet then ride the pedals (active impedance, 150 N each).

Runtime wiring (nervous-style, seed 000 §7.2 / seed 003 §6.3.4): the correction modules (navigation,
posture control, sitting recovery, PPDM) write the reference channels ``ref:*`` — the loop's own
channels :data:`REF_CHANNELS` — in a :class:`~shintai.core.runtime.Loop` (parallel: they add) or under a
:class:`~shintai.core.runtime.Switcher` (switching); :class:`Rider` reads them and solves the
whole-body IK on the robot's *reference model* (the vehicle at the origin, the waist on the seat
displaced by the commanded base correction — the way hrpsys solves on its reference model, §7.4.1
"model A"), putting hands on the grips at ``ref:theta_h`` and, unless the legs pedal by themselves,
soles on the pedals at the crank angle. Every reference is seen one control period after it is
written (``delay=1``, 4 ms; 0 before anything is written): the modules of one tick all read the
previous tick's references — a declared delay, which the results depend on.

Reference channels (additive: summed over modules; a tick nobody writes one reads 0):

==================  ==============================================================================
``ref:theta_h``     handle target θ_h^ref [rad] (Eq. 4.21)
``ref:crank_rate``  crank rate ω_c^ref [rad/s] (Eq. 4.18) — the motor's velocity target
``ref:chest_roll``  Δφ_C, roll of the reference waist about the hip contact point (Eq. 4.9) [rad]
``ref:com_shift``   lateral shift of the reference waist y_g − y_g(0) (Eqs. 4.3–4.7) [m]
``ref:hip_lift``    lift of the reference waist above the saddle [m] (STAND, Table 7.6)
``ref:foot_fz``     extra vertical target force of both feet [N] (on top of the base force)
``ref:foot_fz_l/r`` extra vertical target force of one foot [N]
``ref:crank_target`` crank angle the feet are placed at when the legs turn the crank (small obstacle)
==================  ==============================================================================
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.core.geometry import roll_of
from shintai.core.runtime import ADD, Channel, Module
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    CRANK_MOTOR_KV,
    CRANK_MOTOR_TORQUE,
    FOOT_FOLLOW_F_TRG,
    HRP2_LINKS,
    IMPEDANCE,
    PEDAL_FRICTION,
    RIDER_PERIOD,
    SADDLE_CROWN_RADIUS,
    SADDLE_FRICTION,
    SADDLE_HALF_WIDTH,
    SIT_BONE_HALF_LENGTH,
    SIT_BONE_RADIUS,
    SIT_BONE_Y,
    STEER_RATE,
    TRICYCLE,
)
from shintai.humanoid.robots.hrp2 import SIDES, ft_reaction
from shintai.humanoid.tricycle.active import grip_plan
from shintai.humanoid.tricycle.constants import DARK, OBSTACLE_GROUP, SEAT, SOLE_BIT, WHEEL_BIT
from shintai.humanoid.tricycle.hrp2_limbs import BAR_IN_HAND, CRANK_AXIS_IN_SOLE, VehicleFrame
from shintai.humanoid.tricycle.passive import ActiveImpedance
from shintai.humanoid.tricycle.riding import (
    ANKLE_FT,
    ARM,
    HAND,
    HIP_SADDLE,
    LEG,
    SOLE,
    WRIST_FT,
    hold_riding_pose,
    riding_posture,
    riding_spec,
)
from shintai.humanoid.tricycle.vehicle import pedal_position, steer_axis
from shintai.sim import ik
from shintai.sim.body import MujocoBody
from shintai.sim.spec import quat_axis

REFS = ("ref:theta_h", "ref:crank_rate", "ref:chest_roll", "ref:com_shift", "ref:hip_lift", "ref:foot_fz",
        "ref:foot_fz_l", "ref:foot_fz_r", "ref:crank_target")
# the loop's reference channels: seen one control period after they are written, 0 until then
REF_CHANNELS = tuple(Channel(name, ADD, delay=1, default=0.0) for name in REFS)
CRANK_MOTOR = "crank_motor"


@dataclass(frozen=True)
class Obstacle:
    """A static box on the floor: ``name``, half sizes (x, y, z) and centre (x, y, z) in the world."""

    name: str
    half: tuple[float, float, float]
    pos: tuple[float, float, float]
    rgba: tuple[float, float, float, float] = (0.55, 0.5, 0.42, 1.0)
    yaw: float = 0.0


def ch4_spec(obstacles: Sequence[Obstacle] = (), crank_motor: bool = True, **riding_options) -> mujoco.MjSpec:
    """The riding scene plus hip pad, saddle contact, obstacles and (optionally) the crank motor."""
    spec = riding_spec(**riding_options)
    add_seat(spec)
    for side in ("l", "r"):  # studded pedals (chosen): soles hold on them while pushing hard (PPDM, STAND)
        spec.geom(f"pedal_{side}").friction = [PEDAL_FRICTION, 0.005, 0.0001]
    for ob in obstacles:
        spec.worldbody.add_geom(name=ob.name, type=mujoco.mjtGeom.mjGEOM_BOX, size=list(ob.half), pos=list(ob.pos),
                                quat=quat_axis([0, 0, 1], ob.yaw).tolist(), rgba=list(ob.rgba), group=OBSTACLE_GROUP,
                                contype=0, conaffinity=SOLE_BIT | WHEEL_BIT, friction=[1.2, 0.005, 0.0001])
    if crank_motor:
        act = spec.add_actuator(name=CRANK_MOTOR, target="crank", trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_velocity(kv=CRANK_MOTOR_KV)
        act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
        act.forcerange = [-CRANK_MOTOR_TORQUE, CRANK_MOTOR_TORQUE]
    return spec


def crowned_saddle(n: int = 21) -> np.ndarray:
    """Vertices of the saddle's collision hull (saddle frame, top at z = 0): a block 0.22 m long,
    :data:`SADDLE_HALF_WIDTH` wide either side, 5 cm deep, its top an arc of radius
    :data:`SADDLE_CROWN_RADIUS` across y (a crowned saddle, §4.3.1)."""
    r = SADDLE_CROWN_RADIUS
    ys = np.linspace(-SADDLE_HALF_WIDTH, SADDLE_HALF_WIDTH, n)
    arc = [(y, np.sqrt(r * r - y * y) - r) for y in ys] + [(SADDLE_HALF_WIDTH, -0.05), (-SADDLE_HALF_WIDTH, -0.05)]
    return np.array([(x, y, z) for x in (-0.13, 0.09) for y, z in arc])


def add_seat(spec: mujoco.MjSpec) -> None:
    """The hip–saddle contact (Table 4.2, unilateral): two sit-bone capsules along x under the waist,
    ±:data:`SIT_BONE_Y` apart, on the crowned saddle hull; placed so that both touch the crown in the
    ``ride`` keyframe (waist origin :attr:`~Hrp2Links.hip_cover` above the saddle top)."""
    friction = [SADDLE_FRICTION, 0.005, 0.0001]
    r, rc = SIT_BONE_RADIUS, SADDLE_CROWN_RADIUS
    z = -HRP2_LINKS.hip_cover - rc + np.sqrt((rc + r) ** 2 - SIT_BONE_Y ** 2)
    for side, y in (("l", SIT_BONE_Y), ("r", -SIT_BONE_Y)):
        spec.body("waist").add_geom(
            name=f"sit_bone_{side}", type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[SIT_BONE_RADIUS, 0, 0],
            fromto=[-SIT_BONE_HALF_LENGTH, y, z, SIT_BONE_HALF_LENGTH, y, z], contype=SEAT, conaffinity=0,
            rgba=[0.3, 0.3, 0.3, 0.0], mass=0.0, friction=friction)
    spec.add_mesh(name="saddle_hull", uservert=crowned_saddle().ravel().tolist())
    saddle = spec.body("saddle")
    for geom in saddle.geoms:  # the flat visual box of vehicles/tricycle.py: the hull is drawn instead
        if geom.contype == 0 and geom.conaffinity == 0:
            geom.rgba[3] = 0.0
    saddle.add_geom(name="saddle_seat", type=mujoco.mjtGeom.mjGEOM_MESH, meshname="saddle_hull",
                    contype=0, conaffinity=SEAT, rgba=DARK, mass=0.0, friction=friction)


def build_ch4(obstacles: Sequence[Obstacle] = (), hip: str = "contact", crank_motor: bool = True,
              theta_c: float = 0.0, start=(0.0, 0.0, 0.0), **riding_options) -> MujocoBody:
    """The ch. 4 riding body at keyframe ``ride``, the tricycle at ``start`` = (x, y, yaw) on the floor.

    ``hip``: ``"weld"`` (hip welded to the saddle, §3.3.2) or ``"contact"`` (sitting only, Table 4.2).
    """
    if hip not in ("weld", "contact"):
        raise ValueError(f"hip must be 'weld' or 'contact', got {hip!r}")
    model = ch4_spec(obstacles, crank_motor, **riding_options).compile()
    qpos = riding_posture(model, 0.0, theta_c)
    # move vehicle and robot together to the start pose
    rot = np.zeros(4)
    mujoco.mju_axisAngle2Quat(rot, np.array([0.0, 0.0, 1.0]), start[2])
    for root in ("tricycle_root", "root"):
        adr = model.joint(root).qposadr[0]
        p, q = qpos[adr:adr + 3].copy(), qpos[adr + 3:adr + 7].copy()
        turned = np.zeros(3)
        mujoco.mju_rotVecQuat(turned, p, rot)
        qpos[adr:adr + 3] = turned + [start[0], start[1], 0.0]
        mujoco.mju_mulQuat(qpos[adr + 3:adr + 7], rot, q)
    hold_riding_pose(model, qpos, riding_options.get("grasp", "weld"))
    body = MujocoBody(model, substeps=round(CONTROL_PERIOD / model.opt.timestep), keyframe="ride")
    body.set_equality(HIP_SADDLE, hip == "weld")
    return body


def vehicle_pose2d(body: MujocoBody) -> np.ndarray:
    """(x, y, yaw) of the tricycle frame (evaluation, and the self-localisation stand-in)."""
    p = body.body_pos("tricycle")
    r = body.data.body("tricycle").xmat.reshape(3, 3)
    return np.array([p[0], p[1], np.arctan2(r[1, 0], r[0, 0])])


def trunk_roll(snapshot) -> float:
    """θ_roll / φ_C: roll of the chest IMU frame from its quaternion (``imu_quat``, §4.3.2)."""
    m = np.zeros(9)
    mujoco.mju_quat2Mat(m, np.asarray(snapshot["imu_quat"], dtype=float))
    return roll_of(m.reshape(3, 3))


def vehicle_roll(body: MujocoBody) -> float:
    return roll_of(body.data.body("tricycle").xmat.reshape(3, 3))


class Rider(Module):
    """Whole-body IK of the seated robot on its reference model, driven by the ``ref:*`` channels.

    Hands: grips of the nominal handle at ``ref:theta_h`` (rate-limited to :data:`STEER_RATE`),
    under a Table 3.4 impedance (``hand_gains``, default the active arm's; Eq. 3.13), bar along the
    hand. Feet (``feet=True``, i.e. not pedalling by themselves): soles on the nominal pedals at the
    crank angle ``crank_of`` (the motor's encoder when the motor drives), under the ``foot_gains``
    impedance (default the active leg's) with a vertical
    target force ``base_fz + ref:foot_fz``. Waist of the reference model: the seated pose turned by
    ``ref:chest_roll`` about the hip contact point (Eq. 4.9), shifted by ``ref:com_shift`` in y and
    lifted by ``ref:hip_lift``. Unreachable targets keep the previous joint command (Eq. 3.14's
    gate on the joint input); such solves are counted in ``unreachable``. ``arms=False`` leaves the arms
    to other modules.
    """

    def __init__(self, body: MujocoBody, feet: bool = True, crank_of=None, base_fz: float = FOOT_FOLLOW_F_TRG,
                 period: float = RIDER_PERIOD, name: str = "rider", hand_gains: str = "active_arm",
                 foot_gains: str = "active_leg", arms: bool = True):
        super().__init__(name, period)
        self.arms = arms
        self.body, self.feet, self.base_fz = body, feet, base_fz
        self.hand_gains, self.foot_gains = hand_gains, foot_gains
        self.crank_of = crank_of or (lambda snap: float(snap["q:crank"]))
        model = body.model
        key = model.key("ride").id
        self.q_ref = model.key_qpos[key].copy()
        # the reference model: vehicle at the origin, waist seated as in the keyframe
        self.frame = VehicleFrame(body)
        tri = model.joint("tricycle_root").qposadr[0]
        root = model.joint("root").qposadr[0]
        self.tri_adr, self.root_adr = tri, root
        data = mujoco.MjData(model)
        data.qpos[:] = self.q_ref
        mujoco.mj_kinematics(model, data)
        r_v = data.body("tricycle").xmat.reshape(3, 3)
        p_v = data.body("tricycle").xpos.copy()
        self.seat_pos = r_v.T @ (data.body("waist").xpos - p_v)
        self.seat_rot = r_v.T @ data.body("waist").xmat.reshape(3, 3)
        self.hip_point = r_v.T @ (data.site("saddle_top").xpos - p_v)
        self.q_ref[tri:tri + 3] = 0.0
        self.q_ref[tri + 3:tri + 7] = [1, 0, 0, 0]
        self.limbs = [s for s in SIDES for _ in (0,)]
        self.joints = ([j for s in SIDES for j in ARM[s]] if arms else []) + \
            ([j for s in SIDES for j in LEG[s]] if feet else [])
        self.adr = [model.joint(j).qposadr[0] for j in self.joints]
        self.q = self.q_ref[self.adr].copy()
        self.unreachable = 0
        self.theta_h = 0.0
        self.last_solution = None

    def reset(self, snapshot) -> None:
        self.t_last = float(snapshot["t"])
        self.hand_imp = {s: ActiveImpedance(*self._gains(self.hand_gains), self.period) for s in SIDES}
        self.foot_imp = {s: ActiveImpedance(*self._gains(self.foot_gains, fz=0.0), self.period) for s in SIDES}
        self.theta_h = float(snapshot.get("ref:theta_h", 0.0))

    @staticmethod
    def _gains(kind: str, fz: float | None = None):
        g = IMPEDANCE[kind]
        return g.m, g.d, g.k, (0.0, 0.0, 0.0) if fz is None else (0.0, 0.0, fz)

    def waist_pose(self, roll: float, shift: float, lift: float) -> tuple[np.ndarray, np.ndarray]:
        """Reference waist (position, rotation) in the vehicle frame (Eq. 4.9: turned about the hip)."""
        rx = np.array([[1, 0, 0], [0, np.cos(roll), -np.sin(roll)], [0, np.sin(roll), np.cos(roll)]])
        pos = self.hip_point + rx @ (self.seat_pos - self.hip_point) + [0.0, shift, lift]
        return pos, rx @ self.seat_rot

    def forces(self, snapshot, sensor: str) -> np.ndarray:
        return self.frame.rotate_to_vehicle(ft_reaction(self.body, snapshot, sensor)[0])

    def update(self, snapshot):
        t = float(snapshot["t"])
        dt = max(t - self.t_last, 0.0)
        self.t_last = t
        goal = float(snapshot.get("ref:theta_h", 0.0))
        self.theta_h += float(np.clip(goal - self.theta_h, -STEER_RATE * dt, STEER_RATE * dt))
        pos, rot = self.waist_pose(snapshot.get("ref:chest_roll", 0.0), snapshot.get("ref:com_shift", 0.0),
                                   snapshot.get("ref:hip_lift", 0.0))
        q0 = self.q_ref.copy()
        q0[self.adr] = self.q
        q0[self.root_adr:self.root_adr + 3] = pos
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, rot.reshape(-1))
        q0[self.root_adr + 3:self.root_adr + 7] = quat
        targets = {}
        for s, sign in SIDES.items():
            side = "left" if s == "l" else "right"
            xi = self.hand_imp[s].step(grip_plan(self.theta_h, side), self.forces(snapshot, WRIST_FT[s]))
            bar = np.zeros(3)
            mujoco.mju_rotVecQuat(bar, np.array([0.0, 1.0, 0.0]), quat_axis(steer_axis(), self.theta_h))
            if self.arms:
                targets[HAND[s]] = ik.Target(pos=xi, axis=(BAR_IN_HAND, -sign * bar))
            if self.feet:
                imp = self.foot_imp[s]
                imp.f_trg = np.array([0.0, 0.0, self.base_fz + snapshot.get("ref:foot_fz", 0.0)
                                      + snapshot.get(f"ref:foot_fz_{s}", 0.0)])
                xi = imp.step(pedal_position(self.crank_of(snapshot), s), self.forces(snapshot, ANKLE_FT[s]))
                targets[SOLE[s]] = ik.Target(pos=xi, axis=(CRANK_AXIS_IN_SOLE, np.array([0.0, 1.0, 0.0])))
        result = ik.solve(self.body.model, targets, q0, self.joints, max_iter=60)
        if result.ok:
            self.q = result.q[self.adr]
        else:
            self.unreachable += 1
        self.log(t, **{"rider.theta_h": self.theta_h, "rider.ok": float(result.ok)})
        return dict(zip(self.joints, self.q))


class CrankMotor(Module):
    """``drive=motor``: the crank motor's velocity target from ``ref:crank_rate`` (a stand-in for the
    legs, not the thesis's method)."""

    def __init__(self, name: str = "crank_motor"):
        super().__init__(name, CONTROL_PERIOD)

    def update(self, snapshot):
        return {CRANK_MOTOR: float(snapshot.get("ref:crank_rate", 0.0))}


def travel_of_crank(omega: float) -> float:
    """Speed [m/s] of the tricycle for a crank rate ω_c (no slip: D_c ω_c / 2π)."""
    return TRICYCLE.travel_per_rev * omega / (2 * np.pi)


class Freewheel:
    """A ratchet in the rear hub (§4.4.3: back-pedalling "provides no pedalling force", so the
    thesis's tricycle must freewheel backwards): the ``drive`` gear equality lets go when the crank
    turns backwards (faster than ``back_rate``) and takes hold again, at the present relative angle
    (a fine-toothed ratchet), as soon as the crank side turns forward at least as fast as the wheel.
    Installed as an after-step hook of the body; ``engaged`` tells the state, ``releases`` counts
    let-goes.

    Simplification (ours): coasting with the crank held still keeps the gear engaged (only a
    backward crank releases it)."""

    def __init__(self, body: MujocoBody, back_rate: float = 0.05):
        m = body.model
        self.body, self.back_rate = body, back_rate
        self.eq = m.equality("drive").id
        self.ratio = float(m.eq_data[self.eq, 1])
        self.wheel, self.crank = m.joint("rear_l_wheel"), m.joint("crank")
        self.w0, self.c0 = m.qpos0[self.wheel.qposadr[0]], m.qpos0[self.crank.qposadr[0]]
        self.engaged, self.releases = True, 0
        body.after_step.append(self)

    def __call__(self) -> None:
        d = self.body.data
        wheel, crank = d.qpos[self.wheel.qposadr[0]], d.qpos[self.crank.qposadr[0]]
        wheel_vel, crank_vel = d.qvel[self.wheel.dofadr[0]], d.qvel[self.crank.dofadr[0]]
        if self.engaged and crank_vel < -self.back_rate:
            self.engaged = False
            self.releases += 1
            self.body.set_equality("drive", False)
        elif not self.engaged and crank_vel > 0 and self.ratio * crank_vel >= wheel_vel:
            self.body.model.eq_data[self.eq, 0] = (wheel - self.w0) - self.ratio * (crank - self.c0)
            self.engaged = True
            self.body.set_equality("drive", True)
