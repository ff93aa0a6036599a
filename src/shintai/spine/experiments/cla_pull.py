"""``spine.cla-pull``: the seated whole-body Cla pulls an object on the desk towards itself, leaning with the
spine to reach behind it (seed 003 §5.2.4, Fig. 5.5); the same motion with the spine locked upright does not reach
the object (Fig. 5.6) (:mod:`shintai.spine.cla.pull`)."""

from __future__ import annotations

from matplotlib.patches import Rectangle

from shintai.scenarios.experiment import film, variant_metric
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.spine.cla.pull import SUCCESS_M, pull_summary, run_pull
from shintai.spine.robots import CLA_DESK_HEIGHT_M, CLA_OBJECT_HALF_M

VARIANTS = ("with_spine", "without_spine")
LABELS = {"with_spine": "with the spine (Fig. 5.5)", "without_spine": "spine locked (Fig. 5.6)"}
VIEW = {"fps": 15, "width": 480, "height": 360, "track": "link0", "distance": 1.1, "azimuth": 130.0,
        "elevation": -15}
QUOTE = "§5.2.4: '脊椎を利用しないで同様の動作を行おうとすると、Fig. 5.6 に示すように、手が対象物に届かない'"


def plot(ctx, runs: dict) -> None:
    with ctx.figure("pull") as (fig, ax):
        for variant, s in runs.items():
            line, = ax.plot(s["t"], s["hand_x_m"], label=f"hand x, {LABELS[variant]}")
            ax.plot(s["t"], s["object_x_m"] + s["object_dx_m"] - CLA_OBJECT_HALF_M, ls="--", color=line.get_color(),
                    label=f"object's near face x, {variant}")
        s = runs["with_spine"]
        ax.axhline(s["reach_straight_m"], color="0.6", lw=0.7, ls=":", label="reach at the desk, spine straight")
        ax.axhline(s["reach_leaning_m"], color="0.3", lw=0.7, ls=":", label="reach at the desk, spine leaning")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("x (forward) [m]")
        ax.set_title("Cla pulls an object on the desk (Figs. 5.5–5.6)", fontsize=9)
        ax.legend(fontsize=6)
    with ctx.figure("side_view") as (fig, ax):
        for variant, s in runs.items():
            ax.plot(s["hand_x_m"], s["hand_z_m"], label=f"hand path, {LABELS[variant]}")
        x0 = runs["with_spine"]["object_x_m"]
        h = CLA_OBJECT_HALF_M
        z = CLA_DESK_HEIGHT_M
        ax.add_patch(Rectangle((x0 - h, z), 2 * h, 2 * h, color="tab:red", alpha=0.4, label="object at start"))
        ax.axhline(z, color="0.5", lw=1.0, label="desk top")
        ax.set_aspect("equal")
        ax.set_xlabel("x (forward) [m]")
        ax.set_ylabel("z [m]")
        ax.legend(fontsize=6)


@scenario(
    "spine.cla-pull",
    source="seed 003 §5.2.4, Figs. 5.5–5.6",
    covers=("003:fig5.5",),
    summary="Whole-body Cla (MuJoCo, muscle spine) seated at a desk: leaning with the spine the hand reaches "
            "behind an object placed just beyond the straight-spine reach and drags it back; spine locked, the "
            "same motion does not reach it",
    params=[
        Param("lean_deg", 70.0, "whole-spine forward lean at the reach (§5.2.4: tuned on the robot; ours)",
              lo=0.0, hi=85.0),
        Param("beyond_reach_m", 0.005, "the object's near face beyond the straight-spine reach (ours)",
              lo=0.0, hi=0.05),
        Param("move_s", 1.0, "each spine posture move [s] (chosen)", lo=0.2, hi=3.0),
        Param("calibration_s", 1.0, "§4.6.4 encoder zeroing before the run [s]", lo=0.1, hi=5.0),
    ],
    checks=[
        Check("success_with_spine", "==", 1, "§5.2.4 (Fig. 5.5): 'Cla が机の上のものを引き寄せる' — with the spine "
              f"the object is pulled (≥ {SUCCESS_M * 100:g} cm toward Cla, our threshold)", name="pulls_with_spine",
              kind="reproduction"),
        Check("success_without_spine", "==", 0, QUOTE + " — the object stays", name="fails_without_spine",
              kind="reproduction"),
        Check("hand_min_gap_without_spine_m", ">", 0.0, QUOTE + " — the hand never touches it",
              name="hand_short_without_spine", kind="reproduction"),
    ],
    thesis={"pull": ThesisValue("pulled with the spine; without it the hand does not reach (photographs)",
                                "seed 003 " + QUOTE, "object_pulled_with_spine_m")},
    video=True,
)
def cla_pull(ctx):
    p = ctx.params
    runs, out = {}, {}
    for i, variant in enumerate(VARIANTS):
        ctx.progress(i / len(VARIANTS), LABELS[variant])
        camera = lambda body, v=variant: film(ctx, body, v, **VIEW)  # noqa: E731
        runs[variant] = s = run_pull(p, variant == "with_spine", camera)
        ctx.sim_time_s += float(s["t"][-1])
        for k in range(0, len(s["t"]), 2):
            ctx.recorder.record(float(s["t"][k]), **{f"{variant}.{key}": s[key][k] for key in
                                                     ("hand_x_m", "hand_z_m", "object_dx_m", "spine_pitch_deg")})
        out |= {variant_metric(key, variant): value for key, value in pull_summary(s).items()}
    s = runs["with_spine"]
    out |= {"object_x_m": s["object_x_m"], "reach_straight_m": s["reach_straight_m"],
            "reach_leaning_m": s["reach_leaning_m"]}
    plot(ctx, runs)
    return out
