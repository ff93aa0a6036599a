"""MjSpec building blocks shared by the bodies: a limited hinge, a capsule limb segment and a joint's position servo.

The humanoid's models (:mod:`shintai.humanoid`, which re-exports :func:`add_hinge`) and the spine's whole
bodies (:mod:`shintai.spine.cla.body`, :mod:`shintai.spine.cla.crawl`) build their joints and limbs with these.
"""

from __future__ import annotations

import mujoco


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
