"""Kenta's visual tracking (seed 003 §5.2.12, Figs. 5.13–5.14): eyes, neck and spine loops of different periods
(:mod:`shintai.spine.tracking_loops`) while both arms swing (§5.2.11), after §4.6.4's encoder zeroing."""

from __future__ import annotations

from shintai.spine.kenta.body import ARM_NAMES, calibrated_kenta
from shintai.spine.robots import KENTA, KENTA_EYE_LIMIT_RAD, KENTA_NECK_LIMIT_RAD
from shintai.spine.tracking_loops import (
    TRACKING_GAINS,
    TRACKING_PERIODS_S,
    ArmSwing,
    GazeLoop,
    SpineGazeLoop,
    Tracking,
    tracking_stages,
)

SWUNG = ("shoulder_pitch_L", "shoulder_pitch_R", "elbow_pitch_L", "elbow_pitch_R")  # ArmSwing's joints


def kenta_tracking(loops: tuple[str, ...], amplitude_m: float, path_period_s: float, zeroing_s: float = 1.0,
                   arm_swing_rad: float = 0.0, arm_period_s: float = 2.0) -> tuple[object, list, Tracking]:
    """Kenta zeroed for ``zeroing_s``, then the stages of its tracking run with the visual ``loops`` on (and
    :class:`ArmSwing` when ``arm_swing_rad`` > 0): (body, stages, :class:`Tracking`)."""
    body, control, zero = calibrated_kenta(seconds=zeroing_s)
    parts = {"eyes": lambda: GazeLoop("eyes", TRACKING_PERIODS_S["eyes"], TRACKING_GAINS["eyes"],
                                      ("eye_pan", "eye_tilt"), +1.0, KENTA_EYE_LIMIT_RAD),
             "neck": lambda: GazeLoop("neck", TRACKING_PERIODS_S["neck"], TRACKING_GAINS["neck"],
                                      ("neck_pan", "neck_tilt"), -1.0, KENTA_NECK_LIMIT_RAD),
             "spine": lambda: SpineGazeLoop(KENTA.model, zero, TRACKING_PERIODS_S["spine"], TRACKING_GAINS["spine"])}
    modules = [parts[name]() for name in loops]
    arms = ArmSwing(arm_swing_rad, arm_period_s) if arm_swing_rad > 0 else None
    eye = body.data.cam_xpos[body.id("camera", "eye_L")].copy()
    stages, run = tracking_stages(body, control, eye, modules, amplitude_m, path_period_s, arms,
                                  [ARM_NAMES.index(nm) for nm in SWUNG])
    return body, stages, run
