"""Seed 000 (Kimura 2018): a humanoid drives a tricycle — models, riding assembly and IK.

* :mod:`~shintai.humanoid.constants` — every number, with its source (thesis or *chosen*).
* :mod:`~shintai.humanoid.robots.hrp2` — the HRP2-JSK-like 32-DoF humanoid (App. A.2.1).
* :mod:`~shintai.humanoid.robots.kenshiro` — Kenshiro's sagittal legs on a crank (§3.5.5).
* :mod:`~shintai.humanoid.vehicles.tricycle` — the tricycle of App. A.1.1.
* :mod:`~shintai.humanoid.vehicles.vboard` — the V-BOARD scooter of App. A.1.2 (Eqs. A.1–A.4) and its
  firmware; :mod:`~shintai.humanoid.vboard_stand` — the humanoid standing on it (§6.2.1).
* :mod:`~shintai.humanoid.riding` — the humanoid seated on the tricycle, as a ``MujocoBody``.
* :mod:`~shintai.sim.ik` (shared) — damped-least-squares IK on MuJoCo site Jacobians.
* the wiring several experiments share: :mod:`~shintai.humanoid.tricycle_rig` (the limbs on the
  operation algorithm, ch. 3), :mod:`~shintai.humanoid.ride` (steering and pedalling together),
  :mod:`~shintai.humanoid.ch4_drive` (the ch. 4 drives and corrections' rig pieces),
  :mod:`~shintai.humanoid.plots`; one file per scenario in ``experiments/``, its account in ``notes/``.

This module holds the MjSpec building blocks the models share: the scene (floor, light,
integrator), hinges, position servos and 6-axis force/torque sensors, and the collision groups.
Models are built with ``compiler.degree = False``: every angle is in radians.
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.humanoid.constants import PHYSICS_TIMESTEP, SERVO_DAMPRATIO
from shintai.sim.spec import add_hinge  # noqa: F401  (shared with the spine's bodies; imported from here)

# Collision bits. Only these pairs collide: floor–sole, floor–tyre and sole–pedal (the unilateral
# foot–pedal contact of Table 3.1); hands hold grips by equality constraints, the hip is welded to
# the saddle (§3.3.2), links do not self-collide. A sole has contype SOLE (conaffinity 0), a pedal
# conaffinity SOLE (contype 0), a tyre contype WHEEL (conaffinity 0); the floor accepts all.
FLOOR = 1
SOLE = 2
WHEEL = 4

_AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


def scene_spec(name: str, timestep: float = PHYSICS_TIMESTEP) -> mujoco.MjSpec:
    """An empty scene: checker floor (z = 0), light, implicit-fast integrator, elliptic cones."""
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
                            material="grid", contype=FLOOR, conaffinity=FLOOR | SOLE | WHEEL)
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


def add_servo(spec: mujoco.MjSpec, joint: str, kp: float, torque: float):
    """A joint position servo named like its joint: stiffness ``kp`` (N m/rad), critically damped,
    output clipped to ±``torque`` (N m) — the hrpsys joint servo with the Table A.2 torque limit."""
    act = spec.add_actuator(name=joint, target=joint, trntype=mujoco.mjtTrn.mjTRN_JOINT)
    act.set_to_position(kp=kp, dampratio=SERVO_DAMPRATIO)
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
