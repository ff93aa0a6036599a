"""Cla rolls over on the floor, from lying on its back to lying on its front, yawing its spine together with the
shoulders and hips (seed 003 §5.2.8, Fig. 5.9), on the whole-body Cla of :mod:`~shintai.spine.cla.body`, with
the spine or with it locked.

§5.2.8: "股関節や肩のアクチュエータのパワーが不足しているため、股関節の力・肩の力だけでは体を捻って半身を起こすことが
できない。脊椎を yaw 軸回りに回転させる動きと肩・股関節の動きを同時に行うことで、肩・股のアクチュエータのパワーと
脊椎の回転力を合わせて、半身を起こすことができる。これにより、仰向けからうつぶせ、うつぶせから仰向けと、両方向の寝返り
ができるようになった".

**The model** (:func:`lying_spec`): cla_body's standing Cla (free pelvis), with every part of the trunk, head and
limbs made to touch the floor (cla_body lets only the hands and soles touch anything). It is calibrated upright
(§4.6.4, as the robot would be), then laid on its back (:func:`lay`).

**The behaviour** (:func:`keys`, hand-made as the thesis's were): the right arm goes overhead (out of the way of
the roll), the left arm points up and the left knee rises; the spine twists the shoulders toward the right ("半身
を起こす") while the left arm reaches across; then the spine twists back the other way with the left hip flexed
further so that the pelvis follows; the limbs return to their rest.
Locked, the same keys run with the spine held straight. The turn of a part is the angle between its front (x
axis) and the world's up: 0° on the back, 90° on a side, 180° on the front.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from shintai.spine.cla.body import LIMB_JOINTS, ClaBody, build_spec, start_targets
from shintai.spine.cla.constants import CONTACT_MIN_SIZE_M, LIE_HEIGHT_M, REST_S, ROLL_OVER_YAW_DEG
from shintai.spine.cla.control import spine_control
from shintai.spine.cla.keyframes import Key, WholeBodyKeys
from shintai.spine.geometry import whole_spine
from shintai.spine.robots import CLA

VARIANTS = ("spine", "locked")


def lying_spec() -> mujoco.MjSpec:
    """The standing Cla's spec with the trunk, head and limbs colliding with the floor (module docstring)."""
    spec = build_spec("standing")
    for geom in spec.geoms:
        body = geom.parent
        if body.name == "world" or geom.contype or geom.name == "wrap" or body.name.endswith(":reel"):
            continue
        if geom.size[0] >= CONTACT_MIN_SIZE_M:
            geom.contype = 1
    return spec


def lay(body: ClaBody) -> None:
    """Put the calibrated Cla on its back on the floor, head toward −x, at rest."""
    m, d = body.model, body.data
    adr = m.jnt_qposadr[body.id("joint", "root")]
    d.qpos[adr:adr + 7] = [0.0, 0.0, LIE_HEIGHT_M, math.cos(-math.pi / 4), 0.0, math.sin(-math.pi / 4), 0.0]
    d.qvel[:] = 0.0
    mujoco.mj_forward(m, d)


def keys(yaw_deg: float = ROLL_OVER_YAW_DEG) -> list[Key]:
    """Supine → prone toward the right (module docstring); yaw + twists the shoulders to the left."""
    yaw = math.radians(yaw_deg)
    return [Key(REST_S, {}, "rest"),
            Key(1.5, {"shoulder_pitch_r": 2.8, "shoulder_pitch_l": 1.57, "hip_l": 1.0, "knee_l": 1.2}, "raise"),
            Key(1.5, {"spine_yaw": -yaw, "shoulder_pitch_l": 2.0, "shoulder_roll_l": -0.3}, "twist"),
            Key(1.5, {"spine_yaw": 2.0 * yaw / 3.0, "hip_l": 1.8}, "follow"),
            Key(1.5, {"spine_yaw": 0.0, "shoulder_pitch_l": 0.0, "shoulder_roll_l": 0.0, "shoulder_pitch_r": 0.0,
                      "hip_l": 0.0, "knee_l": 0.0}, "lie"),
            Key(1.0, {}, "hold")]


def turn_deg(body: ClaBody, part: str) -> float:
    """The angle between ``part``'s front (x axis) and the world's up [deg]: 0 supine, 180 prone."""
    R = body.data.xmat[body.id("body", part)].reshape(3, 3)
    return math.degrees(math.acos(float(np.clip(R[2, 0], -1.0, 1.0))))


def build(spine: bool, yaw_deg: float = ROLL_OVER_YAW_DEG, calibration_s: float = 1.0):
    """A lying Cla, calibrated upright then laid down, its spine locked unless ``spine``; the keys' player and
    the muscle controller."""
    body = ClaBody("standing", spec=lying_spec())
    control, zero = spine_control(body, calibration_s=calibration_s)
    lay(body)
    if not spine:
        body.lock_spine(True)
    start = {**start_targets("standing"), "spine_roll": 0.0, "spine_pitch": 0.0, "spine_yaw": 0.0}
    player = WholeBodyKeys(CLA.model, zero, LIMB_JOINTS, start, keys(yaw_deg))
    return body, player, control


def signals(body: ClaBody) -> dict:
    return {"pelvis_turn_deg": turn_deg(body, "link0"), "shoulder_turn_deg": turn_deg(body, f"link{CLA.n}"),
            "whole_deg": np.degrees(whole_spine(body.theta())),
            "pelvis": body.body_pos("link0").copy()}
