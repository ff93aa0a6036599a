"""An HRP2-JSK-like humanoid, built in code with MjSpec (seed 000 App. A.2.1, Tables A.1/A.2).

32 joints (Table A.1): per arm shoulder pitch/roll/yaw, elbow pitch, wrist yaw/roll/pitch and the
1-DoF gripper (8 × 2), per leg hip yaw/roll/pitch, knee pitch, ankle pitch/roll (6 × 2), waist
yaw/pitch, neck yaw/pitch; 56.5 kg in all. Joint ranges and torque limits are Table A.2's
(:mod:`shintai.humanoid.constants`); link lengths and masses are chosen there
(:class:`~shintai.humanoid.constants.Hrp2Links`, ``HRP2_MASSES``) since the thesis has none.

Each joint has a position servo named like the joint (the hrpsys joint servo, run at the 4 ms
control period): stiffness = max torque / 0.05 rad, critically damped, force clipped to the Table
A.2 torque. The root is a free joint ``root`` on the body ``waist``.

Names (``s`` is ``l`` or ``r``):

=============  ==================================================================================
joints/servos  ``s_shoulder_pitch``, ``s_shoulder_roll``, ``s_shoulder_yaw``, ``s_elbow_pitch``,
               ``s_wrist_yaw``, ``s_wrist_roll``, ``s_wrist_pitch``, ``s_gripper``, ``s_hip_yaw``,
               ``s_hip_roll``, ``s_hip_pitch``, ``s_knee_pitch``, ``s_ankle_pitch``,
               ``s_ankle_roll``, ``waist_yaw``, ``waist_pitch``, ``neck_yaw``, ``neck_pitch``
bodies         ``waist`` (pelvis, root), ``chest``, ``head``, ``s_hand``, ``s_foot`` and one
               body per joint (``s_thigh``, ``s_shank``, ``s_forearm``, …)
sites          ``s_wrist_ft``/``s_ankle_ft`` (F/T sensor frames), ``s_grasp`` (grasp centre,
               0.10 m beyond the wrist; its x axis is the axis of a grasped bar), ``s_sole``
               (sole, under the ankle axis, foot frame), ``imu`` (chest), ``head_camera`` (depth
               sensor origin on the head's face, x forward; :mod:`shintai.humanoid.tricycle.navigation`)
sensors        ``s_wrist_force``/``s_wrist_torque``, ``s_ankle_force``/``s_ankle_torque``: what
               the hand/foot receives from its parent link, in the site frame (see
               :func:`shintai.humanoid.add_ft_sensor` and :func:`ft_reaction`); ``imu_quat``
               (framequat), ``imu_gyro``, ``imu_acc`` (accelerometer; +g up when still)
keyframe       ``stand`` (in :func:`build_hrp2`): standing on the floor, knees bent
=============  ==================================================================================

Sign convention: see :mod:`shintai.humanoid.constants` (pitch +y, roll +x, yaw +z; forward hip,
shoulder, elbow, ankle pitch negative). The grippers are thumb *roll* joints, mirrored like the
other roll joints: the right gripper opens toward +, the left toward −.
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.core.geometry import cross3
from shintai.humanoid.constants import (
    ARMATURE_BIG,
    ARMATURE_SMALL,
    ARMATURE_SPLIT,
    ARM_JOINTS,
    BLUE,
    GREY,
    HRP2_LINKS,
    HRP2_MASSES,
    LEG_JOINTS,
    NECK_JOINTS,
    SCENE,
    SERVO_DAMPRATIO,
    SERVO_SATURATION_ERROR,
    SOLE,
    STANDING_POSTURE,
    SUBSTEPS,
    WAIST_JOINTS,
    WHITE,
    Hrp2Links,
    JointSpec,
    joint_range,
)
from shintai.sim.body import MujocoBody
from shintai.sim.spec import (
    add_ft_sensor,
    add_hinge,
    add_servo,
    add_visual,
    axis_vector,
    fill_keyframe,
    scene_spec,
    set_joints,
)

SIDES = {"l": 1.0, "r": -1.0}  # y sign of each limb
CAPSULE, BOX, SPHERE = mujoco.mjtGeom.mjGEOM_CAPSULE, mujoco.mjtGeom.mjGEOM_BOX, mujoco.mjtGeom.mjGEOM_SPHERE

ARM = [f"{s}_{j.name}" for s in SIDES for j in ARM_JOINTS]
LEG = [f"{s}_{j.name}" for s in SIDES for j in LEG_JOINTS]
TORSO = [j.name for j in WAIST_JOINTS + NECK_JOINTS]
JOINTS = tuple(LEG + TORSO + ARM)  # the 32 joints of Table A.1
ANKLE_FT_SITE = {s: f"{s}_ankle_ft" for s in SIDES}
WRIST_FT_SITE = {s: f"{s}_wrist_ft" for s in SIDES}


def _joint(spec, body, spec_row: JointSpec, side: str = "") -> str:
    """Hinge + servo for one Table A.2 row, on ``body`` (side "", "l" or "r")."""
    name = f"{side}_{spec_row.name}" if side else spec_row.name
    armature = ARMATURE_BIG if spec_row.torque >= ARMATURE_SPLIT else ARMATURE_SMALL
    add_hinge(body, name, axis_vector(spec_row.axis), joint_range(spec_row, side), armature=armature)
    add_servo(spec, name, spec_row.torque / SERVO_SATURATION_ERROR, spec_row.torque, SERVO_DAMPRATIO)
    return name


def _chain(spec, parent, rows, names, side, pos):
    """Nested bodies ``names`` at ``pos`` in ``parent``, one Table A.2 joint each, the axes meeting
    at one point (hip, shoulder, wrist, ankle, waist, neck); returns the bodies."""
    bodies = []
    for row, name in zip(rows, names):
        body = parent.add_body(name=f"{side}_{name}" if side else name, pos=pos)
        _joint(spec, body, row, side)
        bodies.append(body)
        parent, pos = body, [0, 0, 0]
    return bodies


def _add_leg(spec, waist, side: str, links: Hrp2Links) -> None:
    s = SIDES[side]
    m = HRP2_MASSES
    yaw, roll, thigh = _chain(spec, waist, LEG_JOINTS[:3], ("hip_yaw_link", "hip_roll_link", "thigh"), side,
                              [0, s * links.hip_y, links.hip_z])
    add_visual(yaw, SPHERE, [0.055], GREY, m["hip_yaw_link"], pos=[0, 0, 0.03])
    add_visual(roll, CAPSULE, [0.05], BLUE, m["hip_roll_link"], fromto=[-0.06, 0, 0, 0.06, 0, 0])
    add_visual(thigh, CAPSULE, [0.065], WHITE, m["thigh"], fromto=[0, 0, -0.03, 0, 0, -links.thigh + 0.03])
    shank = thigh.add_body(name=f"{side}_shank", pos=[0, 0, -links.thigh])
    _joint(spec, shank, LEG_JOINTS[3], side)
    add_visual(shank, CAPSULE, [0.055], WHITE, m["shank"], fromto=[0, 0, 0, 0, 0, -links.shank + 0.04])
    ankle, foot = _chain(spec, shank, LEG_JOINTS[4:], ("ankle_link", "foot"), side, [0, 0, -links.shank])
    add_visual(ankle, SPHERE, [0.045], GREY, m["ankle_link"])
    h = links.ankle_height
    foot.add_geom(name=f"{side}_sole", type=BOX, size=[links.foot_length / 2, links.foot_width / 2, 0.0125],
                  pos=[links.foot_forward, s * links.foot_outward, -h + 0.0125], rgba=BLUE, mass=m["foot"],
                  contype=SOLE, conaffinity=0)
    add_visual(foot, BOX, [0.06, 0.05, 0.035], WHITE, pos=[0, 0, -0.06])
    foot.add_site(name=ANKLE_FT_SITE[side], pos=[0, 0, -links.ankle_ft])
    foot.add_site(name=f"{side}_sole", pos=[0, 0, -h])
    add_ft_sensor(spec, ANKLE_FT_SITE[side], f"{side}_ankle")


def _add_arm(spec, chest, side: str, links: Hrp2Links) -> None:
    s = SIDES[side]
    m = HRP2_MASSES
    pitch, roll, upper = _chain(spec, chest, ARM_JOINTS[:3], ("shoulder_pitch_link", "shoulder_roll_link", "upper_arm"),
                                side, [0, s * links.shoulder_y, links.shoulder_z])
    add_visual(pitch, SPHERE, [0.065], BLUE, m["shoulder_pitch_link"])
    add_visual(roll, CAPSULE, [0.05], WHITE, m["shoulder_roll_link"], fromto=[0, 0, 0, 0, 0, -0.06])
    add_visual(upper, CAPSULE, [0.055], WHITE, m["upper_arm"], fromto=[0, 0, -0.06, 0, 0, -links.upper_arm + 0.03])
    forearm = upper.add_body(name=f"{side}_forearm", pos=[0, 0, -links.upper_arm])
    _joint(spec, forearm, ARM_JOINTS[3], side)
    add_visual(forearm, CAPSULE, [0.045], WHITE, m["forearm"], fromto=[0, 0, 0, 0, 0, -links.forearm + 0.03])
    wyaw, wroll, hand = _chain(spec, forearm, ARM_JOINTS[4:7], ("wrist_yaw_link", "wrist_roll_link", "hand"), side,
                               [0, 0, -links.forearm])
    add_visual(wyaw, SPHERE, [0.035], GREY, m["wrist_yaw_link"])
    add_visual(wroll, SPHERE, [0.03], GREY, m["wrist_roll_link"])
    add_visual(hand, BOX, [0.025, 0.035, 0.05], GREY, m["hand"], pos=[0, -s * 0.01, -0.07])
    hand.add_site(name=WRIST_FT_SITE[side], pos=[0, 0, -links.wrist_ft])
    hand.add_site(name=f"{side}_grasp", pos=[0, 0, -links.hand])
    add_ft_sensor(spec, WRIST_FT_SITE[side], f"{side}_wrist")
    thumb = hand.add_body(name=f"{side}_thumb", pos=[0, s * 0.03, -0.05])
    _joint(spec, thumb, ARM_JOINTS[7], side)
    add_visual(thumb, BOX, [0.012, 0.008, 0.04], BLUE, m["thumb"], pos=[0, 0, -0.04])


def add_hrp2(spec: mujoco.MjSpec, parent, pos, links: Hrp2Links = HRP2_LINKS):
    """Add the humanoid under ``parent`` with its waist origin at ``pos`` (free root joint ``root``).

    Returns the ``waist`` body. Standing straight at zero posture the soles are 0.78 m below it.
    """
    m = HRP2_MASSES
    waist = parent.add_body(name="waist", pos=list(pos))
    waist.add_freejoint(name="root")
    add_visual(waist, BOX, [0.11, 0.14, 0.09], GREY, m["waist"], pos=[-0.01, 0, 0.09 - links.hip_cover])
    yaw, chest = _chain(spec, waist, WAIST_JOINTS, ("chest_yaw_link", "chest"), "", [0, 0, links.waist_z])
    add_visual(yaw, CAPSULE, [0.07], GREY, m["chest_yaw_link"], fromto=[0, 0, -0.05, 0, 0, 0.05])
    half_depth = links.chest_depth / 2 - 0.04
    add_visual(chest, BOX, [half_depth, 0.16, 0.19], WHITE, m["chest"], pos=[-0.02, 0, 0.27])
    add_visual(chest, BOX, [0.04, 0.10, 0.10], GREY, pos=[-0.02 - half_depth - 0.04, 0, 0.28])  # ZBOX (§A.2.1)
    add_visual(chest, BOX, [0.05, 0.26, 0.04], BLUE, pos=[-0.01, 0, links.shoulder_z])
    chest.add_site(name="imu", pos=[0, 0, links.imu_z])
    neck, head = _chain(spec, chest, NECK_JOINTS, ("neck_yaw_link", "head"), "", [0, 0, links.neck_z])
    add_visual(neck, CAPSULE, [0.035], GREY, m["neck_yaw_link"], fromto=[0, 0, -0.09, 0, 0, 0.0])
    add_visual(head, BOX, [0.09, 0.08, links.head_top / 2], WHITE, m["head"], pos=[0.01, 0, links.head_top / 2])
    add_visual(head, BOX, [0.03, 0.09, 0.03], GREY, pos=[0.09, 0, links.head_top / 2 + 0.02])  # MultiSense face
    # Depth-sensor origin of the head stereo camera (MultiSense S7, §A.2.1, §4.4.2); x forward.
    head.add_site(name="head_camera", pos=[0.12, 0, links.head_top / 2 + 0.02])
    for side in SIDES:
        _add_leg(spec, waist, side, links)
        _add_arm(spec, chest, side, links)
    kinds = (mujoco.mjtSensor.mjSENS_FRAMEQUAT, mujoco.mjtSensor.mjSENS_GYRO, mujoco.mjtSensor.mjSENS_ACCELEROMETER)
    for name, kind in zip(("imu_quat", "imu_gyro", "imu_acc"), kinds):
        spec.add_sensor(name=name, type=kind, objtype=mujoco.mjtObj.mjOBJ_SITE, objname="imu")
    return waist


def side_posture(per_side: dict[str, float]) -> dict[str, float]:
    """Joint values of both limbs from one limb's (left signs: roll, yaw and gripper mirror)."""
    return {f"{side}_{joint}": value * (s if joint.endswith(("roll", "yaw", "gripper")) else 1.0)
            for side, s in SIDES.items() for joint, value in per_side.items()}


def build_hrp2(links: Hrp2Links = HRP2_LINKS, substeps: int = SUBSTEPS) -> MujocoBody:
    """The humanoid standing on the floor (keyframe ``stand``), one body step = 4 ms."""
    spec = scene_spec("hrp2-jsk", *SCENE)
    add_hrp2(spec, spec.worldbody, [0, 0, 1.0], links)
    spec.add_key(name="stand")
    model = spec.compile()
    qpos = model.qpos0.copy()
    posture = side_posture(STANDING_POSTURE)
    set_joints(model, qpos, posture)
    hip, knee = posture["l_hip_pitch"], posture["l_knee_pitch"]
    leg = links.thigh * np.cos(hip) + links.shank * np.cos(hip + knee)
    qpos[:3] = [0, 0, -links.hip_z + leg + links.ankle_height]
    fill_keyframe(model, "stand", qpos)
    return MujocoBody(model, substeps=substeps, keyframe="stand", spec=spec)


def ft_reaction(body: MujocoBody, snapshot, name: str) -> tuple[np.ndarray, np.ndarray]:
    """(force, torque) the environment applies to a hand or foot, world frame, from its F/T sensor.

    ``name`` is ``l_wrist``, ``r_wrist``, ``l_ankle`` or ``r_ankle``. Quasi-static: the link below the
    sensor (hand with thumb, or foot) is held by the sensor, the environment and gravity, so
    f_env = −R f_sensor − m g (the hrpsys sign: pressing on a pedal gives +z). The torque is about
    the sensor site, end-effector weight compensated likewise. Uses the site orientation of the
    body's current data (one physics step newer than the snapshot's sensors, see
    :class:`~shintai.sim.body.MujocoBody`).
    """
    site = f"{name}_ft"
    rot = body.site_xmat(site)
    link = body.model.site_bodyid[body.id("site", site)]
    mass = body.model.body_subtreemass[link]
    weight = mass * body.model.opt.gravity
    com = body.data.subtree_com[link] - body.site_pos(site)
    force = -rot @ snapshot[f"{name}_force"] - weight
    torque = -rot @ snapshot[f"{name}_torque"] - cross3(com, weight)
    return force, torque
