"""``quadruped.avoid-unseen``: seed 004 §4.2.2, the shipped fixed-order action network in an environment off
the training grid (one batched walk of the crawl executor: a compute experiment, see notes)."""

from __future__ import annotations

from shintai.quadruped import world as W
from shintai.quadruped.walks import WEIGHTS, avoid, avoid_checks
from shintai.scenarios.registry import Check, ThesisValue, scenario


@scenario(
    "quadruped.avoid-unseen",
    source="seed 004 §4.2.2 (Figs. 20-21)",
    summary="trained action network in an environment off the training grid: left wall, right 0.07 m obstacle, "
            "destination (0.35, 2.1)",
    covers=("004:fig20",),
    params=[WEIGHTS],
    checks=avoid_checks("§4.2.2", "2 and 4", "1 and 3") + (
        Check("passing_x_m", ">", 0.0, "thesis §4.2.2: '左側の障害物が越えられない高さであるため、ロボットは右方へ"
              "移動していることが分かる' (the left obstacle is a wall, the robot moves right)", kind="reproduction"),),
    thesis={
        "final_error_m": ThesisValue(0.054, "seed 004 §4.2.2: (x_de, y_de) = (-0.048, 0.024) m", "final_error_m"),
        "cycles": ThesisValue(9, "seed 004 §4.2.2", "cycles"),
        "legs_on_obstacle": ThesisValue("24", "seed 004 §4.2.2: legs 2 and 4 climb, 1 and 3 stay on the ground",
                                        "legs_on_obstacle"),
        "direction": ThesisValue("right", "seed 004 §4.2.2", "passing_x_m"),
        "climbed_thesis_legs": ThesisValue(2, "seed 004 §4.2.2: legs 2 and 4 on the 0.07 m obstacle",
                                           "climbed_thesis_legs"),
    },
    video=True,
    smoke={},
)
def avoid_unseen(ctx) -> dict:
    return avoid(ctx, W.scenario_422(), climbers=(2, 4))
