"""Whole-body Cla: the muscle spine of :mod:`~shintai.spine.bodies_mujoco` with arms, neck and head, and legs,
seated on a stool before a desk or standing (seed 003 §3.6.2, Fig. 3.36; the behaviours of §5.2).

**The spine** is exactly the MuJoCo Cla of :func:`~shintai.spine.bodies_mujoco.build_spec`: five joints of three
hinges each (yaw, pitch, roll; θ of eq. 4.1 is their ``qpos``), the silicone discs, the eight wire muscles on
reels driven by duty (``duty`` channel), tension sensors and encoders, 0.5-ms steps; the raised-arm loads of E11
are replaced by real arms and the head load by a head on a neck. It is commanded as every Cla experiment does
(:mod:`~shintai.spine.cla.control`): :func:`~shintai.spine.cla.control.spine_control` (the §4.6.4 encoder zeroing,
then :class:`~shintai.spine.control.MuscleControl` in L mode) with :class:`~shintai.spine.cla.postures.PostureTargets`,
whose ``goal`` channel takes a uniform-bend posture Θ = (φ, θ, ψ) (whole-spine roll, pitch, yaw, rad; eq. 4.25's
lengths become the length targets).

**Limbs** (§3.6.2: "脚は股関節・膝関節が pitch 軸のみで足首関節が pitch・roll 軸、腕は肩関節が roll・pitch 軸で肘
および手首関節が pitch 軸のみ"): per arm ``shoulder_roll_<s>`` (+ = abduction, away from the body),
``shoulder_pitch_<s>`` (+ = raising the arm forward), ``elbow_<s>`` (+ = flexion), ``wrist_<s>`` (+ = flexion
forward); per leg ``hip_<s>`` (+ = flexion, thigh forward), ``knee_<s>`` (+ = flexion), ``ankle_pitch_<s>``,
``ankle_roll_<s>``; the neck ``neck_yaw`` (+ = look left) and ``neck_pitch`` (+ = look down) (§5.2.10's
pan/tilt). ``<s>`` is ``r`` or ``l``. Every one is a position servo (S9204 software servo, §3.6.2) whose
actuator has the joint's name: a command ``{"elbow_r": 1.2}`` sets its target [rad].

**Sensors** (§3.6.2): the accelerometers ``acc_waist`` (pelvis) and ``acc_chest`` (clavicle, the shoulders;
eq. 3.4's posture is the snapshot's ``posture``), four FSRs per foot at the sole's corners (touch sensors
``fsr_<s>1..4``; the centre of pressure of eq. 3.5 is the snapshot's ``cop``), the head camera ``head_cam``
(its viewing direction is the sensor ``gaze``, a unit vector in the world), the hands' positions
``hand_r_pos``/``hand_l_pos``.

**Seated** (§5.2.1: "足が地面に着かない程度の高さの椅子に座り"): the pelvis is fixed on the stool (the pedestal
and a seat), thighs forward, feet off the floor; a desk in front (:data:`~shintai.spine.robots.CLA_DESK_HEIGHT_M`)
with free objects. **Standing**: the pelvis is free (joint ``root``) on the legs; the feet touch the floor only
through their four corner spheres, under the FSRs.

**The spine lock** (the thesis's "without the spine", Figs. 5.4 and 5.6): an equality per spine hinge
(``lock_j<i>_<axis>``) holds it at the angle it has when :meth:`ClaBody.lock_spine` is called (or the
``spine_lock`` channel turns on).

**Grips**: a weld per hand and object (``grip_<s>_<object>``), off at start; :meth:`ClaBody.grip` welds the
object to the hand where it is now (a hand that closes on it), and lets go.
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.core.runtime import SET, declare
from shintai.sim.spec import add_capsule, add_hinge, add_position_actuator
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.bodies_mujoco import build_spec as build_spine
from shintai.spine.cla.constants import CORNER_RADIUS_M, FSR_CORNERS, ROBOT, SEAT_KP, SEAT_KV, SEAT_TORQUE_NM, WORLD
from shintai.spine.robots import (
    CLA,
    CLA_ARM_KG,
    CLA_DESK_HALF_M,
    CLA_DESK_HEIGHT_M,
    CLA_DESK_NEAR_M,
    CLA_FOOT_HALF_M,
    CLA_FOREARM_M,
    CLA_FOV_DEG,
    CLA_FRICTION,
    CLA_HAND_M,
    CLA_HAND_RADIUS_M,
    CLA_HEAD_KG,
    CLA_HEAD_RADIUS_M,
    CLA_HIP_M,
    CLA_JOINTS,
    CLA_LEG_KG,
    CLA_NECK_M,
    CLA_NECK_TORQUE_NM,
    CLA_OBJECT_HALF_M,
    CLA_OBJECT_KG,
    CLA_PELVIS_KG,
    CLA_SEAT_HALF_M,
    CLA_SEAT_HEIGHT_M,
    CLA_SHANK_M,
    CLA_SHOULDER_M,
    CLA_THIGH_M,
    CLA_TIMESTEP_S,
    CLA_TRUNK_LOADS,
    CLA_UPPER_ARM_M,
    CRAWL_LIMB_KP,
    CRAWL_LIMB_KV,
    CRAWL_LIMB_TORQUE_NM,
    PELVIS_HEIGHT_M,
)

POSTURES = ("seated", "standing")
SIDES = ("r", "l")
AXES = ("yaw", "pitch", "roll")
SPINE_JOINTS = tuple(f"j{i + 1}_{a}" for i in range(CLA_JOINTS) for a in AXES)
ARM_JOINTS = ("shoulder_roll", "shoulder_pitch", "elbow", "wrist")
LEG_JOINTS = ("hip", "knee", "ankle_pitch", "ankle_roll")
NECK_JOINTS = ("neck_yaw", "neck_pitch")
LIMB_JOINTS = tuple(f"{j}_{s}" for s in SIDES for j in ARM_JOINTS + LEG_JOINTS) + NECK_JOINTS
OBJECTS = ("desk_object", "floor_object")  # free objects of the seated scene
# The seated start: thighs forward (hip 90°), shanks down, arms hanging a little forward (chosen)
SEATED_POSE = {"hip": 1.5708, "knee": 1.5708, "shoulder_pitch": 0.0, "elbow": 0.3}
STAND_HEIGHT_M = -CLA_HIP_M[2] + CLA_THIGH_M + CLA_SHANK_M + 2 * CLA_FOOT_HALF_M[2]  # pelvis origin above floor
LIMB_ROLL_AXIS = {"r": [-1.0, 0.0, 0.0], "l": [1.0, 0.0, 0.0]}  # + = outward for both sides


def _sign(side: str) -> float:
    return -1.0 if side == "r" else 1.0


def _hinge(body, name: str, axis, lo: float, hi: float) -> None:
    add_hinge(body, name, axis, (lo, hi), armature=1e-4, damping=0.02)


def build_spec(posture: str = "seated", desk: bool = True, seat_tilt: bool = False) -> mujoco.MjSpec:
    """Whole-body Cla (module docstring), ``posture`` "seated" (on a stool; ``desk``: a desk and objects in
    front) or "standing" (free on the floor). ``seat_tilt`` (seated): the seat tilts with the pelvis on two
    hinges at the seat's top, ``seat_roll`` (+ = to the right) and ``seat_pitch`` (+ = forward), each driven by a
    stiff position actuator of the same name (the experimenter tilting the chair, §5.2.2's disturbance)."""
    if posture not in POSTURES:
        raise ValueError(f"posture must be one of {POSTURES}, got {posture!r}")
    spec = build_spine(CLA, loads=CLA_TRUNK_LOADS[:1], joint="hinge", interference=True, timestep=CLA_TIMESTEP_S)
    spec.modelname = f"cla_{posture}"
    spec.visual.global_.fovy = 45.0
    spec.delete(spec.geom("ground"))
    world = spec.worldbody
    spec.add_texture(name="grid", type=mujoco.mjtTexture.mjTEXTURE_2D, builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER,
                     rgb1=[0.85, 0.85, 0.87], rgb2=[0.72, 0.73, 0.76], width=256, height=256)
    spec.add_material(name="grid", textures=["", "grid"], texrepeat=[10, 10], texuniform=True)  # 10-cm squares
    world.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[3, 3, 0.05], material="grid",
                   contype=0, conaffinity=WORLD, friction=[CLA_FRICTION, 0.005, 1e-4])
    pelvis = spec.body("link0")
    pelvis.add_geom(name="pelvis_mass", type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.035, 0.06, 0.015],
                    pos=[0, 0, -0.03], mass=CLA_PELVIS_KG, rgba=[0.45, 0.45, 0.5, 1], contype=0, conaffinity=0)
    if posture == "standing":
        spec.delete(spec.geom("pedestal"))
        pelvis.pos = [0, 0, STAND_HEIGHT_M + 0.002]
        pelvis.add_freejoint(name="root")
    else:
        seat_top = CLA_SEAT_HEIGHT_M - PELVIS_HEIGHT_M  # in the pelvis frame
        holder = pelvis if seat_tilt else world
        holder.add_geom(name="seat", type=mujoco.mjtGeom.mjGEOM_BOX, size=[*CLA_SEAT_HALF_M, 0.012],
                        pos=[-0.02, 0, (seat_top if seat_tilt else CLA_SEAT_HEIGHT_M) - 0.012],
                        rgba=[0.55, 0.4, 0.3, 1], contype=0, conaffinity=WORLD)
        if seat_tilt:
            for name, axis in (("seat_roll", [1, 0, 0]), ("seat_pitch", [0, 1, 0])):
                pelvis.add_joint(name=name, type=mujoco.mjtJoint.mjJNT_HINGE, axis=axis, pos=[0, 0, seat_top],
                                 range=[-0.6, 0.6], limited=True, damping=1.0, armature=0.01)
    _add_arms(spec)
    _add_head(spec)
    _add_legs(spec)
    for joint in LIMB_JOINTS:
        limit = CLA_NECK_TORQUE_NM if joint.startswith("neck") else CRAWL_LIMB_TORQUE_NM
        add_position_actuator(spec, joint, CRAWL_LIMB_KP, CRAWL_LIMB_KV, limit)
    if posture == "seated" and seat_tilt:
        for joint in ("seat_roll", "seat_pitch"):
            add_position_actuator(spec, joint, SEAT_KP, SEAT_KV, SEAT_TORQUE_NM)
    for joint in SPINE_JOINTS:
        spec.add_equality(name=f"lock_{joint}", type=mujoco.mjtEq.mjEQ_JOINT, name1=joint, active=False,
                          solref=[0.001, 1.0], solimp=[0.9999, 0.9999, 0.001, 0.5, 2])
    objects = ()
    if posture == "seated" and desk:
        objects = _add_scene(spec)
    for obj in objects:
        for side in SIDES:
            spec.add_equality(name=f"grip_{side}_{obj}", type=mujoco.mjtEq.mjEQ_WELD, name1=f"hand_{side}",
                              name2=obj, objtype=mujoco.mjtObj.mjOBJ_BODY, active=False, solref=[0.01, 1.0])
    _add_sensors(spec)
    _add_key(spec, posture)
    return spec


def _add_arms(spec) -> None:
    clav, limb = spec.body(f"link{CLA_JOINTS}"), [0.55, 0.6, 0.75, 1]
    sx, sy, sz = CLA_SHOULDER_M
    for side in SIDES:
        s = _sign(side)
        upper = clav.add_body(name=f"upper_arm_{side}", pos=[sx, s * sy, sz])
        _hinge(upper, f"shoulder_roll_{side}", LIMB_ROLL_AXIS[side], -0.3, 2.6)
        _hinge(upper, f"shoulder_pitch_{side}", [0, -1, 0], -1.0, 3.1)
        add_capsule(upper, [0, 0, -CLA_UPPER_ARM_M], 0.013, CLA_ARM_KG[0], limb)
        fore = upper.add_body(name=f"forearm_{side}", pos=[0, 0, -CLA_UPPER_ARM_M])
        _hinge(fore, f"elbow_{side}", [0, -1, 0], 0.0, 2.6)
        add_capsule(fore, [0, 0, -CLA_FOREARM_M], 0.011, CLA_ARM_KG[1], limb)
        hand = fore.add_body(name=f"hand_{side}", pos=[0, 0, -CLA_FOREARM_M])
        _hinge(hand, f"wrist_{side}", [0, -1, 0], -1.5, 1.5)
        hand.add_geom(name=f"hand_{side}", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[CLA_HAND_RADIUS_M],
                      pos=[0, 0, -CLA_HAND_M], mass=CLA_ARM_KG[2], rgba=[0.95, 0.8, 0.65, 1], contype=ROBOT,
                      conaffinity=0, friction=[CLA_FRICTION, 0.005, 1e-4], condim=4)
        hand.add_site(name=f"hand_{side}", pos=[0, 0, -CLA_HAND_M], size=[0.004, 0, 0])


def _add_head(spec) -> None:
    clav = spec.body(f"link{CLA_JOINTS}")
    head = clav.add_body(name="head", pos=[0, 0, CLA_NECK_M])
    _hinge(head, "neck_yaw", [0, 0, 1], -1.5, 1.5)
    _hinge(head, "neck_pitch", [0, 1, 0], -0.8, 1.0)
    clav.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, fromto=[0, 0, 0.02, 0, 0, CLA_NECK_M], size=[0.01, 0, 0],
                  mass=0.0, rgba=[0.45, 0.45, 0.5, 1], contype=0, conaffinity=0)
    head.add_geom(name="head", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[CLA_HEAD_RADIUS_M],
                  pos=[0, 0, CLA_HEAD_RADIUS_M], mass=CLA_HEAD_KG, rgba=[0.9, 0.9, 0.92, 1], contype=0, conaffinity=0)
    for y in (-0.018, 0.018):  # the two CCD cameras' lenses (§3.6.2), for the picture
        head.add_geom(type=mujoco.mjtGeom.mjGEOM_CYLINDER, size=[0.007, 0.004], pos=[CLA_HEAD_RADIUS_M, y,
                      CLA_HEAD_RADIUS_M], quat=[0.7071, 0, 0.7071, 0], mass=0.0, rgba=[0.1, 0.1, 0.1, 1],
                      contype=0, conaffinity=0)
    eye = [CLA_HEAD_RADIUS_M + 0.005, 0, CLA_HEAD_RADIUS_M]
    head.add_site(name="gaze", pos=eye, size=[0.003, 0, 0])  # x axis = the camera's viewing direction
    head.add_camera(name="head_cam", pos=eye, xyaxes=[0, -1, 0, 0, 0, 1], fovy=CLA_FOV_DEG)


def _add_legs(spec) -> None:
    pelvis, limb = spec.body("link0"), [0.55, 0.6, 0.75, 1]
    hx, hy, hz = CLA_HIP_M
    fx, fy, fz = CLA_FOOT_HALF_M
    for side in SIDES:
        s = _sign(side)
        thigh = pelvis.add_body(name=f"thigh_{side}", pos=[hx, s * hy, hz])
        _hinge(thigh, f"hip_{side}", [0, -1, 0], -1.0, 2.2)
        add_capsule(thigh, [0, 0, -CLA_THIGH_M], 0.018, CLA_LEG_KG[0], limb)
        shank = thigh.add_body(name=f"shank_{side}", pos=[0, 0, -CLA_THIGH_M])
        _hinge(shank, f"knee_{side}", [0, 1, 0], 0.0, 2.6)
        add_capsule(shank, [0, 0, -CLA_SHANK_M], 0.015, CLA_LEG_KG[1], limb)
        foot = shank.add_body(name=f"foot_{side}", pos=[0, 0, -CLA_SHANK_M])
        _hinge(foot, f"ankle_pitch_{side}", [0, -1, 0], -0.8, 0.8)
        _hinge(foot, f"ankle_roll_{side}", LIMB_ROLL_AXIS[side], -0.5, 0.5)
        foot.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[fx, fy, fz - 0.003], pos=[0.015, 0, -fz],
                      mass=CLA_LEG_KG[2], rgba=limb, contype=0, conaffinity=0)
        for k, (cx, cy) in enumerate(FSR_CORNERS):
            at = [0.015 + cx * (fx - CORNER_RADIUS_M), cy * (fy - CORNER_RADIUS_M), -2 * fz + CORNER_RADIUS_M]
            foot.add_geom(name=f"sole_{side}{k + 1}", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[CORNER_RADIUS_M],
                          pos=at, mass=0.0, rgba=[0.3, 0.3, 0.3, 1], contype=ROBOT, conaffinity=0,
                          friction=[CLA_FRICTION, 0.005, 1e-4])
            foot.add_site(name=f"fsr_{side}{k + 1}", pos=at, size=[1.6 * CORNER_RADIUS_M, 0, 0],
                          rgba=[0.9, 0.3, 0.2, 0.4])


def _add_scene(spec) -> tuple[str, ...]:
    """The desk (a top on four legs) and the free objects: ``desk_object`` on the desk in front of the right
    arm, ``floor_object`` on the floor to Cla's right (the scenarios move them with :meth:`ClaBody.place`)."""
    world, wood = spec.worldbody, [0.7, 0.55, 0.35, 1]
    dx, dy = CLA_DESK_HALF_M
    cx = CLA_DESK_NEAR_M + dx
    world.add_geom(name="desk", type=mujoco.mjtGeom.mjGEOM_BOX, size=[dx, dy, 0.01],
                   pos=[cx, 0, CLA_DESK_HEIGHT_M - 0.01], rgba=wood, contype=0, conaffinity=WORLD,
                   friction=[CLA_FRICTION, 0.005, 1e-4])
    for ex in (-1, 1):
        for ey in (-1, 1):
            world.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.01, 0.01, (CLA_DESK_HEIGHT_M - 0.02) / 2],
                           pos=[cx + ex * (dx - 0.02), ey * (dy - 0.02), (CLA_DESK_HEIGHT_M - 0.02) / 2],
                           rgba=wood, contype=0, conaffinity=0)
    h = CLA_OBJECT_HALF_M
    where = {"desk_object": [CLA_DESK_NEAR_M + 0.15, -CLA_SHOULDER_M[1], CLA_DESK_HEIGHT_M + h],
             "floor_object": [0.05, -0.22, h]}
    colour = {"desk_object": [0.85, 0.3, 0.25, 1], "floor_object": [0.25, 0.55, 0.85, 1]}
    for name in OBJECTS:
        body = world.add_body(name=name, pos=where[name])
        body.add_freejoint(name=name)
        body.add_geom(name=name, type=mujoco.mjtGeom.mjGEOM_BOX, size=[h, h, h], mass=CLA_OBJECT_KG,
                      rgba=colour[name], contype=WORLD, conaffinity=WORLD | ROBOT,
                      friction=[CLA_FRICTION, 0.005, 1e-4], condim=4)
    return OBJECTS


def _add_sensors(spec) -> None:
    for side in SIDES:
        for k in range(len(FSR_CORNERS)):
            spec.add_sensor(name=f"fsr_{side}{k + 1}", type=mujoco.mjtSensor.mjSENS_TOUCH,
                            objtype=mujoco.mjtObj.mjOBJ_SITE, objname=f"fsr_{side}{k + 1}")
        spec.add_sensor(name=f"hand_{side}_pos", type=mujoco.mjtSensor.mjSENS_FRAMEPOS,
                        objtype=mujoco.mjtObj.mjOBJ_SITE, objname=f"hand_{side}")
    spec.add_sensor(name="gaze", type=mujoco.mjtSensor.mjSENS_FRAMEXAXIS, objtype=mujoco.mjtObj.mjOBJ_SITE,
                    objname="gaze")


def start_targets(posture: str) -> dict[str, float]:
    """The limb servos' targets at the start of ``posture`` (every limb joint named; the rest at 0)."""
    targets = dict.fromkeys(LIMB_JOINTS, 0.0)
    if posture == "seated":
        for side in SIDES:
            for joint in ("hip", "knee", "shoulder_pitch", "elbow"):
                targets[f"{joint}_{side}"] = SEATED_POSE[joint]
    return targets


def _add_key(spec, posture: str) -> None:
    m = spec.compile()
    d = mujoco.MjData(m)
    for joint, q in start_targets(posture).items():
        d.qpos[m.jnt_qposadr[m.joint(joint).id]] = q
        d.ctrl[m.actuator(joint).id] = q
    spec.add_key(name=posture, qpos=d.qpos.tolist(), ctrl=d.ctrl.tolist())


class ClaBody(SpineBody):
    """The whole-body Cla (module docstring) as a :class:`~shintai.spine.bodies_mujoco.SpineBody`, started at
    the keyframe of its posture. Snapshot adds to SpineBody's: ``cop`` (2,) the centre of pressure of both
    feet (eq. 3.5, world x, y [m]; NaN when no FSR is loaded), ``cop_r``/``cop_l`` (2,) per foot,
    ``sole_force`` (8,) the FSRs [N] (r1..r4, l1..l4), ``spine_locked`` (bool); every named sensor
    (``fsr_*``, ``hand_r_pos``, ``hand_l_pos``, ``gaze``, ``acc_chest``, ``acc_waist``) as MujocoBody does."""

    def __init__(self, posture: str = "seated", desk: bool = True, control_period: float | None = None,
                 seat_tilt: bool = False, spec: mujoco.MjSpec | None = None):
        # spec: a build_spec(posture, …) its user edited (e.g. the floor's height), instead of building one
        super().__init__(CLA, timestep=CLA_TIMESTEP_S, control_period=control_period,
                         spec=spec if spec is not None else build_spec(posture, desk, seat_tilt))
        self.posture = posture
        m = self.model
        self._locks = np.array([self.id("equality", f"lock_{j}") for j in SPINE_JOINTS])
        self._lock_q = m.jnt_qposadr[[self.id("joint", j) for j in SPINE_JOINTS]]
        self._fsr_sites = np.array([self.id("site", f"fsr_{s}{k + 1}") for s in SIDES for k in range(4)])
        self._fsr_cols = np.array([m.sensor_adr[self.id("sensor", f"fsr_{s}{k + 1}")] for s in SIDES
                                   for k in range(4)])
        self.objects = tuple(o for o in OBJECTS if mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, o) >= 0)
        self.channels = {**self.channels, **declare("spine_lock", kind=SET)}
        self.reset(posture)
        mujoco.mj_forward(m, self.data)

    def apply(self, command) -> None:
        """SpineBody's channels, and ``spine_lock`` (set): the spine locked where it is when it turns on."""
        command = dict(command)
        lock = command.pop("spine_lock", None)
        if lock is not None and bool(lock) != self.spine_locked:
            self.lock_spine(bool(lock))
        super().apply(command)

    # -- the spine lock ---------------------------------------------------------------------------------

    def lock_spine(self, on: bool = True) -> None:
        """Lock every spine hinge at its present angle (equality constraints), or free them."""
        if on:
            self.model.eq_data[self._locks, 0] = self.data.qpos[self._lock_q]
            self.model.eq_data[self._locks, 1:5] = 0.0
        self.data.eq_active[self._locks] = bool(on)

    @property
    def spine_locked(self) -> bool:
        return bool(self.data.eq_active[self._locks].all())

    # -- objects ----------------------------------------------------------------------------------------

    def place(self, obj: str, pos) -> None:
        """Put a free object at ``pos`` (world, its centre), at rest, upright."""
        adr = self.model.jnt_qposadr[self.id("joint", obj)]
        self.data.qpos[adr:adr + 7] = [*pos, 1.0, 0.0, 0.0, 0.0]
        self.data.qvel[self.model.jnt_dofadr[self.id("joint", obj)]:][:6] = 0.0
        self.forward()

    def object_pos(self, obj: str) -> np.ndarray:
        return self.body_pos(obj)

    def grip(self, side: str, obj: str, on: bool = True) -> None:
        """Weld ``obj`` to hand ``side`` where it is relative to the hand now (on), or let go (off)."""
        eq = self.id("equality", f"grip_{side}_{obj}")
        if on:
            d, b1, b2 = self.data, self.id("body", f"hand_{side}"), self.id("body", obj)
            R1 = d.xmat[b1].reshape(3, 3)
            rel = R1.T @ (d.xpos[b2] - d.xpos[b1])
            q1inv, q = np.zeros(4), np.zeros(4)
            mujoco.mju_negQuat(q1inv, d.xquat[b1])
            mujoco.mju_mulQuat(q, q1inv, d.xquat[b2])
            self.model.eq_data[eq, :3] = 0.0
            self.model.eq_data[eq, 3:6] = rel
            self.model.eq_data[eq, 6:10] = q
            self.model.eq_data[eq, 10] = 1.0
        self.data.eq_active[eq] = bool(on)

    # -- sensors ----------------------------------------------------------------------------------------

    def sole_forces(self) -> np.ndarray:
        """The eight FSRs [N] (r1..r4, l1..l4; corners :data:`FSR_CORNERS`)."""
        return self.data.sensordata[self._fsr_cols].copy()

    def cop(self, forces=None) -> dict[str, np.ndarray]:
        """Eq. 3.5, p_z = Σ f_i p_i / Σ f_i, with p_i the FSR sites (world x, y), per foot and for both."""
        f = self.sole_forces() if forces is None else np.asarray(forces, dtype=float)
        p = self.data.site_xpos[self._fsr_sites, :2]
        out = {}
        for key, sel in (("cop_r", slice(0, 4)), ("cop_l", slice(4, 8)), ("cop", slice(0, 8))):
            total = f[sel].sum()
            out[key] = (f[sel] @ p[sel]) / total if total > 1e-6 else np.full(2, np.nan)
        return out

    def gaze(self) -> np.ndarray:
        """The head camera's viewing direction (world unit vector)."""
        return self.data.site_xmat[self.id("site", "gaze")].reshape(3, 3)[:, 0].copy()

    def snapshot(self):
        snap = super().snapshot()
        f = self.sole_forces()
        snap["sole_force"] = f
        snap.update(self.cop(f))
        snap["spine_locked"] = self.spine_locked
        return snap


__all__ = ["ClaBody", "build_spec", "start_targets",
           "LIMB_JOINTS", "SPINE_JOINTS", "OBJECTS", "POSTURES", "PELVIS_HEIGHT_M"]
