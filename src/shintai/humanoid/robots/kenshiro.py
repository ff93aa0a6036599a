"""Kenshiro's two sagittal legs on the tricycle crank (seed 000 §3.5.5, Fig. 3.31, App. A.2.2).

The waist is fixed to the tricycle (§3.5.5: "腰リンクは三輪車に固定"), and the tricycle is a fixed
rig here: a crank with its load and two freely turning pedals, no wheels. Each leg is planar
(x forward, z up): hip, knee and ankle pitch. Kenshiro is tendon-driven and position controlled
(§3.5.5: no impedance control), so each joint has a position servo; the control period is 16 ms.

Geometry (Fig. 3.31): thigh L1 = 0.348, shank L2 = 0.343, foot L3 = 0.260, ankle → pedal contact
D_ap = 0.075, crank centre (D_cx, D_cz) = (0.080, 0.605) from the hip (forward, down; chosen
directions), crank radius r = 0.100 m. The contact point (the end effector p_i of Eq. 3.7 and q_i of
Eq. 3.24) lies on the sole, D_ap below the ankle along the sole normal (chosen reading of D_ap).

Angles (the package convention, :mod:`shintai.humanoid.constants`): every joint turns about +y;
the foot pitch ψ = hip + knee + ankle is the sole's rotation from level (ψ > 0: toe down).
Hip flexion is negative, knee flexion positive. The crank angle θ_c = 0 puts the left crank arm
forward, level; θ_c grows with forward pedalling; the right pedal is at θ_c + π.

Names in the model:

================  ==========================================================================
joints/servos     ``l_hip_pitch``, ``l_knee_pitch``, ``l_ankle_pitch`` and ``r_…``
                  (each servo is named like its joint), ``crank``, ``pedal_l``, ``pedal_r``
sites             ``l_contact``/``r_contact`` (sole contact point), ``l_foot_ft``/``r_foot_ft``
                  (at the ankle, foot frame), ``pedal_l_top``/``pedal_r_top`` (pedal platform
                  centre), ``crank_centre``
sensors           ``l_foot_force``, ``l_foot_torque``, ``r_foot_force``, ``r_foot_torque``: the
                  force/torque the foot receives from the shank, in the foot frame (see
                  :func:`shintai.humanoid.add_ft_sensor`); the thesis's foot 6-axis sensor
keyframe          ``ride``: feet on the pedals at the builder's crank angle (see :func:`riding_posture`)
================  ==========================================================================

Planar helpers work in the hip frame (origin at the hip axis, x forward, z up) on (x, z) pairs:
:func:`pedal_axle`, :func:`pedal_contact`, :func:`leg_fk`, :func:`leg_ik`.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from shintai.humanoid.constants import (
    KENSHIRO,
    PHYSICS_TIMESTEP,
    SCENE,
    SERVO_DAMPRATIO,
    SERVO_SATURATION_ERROR,
    SKIN,
    SOLE,
    TRICYCLE,
    KenshiroSpec,
)
from shintai.humanoid.tricycle.vehicle import add_crank
from shintai.sim.body import MujocoBody
from shintai.sim.spec import add_ft_sensor, add_hinge, add_servo, add_visual, fill_keyframe, scene_spec, set_joints

SIDES = {"l": 1.0, "r": -1.0}  # y sign of each leg
JOINTS = ("hip_pitch", "knee_pitch", "ankle_pitch")
PEDAL_HALF_THICKNESS = TRICYCLE.pedal_size[2] / 2
HIP_HEIGHT = TRICYCLE.crank_height + KENSHIRO.d_cz  # m above the floor; the crank as on the tricycle


def crank_arm_angle(theta_c: float, side: str) -> float:
    """The crank angle of one side's arm: the left arm at θ_c, the right at θ_c + π."""
    return theta_c + (0.0 if side == "l" else math.pi)


def pedal_axle(theta_c: float, side: str, k: KenshiroSpec = KENSHIRO) -> np.ndarray:
    """(x, z) of a pedal axle in the hip frame: crank centre + r (cos a, −sin a), a = arm angle."""
    a = crank_arm_angle(theta_c, side)
    return np.array([k.d_cx + k.crank_radius * math.cos(a), -k.d_cz - k.crank_radius * math.sin(a)])


def pedal_contact(theta_c: float, side: str, foot_pitch: float = 0.0, k: KenshiroSpec = KENSHIRO) -> np.ndarray:
    """(x, z) of the contact point of a sole lying flat on the pedal, the sole at ``foot_pitch``."""
    return pedal_axle(theta_c, side, k) + PEDAL_HALF_THICKNESS * np.array([math.sin(foot_pitch), math.cos(foot_pitch)])


def leg_fk(q, k: KenshiroSpec = KENSHIRO) -> tuple[np.ndarray, float]:
    """(contact point (x, z), foot pitch ψ) of joint angles (hip, knee, ankle), hip frame."""
    hip, knee, ankle = q
    knee_xz = k.l1 * np.array([-math.sin(hip), -math.cos(hip)])
    ankle_xz = knee_xz + k.l2 * np.array([-math.sin(hip + knee), -math.cos(hip + knee)])
    psi = hip + knee + ankle
    return ankle_xz + k.d_ap * np.array([-math.sin(psi), -math.cos(psi)]), psi


def leg_ik(contact, foot_pitch: float, k: KenshiroSpec = KENSHIRO) -> np.ndarray | None:
    """Joint angles (hip, knee, ankle) putting the contact point at ``contact`` (x, z) with the sole
    at ``foot_pitch``; knee flexed forward (knee ≥ 0). None if out of reach or out of the ranges."""
    ankle = np.asarray(contact, dtype=float) + k.d_ap * np.array([math.sin(foot_pitch), math.cos(foot_pitch)])
    d2 = float(ankle @ ankle)
    c = (d2 - k.l1**2 - k.l2**2) / (2 * k.l1 * k.l2)
    if not -1.0 <= c <= 1.0:
        return None
    knee = math.acos(c)
    shank = np.array([-k.l2 * math.sin(knee), -k.l1 - k.l2 * math.cos(knee)])  # ankle at hip = 0
    # a rotation about +y by θ adds θ to atan2(x, z)
    hip = math.atan2(ankle[0], ankle[1]) - math.atan2(shank[0], shank[1])
    hip = math.remainder(hip, 2 * math.pi)
    q = np.array([hip, knee, foot_pitch - hip - knee])
    ranges = (k.hip_range, k.knee_range, k.ankle_range)
    return q if all(lo <= v <= hi for v, (lo, hi) in zip(q, ranges)) else None


def _add_leg(spec: mujoco.MjSpec, waist, side: str, k: KenshiroSpec) -> None:
    y = SIDES[side] * k.pedal_spacing / 2
    limits = {"hip_pitch": k.hip_range, "knee_pitch": k.knee_range, "ankle_pitch": k.ankle_range}
    torques = {"hip_pitch": k.hip_torque, "knee_pitch": k.knee_torque, "ankle_pitch": k.ankle_torque}
    thigh = waist.add_body(name=f"{side}_thigh", pos=[0, y, 0])
    shank = thigh.add_body(name=f"{side}_shank", pos=[0, 0, -k.l1])
    foot = shank.add_body(name=f"{side}_foot", pos=[0, 0, -k.l2])
    capsule = mujoco.mjtGeom.mjGEOM_CAPSULE
    add_visual(thigh, capsule, [0.045], SKIN, k.thigh_mass, fromto=[0, 0, 0, 0, 0, -k.l1])
    add_visual(shank, capsule, [0.035], SKIN, k.shank_mass, fromto=[0, 0, 0, 0, 0, -k.l2])
    foot.add_geom(name=f"{side}_sole", type=mujoco.mjtGeom.mjGEOM_BOX, mass=k.foot_mass,
                  pos=[k.l3 / 2 - k.heel, 0, -k.d_ap + 0.015], size=[k.l3 / 2, 0.045, 0.015],
                  rgba=[0.3, 0.3, 0.35, 1], contype=SOLE, conaffinity=0)
    add_visual(foot, capsule, [0.03], SKIN, fromto=[0, 0, 0, 0, 0, -k.d_ap + 0.03])
    foot.add_site(name=f"{side}_contact", pos=[0, 0, -k.d_ap])
    foot.add_site(name=f"{side}_foot_ft", pos=[0, 0, 0])
    for body, joint in zip((thigh, shank, foot), JOINTS):
        name = f"{side}_{joint}"
        add_hinge(body, name, [0, 1, 0], limits[joint], armature=k.armature)
        add_servo(spec, name, torques[joint] / SERVO_SATURATION_ERROR, torques[joint], SERVO_DAMPRATIO)
    add_ft_sensor(spec, f"{side}_foot_ft", f"{side}_foot")


def kenshiro_spec(k: KenshiroSpec = KENSHIRO, crank_damping: float = TRICYCLE.crank_damping,
                  crank_friction: float = TRICYCLE.crank_friction) -> mujoco.MjSpec:
    """Kenshiro's legs, waist fixed above the crank rig (keyframe ``ride`` still to be filled)."""
    spec = scene_spec("kenshiro-pedalling", *SCENE)
    waist = spec.worldbody.add_body(name="waist", pos=[0, 0, HIP_HEIGHT])
    add_visual(waist, mujoco.mjtGeom.mjGEOM_BOX, [0.09, 0.16, 0.1], SKIN, pos=[-0.02, 0, 0.08])
    for side in SIDES:
        _add_leg(spec, waist, side, k)
    add_crank(spec.worldbody, [k.d_cx, 0, TRICYCLE.crank_height], k.crank_radius, k.pedal_spacing / 2,
              crank_damping, crank_friction)
    spec.add_key(name="ride")
    return spec


def riding_posture(theta_c: float = 0.0, foot_pitch: float = 0.0, k: KenshiroSpec = KENSHIRO) -> dict[str, float]:
    """Joint values with both soles flat on their pedals at crank angle ``theta_c``.

    Each sole is at ``foot_pitch`` if the leg reaches so, else at the nearest pitch that it reaches
    (1° steps, up to 60° away); the pedal platform lies level with the sole.
    """
    values = {"crank": theta_c}
    for side in SIDES:
        for offset in sorted(np.radians(np.arange(-60, 61)), key=abs):
            psi = foot_pitch + offset
            q = leg_ik(pedal_contact(theta_c, side, psi, k), psi, k)
            if q is not None:
                break
        else:
            raise ValueError(f"Kenshiro's {side} foot cannot reach its pedal at θ_c = {theta_c:.3f} rad")
        values.update({f"{side}_{j}": v for j, v in zip(JOINTS, q)})
        values[f"pedal_{side}"] = psi - theta_c  # the platform level with the sole
    return values


def build_kenshiro(theta_c: float = 0.0, foot_pitch: float = 0.0, k: KenshiroSpec = KENSHIRO,
                   crank_damping: float = TRICYCLE.crank_damping, crank_friction: float = TRICYCLE.crank_friction,
                   substeps: int | None = None) -> MujocoBody:
    """Kenshiro pedalling rig as a MujocoBody, reset to keyframe ``ride`` (feet on the pedals).

    One body step is Kenshiro's 16 ms control period (§3.5.5) unless ``substeps`` says otherwise.
    """
    spec = kenshiro_spec(k, crank_damping, crank_friction)
    model = spec.compile()
    qpos = model.qpos0.copy()
    set_joints(model, qpos, riding_posture(theta_c, foot_pitch, k))
    fill_keyframe(model, "ride", qpos)
    steps = round(k.control_period / PHYSICS_TIMESTEP) if substeps is None else substeps
    return MujocoBody(model, substeps=steps, keyframe="ride", spec=spec)
