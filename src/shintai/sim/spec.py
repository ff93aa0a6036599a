"""MjSpec building blocks shared by the bodies: the scene (floor, light, integrator), a limited hinge, a capsule
limb segment, visual geoms, box inertia, position servos (by gains, or by stiffness and damping ratio), 6-axis
force/torque sensors, and keyframes that hold a posture. The humanoid's models and the spine's whole bodies build
their joints and limbs with these.
"""

from __future__ import annotations

import mujoco
import numpy as np

_AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


def add_hinge(body, name: str, axis, limits: tuple[float, float] | None = None, armature: float = 0.0,
              damping: float = 0.0, frictionloss: float = 0.0):
    """A hinge joint at the body origin; ``limits`` (rad) makes it limited."""
    joint = body.add_joint(name=name, type=mujoco.mjtJoint.mjJNT_HINGE, axis=list(axis), armature=armature,
                           damping=damping, frictionloss=frictionloss)
    if limits is not None:
        joint.limited = mujoco.mjtLimited.mjLIMITED_TRUE
        joint.range = list(limits)
    return joint


def add_capsule(body, to, radius: float, mass: float, rgba, contype: int = 0, conaffinity: int = 0, **kw):
    """A capsule from the body origin to ``to`` (body frame) of ``radius`` [m] carrying ``mass`` [kg];
    ``contype``/``conaffinity`` its contact bits (0: it collides with nothing), ``kw`` further geom fields."""
    return body.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, fromto=[0, 0, 0, *to], size=[radius, 0, 0], mass=mass,
                         rgba=rgba, contype=contype, conaffinity=conaffinity, **kw)


def add_position_actuator(spec, joint: str, kp: float, kv: float, limit: float):
    """A position servo on ``joint`` named after it: force kp·(target − q) − kv·q̇, limited to ±``limit``."""
    act = spec.add_actuator(name=joint, target=joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
    act.gaintype, act.biastype = mujoco.mjtGain.mjGAIN_FIXED, mujoco.mjtBias.mjBIAS_AFFINE
    act.gainprm[0] = kp
    act.biasprm[:3] = [0.0, -kp, -kv]
    act.forcelimited, act.forcerange = True, [-limit, limit]
    return act


def scene_spec(name: str, timestep: float, floor_contype: int, floor_conaffinity: int) -> mujoco.MjSpec:
    """An empty scene: checker floor (z = 0) with its contact bits, light, implicit-fast integrator, elliptic
    cones; angles in radians (``compiler.degree = False``)."""
    spec = mujoco.MjSpec()
    spec.modelname = name
    spec.compiler.degree = False
    spec.option.timestep = timestep
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.visual.global_.offwidth = 1280
    spec.visual.global_.offheight = 960
    spec.add_texture(name="grid", type=mujoco.mjtTexture.mjTEXTURE_2D, builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER,
                     rgb1=[0.82, 0.84, 0.86], rgb2=[0.72, 0.74, 0.77], width=256, height=256)
    spec.add_material(name="grid", textures=["", "grid"], texrepeat=[4, 4], texuniform=True)
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[20, 20, 0.05],
                            material="grid", contype=floor_contype, conaffinity=floor_conaffinity)
    spec.worldbody.add_light(pos=[0.5, -1.0, 3.0], dir=[-0.2, 0.4, -1.0], diffuse=[0.8, 0.8, 0.8])
    return spec


def axis_vector(axis: str) -> list[float]:
    """The unit vector of ``"x"``, ``"y"`` or ``"z"``."""
    return list(_AXES[axis])


def quat_axis(axis, angle: float) -> np.ndarray:
    """Quaternion of a rotation by ``angle`` about the unit vector ``axis``."""
    q = np.zeros(4)
    mujoco.mju_axisAngle2Quat(q, np.asarray(axis, dtype=float), angle)
    return q


def add_visual(body, kind, size, rgba, mass: float = 0.0, **where):
    """A geom that collides with nothing; with ``mass`` > 0 it carries (part of) the link's mass and
    inertia. ``size`` may be short (a sphere's radius); ``where`` is pos/quat/fromto."""
    return body.add_geom(type=kind, size=list(size) + [0] * (3 - len(size)), rgba=rgba, mass=mass,
                         contype=0, conaffinity=0, **where)


def box_inertia(mass: float, size) -> list[float]:
    """Principal inertia of a solid box of full edge lengths ``size`` (x, y, z)."""
    x, y, z = size
    return [mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12, mass * (x * x + y * y) / 12]


def add_servo(spec: mujoco.MjSpec, joint: str, kp: float, torque: float, dampratio: float):
    """A joint position servo named like its joint: stiffness ``kp`` (N m/rad), damping ratio ``dampratio``,
    output clipped to ±``torque`` (N m)."""
    act = spec.add_actuator(name=joint, target=joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
    act.set_to_position(kp=kp, dampratio=dampratio)
    act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
    act.forcerange = [-torque, torque]
    return act


def set_joints(model: mujoco.MjModel, qpos: np.ndarray, values: dict[str, float]) -> None:
    """Write hinge/slide joint values (by joint name) into a qpos vector."""
    for name, value in values.items():
        qpos[model.joint(name).qposadr[0]] = value


def servo_ctrl(model: mujoco.MjModel, qpos: np.ndarray) -> np.ndarray:
    """The ctrl vector that holds ``qpos``: each position servo gets its joint's value."""
    return np.array([qpos[model.jnt_qposadr[model.actuator_trnid[i, 0]]] for i in range(model.nu)])


def fill_keyframe(model: mujoco.MjModel, key: str, qpos: np.ndarray) -> None:
    """Set keyframe ``key`` to ``qpos`` with every servo commanded to hold it."""
    k = model.key(key).id
    model.key_qpos[k] = qpos
    model.key_ctrl[k] = servo_ctrl(model, qpos)


def add_ft_sensor(spec: mujoco.MjSpec, site: str, name: str) -> tuple[str, str]:
    """A 6-axis force/torque sensor at ``site``: ``<name>_force`` and ``<name>_torque``.

    MuJoCo semantics: the force and torque (about the site, in the site frame) that the site's
    body receives from its parent body, i.e. what holds the subtree below the sensor.
    """
    names = f"{name}_force", f"{name}_torque"
    for sensor_name, kind in zip(names, (mujoco.mjtSensor.mjSENS_FORCE, mujoco.mjtSensor.mjSENS_TORQUE)):
        spec.add_sensor(name=sensor_name, type=kind, objtype=mujoco.mjtObj.mjOBJ_SITE, objname=site)
    return names
