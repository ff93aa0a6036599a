"""The tricycle of seed 000 App. A.1.1 (Figs. A.1, A.2), built in code with MjSpec.

One steered front wheel (r 0.25 m) and two back wheels (r 0.20 m, tread 0.40 m), 0.60 m ahead of /
behind the crank shaft. The **left back wheel is driven** through a gear giving D_c = 2.45 m per crank
revolution (a joint-coupling equality ``drive``: rear-left wheel angle = 1.95 × crank angle); the
right back wheel turns freely. The handle (steering) turns about a raked axis through the front
axle, limited to the physical ≈ 90° (§A.1.1; the controllers keep to Θ_H = 25°). Grips at ±0.24 m,
0.90 m above the ground; saddle 0.45 m above the crank shaft, 0.35 m behind the grips. Pedals turn
freely on the crank arms and bind nothing: a sole only presses on them (Table 3.1). The crank
load (not in the thesis) is a viscous ``crank_damping`` plus a dry ``crank_friction``. The tricycle
has no sensors (§3.4.4): controllers estimate θ_h and θ_c from the robot; scenarios may log the
true ``q:handle`` and ``q:crank`` for evaluation.

Vehicle frame: origin on the ground under the crank shaft, x forward, z up. θ_h > 0 turns left
(about the raked axis, up-and-back); θ_c = 0 puts the left crank arm forward, level, θ_c grows with
forward pedalling (the convention of :mod:`shintai.humanoid.tricycle.active`).

Names:

==========  ====================================================================================
joints      ``tricycle_root`` (free), ``handle``, ``crank``, ``pedal_l``, ``pedal_r``,
            ``front_wheel``, ``rear_l_wheel`` (driven), ``rear_r_wheel``
bodies      ``tricycle`` (frame), ``saddle``, ``handle``, ``crank``, ``pedal_l``, ``pedal_r``, wheels
sites       ``grip_l``, ``grip_r`` (grip centres; their y axis is the bar axis), ``pedal_l_top``,
            ``pedal_r_top`` (pedal platform centres), ``crank_centre``, ``saddle_top``, ``steer_axis``
            (where the steering axis crosses the grip height; its z axis is the steering axis)
equality    ``drive`` (crank → rear-left wheel gear)
functions   the nominal kinematic model: :func:`steer_point`, :func:`steer_axis`,
            :func:`grip_position`, :func:`crank_centre`, :func:`pedal_position` (vehicle frame)
actuators   only with ``servos=True``: position servos ``handle`` and ``crank`` to drive the
            tricycle without a rider (tests, demos)
==========  ====================================================================================
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from shintai.humanoid.constants import (
    SCENE,
    SOLE,
    SUBSTEPS,
    THETA_H0,
    TRICYCLE,
    TRICYCLE_DRIVE_SERVOS,
    WHEEL,
    TricycleSpec,
)
from shintai.humanoid.tricycle.constants import DARK, FRAME, METAL
from shintai.sim.body import MujocoBody
from shintai.sim.spec import add_hinge, add_visual, box_inertia, fill_keyframe, quat_axis, scene_spec, set_joints

Y_AXIS_QUAT = [math.cos(math.pi / 4), math.sin(math.pi / 4), 0, 0]  # turns a cylinder's z axis onto y
CAPSULE, CYLINDER, BOX = mujoco.mjtGeom.mjGEOM_CAPSULE, mujoco.mjtGeom.mjGEOM_CYLINDER, mujoco.mjtGeom.mjGEOM_BOX


def _wheel(parent, name: str, pos, radius: float, mass: float, t: TricycleSpec):
    """A wheel turning about y: a tyre that touches only the floor, and a visible spoke.

    The tyre is a thin ellipsoid (chosen): it rolls on one smooth contact point, where MuJoCo's
    cylinder–plane contact jumps between rim points and lets the driven wheel slip.
    """
    wheel = parent.add_body(name=name, pos=list(pos))
    add_hinge(wheel, name, [0, 1, 0], damping=t.wheel_damping)
    wheel.add_geom(name=name, type=mujoco.mjtGeom.mjGEOM_ELLIPSOID, size=[radius, 0.025, radius], rgba=DARK,
                   mass=mass, contype=WHEEL, conaffinity=0, friction=[t.wheel_friction, 0.005, 0.0001])
    add_visual(wheel, BOX, [radius * 0.9, 0.022, 0.012], METAL)
    return wheel


def add_crank(parent, centre, radius: float, pedal_y: float, damping: float, friction: float,
              t: TricycleSpec = TRICYCLE):
    """The crank at ``centre`` (axis y) with two freely turning pedals at ±``pedal_y``.

    Bodies and joints ``crank``, ``pedal_l``, ``pedal_r``; sites ``crank_centre``, ``pedal_l_top``,
    ``pedal_r_top``. The left arm points +x at crank angle 0, the right arm −x. Kenshiro's rig
    (:mod:`shintai.humanoid.robots.kenshiro`) uses it too.
    """
    crank = parent.add_body(name="crank", pos=list(centre))
    add_hinge(crank, "crank", [0, 1, 0], damping=damping, frictionloss=friction)
    crank.add_site(name="crank_centre")
    add_visual(crank, CYLINDER, [0.09, 0.005], METAL, t.crank_mass, quat=Y_AXIS_QUAT)
    for side, sign in (("l", 1.0), ("r", -1.0)):
        x = sign * radius
        add_visual(crank, CAPSULE, [0.012], METAL, fromto=[0, sign * 0.03, 0, x, sign * (pedal_y - 0.06), 0])
        pedal = crank.add_body(name=f"pedal_{side}", pos=[x, sign * pedal_y, 0])
        add_hinge(pedal, f"pedal_{side}", [0, 1, 0], damping=t.pedal_damping)
        pedal.add_geom(name=f"pedal_{side}", type=BOX, size=[s / 2 for s in t.pedal_size], rgba=DARK,
                       contype=0, conaffinity=SOLE)
        pedal.explicitinertial = True
        pedal.mass, pedal.ipos = t.pedal_mass, [0, 0, -t.pedal_com_drop]
        pedal.inertia = box_inertia(t.pedal_mass, t.pedal_size)
        pedal.add_site(name=f"pedal_{side}_top", pos=[0, 0, t.pedal_size[2] / 2])
    return crank


def steer_axis(t: TricycleSpec = TRICYCLE) -> np.ndarray:
    """Unit steering axis (vehicle frame): up and back by the rake."""
    return np.array([-math.sin(t.steer_rake), 0.0, math.cos(t.steer_rake)])


# The nominal kinematic model (vehicle frame) that controllers use to plan the active limbs
# (§3.4.2: "from the kinematic parameters"); the simulated tricycle differs from it only by the
# builder's handle_error / crank_error.
def steer_point(t: TricycleSpec = TRICYCLE) -> np.ndarray:
    """Where the steering axis crosses the grip height."""
    return np.array([t.steer_top[0], 0.0, t.steer_top[1]])


def grip_position(theta_h: float, side: str, t: TricycleSpec = TRICYCLE) -> np.ndarray:
    """Centre of grip ``side`` ("l"/"r") at handle angle θ_h: the θ_h = 0 grip turned about the axis."""
    grip0 = np.array([t.grip_x, (1.0 if side == "l" else -1.0) * t.handle_width / 2, t.grip_height])
    turned = np.zeros(3)
    mujoco.mju_rotVecQuat(turned, grip0 - steer_point(t), quat_axis(steer_axis(t), theta_h))
    return steer_point(t) + turned


def crank_centre(t: TricycleSpec = TRICYCLE) -> np.ndarray:
    """The crank shaft's centre."""
    return np.array([0.0, 0.0, t.crank_height])


def pedal_position(theta_c: float, side: str, t: TricycleSpec = TRICYCLE) -> np.ndarray:
    """Centre of pedal ``side``'s platform top at crank angle θ_c, the platform level: the left arm at
    θ_c, the right at θ_c + π, on the circle of radius r about the crank centre."""
    arm = theta_c + (0.0 if side == "l" else math.pi)
    y = (1.0 if side == "l" else -1.0) * t.pedal_width / 2
    return crank_centre(t) + [t.crank_radius * math.cos(arm), y, -t.crank_radius * math.sin(arm) + t.pedal_size[2] / 2]


def _add_handle(frame, t: TricycleSpec, error) -> None:
    """Handle, fork and front wheel. ``error`` moves the true steering axis (vehicle frame) while
    the grips stay at their nominal places: the handle-model error of experiment E1."""
    pivot = steer_point(t) + np.asarray(error, dtype=float)
    handle = frame.add_body(name="handle", pos=pivot.tolist())
    add_hinge(handle, "handle", steer_axis(t), (-THETA_H0, THETA_H0), damping=t.steer_damping)
    handle.add_site(name="steer_axis", quat=quat_axis([0, 1, 0], -t.steer_rake).tolist())
    axle = np.array([t.front_axle[0], 0.0, t.front_axle[1]]) - pivot
    grips = {side: grip_position(0.0, side, t) - pivot for side in ("l", "r")}
    stem_top = 0.08 * steer_axis(t)
    add_visual(handle, CAPSULE, [0.02], FRAME, t.handle_mass, fromto=[*axle, *stem_top])
    for side, grip in grips.items():
        s = 1.0 if side == "l" else -1.0
        inner = grip - [0, s * 0.07, 0]
        add_visual(handle, CAPSULE, [0.012], METAL, fromto=[*stem_top, *(inner * [1, 0, 1] + [0, s * 0.05, 0])])
        add_visual(handle, CAPSULE, [0.012], METAL, fromto=[*(inner * [1, 0, 1] + [0, s * 0.05, 0]), *inner])
        add_visual(handle, CYLINDER, [0.018, 0.06], DARK, pos=grip.tolist(), quat=Y_AXIS_QUAT)
        handle.add_site(name=f"grip_{side}", pos=grip.tolist())
    for s in (1.0, -1.0):  # fork blades
        blade = [0, s * 0.04, 0]
        add_visual(handle, CAPSULE, [0.012], FRAME, fromto=[*(axle + blade), *(axle * 0.4 + blade)])
    _wheel(handle, "front_wheel", axle, t.front_tire_radius, t.front_wheel_mass, t)


def add_tricycle(spec: mujoco.MjSpec, parent, pos=(0.0, 0.0, 0.0), t: TricycleSpec = TRICYCLE, *,
                 crank_damping: float | None = None, crank_friction: float | None = None,
                 handle_error=(0.0, 0.0, 0.0), crank_error=(0.0, 0.0), servos: bool = False):
    """Add the tricycle (free body ``tricycle``) with its vehicle-frame origin at ``pos``.

    ``crank_damping``/``crank_friction`` set the crank load (defaults from ``t``);
    ``handle_error`` (x, y, z) moves the true steering axis, ``crank_error`` (x, z) the true crank
    centre, away from the nominal geometry ``t`` that controllers use (model errors of E1/E4).
    """
    frame = parent.add_body(name="tricycle", pos=list(pos))
    frame.add_freejoint(name="tricycle_root")
    rear_x, rear_z = -t.crank_to_back, t.back_tire_radius
    crank = crank_centre(t) + [crank_error[0], 0.0, crank_error[1]]
    saddle_x, saddle_z = t.saddle
    head = steer_point(t) - 0.3 * steer_axis(t)  # head tube, lower end
    seat = [saddle_x, 0, saddle_z - 0.05]
    add_visual(frame, CAPSULE, [0.025], FRAME, t.frame_mass, fromto=[*crank, *head])  # down tube
    add_visual(frame, CAPSULE, [0.022], FRAME, fromto=[*head, *(head + 0.2 * steer_axis(t))])  # head tube
    add_visual(frame, CAPSULE, [0.02], FRAME, fromto=[*crank, *seat])  # seat tube
    add_visual(frame, CAPSULE, [0.018], FRAME, fromto=[*crank, rear_x, 0, rear_z])  # chain stay
    add_visual(frame, CAPSULE, [0.018], FRAME, fromto=[*seat, rear_x, 0, rear_z])  # seat stay
    add_visual(frame, CAPSULE, [0.02], FRAME, fromto=[rear_x, -t.tread / 2, rear_z, rear_x, t.tread / 2, rear_z])
    add_visual(frame, BOX, [0.17, 0.19, 0.01], [0.55, 0.45, 0.3, 1],  # rear carrier
               pos=[rear_x, 0, rear_z + t.back_tire_radius + 0.05])
    saddle = frame.add_body(name="saddle", pos=[saddle_x, 0, saddle_z])
    add_visual(saddle, BOX, [0.11, 0.10, 0.025], DARK, pos=[-0.02, 0, -0.025])
    saddle.add_site(name="saddle_top")
    _add_handle(frame, t, handle_error)
    for side, s in (("l", 1.0), ("r", -1.0)):
        _wheel(frame, f"rear_{side}_wheel", [rear_x, s * t.tread / 2, rear_z], t.back_tire_radius,
               t.back_wheel_mass, t)
    add_crank(frame, crank, t.crank_radius, t.pedal_width / 2,
              t.crank_damping if crank_damping is None else crank_damping,
              t.crank_friction if crank_friction is None else crank_friction, t)
    spec.add_equality(name="drive", type=mujoco.mjtEq.mjEQ_JOINT, name1="rear_l_wheel", name2="crank",
                      data=[0, t.gear_ratio] + [0] * 10)
    if servos:
        for joint, (kp, kv) in TRICYCLE_DRIVE_SERVOS.items():
            act = spec.add_actuator(name=joint, target=joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            act.set_to_position(kp=kp, kv=kv)
    return frame


def tricycle_state(model: mujoco.MjModel, qpos: np.ndarray, theta_h: float = 0.0, theta_c: float = 0.0,
                   t: TricycleSpec = TRICYCLE) -> None:
    """Set handle and crank angles in ``qpos``, with the driven wheel geared and the pedals level."""
    set_joints(model, qpos, {"handle": theta_h, "crank": theta_c, "rear_l_wheel": t.gear_ratio * theta_c,
                             "pedal_l": -theta_c, "pedal_r": -theta_c})


def build_tricycle(theta_h: float = 0.0, theta_c: float = 0.0, t: TricycleSpec = TRICYCLE, *,
                   servos: bool = True, substeps: int = SUBSTEPS, **options) -> MujocoBody:
    """The tricycle alone on the floor, keyframe ``park`` (servos, if any, holding θ_h and θ_c).

    ``options`` go to :func:`add_tricycle` (crank load, model errors).
    """
    spec = scene_spec("tricycle", *SCENE)
    add_tricycle(spec, spec.worldbody, t=t, servos=servos, **options)
    spec.add_key(name="park")
    model = spec.compile()
    qpos = model.qpos0.copy()
    tricycle_state(model, qpos, theta_h, theta_c, t)
    fill_keyframe(model, "park", qpos)
    return MujocoBody(model, substeps=substeps, keyframe="park", spec=spec)
