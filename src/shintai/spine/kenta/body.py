"""Kenta's whole body in MuJoCo (seed 003 §3.7, §3.7.4, Figs. 3.39–3.52): the 40-muscle, 10-joint spine with its
ligaments (:func:`~shintai.spine.bodies_mujoco.build_spec`, §3.7.1–3.7.2) plus arms, neck, head and eyes.

* **Arms** (§3.7.4, Fig. 3.51): a ball joint near the chest centre and one at the upper-arm root (6 DOF), a
  1-DOF elbow, a 3-DOF wrist; each axis a hinge with a position servo (the arm muscles' routing, Fig. 3.50, is
  not in the text).
* **Neck** (Fig. 3.52): "a reduced spine", 5 ball joints (three hinges each) on silicone spacers, driven by six
  wires through guide holes, so "each joint angle cannot be set individually, but the whole posture can". A
  wire sliding through guides at a fixed offset from the axes changes length by offset × the *sum* of the
  joint angles it crosses: the wires are modelled as three fixed tendons (pan = Σ yaw, tilt = Σ pitch, roll =
  Σ roll) each with a position servo; the spacers' stiffness shares the angle among the joints.
* **Eyes**: one closed linkage joining both eyes, pan then tilt by two RC servos; a camera in each eye
  (``eye_L``, ``eye_R``) looking along the gaze.
* **Target**: a mocap ball the tracking experiments move (``target`` channel, a position); the eyes' "colour
  region detection" (§5.2.10) is its centre projected into the left eye camera: ``target_image`` (horizontal,
  vertical) angles of the target from the optical axis [rad], ``target_visible`` whether it is in the field of view.
* **The teacher's hands** (§4.2.1): the ``shape`` channel (set) holds every spine joint at a posture θ (3n,)
  by position servos on its hinges (K, D: ``TEACHER_*``), as hands moulding the whole spine; a tick without a
  writer lets go.

Constants with their sources: ``KENTA_*`` in :mod:`shintai.spine.robots`.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from shintai.core.constants import KGF_N
from shintai.core.runtime import SET, Loop, declare
from shintai.sim.spec import add_capsule
from shintai.spine.bodies_mujoco import SpineBody, build_spec
from shintai.spine.control import Gains, Mode, MuscleControl
from shintai.spine.kenta.constants import (
    SPINE_ARMATURE_KGM2,
    SPINE_STOP_SOLREF_S,
    TARGET_RADIUS_M,
    TEACHER_D_NMS_RAD,
    TEACHER_GROUP,
    TEACHER_K_NM_RAD,
)
from shintai.spine.robots import (
    CALIBRATION_KGF,
    KENTA,
    KENTA_ARM_KG,
    KENTA_ARM_KP,
    KENTA_ARM_TORQUE_NM,
    KENTA_CAMERA_FOVY_DEG,
    KENTA_CHEST_BALL_Y_M,
    KENTA_CLAVICLE_M,
    KENTA_EYE_KP,
    KENTA_EYE_LIMIT_RAD,
    KENTA_EYE_X_M,
    KENTA_EYE_Y_M,
    KENTA_FOREARM_M,
    KENTA_HEAD_HALF_M,
    KENTA_HEAD_KG,
    KENTA_LIGAMENTS,
    KENTA_NECK_JOINTS,
    KENTA_NECK_KP,
    KENTA_NECK_K_NM_RAD,
    KENTA_NECK_LIMIT_RAD,
    KENTA_NECK_SEGMENT_M,
    KENTA_NECK_TORQUE_NM,
    KENTA_TORSO_M,
    KENTA_UPPER_ARM_M,
)
from shintai.spine.tracking_loops import image_offset

HINGE = mujoco.mjtJoint.mjJNT_HINGE
AXES = {"yaw": [0, 0, 1], "pitch": [0, 1, 0], "roll": [1, 0, 0]}
# The arms' joints in order, per side: (body, axis, range [deg]); ranges chosen (a human's, roughly)
ARM_JOINTS = (("chest", "yaw", 30), ("chest", "pitch", 30), ("chest", "roll", 30),
              ("shoulder", "yaw", 90), ("shoulder", "pitch", 120), ("shoulder", "roll", 90),
              ("elbow", "pitch", 140), ("wrist", "yaw", 60), ("wrist", "pitch", 60), ("wrist", "roll", 60))
ARM_NAMES = tuple(f"{part}_{axis}_{side}" for side in "LR" for part, axis, _ in ARM_JOINTS)
NECK_AXES = ("pan", "tilt", "roll")


def _servo(spec, name: str, joint: str, kp: float, torque: float, lim: float, tendon: bool = False) -> None:
    act = spec.add_actuator(name=name, target=joint,
                            trntype=mujoco.mjtTrn.mjTRN_TENDON if tendon else mujoco.mjtTrn.mjTRN_JOINT)
    act.set_to_position(kp=kp, kv=0.05 * kp)
    act.ctrllimited, act.ctrlrange = True, [-lim, lim]
    act.forcelimited, act.forcerange = True, [-torque, torque]


def _capsule(body, to, radius, mass, rgba=(0.75, 0.75, 0.8, 1)) -> None:
    add_capsule(body, to, radius, mass, list(rgba))  # a limb segment that collides with nothing


def _add_arm(spec, top, side: str) -> None:
    s = 1.0 if side == "L" else -1.0
    parent = top
    where = {"chest": [0, s * KENTA_CHEST_BALL_Y_M, KENTA_TORSO_M], "shoulder": [0, s * KENTA_CLAVICLE_M, 0],
             "elbow": [0, 0, -KENTA_UPPER_ARM_M], "wrist": [0, 0, -KENTA_FOREARM_M]}
    segment = {"chest": ([0, s * KENTA_CLAVICLE_M, 0], 0.02, KENTA_ARM_KG[0]),
               "shoulder": ([0, 0, -KENTA_UPPER_ARM_M], 0.025, KENTA_ARM_KG[1]),
               "elbow": ([0, 0, -KENTA_FOREARM_M], 0.022, 0.8 * KENTA_ARM_KG[2]),
               "wrist": ([0, 0, -0.07], 0.02, 0.2 * KENTA_ARM_KG[2])}
    bodies = {}
    for part, axis, lim_deg in ARM_JOINTS:
        if part not in bodies:
            parent = bodies[part] = parent.add_body(name=f"{part}_{side}", pos=where[part])
            _capsule(parent, *segment[part])
        joint = f"{part}_{axis}_{side}"
        lim = math.radians(lim_deg)
        lo, hi = (0.0, lim) if part == "elbow" else (-lim, lim)
        parent.add_joint(name=joint, type=HINGE, axis=AXES[axis], range=[lo, hi], limited=True, damping=0.5,
                         armature=0.01)
        _servo(spec, joint, joint, KENTA_ARM_KP, KENTA_ARM_TORQUE_NM, lim)


def _add_head(spec, top) -> None:
    body, joints = top, {a: [] for a in ("yaw", "pitch", "roll")}
    lim = KENTA_NECK_LIMIT_RAD / KENTA_NECK_JOINTS * 1.25
    for i in range(KENTA_NECK_JOINTS):
        body = body.add_body(name=f"neck{i + 1}", pos=[0, 0, KENTA_TORSO_M + 0.02 if i == 0 else KENTA_NECK_SEGMENT_M])
        for axis in ("yaw", "pitch", "roll"):
            name = f"neck{i + 1}_{axis}"
            body.add_joint(name=name, type=HINGE, axis=AXES[axis], stiffness=KENTA_NECK_K_NM_RAD, damping=0.05,
                           armature=1e-4, limited=True, range=[-lim, lim])
            joints[axis].append(name)
        _capsule(body, [0, 0, KENTA_NECK_SEGMENT_M], 0.012, 0.03, (0.93, 0.9, 0.8, 1))
    for wire, axis in zip(NECK_AXES, ("yaw", "pitch", "roll")):
        tendon = spec.add_tendon(name=f"neck_{wire}")
        for name in joints[axis]:
            tendon.wrap_joint(name, 1.0)
        _servo(spec, f"neck_{wire}", f"neck_{wire}", KENTA_NECK_KP, KENTA_NECK_TORQUE_NM, KENTA_NECK_LIMIT_RAD,
               tendon=True)
    head = body.add_body(name="head", pos=[0, 0, KENTA_NECK_SEGMENT_M])
    hx, hy, hz = KENTA_HEAD_HALF_M
    head.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[hx, hy, hz], pos=[0.0, 0, hz], mass=KENTA_HEAD_KG,
                  rgba=[0.8, 0.8, 0.85, 1], contype=0, conaffinity=0)
    pan = head.add_body(name="eyes", pos=[KENTA_EYE_X_M + 0.005, 0, 1.2 * hz])
    pan.add_joint(name="eye_pan", type=HINGE, axis=[0, 0, 1], range=[-KENTA_EYE_LIMIT_RAD, KENTA_EYE_LIMIT_RAD],
                  limited=True, damping=0.005, armature=1e-4)
    pan.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.005, KENTA_EYE_Y_M, 0.005], mass=0.01,
                 rgba=[0.3, 0.3, 0.3, 1], contype=0, conaffinity=0)  # the linkage joining both eyes
    tilt = pan.add_body(name="eyes_tilt")
    tilt.add_joint(name="eye_tilt", type=HINGE, axis=[0, -1, 0], range=[-KENTA_EYE_LIMIT_RAD, KENTA_EYE_LIMIT_RAD],
                   limited=True, damping=0.005, armature=1e-4)
    for side, s in (("L", 1.0), ("R", -1.0)):
        tilt.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.014, 0, 0], pos=[0, s * KENTA_EYE_Y_M, 0],
                      mass=0.01, rgba=[0.1, 0.1, 0.1, 1], contype=0, conaffinity=0)
        tilt.add_camera(name=f"eye_{side}", pos=[0.015, s * KENTA_EYE_Y_M, 0], xyaxes=[0, -1, 0, 0, 0, 1],
                        fovy=KENTA_CAMERA_FOVY_DEG)
    for name in ("eye_pan", "eye_tilt"):
        _servo(spec, name, name, KENTA_EYE_KP, 0.5, KENTA_EYE_LIMIT_RAD)


def kenta_spec(timestep: float = 5e-4, target=(0.9, 0.0, 1.0)) -> mujoco.MjSpec:
    """The MjSpec of Kenta's whole body (module docstring); ``target`` is the ball's initial position."""
    spec = build_spec(KENTA, loads=(), ligaments=KENTA_LIGAMENTS, timestep=timestep)
    spec.modelname = "kenta_body"
    spec.visual.global_.offwidth, spec.visual.global_.offheight = 640, 480
    top = spec.body(f"link{KENTA.n}")
    top.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.05, KENTA_CHEST_BALL_Y_M + 0.04, 0.5 * KENTA_TORSO_M],
                 pos=[0, 0, 0.5 * KENTA_TORSO_M + 0.01], rgba=[0.55, 0.6, 0.75, 0.35], mass=0.0, contype=0,
                 conaffinity=0)
    for i in range(1, KENTA.n + 1):  # §3.7.1's hardware locks against over-bending: stiff stops at the limits
        for axis in ("roll", "pitch", "yaw"):
            spec.joint(f"j{i}_{axis}").solref_limit = [SPINE_STOP_SOLREF_S, 1.0]
            spec.joint(f"j{i}_{axis}").armature = SPINE_ARMATURE_KGM2
    for i in range(1, KENTA.n + 1):  # the teacher's hands: position servos in actuator group TEACHER_GROUP
        for axis in ("roll", "pitch", "yaw"):
            act = spec.add_actuator(name=f"teach:j{i}_{axis}", target=f"j{i}_{axis}", trntype=mujoco.mjtTrn.mjTRN_JOINT,
                                    group=TEACHER_GROUP)
            act.set_to_position(kp=TEACHER_K_NM_RAD, kv=TEACHER_D_NMS_RAD)
    for side in "LR":
        _add_arm(spec, top, side)
    _add_head(spec, top)
    ball = spec.worldbody.add_body(name="target", mocap=True, pos=list(target))
    ball.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[TARGET_RADIUS_M, 0, 0], rgba=[0.95, 0.2, 0.1, 1],
                  contype=0, conaffinity=0)
    spec.worldbody.add_camera(name="side", pos=[0.9, -1.4, 1.1], xyaxes=[0.85, 0.53, 0, -0.15, 0.25, 0.96])
    return spec


class KentaBody(SpineBody):
    """Kenta's whole body: :class:`SpineBody` (the spine's muscles, sensors, ``duty`` and ``hand``) plus the
    arm, neck (``neck_pan``, ``neck_tilt``, ``neck_roll``: whole-neck angles) and eye (``eye_pan``,
    ``eye_tilt``) position servos as actuator channels, ``shape`` (set, (3n,): the teacher's hands) and
    ``target`` (set, (3,): the ball's position). Snapshot adds ``target_image``, ``target_visible``, ``gaze``
    (pan and tilt of each part: (3, 2) rows spine, neck, eyes [rad]) and ``arms`` (20,) [rad]."""

    def __init__(self, timestep: float = 5e-4, control_period: float | None = None):
        super().__init__(KENTA, ligaments=KENTA_LIGAMENTS, timestep=timestep, control_period=control_period,
                         spec=kenta_spec(timestep))
        self.channels = {**self.channels, **declare("shape", "target", kind=SET)}
        m = self.model
        self._arm_q = m.jnt_qposadr[[self.id("joint", nm) for nm in ARM_NAMES]]
        neck = {ax: m.jnt_qposadr[[self.id("joint", f"neck{i}_{ax}") for i in range(1, KENTA_NECK_JOINTS + 1)]]
                for ax in ("yaw", "pitch")}
        self._neck_q = (neck["yaw"], neck["pitch"])
        self._eye_q = m.jnt_qposadr[[self.id("joint", "eye_pan"), self.id("joint", "eye_tilt")]]
        self._cam = self.id("camera", "eye_L")
        self._target = m.body_mocapid[self.id("body", "target")]
        self._teach = np.array([self.id("actuator", f"teach:j{i}_{ax}") for i in range(1, KENTA.n + 1)
                                for ax in ("roll", "pitch", "yaw")])
        self.let_go()

    def let_go(self) -> None:
        self.model.opt.disableactuator |= 1 << TEACHER_GROUP

    def shape(self, theta) -> None:
        """The teacher's hands hold every spine joint at θ (3n,) [rad] (implicit position servos)."""
        self.data.ctrl[self._teach] = theta
        self.model.opt.disableactuator &= ~(1 << TEACHER_GROUP)

    def gaze(self) -> np.ndarray:
        """(pan, tilt) of the spine (Σ yaw, −Σ pitch: a forward bend looks down), the neck and the eyes [rad]."""
        q = self.data.qpos
        spine = self.data.qpos[self.spine_qpos].reshape(-1, 3)
        yaw, pitch = self._neck_q
        return np.array([[spine[:, 2].sum(), -spine[:, 1].sum()], [q[yaw].sum(), -q[pitch].sum()],
                         [q[self._eye_q[0]], q[self._eye_q[1]]]])

    def target_image(self):
        d = self.data
        return image_offset(d.cam_xpos[self._cam], d.cam_xmat[self._cam], d.mocap_pos[self._target])

    def snapshot(self):
        snap = super().snapshot()
        offset, visible = self.target_image()
        snap["target_image"], snap["target_visible"] = offset, float(visible)
        snap["gaze"] = self.gaze()
        snap["arms"] = self.data.qpos[self._arm_q].copy()
        return snap

    def apply(self, command) -> None:
        command = dict(command)
        shape = command.pop("shape", None)
        if shape is None:
            self.let_go()
        else:
            self.shape(np.asarray(shape, dtype=float))
        target = command.pop("target", None)
        if target is not None:
            self.data.mocap_pos[self._target] = target
        super().apply(command)


def calibrated_kenta(teach_kgf: float = 1.0, seconds: float = 1.0):
    """Kenta with its muscle controller after §4.6.4's encoder zeroing: the teacher's hands hold the basic
    posture while every muscle runs LL at the "just taut" limit (CALIBRATION_KGF) toward a 10 mm shorter
    target; the encoders are zeroed there and every muscle is left in L mode holding it. Returns
    (body, control, the model lengths at the basic posture = the encoder zero)."""
    body = KentaBody()
    control = MuscleControl(KENTA.m, Gains(T_r=teach_kgf * KGF_N, T_l=CALIBRATION_KGF * KGF_N))
    control.set_modes(Mode.LL)
    control.set_targets(l_r=body.snapshot()["encoder"] + 0.01)
    zero = np.zeros(3 * KENTA.n)
    Loop(body, [control], base={"shape": zero}).run(seconds)
    body.zero_encoders()
    control.set_gains(T_l=teach_kgf * KGF_N)
    control.set_targets(l_r=np.zeros(KENTA.m))
    control.set_modes(Mode.L)
    control.reset(body.snapshot())
    return body, control, KENTA.model.lengths(zero)
