"""HRP2-JSK seated on the tricycle: the riding assembly of seed 000 Ch. 3 as one ``MujocoBody``.

Five contacts close the loops of Fig. 3.2 / Eq. 3.1: the hip is **welded** to the saddle (the
thesis assumes the waist fixed, §3.3.2; equality ``hip_saddle``), each hand holds its grip with a
switchable equality (``hold_l``, ``hold_r``: a weld = the 6-DoF bilateral grasp of Table 3.1, a
connect = a point hold, or — ``grip`` — a connect plus a second one on the bar, ``hold_l_bar``,
``hold_r_bar``: the hand holds the round grip but can turn in it, E1's choice), and each sole rests
on its freely turning pedal in unilateral contact (no binding, Table 3.1). The initial posture is
found by IK (:mod:`shintai.sim.ik`): hands on the grips with the bar across the hand, soles flat
on level pedals, waist leaning forward; every servo holds it (keyframe ``ride``).

:func:`build_riding` makes the body; its options choose which grips are held and how, the crank
load, the start angles, and the model errors of the experiments (E1: the true grips farther out from the
steering axis, or the axis shifted or inclined, away from the nominal handle the controllers use;
E4: the true crank centre moved). The controllers' model
is always the nominal :data:`~shintai.humanoid.constants.TRICYCLE`.

:func:`grasp` takes hold **at the current pose** (it rewrites the equality's stored relative pose
before switching it on; see :meth:`~shintai.sim.body.MujocoBody.set_equality`), :func:`release`
lets go.

Names for controllers and scenarios (``s`` is ``l`` or ``r``):

* F/T sensors (snapshot keys): ``s_wrist_force``, ``s_wrist_torque``, ``s_ankle_force``,
  ``s_ankle_torque`` (raw MuJoCo convention; :func:`shintai.humanoid.robots.hrp2.ft_reaction` gives
  the environment's force on the hand/foot in the world frame, the hrpsys sign);
  IMU: ``imu_quat``, ``imu_gyro``, ``imu_acc`` (chest).
* Sites: hands ``s_grasp``, soles ``s_sole``; grips ``grip_s``, pedals ``pedal_s_top``,
  ``crank_centre``, ``steer_axis``, ``saddle_top``.
* Joints: the 32 of :mod:`~shintai.humanoid.robots.hrp2` (servos named alike); the tricycle's
  ``handle`` and ``crank`` (no sensors on the tricycle, §3.4.4: estimate θ_h, θ_c from the robot's
  FK; ``q:handle``/``q:crank`` are the true angles, for evaluation only).
* Equalities: ``hip_saddle``, ``hold_l``, ``hold_r`` (+ ``hold_l_bar``, ``hold_r_bar`` with the grip
  grasp), ``drive`` (the crank gear).
"""

from __future__ import annotations

import dataclasses

import mujoco
import numpy as np

from shintai.humanoid.constants import (
    ARM_JOINTS,
    GRIP_BAR_OFFSET,
    GRIPPER_CLOSED,
    HRP2_LINKS,
    LEG_JOINTS,
    RIDING_POSTURE,
    RIDING_WAIST_PITCH,
    SCENE,
    SUBSTEPS,
    TRICYCLE,
)
from shintai.humanoid.robots.hrp2 import SIDES, add_hrp2, side_posture
from shintai.humanoid.tricycle.vehicle import add_tricycle, tricycle_state
from shintai.sim import ik
from shintai.sim.body import MujocoBody
from shintai.sim.spec import fill_keyframe, scene_spec, set_joints

HOLD = {s: f"hold_{s}" for s in SIDES}  # grip equalities
HOLD_BAR = {s: f"hold_{s}_bar" for s in SIDES}  # second point hold of the "grip" grasp (on the bar)
GRASPS = ("weld", "connect", "grip")
HIP_SADDLE = "hip_saddle"
GRIP = {s: f"grip_{s}" for s in SIDES}  # tricycle grip sites
PEDAL = {s: f"pedal_{s}_top" for s in SIDES}  # pedal platform sites
HAND = {s: f"{s}_grasp" for s in SIDES}  # hand grasp sites
SOLE = {s: f"{s}_sole" for s in SIDES}  # sole sites
WRIST_FT = {s: f"{s}_wrist" for s in SIDES}  # sensor name stems: + "_force", "_torque"
ANKLE_FT = {s: f"{s}_ankle" for s in SIDES}
IMU = ("imu_quat", "imu_gyro", "imu_acc")
ARM = {s: [f"{s}_{j.name}" for j in ARM_JOINTS[:7]] for s in SIDES}  # 7 arm joints (no gripper)
LEG = {s: [f"{s}_{j.name}" for j in LEG_JOINTS] for s in SIDES}
HANDLE, CRANK = "handle", "crank"
POSTURE = {"waist_pitch": RIDING_WAIST_PITCH, **side_posture(RIDING_POSTURE)}  # pursued by the IK
IK_JOINTS = ["waist_pitch"] + [j for s in SIDES for j in ARM[s] + LEG[s]]  # moved to seat the robot


def riding_spec(grasp: str = "weld", held=("l", "r"), crank_damping: float | None = None,
                crank_friction: float | None = None, handle_error=(0.0, 0.0, 0.0),
                crank_error=(0.0, 0.0), grip_error: float = 0.0, rake_error: float = 0.0) -> mujoco.MjSpec:
    """The scene: tricycle at the origin, humanoid above the saddle, the equalities (relative poses
    still to be set, see :func:`build_riding`)."""
    if grasp not in GRASPS:
        raise ValueError(f"grasp must be one of {GRASPS}, got {grasp!r}")
    unknown = set(held) - set(SIDES)
    if unknown:
        raise ValueError(f"held names grips 'l' and 'r' only, got {sorted(unknown)}")
    spec = scene_spec("hrp2-tricycle", *SCENE)
    true = TRICYCLE  # the simulated tricycle: the nominal one but for the handle-model errors of E1
    if grip_error or rake_error:
        true = dataclasses.replace(TRICYCLE, handle_width=TRICYCLE.handle_width + 2 * grip_error,
                                   steer_rake=TRICYCLE.steer_rake + rake_error)
    add_tricycle(spec, spec.worldbody, t=true, crank_damping=crank_damping, crank_friction=crank_friction,
                 handle_error=handle_error, crank_error=crank_error)
    x, z = TRICYCLE.saddle
    add_hrp2(spec, spec.worldbody, [x, 0, z + HRP2_LINKS.hip_cover])  # the hip cover on the saddle
    weld = mujoco.mjtEq.mjEQ_WELD
    spec.add_equality(name=HIP_SADDLE, type=weld, name1="saddle", name2="waist", objtype=mujoco.mjtObj.mjOBJ_BODY)
    kind = weld if grasp == "weld" else mujoco.mjtEq.mjEQ_CONNECT
    for s in SIDES:
        spec.add_equality(name=HOLD[s], type=kind, name1="handle", name2=f"{s}_hand",
                          objtype=mujoco.mjtObj.mjOBJ_BODY, active=s in held)
        if grasp == "grip":  # a second point hold on the bar: the hand may turn about the bar only
            spec.add_equality(name=HOLD_BAR[s], type=mujoco.mjtEq.mjEQ_CONNECT, name1="handle", name2=f"{s}_hand",
                              objtype=mujoco.mjtObj.mjOBJ_BODY, active=s in held)
    spec.add_key(name="ride")
    return spec


def riding_posture(model: mujoco.MjModel, theta_h: float = 0.0, theta_c: float = 0.0) -> np.ndarray:
    """qpos of the robot on the saddle with hands on the grips and soles flat on level pedals.

    Raises ValueError if the IK does not reach (the grips and pedals out of the robot's reach).
    """
    qpos = model.qpos0.copy()
    tricycle_state(model, qpos, theta_h, theta_c)
    set_joints(model, qpos, {**POSTURE, **side_posture({"gripper": GRIPPER_CLOSED})})
    data = mujoco.MjData(model)
    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    vehicle = data.body("tricycle").xmat.reshape(3, 3).copy()
    targets = {}
    for s, sign in SIDES.items():
        grip = data.site(GRIP[s])
        bar = grip.xmat.reshape(3, 3)[:, 1]  # the bar runs along the hand's x axis, pointing to the stem
        targets[HAND[s]] = ik.Target(pos=grip.xpos.copy(), axis=([1.0, 0.0, 0.0], -sign * bar))
        targets[SOLE[s]] = (data.site(PEDAL[s]).xpos.copy(), vehicle)
    result = ik.solve(model, targets, qpos, IK_JOINTS, posture=POSTURE)
    if not result.ok:
        raise ValueError(f"riding posture not reachable: residual {result.residual[0]:.4f} m, "
                         f"{result.residual[1]:.4f} rad")
    return result.q


def hold_here(model: mujoco.MjModel, data: mujoco.MjData, name: str, anchor_site: str | None = None,
              offset=(0.0, 0.0, 0.0)) -> None:
    """Make equality ``name`` (a body–body weld or connect) hold the bodies' current relative pose.

    The anchor is ``anchor_site`` (a site on body2, e.g. the hand's grasp centre) or body2's origin,
    moved by ``offset`` (in the site's frame).
    Weld data: the anchor in body2's frame, the same point in body1's frame, the rotation of body2
    relative to body1; connect data: the anchor in body1's and in body2's frame.
    """
    eq = model.equality(name).id
    b1, b2 = model.eq_obj1id[eq], model.eq_obj2id[eq]
    anchor = np.zeros(3) if anchor_site is None else model.site(anchor_site).pos.copy()
    if anchor_site is not None and np.any(offset):
        turned = np.zeros(3)
        mujoco.mju_rotVecQuat(turned, np.asarray(offset, dtype=float), model.site(anchor_site).quat)
        anchor = anchor + turned
    point = data.xpos[b2] + data.xmat[b2].reshape(3, 3) @ anchor
    in_b1 = data.xmat[b1].reshape(3, 3).T @ (point - data.xpos[b1])
    if model.eq_type[eq] == mujoco.mjtEq.mjEQ_CONNECT:
        model.eq_data[eq, :6] = np.concatenate([in_b1, anchor])
        return
    inv, rel = np.zeros(4), np.zeros(4)
    mujoco.mju_negQuat(inv, data.xquat[b1])
    mujoco.mju_mulQuat(rel, inv, data.xquat[b2])
    model.eq_data[eq, :10] = np.concatenate([anchor, in_b1, rel])


def _bar_hold(model: mujoco.MjModel, side: str) -> bool:
    return mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_EQUALITY, HOLD_BAR[side]) >= 0


def grasp(body: MujocoBody, side: str) -> None:
    """Hold grip ``side`` at the hand's current pose (rewrites ``hold_<side>``, then switches it on)."""
    hold_here(body.model, body.data, HOLD[side], HAND[side])
    body.set_equality(HOLD[side], True)
    if _bar_hold(body.model, side):
        hold_here(body.model, body.data, HOLD_BAR[side], HAND[side], GRIP_BAR_OFFSET)
        body.set_equality(HOLD_BAR[side], True)


def release(body: MujocoBody, side: str) -> None:
    """Let go of grip ``side``."""
    body.set_equality(HOLD[side], False)
    if _bar_hold(body.model, side):
        body.set_equality(HOLD_BAR[side], False)


def build_riding(theta_h: float = 0.0, theta_c: float = 0.0, held=("l", "r"), grasp: str = "weld",
                 crank_damping: float | None = None, crank_friction: float | None = None,
                 handle_error=(0.0, 0.0, 0.0), crank_error=(0.0, 0.0), substeps: int = SUBSTEPS,
                 grip_error: float = 0.0, rake_error: float = 0.0) -> MujocoBody:
    """HRP2-JSK riding the tricycle, reset to keyframe ``ride``; one body step = 4 ms (hrpsys).

    ``theta_h``/``theta_c``: start handle and crank angles (θ_c = 0: left pedal forward, Fig. 3.11);
    ``held``: grips held at the start (``"l"``, ``"r"``); ``grasp``: ``"weld"`` (6-DoF grasp,
    Table 3.1), ``"connect"`` (point hold) or ``"grip"`` (two point holds on the bar, ``GRIP_BAR_OFFSET``
    apart: the hand holds a round grip it can turn in, see the constant); ``crank_damping`` (N m s/rad)
    and ``crank_friction``
    (N m): the crank load (defaults in :class:`~shintai.humanoid.constants.TricycleSpec`);
    ``handle_error`` (x, y, z) m: the true steering axis moved from the nominal one (E1);
    ``crank_error`` (x, z) m: the true crank centre moved (E4); ``grip_error`` m: the true grips this
    much farther out from the steering axis (each side; a handlebar half-width error, E1);
    ``rake_error`` rad: the true steering axis inclined this much more than the nominal rake (E1).
    """
    spec = riding_spec(grasp, held, crank_damping, crank_friction, handle_error, crank_error, grip_error, rake_error)
    model = spec.compile()
    hold_riding_pose(model, riding_posture(model, theta_h, theta_c), grasp)
    return MujocoBody(model, substeps=substeps, keyframe="ride", spec=spec)


def hold_riding_pose(model: mujoco.MjModel, qpos: np.ndarray, grasp: str) -> None:
    """Store ``qpos`` as keyframe ``ride`` and set the hip and grasp equalities to hold it as it is."""
    fill_keyframe(model, "ride", qpos)
    data = mujoco.MjData(model)
    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    hold_here(model, data, HIP_SADDLE)
    for side in SIDES:
        hold_here(model, data, HOLD[side], HAND[side])
        if grasp == "grip":
            hold_here(model, data, HOLD_BAR[side], HAND[side], GRIP_BAR_OFFSET)
