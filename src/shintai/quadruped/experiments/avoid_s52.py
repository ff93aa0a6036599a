"""``quadruped.avoid-s52``: the walk of Table 3 (seed 004 §5.2.1, Fig. 30; its outcome at the end of §6.2.2)
with the shipped fixed-order action network in §5.2's environment (one batched walk of the crawl executor)."""

from __future__ import annotations

from shintai.quadruped import world as W
from shintai.quadruped.walks import WEIGHTS, avoid, avoid_checks
from shintai.scenarios.registry import Check, ThesisValue, scenario

SECTION = "end of §6.2.2 (the fixed-order walk of §5.2.1, Table 3)"
LEGS = ("derived: §5.2.1 names no legs for this walk; in the same environment §6.2.2's walk climbs the right, "
        "0.12 m obstacle with legs 2 and 4 ('右側の障害物に対しては、脚2、脚4ともに乗り越え動作により障害物を回避'), "
        "and so do Table 3's printed actions in our executor (quadruped.replay); legs 1 and 3 pass the wall")


@scenario(
    "quadruped.avoid-s52",
    source="seed 004 §5.2.1 (Fig. 30, Table 3), end of §6.2.2",
    summary="trained action network, fixed crawl order: right 0.12 m obstacle, left wall, destination (-0.15, 2.2) "
            "— the walk of Table 3",
    covers=("004:table3",),
    params=[WEIGHTS],
    checks=avoid_checks(SECTION, "2 and 4", "1 and 3", cycles=10, legs_basis=LEGS) + (
        Check("passing_x_m", ">", 0.0, "thesis Table 3: its ΔXr are positive until cycle 5 (22-45 mm), the walk "
              "passes the obstacles shifted right of the wall (dead-reckoned x = 0.14 m at y = 0.84 m)",
              kind="reproduction"),
        Check("final_error_m", "<=", 0.073, "thesis end of §6.2.2: 'ゴール時のロボットの重心から目的地点までの距離"
              "誤差は (x_de, y_de) = (0.068, -0.027) [m]' (|e| = 0.073 m); ours no farther from the destination. "
              "Not the vector: the thesis's printed actions do not end at it (quadruped.replay)",
              name="final_error_within_thesis", kind="reproduction"),),
    thesis={
        "final_error_m": ThesisValue(0.073, "seed 004 end of §6.2.2: (x_de, y_de) = (0.068, -0.027) m", "final_error_m"),
        "final_error_x_m": ThesisValue(0.068, "seed 004 end of §6.2.2", "final_error_x_m"),
        "final_error_y_m": ThesisValue(-0.027, "seed 004 end of §6.2.2", "final_error_y_m"),
        "cycles": ThesisValue(10, "seed 004 end of §6.2.2 ('10回'; Table 3's 10 rows)", "cycles"),
        "legs_on_obstacle": ThesisValue("24", "not printed for this walk (§6.2.2's walk in the same environment and "
                                        "Table 3's actions in our executor: legs 2 and 4)", "legs_on_obstacle"),
        "direction": ThesisValue("right", "seed 004 Table 3 (ΔXr > 0 while passing)", "passing_x_m"),
    },
    smoke={},
)
def avoid_s52(ctx) -> dict:
    return avoid(ctx, W.scenario_52(), climbers=(2, 4))
