"""``spine.kenta-spine-neck-arms``: Fig. 5.13 on the whole-body Kenta (seed 003 §5.2.11): the spine commanded through
a posture sequence by the forward model (eq. 4.25, L mode) while the neck and both arms swing; the three move at
once (:mod:`shintai.spine.kenta.spine_neck_arms`)."""

from __future__ import annotations

import math

from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.kenta.constants import KENTA_KEY_POSTURES_DEG
from shintai.spine.kenta.plots import spine_neck_arms
from shintai.spine.kenta.spine_neck_arms import all_at_once_metrics, all_at_once_rig, all_at_once_series
from shintai.spine.robots import CONCURRENT_THRESHOLD_DEG, CONCURRENT_WINDOW_S

VIEW = {"track": "link0", "distance": 2.0, "azimuth": 140.0, "elevation": -12}


def rig(params, variant, seed):
    return all_at_once_rig(KENTA_KEY_POSTURES_DEG, int(params["cycles"]), params["key_s"],
                           math.radians(params["neck_swing_deg"]), params["neck_period_s"],
                           math.radians(params["arm_swing_deg"]), params["arm_period_s"], params["zeroing_s"], VIEW)


def _run(runs):
    run = next(iter(runs.values()))
    return run.log, run.state


experiment(
    "spine.kenta-spine-neck-arms",
    source="seed 003 §5.2.11, Fig. 5.13",
    covers=("003:fig5.13",),
    summary="Kenta moves spine, neck and both arms at once: the spine through three whole-spine postures by the "
            "forward model (eq. 4.25) in L mode, the neck's pan and tilt and both arms swinging",
    params=[
        Param("zeroing_s", 1.0, "§4.6.4 encoder zeroing time before the motion [s]", lo=0.2, hi=5.0),
        Param("cycles", 2, "times through the three key postures (KENTA_KEY_POSTURES_DEG)", lo=1, hi=10),
        Param("key_s", 2.0, "time from one key posture to the next, linearly [s]", lo=0.2, hi=10.0),
        Param("neck_swing_deg", 20.0, "the whole neck's pan amplitude (tilt: half) [deg]", lo=0.0, hi=60.0),
        Param("neck_period_s", 3.0, "the neck's pan period (tilt: 0.7 of it) [s]", lo=0.5, hi=20.0),
        Param("arm_swing_deg", 30.0, "the shoulders' pitch amplitude, in antiphase, elbows with them [deg]", lo=0.0,
              hi=60.0),
        Param("arm_period_s", 2.0, "the arms' swing period [s]", lo=0.5, hi=20.0),
    ],
    checks=[
        Check("concurrent_fraction", ">=", 1.0,
              "§5.2.11 '腱太が, 脊椎の動きと首の動き・両腕の動きを同時に行っている様子を Fig. 5.13 に示す': in every "
              f"{CONCURRENT_WINDOW_S:g} s window the spine, the neck and each arm turn by more than "
              f"{CONCURRENT_THRESHOLD_DEG:g}° (ours: the thesis prints no number)", kind="reproduction",
              row="003:fig5.13"),
        Check("spine_sweep_deg", ">=", 10.0,
              "the spine goes through its posture sequence, not a tremor: one whole-spine angle spans ≥ 10° (ours)",
              kind="consistency"),
        Check("arm_following_error_deg", "<=", 5.0,
              "the arms follow their commanded swing (derived: our servos and swing; 5° ours)", kind="consistency"),
    ],
    thesis={"all_at_once": ThesisValue("spine, neck and both arms moving at the same time",
                                       "seed 003 §5.2.11 '脊椎の動きと首の動き・両腕の動きを同時に行っている'",
                                       "concurrent_fraction")},
    video=True,
    rig=rig, metrics=lambda runs, params: all_at_once_metrics(*_run(runs)),
    plots=lambda ctx, runs, params: spine_neck_arms(ctx, all_at_once_series(*_run(runs))),
    smoke={"zeroing_s": 0.2, "cycles": 1, "key_s": 0.3},
)
