"""Cla standing: the arm-swing reflex of §5.2.7 that keeps the centre of pressure near the front–back centre of
the soles while the spine bends sideways (the centre of pressure itself, eq. 3.5 from the four FSRs of each
foot, is the whole-body Cla's snapshot ``cop``: :class:`~shintai.spine.cla.body.ClaBody`).

§5.2.7 (Fig. 5.8): "ゆっくりと左右の脊椎を屈曲する運動を行う. … 常に足裏の前後方向の中心付近に重心の投影点が来る
ように, 両腕を前後にゆっくりと動かしながらバランスをとる. 足裏の重心投影点が足裏中心より前方に来たら, 両腕を後に
動かし重心を戻そうとする. 逆に重心投影点が後方に行ったら, 両腕を少しずつ前に出し重心が足裏中心付近に来るまで少し
ずつ動かす. こうした反射を, 左右の側屈の動作と並列に行う". The thesis gives no gain, band or speed; ours are the
``COP_*`` constants below, each with its reason.
"""

from __future__ import annotations

import math

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.spine.cla.body import LIMB_JOINTS, ClaBody, start_targets
from shintai.spine.cla.constants import (
    BEND_DEG,
    COP_ARM_RANGE_RAD,
    COP_ARM_SPEED_RAD_S,
    COP_BAND_M,
    COP_FULL_M,
    HALF_PERIOD_S,
    SETTLE_S,
)
from shintai.spine.cla.control import spine_control
from shintai.spine.cla.keyframes import Key, WholeBodyKeys
from shintai.spine.geometry import whole_spine
from shintai.spine.robots import CLA


def reflex_rate(error_m: float) -> float:
    """The arms' pitch-offset rate [rad/s] for a CoP ``error_m`` ahead (+) or behind (−) the sole centre:
    0 within :data:`COP_BAND_M`, then growing linearly to :data:`COP_ARM_SPEED_RAD_S` at :data:`COP_FULL_M`;
    CoP ahead → arms back (negative: our arm pitch is positive forward), behind → forward (§5.2.7)."""
    if not math.isfinite(error_m) or abs(error_m) <= COP_BAND_M:
        return 0.0
    excess = (abs(error_m) - COP_BAND_M) / (COP_FULL_M - COP_BAND_M)
    return -math.copysign(COP_ARM_SPEED_RAD_S * min(excess, 1.0), error_m)


class ArmSwingReflex(Module):
    """§5.2.7's reflex as a module: reads the front–back CoP error (``cop_error(snapshot)`` [m]: the CoP of eq.
    3.5 minus the soles' front–back centre) and integrates the arms' pitch offset (:func:`reflex_rate`), added to
    both shoulders' pitch servos (``channels``; the Loop sums it onto the behaviour's own targets);
    ``enabled=False`` holds the offset at 0 (no arm swing)."""

    def __init__(self, cop_error, channels=("shoulder_pitch_r", "shoulder_pitch_l"), enabled: bool = True,
                 period: float | None = None, name: str = "arm_swing_reflex"):
        super().__init__(name, period)
        self.cop_error = cop_error  # snapshot → front–back CoP error [m]
        self.channels = tuple(channels)
        self.enabled = enabled
        self.offset = 0.0

    def reset(self, snapshot: Snapshot) -> None:
        self.offset = 0.0
        self._last_t = float(snapshot["t"])

    def update(self, snapshot: Snapshot):
        t = float(snapshot["t"])
        dt, self._last_t = t - self._last_t, t
        if self.enabled:
            rate = reflex_rate(float(self.cop_error(snapshot)))
            self.offset = float(np.clip(self.offset + rate * dt, -COP_ARM_RANGE_RAD, COP_ARM_RANGE_RAD))
        return dict.fromkeys(self.channels, self.offset)


VARIANTS = ("swing", "no_swing")


def bend_keys(cycles: int, bend_deg: float = BEND_DEG, half_period_s: float = HALF_PERIOD_S):
    """Rest, then ``cycles`` × (bend right, bend left), then upright: whole-spine roll keys, minimum jerk."""
    roll = math.radians(bend_deg)
    keys = [Key(SETTLE_S, {}, "stand")]
    for _ in range(cycles):
        keys += [Key(half_period_s, {"spine_roll": roll}, "right"), Key(half_period_s, {"spine_roll": -roll}, "left")]
    return keys + [Key(half_period_s / 2, {"spine_roll": 0.0}, "upright")]


def sole_centre_x(body) -> float:
    """The soles' front–back centre: the mean x of the eight FSR sites (world) [m]."""
    return float(np.mean([body.site_pos(f"fsr_{s}{k}")[0] for s in ("r", "l") for k in range(1, 5)]))


def build(swing: bool, cycles: int, bend_deg: float = BEND_DEG, half_period_s: float = HALF_PERIOD_S,
          calibration_s: float = 1.0):
    """A standing Cla, calibrated; the bends' player and the reflex (first stage), the muscle controller."""
    body = ClaBody("standing")
    control, zero = spine_control(body, calibration_s=calibration_s)
    centre = sole_centre_x(body)
    start = {**start_targets("standing"), "spine_roll": 0.0, "spine_pitch": 0.0, "spine_yaw": 0.0}
    player = WholeBodyKeys(CLA.model, zero, LIMB_JOINTS, start, bend_keys(cycles, bend_deg, half_period_s))
    reflex = ArmSwingReflex(lambda snap: snap["cop"][0] - sole_centre_x(body), enabled=swing)
    return body, player, reflex, control, centre


def signals(body, reflex: ArmSwingReflex, snap) -> dict:
    return {"cop": np.asarray(snap["cop"], dtype=float), "sole_centre_x": sole_centre_x(body),
            "force": float(np.sum(snap["sole_force"])), "arm_offset_deg": math.degrees(reflex.offset),
            "roll_deg": math.degrees(float(whole_spine(body.theta())[0])),
            "pelvis_z": float(body.body_pos("link0")[2]),
            "com": body.data.subtree_com[body.id("body", "link0")].copy()}
