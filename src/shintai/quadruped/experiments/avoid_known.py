"""``quadruped.avoid-known``: seed 004 §4.2.1 with the shipped fixed-order action network (one batched
walk of the crawl executor: a compute experiment, see notes)."""

from __future__ import annotations

from shintai.quadruped import world as W
from shintai.quadruped.walks import WEIGHTS, avoid, avoid_checks
from shintai.scenarios.registry import Check, ThesisValue, scenario


@scenario(
    "quadruped.avoid-known",
    source="seed 004 §4.2.1 (Figs. 18-19)",
    summary="trained action network, fixed crawl order: right wall, left 0.12 m obstacle, destination (-0.15, 2.2)",
    covers=("004:fig18",),
    params=[WEIGHTS],
    checks=avoid_checks("§4.2.1", "1 and 3", "2 and 4") + (
        Check("passing_x_m", "<", 0.0, "thesis §4.2.1: '右側の障害物が越えられない高さであるため、ロボットは左方へ"
              "移動していることが分かる' (the right obstacle is a wall, the robot moves left)", kind="reproduction"),),
    thesis={
        "final_error_m": ThesisValue(0.059, "seed 004 §4.2.1: (x_de, y_de) = (-0.037, 0.046) m", "final_error_m"),
        "cycles": ThesisValue(9, "seed 004 §4.2.1", "cycles"),
        "legs_on_obstacle": ThesisValue("13", "seed 004 §4.2.1: legs 1 and 3 climb, 2 and 4 pass between",
                                        "legs_on_obstacle"),
        "direction": ThesisValue("left", "seed 004 §4.2.1", "passing_x_m"),
        "climbed_thesis_legs": ThesisValue(2, "seed 004 §4.2.1: legs 1 and 3 on the 0.12 m obstacle",
                                           "climbed_thesis_legs"),
    },
    demo=True,
    estimate_s=1.0,
    video=True,
    smoke={},
)
def avoid_known(ctx) -> dict:
    return avoid(ctx, W.scenario_421(), climbers=(1, 3))
