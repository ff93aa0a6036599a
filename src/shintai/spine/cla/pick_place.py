"""Cla seated picks an object from the floor and puts it on the desk (seed 003 §5.2.5–5.2.6, Fig. 5.7; Figs.
2.1–2.2), on the whole-body Cla of :mod:`~shintai.spine.cla.body`, with the spine or with it locked.

§5.2.5: "椅子に座った状態で床に置いてある物を拾おうとするとき、手を伸ばしただけでは床に手が届かず拾うことができない。
脊椎の動きを利用して脊椎を側屈させればそれが可能になる。… Cla は脊椎の roll 方向の自由度を用いる事で、重心を椅子の上
に置いたまま床の物を拾うことができる". §5.2.6: "拾ったものを机の上に置くときも、座った状態では、脊椎を動かさなければ
机の上に置くことができない … 脊椎をねじることで … 机の上に手を伸ばして物を机の上に置くことができた".

**The behaviour** (:func:`keys`): rest → bend the spine sideways (roll) with the right hand above the object →
hand down onto it → close the hand → straighten, the hand up → twist the spine (yaw) with the hand above the
place spot → lower → open → withdraw. Every arm key is solved on the model (:class:`~shintai.spine.cla.reach.ArmIK`)
for its hand target and the key's spine posture; with the spine locked the same targets are solved with the
spine straight. The hand closes (:class:`Grip`) at the end of the reach if its surface is within
:data:`GRIP_TOLERANCE_M` of the object (a weld, :meth:`~shintai.spine.cla.body.ClaBody.grip`: Cla's hand is
not described), and opens at the end of the lowering.

**The scene** (:func:`seated_spec`, :func:`set_scene`): §5.2.1's chair is "足が地面に着かない程度の高さ" — just high
enough that the feet do not touch the floor. cla_body's stool holds the pelvis 0.45 m up with the soles 0.27 m
above its floor; the floor is raised here to :data:`FLOOR_CLEARANCE_M` below the soles (the chair's height is not
in the text).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.spine.cla.body import LIMB_JOINTS, SPINE_JOINTS, ClaBody, build_spec, start_targets
from shintai.spine.cla.constants import (
    FLOOR_CLEARANCE_M,
    GRIP_TOLERANCE_M,
    HOVER_M,
    OBJECT_XY_M,
    PICK_PLACE_YAW_DEG,
    ROLL_DEG,
)
from shintai.spine.cla.control import spine_control
from shintai.spine.cla.keyframes import Key, WholeBodyKeys
from shintai.spine.cla.reach import ArmIK
from shintai.spine.geometry import whole_spine
from shintai.spine.robots import (
    CLA,
    CLA_DESK_HALF_M,
    CLA_DESK_HEIGHT_M,
    CLA_DESK_NEAR_M,
    CLA_HAND_RADIUS_M,
    CLA_OBJECT_HALF_M,
)

SPOT_XY_M = (CLA_DESK_NEAR_M + 0.15, 0.0)  # the place spot: the desk's middle, 15 cm beyond its near edge


def over_desk(hand) -> bool:
    """Would an object held in this hand rest on the desk if let go: the hand above the desk's top (inside its
    outline, the object's half size in from the edges) and no higher than an object's height + 1 cm above it."""
    x, y, z = hand
    h = CLA_OBJECT_HALF_M
    return bool(CLA_DESK_NEAR_M + h < x < CLA_DESK_NEAR_M + 2 * CLA_DESK_HALF_M[0] - h
                and abs(y) < CLA_DESK_HALF_M[1] - h
                and 0.0 < z - CLA_HAND_RADIUS_M - CLA_DESK_HEIGHT_M < 2 * h + 0.01)
# Key durations [s] (§5.2: "ゆっくり" is all the text says of speed)
DURATIONS = {"rest": 0.5, "bend": 2.0, "reach": 1.0, "grip": 0.3, "lift": 2.0, "twist": 2.0, "lower": 1.0,
             "release": 0.3, "withdraw": 1.0}
VARIANTS = ("spine", "locked")


def seated_spec() -> mujoco.MjSpec:
    """cla_body's seated spec with the floor raised to :data:`FLOOR_CLEARANCE_M` below the lowest sole contact
    sphere (module docstring)."""
    spec = build_spec("seated")
    m = spec.compile()
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, m.key("seated").id)
    mujoco.mj_forward(m, d)
    soles = [i for i in range(m.ngeom) if (m.geom(i).name or "").startswith("sole_")]
    z = float(min(d.geom_xpos[i][2] - m.geom_size[i][0] for i in soles)) - FLOOR_CLEARANCE_M
    spec.geom("floor").pos = [0.0, 0.0, z]
    return spec


def set_scene(body: ClaBody) -> dict[str, np.ndarray]:
    """Raise the floor, put the object on it, move the desk's own object out of the way; the grasp point (the
    hand's centre on the object's top), the place spot (the hand's centre when the object rests there)."""
    z = float(body.model.geom_pos[body.id("geom", "floor"), 2])
    body.place("floor_object", [*OBJECT_XY_M, z + CLA_OBJECT_HALF_M])
    body.place("desk_object", [CLA_DESK_NEAR_M + 0.33, 0.25, CLA_DESK_HEIGHT_M + CLA_OBJECT_HALF_M])
    top = z + 2 * CLA_OBJECT_HALF_M
    return {"floor_z": z, "object0": body.object_pos("floor_object"),
            "grasp": np.array([*OBJECT_XY_M, top + CLA_HAND_RADIUS_M]),
            "spot": np.array([*SPOT_XY_M, CLA_DESK_HEIGHT_M + 2 * CLA_OBJECT_HALF_M + CLA_HAND_RADIUS_M + 0.003])}


def keys(ik: ArmIK, scene: dict, spine: bool, roll_deg: float = ROLL_DEG, yaw_deg: float = PICK_PLACE_YAW_DEG
         ) -> tuple[list[Key], dict[str, float]]:
    """The behaviour's keys (module docstring) and the distance the solver leaves at each hand target [m]. The
    spine's keys are the same in both variants (locked, the spine does not follow them); the arm's are solved
    for the spine the variant has."""
    roll, yaw = math.radians(roll_deg), math.radians(yaw_deg)
    up = np.array([0.0, 0.0, HOVER_M])
    plan = [("bend", (roll, 0, 0), scene["grasp"] + up), ("reach", (roll, 0, 0), scene["grasp"]),
            ("lift", (0, 0, 0), np.array([0.12, -0.12, CLA_DESK_HEIGHT_M + 0.12])),
            ("twist", (0, 0, yaw), scene["spot"] + up), ("lower", (0, 0, yaw), scene["spot"]),
            ("withdraw", (0, 0, 0), np.array([0.12, -0.12, CLA_DESK_HEIGHT_M + 0.12]))]
    out, gaps, guess = [Key(DURATIONS["rest"], {}, "rest")], {}, None
    for label, whole, target in plan:
        arm, gap = ik.solve("r", whole if spine else (0, 0, 0), target, guess)
        guess, gaps[label] = arm, gap
        out.append(Key(DURATIONS[label], {"spine_roll": whole[0], "spine_yaw": whole[2], **arm}, label))
        if label in ("reach", "lower"):
            hold = "grip" if label == "reach" else "release"
            out.append(Key(DURATIONS[hold], {}, hold))
    return out, gaps


class Grip(Module):
    """Cla's right hand: closes on the object when the keys enter ``grip`` if its surface is within
    :data:`GRIP_TOLERANCE_M` of the object's top, opens when they enter ``release`` (where the hand is then is
    kept, gripping or not). It acts on the body
    directly (a weld, :meth:`~shintai.spine.cla.body.ClaBody.grip`), as the hand's own servo would."""

    def __init__(self, body: ClaBody, player: WholeBodyKeys, obj: str = "floor_object", name: str = "grip"):
        super().__init__(name)
        self.body, self.player, self.obj = body, player, obj
        self.gripped, self.closed_at, self.gap_at_grip = False, None, math.nan
        self.hand_at_release: np.ndarray | None = None

    def update(self, snapshot: Snapshot):
        label = self.player.label(snapshot["t"])
        if label == "grip" and self.closed_at is None:
            hand, obj = self.body.site_pos("hand_r"), self.body.object_pos(self.obj)
            top = obj[2] + CLA_OBJECT_HALF_M
            self.gap_at_grip = float(max(hand[2] - CLA_HAND_RADIUS_M - top, 0.0)
                                     + max(np.abs(hand[:2] - obj[:2]).max() - CLA_OBJECT_HALF_M, 0.0))
            self.closed_at = snapshot["t"]
            if self.gap_at_grip <= GRIP_TOLERANCE_M:
                self.body.grip("r", self.obj, True)
                self.gripped = True
        elif label == "release" and self.hand_at_release is None:
            self.hand_at_release = self.body.site_pos("hand_r").copy()
            if self.gripped:
                self.body.grip("r", self.obj, False)
                self.gripped = False
        return None


def com_margin(body: ClaBody) -> float:
    """How far the whole robot's centre of mass projects inside the seat's sides [m] (negative: beyond one):
    the lateral margin, the one a sideways reach spends (Fig. 2.1). Front–back the CoM sits at the stool's front
    edge from the start (the thighs lie forward over it; cla_body's stool), and the pelvis is fixed on it."""
    m, d = body.model, body.data
    com_y = d.subtree_com[body.id("body", "link0")][1]
    seat = body.id("geom", "seat")
    return float(m.geom_size[seat][1] - abs(com_y - d.geom_xpos[seat][1]))


def build(spine: bool, roll_deg: float = ROLL_DEG, yaw_deg: float = PICK_PLACE_YAW_DEG, calibration_s: float = 1.0):
    """A seated Cla in the scene, calibrated (§4.6.4, ``calibration_s``), its spine locked unless ``spine``; the
    keys' player (first stage), the hand, the muscle controller (second stage), the scene and the solver's gaps."""
    body = ClaBody("seated", spec=seated_spec())
    scene = set_scene(body)
    control, zero = spine_control(body, calibration_s=calibration_s)
    if not spine:
        body.lock_spine(True)
    ik = ArmIK(body.model, body.data, SPINE_JOINTS, CLA.n)
    key_list, gaps = keys(ik, scene, spine, roll_deg, yaw_deg)
    start = {**start_targets("seated"), "spine_roll": 0.0, "spine_pitch": 0.0, "spine_yaw": 0.0}
    player = WholeBodyKeys(CLA.model, zero, LIMB_JOINTS, start, key_list)
    grip = Grip(body, player)
    return body, player, grip, control, scene, gaps


def signals(body: ClaBody, grip: Grip, scene: dict) -> dict:
    """What is recorded: hand and object positions, the whole-spine (roll, pitch, yaw), the CoM margin."""
    return {"hand": body.site_pos("hand_r"), "object": body.object_pos("floor_object"),
            "whole_deg": np.degrees(whole_spine(body.theta())), "com_margin": com_margin(body),
            "gripped": float(grip.gripped), "spot_gap": float(np.linalg.norm(body.site_pos("hand_r") - scene["spot"]))}
