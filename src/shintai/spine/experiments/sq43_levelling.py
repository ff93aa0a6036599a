"""``spine.sq43-levelling``: SQ43 keeps its shoulder level by its accelerometers while a board under the left
front foot rises and lowers (seed 003 §3.2.4, Fig. 3.6), on the MuJoCo SQ43 (:mod:`shintai.spine.sq43.body`).
Two runs (with and without the levelling) whose board moves by script and whose controller acts on steady
windows only: a compute experiment (:func:`shintai.spine.sq43.gaits.simulate_levelling`)."""

from __future__ import annotations

import numpy as np

from shintai.scenarios.experiment import film, variant_metric
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.spine.sq43.gaits import Levelling, simulate_levelling

VARIANTS = ("with", "without")
VIEW = {"fps": 20, "width": 480, "height": 360, "track": "shoulder", "distance": 0.8, "azimuth": 180.0,
        "elevation": -15}
UP, DOWN = (5.0, 6.0), (10.0, 11.0)  # the windows the settled roll is averaged over (board held up / down) [s]


def summary(series) -> dict:
    t, roll = series["t"], series["roll_deg"]
    up = (t >= UP[0]) & (t < UP[1])
    down = (t >= DOWN[0]) & (t < DOWN[1])
    return {"max_shoulder_roll_deg": float(np.abs(roll).max()),
            "settled_roll_up_deg": float(roll[up].mean()), "settled_roll_down_deg": float(roll[down].mean()),
            "adjustments": len(series["acted_s"]),
            "lf_length_up_mm": float(series["lf_length_mm"][up].mean())}


def plot(ctx, runs: dict, rise_mm: float) -> None:
    with ctx.figure("levelling_roll") as (fig, ax):
        for v, s in runs.items():
            ax.plot(s["t"], s["roll_deg"], label=f"shoulder roll, {v} levelling")
        for a in runs["with"]["acted_s"]:
            ax.axvline(a, color="0.8", lw=0.6)
        ax2 = ax.twinx()
        ax2.plot(runs["with"]["t"], runs["with"]["board_mm"], "k--", lw=0.8, label="board height")
        ax2.set_ylabel("board under LF [mm]")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("shoulder roll [deg] (+: left side up)")
        ax.set_title(f"SQ43 levelling (Fig. 3.6): board up {rise_mm:g} mm and down; grey: controller steps", fontsize=9)
        ax.legend(fontsize=7, loc="upper right")
    with ctx.figure("levelling_leg") as (fig, ax):
        ax.plot(runs["with"]["t"], runs["with"]["lf_length_mm"], label="LF leg length (with levelling)")
        ax.plot(runs["with"]["t"], runs["with"]["acc_roll_deg"] + runs["with"]["lf_length_mm"].mean(), lw=0.6,
                label="accelerometer roll [deg] (offset)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("[mm]")
        ax.legend(fontsize=7)


@scenario(
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
)
def sq43_levelling(ctx):
    p = ctx.params
    runs = {}
    for i, variant in enumerate(VARIANTS):
        ctx.progress(0.5 * i, f"{variant} levelling")
        camera = (lambda body: film(ctx, body, **VIEW)) if variant == "with" else None
        levelling = Levelling(gain=p["gain"]) if variant == "with" else None
        runs[variant] = simulate_levelling(levelling, p["rise_mm"], camera=camera)
        ctx.sim_time_s += float(runs[variant]["t"][-1])
        s = runs[variant]
        for k in range(0, len(s["t"]), 5):
            ctx.recorder.record(float(s["t"][k]), **{f"{variant}.roll_deg": s["roll_deg"][k],
                                                    f"{variant}.board_mm": s["board_mm"][k],
                                                    f"{variant}.lf_length_mm": s["lf_length_mm"][k]})
    plot(ctx, runs, p["rise_mm"])
    metrics = {}
    for variant, s in runs.items():
        metrics |= {variant_metric(key, variant): value for key, value in summary(s).items()}
    for w in ("up", "down"):
        metrics[f"abs_settled_roll_{w}_with_deg"] = abs(metrics[f"settled_roll_{w}_with_deg"])
    return metrics
