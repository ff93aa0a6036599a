"""Motion capture onto spined robots (seed 003 §5.8, Fig. 5.28): the shipped clip and the retargeting.

**The clip.** §5.8.2 played "a sample BVH file of 3D Studio MAX" in which the figure twists its trunk to
prepare a backward somersault. That file is not ours to ship, so :func:`twist_clip` writes a clip of the same
kind from a simple kinematic human (hips, three spine segments, chest, neck, head, collars, arms, legs; Y up,
Z forward, X to the figure's left, cm, every joint ``CHANNELS 3 Zrotation Xrotation Yrotation`` as §5.8.2
quotes): stand, crouch and wind the trunk up (shoulders turned :data:`TWIST_PEAK_DEG` against the pelvis, the
pelvis turned a little the other way, arms swung), hold, unwind with the arms swung up into a take-off pose.
``twist_clip.bvh`` beside this file is its output (:func:`regenerate`; a test checks they are equal).

**Retargeting.** §5.8.2 maps the DOFs that the BVH and the robot model share and leaves the others still
("腿太 … 脊椎に 10 節もあると BVH より自由度が多い場合もある. その場合は, BVH ファイルに無い自由度は動かさない");
how a BVH spine is spread over a 5- or 10-joint spine is not described (spec 003 §1.9 [?]). Here the BVH's
trunk rotation (hips → chest, the product of the spine joints' rotations) is expressed in the robot frame
(x forward, y left, z up), split into whole-spine angles Θ = (φ, θ, ψ) (the rpy of
:func:`~shintai.spine.geometry.matrix_rpy`) and

* ``uniform`` (default): shared equally by the n joints, Θ/n each — the uniform-bend interface of §4.4.4,
  eq. 4.29 (:func:`~shintai.spine.geometry.uniform_posture`);
* ``by_joint``: the thesis's literal DOF matching — BVH spine joint k drives robot joint k (bottom up), the
  robot joints beyond the BVH's spine joints stay still;

each joint angle clamped to the robot's limits (Cla ±18°, Kenta ±10° per axis, §3.6.1, §3.7.1). The HRP2
model of seed 000 (Table A.2) has a waist yaw (±45°) and pitch (−5°…+60°) and no roll: Θ's yaw and pitch go
to them, clamped. The humanoid of Fig. 5.28 — the HRP of 2001, "脊椎を持たないヒューマノイド" — has no trunk
joint at all (``hrp_rigid``: the same model with the waist held at zero). Only the HRP2's arms are retargeted
(:func:`hrp2_arms`: shoulder pitch and roll from the upper arm's direction, elbow from the forearm's angle);
Cla's arms are a fixed load in our model and Kenta has no arm model here.

**Twist.** A trunk's twist is the yaw of its shoulder line against its pelvis line, measured in the pelvis
frame's horizontal plane: for the human the line between the two upper-arm roots against the line between the
two hip joints; for a robot the top link's lateral axis against the base's, both through forward kinematics
(:meth:`~shintai.spine.geometry.Chain.frames`), so clamping, the non-commuting split and Kenta's wedge
vertebrae all show in the robot's achieved twist.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shintai.core.geometry import rot_y, rot_z
from shintai.humanoid.constants import WAIST_JOINTS, joint_range
from shintai.spine.geometry import matrix_rpy
from shintai.spine.mocap.bvh import Bvh, Joint, dumps, read
from shintai.spine.mocap.constants import (
    DURATION_S,
    FLEXION_DEG,
    FPS,
    PELVIS_COUNTER_DEG,
    SIDE_BEND_DEG,
    TWIST_PEAK_DEG,
)
from shintai.spine.robots import CLA, KENTA

SHIPPED_CLIP = Path(__file__).parent / "twist_clip.bvh"
SPINE_SHARE = {"Spine": 0.30, "Spine1": 0.35, "Chest": 0.35}  # how the human's three spine joints share it
ROT = ("Zrotation", "Xrotation", "Yrotation")  # §5.8.2's example channel order
# BVH (X left, Y up, Z forward) → robot (x forward, y left, z up)
TO_ROBOT = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])

# name, parent, offset [cm] (T-pose), end site
SKELETON = (
    ("Hips", None, (0.0, 95.0, 0.0), None),
    ("Spine", "Hips", (0.0, 10.0, 0.0), None),
    ("Spine1", "Spine", (0.0, 12.0, 0.0), None),
    ("Chest", "Spine1", (0.0, 12.0, 0.0), None),
    ("Neck", "Chest", (0.0, 16.0, 0.0), None),
    ("Head", "Neck", (0.0, 9.0, 0.0), (0.0, 16.0, 0.0)),
    ("LeftShoulder", "Chest", (4.0, 12.0, 0.0), None),
    ("LeftArm", "LeftShoulder", (13.0, 0.0, 0.0), None),
    ("LeftForeArm", "LeftArm", (28.0, 0.0, 0.0), None),
    ("LeftHand", "LeftForeArm", (25.0, 0.0, 0.0), (9.0, 0.0, 0.0)),
    ("RightShoulder", "Chest", (-4.0, 12.0, 0.0), None),
    ("RightArm", "RightShoulder", (-13.0, 0.0, 0.0), None),
    ("RightForeArm", "RightArm", (-28.0, 0.0, 0.0), None),
    ("RightHand", "RightForeArm", (-25.0, 0.0, 0.0), (-9.0, 0.0, 0.0)),
    ("LeftUpLeg", "Hips", (9.0, -6.0, 0.0), None),
    ("LeftLeg", "LeftUpLeg", (0.0, -43.0, 0.0), None),
    ("LeftFoot", "LeftLeg", (0.0, -42.0, 0.0), (0.0, -4.0, 14.0)),
    ("RightUpLeg", "Hips", (-9.0, -6.0, 0.0), None),
    ("RightLeg", "RightUpLeg", (0.0, -43.0, 0.0), None),
    ("RightFoot", "RightLeg", (0.0, -42.0, 0.0), (0.0, -4.0, 14.0)),
)


def smooth(t, t0: float, t1: float) -> np.ndarray:
    """Minimum-jerk step from 0 (t ≤ t0) to 1 (t ≥ t1)."""
    u = np.clip((np.asarray(t, dtype=float) - t0) / (t1 - t0), 0.0, 1.0)
    return u**3 * (10 - 15 * u + 6 * u**2)


def twist_clip() -> Bvh:
    """The shipped clip (module docstring): 91 frames at 30 fps; the twist peaks at frame 45 (t = 1.5 s)
    and is held to t = 1.9 s."""
    t = np.arange(round(DURATION_S * FPS) + 1) / FPS
    wind = smooth(t, 0.4, 1.5) - smooth(t, 1.9, 2.6)  # the trunk wind-up
    crouch = smooth(t, 0.3, 1.3) - smooth(t, 1.9, 2.5)
    up = smooth(t, 1.9, 2.6)  # arms swung up for the take-off
    twist = TWIST_PEAK_DEG * wind
    zero = np.zeros_like(t)
    values: dict[str, tuple] = {name: (zero, zero, zero) for name, *_ in SKELETON}  # (Z, X, Y) per joint
    values["Hips"] = (zero, 12.0 * crouch, -PELVIS_COUNTER_DEG * wind)
    for name, share in SPINE_SHARE.items():
        values[name] = (share * SIDE_BEND_DEG * wind, share * FLEXION_DEG * crouch, share * twist)
    values["Neck"] = (zero, -8.0 * crouch, -0.4 * twist)  # the head keeps roughly facing forward
    for side, s in (("Left", 1.0), ("Right", -1.0)):
        values[f"{side}Arm"] = (s * (-75.0 + 160.0 * up), zero, -40.0 * wind + s * 20.0 * crouch * (1 - up))
        values[f"{side}ForeArm"] = (zero, zero, s * 35.0 * crouch * (1 - up))
        values[f"{side}UpLeg"] = (zero, -50.0 * crouch, PELVIS_COUNTER_DEG * wind)
        values[f"{side}Leg"] = (zero, 75.0 * crouch, zero)
        values[f"{side}Foot"] = (zero, -37.0 * crouch, zero)
    joints, columns, col = [], [], 0
    names = [name for name, *_ in SKELETON]
    for name, parent, offset, end in SKELETON:
        channels = (("Xposition", "Yposition", "Zposition") if parent is None else ()) + ROT
        joints.append(Joint(name, -1 if parent is None else names.index(parent), np.array(offset, float), channels,
                            None if end is None else np.array(end, float), first_column=col))
        col += len(channels)
        if parent is None:
            columns += [zero, -18.0 * crouch, zero]  # the root sinks 18 cm in the crouch (feet stay down)
        columns += list(values[name])
    return Bvh(joints, np.stack(columns, axis=1), 1.0 / FPS, "twist_clip")


def regenerate(path: str | Path = SHIPPED_CLIP) -> Path:
    """Write :func:`twist_clip` as BVH to ``path`` (the shipped file by default)."""
    Path(path).write_text(dumps(twist_clip()))
    return Path(path)


def load(path: str | Path | None = None) -> Bvh:
    """A user's BVH file, or the shipped clip."""
    return read(SHIPPED_CLIP if path in (None, "") else path)


# ---------------------------------------------------------------------------------------------------------
# Trunk of the BVH
# ---------------------------------------------------------------------------------------------------------

TRUNK_NAMES = {  # candidates per role, first match wins (common BVH namings)
    "pelvis": ("Hips", "hip", "Pelvis", "pelvis", "Root"),
    "chest": ("Chest", "Spine2", "Spine1", "chest", "abdomen", "Spine"),  # the highest spine joint
    "left_shoulder": ("LeftArm", "LeftUpArm", "lShldr", "LeftShoulder", "l_shoulder"),
    "right_shoulder": ("RightArm", "RightUpArm", "rShldr", "RightShoulder", "r_shoulder"),
    "left_hip": ("LeftUpLeg", "LeftHip", "lThigh", "l_hip"),
    "right_hip": ("RightUpLeg", "RightHip", "rThigh", "r_hip"),
}


def trunk_joints(bvh: Bvh) -> dict[str, str]:
    """The joints playing each trunk role; ValueError naming the missing role (one line)."""
    names = {j.name for j in bvh.joints}
    found = {}
    for role, candidates in TRUNK_NAMES.items():
        hit = next((c for c in candidates if c in names), None)
        if hit is None:
            raise ValueError(f"{bvh.source}: no {role.replace('_', ' ')} joint (looked for {', '.join(candidates)})")
        found[role] = hit
    return found


def spine_path(bvh: Bvh, pelvis: str, chest: str) -> list[str]:
    """The joints from just above the pelvis up to the chest (bottom up); ValueError if chest is not above."""
    index = {j.name: i for i, j in enumerate(bvh.joints)}
    path, i = [], index[chest]
    while i >= 0 and bvh.joints[i].name != pelvis:
        path.append(bvh.joints[i].name)
        i = bvh.joints[i].parent
    if i < 0:
        raise ValueError(f"{bvh.source}: {chest} is not below {pelvis}")
    return path[::-1]


@dataclass(frozen=True)
class HumanTrunk:
    times_s: np.ndarray
    twist_deg: np.ndarray  # (F,) shoulder line against pelvis line
    rotation: np.ndarray  # (F, 3, 3) pelvis → chest, robot axes
    segments: np.ndarray  # (F, k, 3, 3) each spine joint's rotation, robot axes, bottom up
    positions: np.ndarray  # (F, J, 3) world joint positions (BVH axes, file units), for pictures


def line_yaw_deg(v_forward, v_left) -> np.ndarray:
    """Yaw [deg] of a left-pointing line (components along the pelvis's forward and left axes)."""
    return np.degrees(np.arctan2(-np.asarray(v_forward), np.asarray(v_left)))


def human_trunk(bvh: Bvh) -> HumanTrunk:
    roles = trunk_joints(bvh)
    index = {j.name: i for i, j in enumerate(bvh.joints)}
    R, p = bvh.world()
    Rp = R[:, index[roles["pelvis"]]]

    def in_pelvis(a: str, b: str) -> np.ndarray:
        return np.einsum("fba,fb->fa", Rp, p[:, index[roles[a]]] - p[:, index[roles[b]]])  # Rpᵀ (a − b)

    shoulders, hips = in_pelvis("left_shoulder", "right_shoulder"), in_pelvis("left_hip", "right_hip")
    twist = line_yaw_deg(shoulders[:, 2], shoulders[:, 0]) - line_yaw_deg(hips[:, 2], hips[:, 0])
    twist = (twist + 180.0) % 360.0 - 180.0
    to_robot = lambda Rb: TO_ROBOT @ Rb @ TO_ROBOT.T
    rotation = to_robot(np.einsum("fba,fbc->fac", Rp, R[:, index[roles["chest"]]]))
    segments = np.stack([to_robot(bvh.local_rotations(name))
                         for name in spine_path(bvh, roles["pelvis"], roles["chest"])], axis=1)
    return HumanTrunk(bvh.times_s, twist, rotation, segments, p)


# ---------------------------------------------------------------------------------------------------------
# Robots
# ---------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Retargeted:
    robot: str
    joint_names: tuple[str, ...]
    targets: np.ndarray  # (F, dof) joint angles [rad], within the limits
    lower: np.ndarray
    upper: np.ndarray
    saturated: np.ndarray  # (F,) bool: some joint target was clamped in that frame
    twist_deg: np.ndarray  # (F,) achieved twist (forward kinematics)
    top: np.ndarray  # (F, 3, 3) top (shoulder) frame in the base (pelvis) frame


ROBOTS = ("cla", "kenta", "hrp2", "hrp_rigid")
SPINE_ROBOTS = {"cla": CLA, "kenta": KENTA}


def _twist_of(top: np.ndarray) -> np.ndarray:
    return line_yaw_deg(top[:, 0, 1], top[:, 1, 1])


def retarget(trunk: HumanTrunk, robot: str, mapping: str = "uniform") -> Retargeted:
    """Joint targets of ``robot``'s trunk over the clip (module docstring), clamped to its limits."""
    F = len(trunk.times_s)
    if robot in SPINE_ROBOTS:
        chain = SPINE_ROBOTS[robot].model.chain
        n = chain.n
        raw = np.zeros((F, n, 3))
        if mapping == "uniform":
            raw[:] = matrix_rpy(trunk.rotation)[:, None, :] / n
        elif mapping == "by_joint":
            k = min(n, trunk.segments.shape[1])
            raw[:, :k] = matrix_rpy(trunk.segments[:, :k])
        else:
            raise ValueError(f"mapping {mapping!r}: expected uniform or by_joint")
        raw = raw.reshape(F, 3 * n)
        targets = np.clip(raw, chain.lower, chain.upper)
        R, _, _ = chain.frames(targets)
        top = np.einsum("fba,fbc->fac", R[:, 0], R[:, -1])
        names = tuple(f"j{i}_{ax}" for i in range(1, n + 1) for ax in ("roll", "pitch", "yaw"))
        lower, upper = chain.lower, chain.upper
    elif robot in ("hrp2", "hrp_rigid"):
        lower = np.array([joint_range(j)[0] for j in WAIST_JOINTS])
        upper = np.array([joint_range(j)[1] for j in WAIST_JOINTS])
        rpy = matrix_rpy(trunk.rotation)
        raw = np.stack([rpy[:, 2], rpy[:, 1]], axis=1) if robot == "hrp2" else np.zeros((F, 2))
        targets = np.clip(raw, lower, upper)
        top = np.stack([rot_z(y) @ rot_y(p) for y, p in targets])
        names = tuple(j.name for j in WAIST_JOINTS)
    else:
        raise ValueError(f"robot {robot!r}: expected one of {', '.join(ROBOTS)}")
    saturated = np.any(np.abs(raw - targets) > 1e-12, axis=1)
    return Retargeted(robot, names, targets, lower, upper, saturated, _twist_of(top), top)


# ---------------------------------------------------------------------------------------------------------
# HRP2's arms
# ---------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ArmTargets:
    """HRP2 arm joint targets [rad] from the BVH's upper arms and forearms, clamped to Table A.2's ranges."""

    targets: dict[str, np.ndarray]  # joint name (``r_shoulder_pitch`` …) → (F,)
    saturated: np.ndarray  # (F,) some arm target clamped
    direction_error_deg: np.ndarray  # (F,) angle between the human's and the robot's upper-arm direction


def hrp2_arms(bvh: Bvh) -> ArmTargets:
    """The upper arm's direction in the chest frame (robot axes) → shoulder pitch and roll of an arm hanging
    along −z at zero (R = Ry(pitch) Rx(roll): d = (−cos r sin p, sin r, −cos r cos p)); the forearm's angle
    to the upper arm → elbow pitch (negative forward, Table A.2); shoulder and wrist yaw stay 0 (an upper
    arm's own axial rotation is not matched). Forward kinematics of the clamped pitch/roll gives the
    achieved direction."""
    roles = trunk_joints(bvh)
    index = {j.name: i for i, j in enumerate(bvh.joints)}
    R, p = bvh.world()
    chest = R[:, index[roles["chest"]]]
    from shintai.humanoid.constants import ARM_JOINTS

    spec = {j.name: j for j in ARM_JOINTS}
    targets, saturated, error = {}, np.zeros(bvh.n_frames, bool), np.zeros(bvh.n_frames)
    for side, role in (("r", "right_shoulder"), ("l", "left_shoulder")):
        arm = index[roles[role]]
        fore = next((i for i, j in enumerate(bvh.joints) if j.parent == arm), None)
        hand = next((i for i, j in enumerate(bvh.joints) if fore is not None and j.parent == fore), None)
        if fore is None or hand is None:
            raise ValueError(f"{bvh.source}: {roles[role]} has no forearm and hand below it")
        upper_dir = np.einsum("fba,fb->fa", chest, p[:, fore] - p[:, arm])  # in the chest frame
        fore_dir = np.einsum("fba,fb->fa", chest, p[:, hand] - p[:, fore])
        d = upper_dir @ TO_ROBOT.T
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        roll = np.arcsin(np.clip(d[:, 1], -1, 1))
        pitch = np.arctan2(-d[:, 0], -d[:, 2])
        lo, hi = joint_range(spec["shoulder_pitch"], side)
        turns = pitch[:, None] + np.array([0.0, -2 * np.pi, 2 * np.pi])  # the turn that needs the least clamping
        pitch = turns[np.arange(len(pitch)), np.argmin(np.maximum(lo - turns, 0) + np.maximum(turns - hi, 0), axis=1)]
        cos_elbow = np.einsum("fa,fa->f", upper_dir, fore_dir) / (
            np.linalg.norm(upper_dir, axis=1) * np.linalg.norm(fore_dir, axis=1))
        raw = {"shoulder_pitch": pitch, "shoulder_roll": roll, "elbow_pitch": -np.arccos(np.clip(cos_elbow, -1, 1))}
        for name, value in raw.items():
            lo, hi = joint_range(spec[name], side)
            clamped = np.clip(value, lo, hi)
            saturated |= np.abs(clamped - value) > 1e-9
            targets[f"{side}_{name}"] = clamped
        pr, rr = targets[f"{side}_shoulder_pitch"], targets[f"{side}_shoulder_roll"]
        achieved = np.stack([-np.cos(rr) * np.sin(pr), np.sin(rr), -np.cos(rr) * np.cos(pr)], axis=1)
        error = np.maximum(error, np.degrees(np.arccos(np.clip(np.einsum("fa,fa->f", achieved, d), -1, 1))))
    return ArmTargets(targets, saturated, error)
