"""Kenta's visual tracking (seed 003 §5.2.12, Figs. 5.13–5.14): eyes, neck and spine loops of different periods
(:mod:`shintai.spine.tracking_loops`) while both arms swing, after §4.6.4's encoder zeroing; the spine loop's
posture from Kenta's own NN inverse model (§4.4.3's method on Kenta's 40 muscles: 40-40-30, 343 uniform bends on
``KENTA_NN_GRID_DEG``) or by Jacobian integration."""

from __future__ import annotations

import numpy as np

from shintai.spine.kenta.body import ARM_NAMES, calibrated_kenta
from shintai.spine.kenta.constants import KENTA_NN_GRID_DEG
from shintai.spine.robots import KENTA, KENTA_EYE_LIMIT_RAD, KENTA_NECK_LIMIT_RAD
from shintai.spine.tracking_loops import (
    TRACKING_GAINS,
    TRACKING_PERIODS_S,
    ArmSwing,
    GazeLoop,
    SpineGazeLoop,
    Tracking,
    posture_estimator,
    tracking_stages,
)

SWUNG = ("shoulder_pitch_L", "shoulder_pitch_R", "elbow_pitch_L", "elbow_pitch_R")  # ArmSwing's joints


def kenta_tracking(loops: tuple[str, ...], amplitude_m: float, path_period_s: float, zeroing_s: float = 1.0,
                   arm_swing_rad: float = 0.0, arm_period_s: float = 2.0, estimator: str = "nn",
                   rng: np.random.Generator | None = None) -> tuple[object, list, Tracking]:
    """Kenta zeroed for ``zeroing_s``, then the stages of its tracking run with the visual ``loops`` on (and
    :class:`ArmSwing` when ``arm_swing_rad`` > 0), the spine's posture by ``estimator`` (``"nn"``: trained here,
    from ``rng``; ``"jacobian"``): (body, stages, :class:`Tracking`)."""
    estimate = shadow = None
    if "spine" in loops:
        estimate = posture_estimator(estimator, KENTA.model, rng if rng is not None else np.random.default_rng(0),
                                     KENTA_NN_GRID_DEG)
        shadow = posture_estimator("jacobian", KENTA.model, None) if estimator == "nn" else None
    body, control, zero = calibrated_kenta(seconds=zeroing_s)
    parts = {"eyes": lambda: GazeLoop("eyes", TRACKING_PERIODS_S["eyes"], TRACKING_GAINS["eyes"],
                                      ("eye_pan", "eye_tilt"), +1.0, KENTA_EYE_LIMIT_RAD),
             "neck": lambda: GazeLoop("neck", TRACKING_PERIODS_S["neck"], TRACKING_GAINS["neck"],
                                      ("neck_pan", "neck_tilt"), -1.0, KENTA_NECK_LIMIT_RAD),
             "spine": lambda: SpineGazeLoop(KENTA.model, zero, TRACKING_PERIODS_S["spine"], TRACKING_GAINS["spine"],
                                                 estimate, shadow=shadow)}
    modules = [parts[name]() for name in loops]
    arms = ArmSwing(arm_swing_rad, arm_period_s) if arm_swing_rad > 0 else None
    eye = body.data.cam_xpos[body.id("camera", "eye_L")].copy()
    stages, run = tracking_stages(body, control, eye, modules, amplitude_m, path_period_s, arms,
                                  [ARM_NAMES.index(nm) for nm in SWUNG])
    return body, stages, run
