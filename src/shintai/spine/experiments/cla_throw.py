"""``spine.cla-throw``: the seated whole-body Cla throws overhand, the spine's motion started first, then the
shoulder's, then the elbow's, so that their speed peaks coincide (seed 003 §5.2.3, Figs. 5.3–5.4); the same
throw with the spine locked (Fig. 5.4), and the ablation: the spine free but every part started together
(:mod:`shintai.spine.cla.throw`)."""

from __future__ import annotations

import numpy as np

from shintai.scenarios.experiment import film, variant_metric
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.spine.cla.throw import run_throw, throw_summary

VIEW = {"fps": 30, "width": 480, "height": 360, "track": "link0", "distance": 1.0, "azimuth": 120.0,
        "elevation": -10}
LABELS = {"with_spine": "with the spine", "without_spine": "spine locked", "simultaneous": "spine, parts together"}
QUOTE = ("§5.2.3: '脊椎を利用しない場合は肩から手先までの関節しか加速に利用できないため、脊椎を利用する場合に比べ"
         "手先の最大速度は小さくなる'")


VARIANTS = ("with_spine", "without_spine", "simultaneous")


def plot(ctx, runs: dict) -> None:
    with ctx.figure("hand_speed") as (fig, ax):
        for variant, s in runs.items():
            ax.plot(s["t"], s["hand_speed_mps"], label=LABELS[variant])
        at = s["pattern"].throw_at
        ax.axvline(at, color="0.7", lw=0.6)
        ax.set_xlim(at - 0.2, s["t"][-1])
        ax.set_xlabel("time [s]")
        ax.set_ylabel("hand speed [m/s]")
        ax.set_title("Cla's throw (Figs. 5.3–5.4): hand speed with and without the spine", fontsize=9)
        ax.legend(fontsize=7)
    with ctx.figure("sequence") as (fig, ax):
        s = runs["with_spine"]
        dt = np.gradient(s["t"])
        for key, label in (("spine_yaw_deg", "spine yaw rate [rad/s]"), ("shoulder_rad", "shoulder rate [rad/s]"),
                           ("elbow_rad", "elbow rate [rad/s]")):
            rate = np.gradient(s[key]) / dt
            ax.plot(s["t"], np.abs(np.radians(rate) if key.endswith("deg") else rate), label=label)
        ax.plot(s["t"], s["hand_speed_mps"], "k", lw=1.2, label="hand speed [m/s]")
        ax.set_xlim(s["pattern"].throw_at - 0.1, s["pattern"].throw_at + 0.8)
        ax.set_xlabel("time [s]")
        ax.set_title("with the spine: spine, shoulder, elbow started in that order, their speed peaks together",
                     fontsize=9)
        ax.legend(fontsize=7)


@scenario(
    "spine.cla-throw",
    source="seed 003 §5.2.3, Figs. 5.3–5.4",
    covers=("003:fig5.3",),
    summary="Whole-body Cla (MuJoCo, muscle spine) throws overhand: spine, then shoulder, then elbow started so "
            "their speed peaks coincide; peak hand speed with the spine vs the same throw with the spine locked",
    params=[
        Param("calibration_s", 1.0, "§4.6.4 encoder zeroing before the run [s]", lo=0.1, hi=5.0),
        Param("windup_s", 1.5, "the wind-up move [s] (chosen; a 0.5-s hold follows)", lo=0.2, hi=5.0),
        Param("spine_s", 0.6, "the spine's throw move (minimum jerk) [s] (chosen)", lo=0.1, hi=2.0),
        Param("shoulder_s", 0.3, "the shoulder's throw move [s] (chosen)", lo=0.05, hi=2.0),
        Param("elbow_s", 0.2, "the elbow's and wrist's throw move [s] (chosen)", lo=0.05, hi=2.0),
    ],
    checks=[
        Check("hand_speed_with_spine_mps", ">", "hand_speed_without_spine_mps", QUOTE, name="spine_raises_hand_speed",
              kind="reproduction"),
        Check("spine_yaw_travel_without_spine_deg", "<", 1.0, "the lock holds: the locked spine does not turn "
              "during the throw (Fig. 5.4: '脊椎を利用しないで')", name="lock_holds", kind="consistency"),
        Check("hand_speed_with_spine_mps", ">", "hand_speed_simultaneous_mps", "§5.2.3: '脊椎根元部から順に動作を開始"
              "し、肩、肘という順に動作を開始することで … 手先が最大速度になる瞬間を同じくすることができ、これにより"
              "物をより強く投げることができる' — sequenced vs started together", name="sequencing_helps",
              kind="reproduction"),
    ],
    thesis={"hand_speed": ThesisValue("higher with the spine (no measured speed)", "seed 003 " + QUOTE,
                                      "hand_speed_with_spine_mps")},
    constraints=[(lambda p: p["spine_s"] >= p["shoulder_s"] >= p["elbow_s"],
                  "spine_s >= shoulder_s >= elbow_s (the proximal part moves longest, §5.2.3's order)")],
    video=True,
)
def cla_throw(ctx):
    p = ctx.params
    runs, out = {}, {}
    names = VARIANTS
    for i, variant in enumerate(names):
        ctx.progress(i / len(names), LABELS[variant])
        camera = (lambda body, v=variant: film(ctx, body, v, **VIEW)) if variant != "simultaneous" else None
        runs[variant] = s = run_throw(p, variant != "without_spine", camera, sequenced=variant != "simultaneous")
        ctx.sim_time_s += float(s["t"][-1])
        for k in range(0, len(s["t"]), 10):
            ctx.recorder.record(float(s["t"][k]), **{f"{variant}.{key}": s[key][k] for key in s if key not in
                                                     ("t", "pattern")})
        out |= {variant_metric(key, variant): value for key, value in throw_summary(s).items()}
    out["hand_speed_gain"] = out["hand_speed_with_spine_mps"] / out["hand_speed_without_spine_mps"]
    starts = runs["with_spine"]["pattern"].starts
    out |= {f"{part}_start_s": t for part, t in starts.items()}
    plot(ctx, runs)
    return out
