"""``spine.sq43-levelling``: SQ43 keeps its shoulder level by its accelerometers while a board under the left
front foot rises and lowers (seed 003 §3.2.4, Fig. 3.6), on the MuJoCo SQ43 (:mod:`shintai.spine.sq43.body`).
Two runs, with and without the levelling (:mod:`shintai.spine.sq43.levelling`): the board moved by script,
the controller acting on steady windows only."""

from __future__ import annotations

import numpy as np

from shintai.scenarios.experiment import variant_metric
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.sq43 import plots as P
from shintai.spine.sq43.constants import DOWN, UP
from shintai.spine.sq43.levelling import Levelling, levelling_rig

VARIANTS = ("with", "without")
VIEW = {"fps": 20, "width": 480, "height": 360, "track": "shoulder", "distance": 0.8, "azimuth": 180.0,
        "elevation": -15}


def rig(params, variant, seed):
    return levelling_rig(Levelling(gain=params["gain"]) if variant == "with" else None, params["rise_mm"], view=VIEW)


def series(run) -> dict:
    """The run's signals after each controller period, and when the controller acted."""
    log = run.log
    out = {"t": log.values("t_s"), **{k: log.values(k) for k in ("board_mm", "roll_deg", "acc_roll_deg",
                                                                  "lf_length_mm")}}
    out["acted_s"] = np.array(run.state.acted)
    return out


def summary(series) -> dict:
    t, roll = series["t"], series["roll_deg"]
    up = (t >= UP[0]) & (t < UP[1])
    down = (t >= DOWN[0]) & (t < DOWN[1])
    return {"max_shoulder_roll_deg": float(np.abs(roll).max()),
            "settled_roll_up_deg": float(roll[up].mean()), "settled_roll_down_deg": float(roll[down].mean()),
            "adjustments": len(series["acted_s"]),
            "lf_length_up_mm": float(series["lf_length_mm"][up].mean())}


def metrics(runs, params):
    out = {}
    for variant, run in runs.items():
        out |= {variant_metric(key, variant): value for key, value in summary(series(run)).items()}
    for w in ("up", "down"):
        out[f"abs_settled_roll_{w}_with_deg"] = abs(out[f"settled_roll_{w}_with_deg"])
    return out


def plots(ctx, runs, params):
    P.levelling(ctx, {v: series(r) for v, r in runs.items()}, params["rise_mm"])


experiment(
    "spine.sq43-levelling",
    source="seed 003 §3.2.4 (posture control), Fig. 3.6",
    covers=("003:fig3.6",),
    summary="SQ43 (MuJoCo): a board lifts and lowers the left front foot; the accelerometer levelling bends the "
            "left front leg until the shoulder is level, vs no levelling",
    params=[
        Param("rise_mm", 20.0, "how far the board lifts the left front foot (not in the text)", lo=1.0, hi=35.0),
        Param("gain", Levelling.gain, "fraction of the measured shoulder height error corrected per steady reading",
              lo=0.05, hi=1.5),
    ],
    checks=[
        Check("settled_roll_up_without_deg", ">", 0.0, "§3.2.4: raising the board under the left front leg tilts "
              "the shoulder '右下がりに' (right side down: positive roll)", kind="reproduction"),
        Check("settled_roll_up_with_deg", "<", "settled_roll_up_without_deg", "§3.2.4 (Fig. 3.6 2→3): '肩部分を水平に"
              "なるように左前脚の曲げ角を調節している' — levelled vs left tilted", name="levelling_levels_up",
              kind="reproduction"),
        Check("abs_settled_roll_up_with_deg", "<=", 1.0, "§3.2.4: the shoulder returns level; 1° = twice the "
              "controller's chosen 0.5° dead band", kind="consistency"),
        Check("abs_settled_roll_down_with_deg", "<=", 1.0, "§3.2.4 (Fig. 3.6 4→6): 'やがて左前脚を伸ばし (5) 水平"
              "に戻る (6)' after the board is lowered", kind="reproduction"),
    ],
    thesis={"tilt": ThesisValue("shoulder tilts right-down when the board rises, levelled by the LF leg bend",
                                "§3.2.4 Fig. 3.6 (photographs only, no number)", "settled_roll_up_without_deg")},
    video=True,
    rig=rig, variants=VARIANTS, filmed=("with",), metrics=metrics, plots=plots,
    smoke={"rise_mm": 15},
)
