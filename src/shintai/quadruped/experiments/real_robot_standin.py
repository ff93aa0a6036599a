"""``quadruped.real-robot-standin``: a stand-in for seed 004 §4.3's real-robot walk (Figs. 22-27): the shipped
fixed-order network with simulated ultrasonic sensors, a first straight cycle to sense, in a left-wall layout
of ours (the thesis prints no obstacle coordinates). One batched walk of the crawl executor."""

from __future__ import annotations

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import fitness as F
from shintai.quadruped import plots as PL
from shintai.quadruped import sensing as U
from shintai.quadruped import training as T
from shintai.quadruped import world as W
from shintai.quadruped.episode import GenomePolicy, rollout
from shintai.quadruped.walks import WEIGHTS, avoid_checks, record_walk, walk_metrics, weights_path, write_cycle_table
from shintai.scenarios.registry import Check, ThesisValue, scenario


class FirstStepStraight:
    """An action policy whose first cycle is ``step`` for every walk (§4.3: the first cycle senses), then ``policy``."""

    def __init__(self, policy, step=C.FIRST_STEP_STRAIGHT):
        self.policy, self.step, self.cycle = policy, np.asarray(step, dtype=float), 0

    def __call__(self, x: np.ndarray, rows: np.ndarray) -> np.ndarray:
        self.cycle += 1
        return np.tile(self.step, (len(rows), 1)) if self.cycle == 1 else self.policy(x, rows)


@scenario(
    "quadruped.real-robot-standin",
    source="seed 004 §4.3 (Figs. 22-27), stand-in",
    summary="a stand-in for the real-robot walk: simulated ultrasonic sensors, first cycle straight ahead, left "
            "wall, destination (0, 1.9) in a layout of ours",
    covers=("004:fig26",),
    params=[WEIGHTS],
    checks=avoid_checks("§4.3", "2 and 4", "1 and 3", cycles_quote="ゴールまで要した歩行周期回数は9回",
                        legs_basis="thesis §4.3: '脚2, 脚4ともに障害物の上を脚を接地していることから障害物を乗り越えている"
                                   "ことが確認できる。脚1と脚3は障害物の間を通過しているため、脚を地面に接地している'") + (
        Check("passing_x_m", ">", 0.0, "thesis §4.3: '左側の障害物はロボットが乗り越えられない高さであるため、右方へ"
              "移動し' (the left obstacle is a wall, the robot moves right)", kind="reproduction"),
        Check("first_cycle_straight", "==", 1, "consistency: the first cycle is the straight sensing step "
              "(§4.3: '1回目の歩行は障害物を認識するためにy方向へ直進移動'), imposed", kind="consistency"),),
    thesis={
        "final_error_m": ThesisValue(0.156, "seed 004 §4.3: (x_de, y_de) = (0.137, 0.075) m", "final_error_m"),
        "cycles": ThesisValue(9, "seed 004 §4.3 (the first a straight step)", "cycles"),
        "legs_on_obstacle": ThesisValue("24", "seed 004 §4.3: legs 2 and 4 on the obstacle, 1 and 3 on the ground",
                                        "legs_on_obstacle"),
        "direction": ThesisValue("right", "seed 004 §4.3", "passing_x_m"),
    },
    smoke={},
)
def real_robot_standin(ctx) -> dict:
    env = W.scenario_43()
    genome = T.load_action(weights_path(ctx.params["weights"]))
    sensors = U.SensedObstacles(seed=ctx.seed)
    policy = FirstStepStraight(GenomePolicy(F.ACTION_NET, genome[None], 1))
    ep = rollout(W.EnvBatch.of([env]), policy, record=True, perception=sensors)
    records = ep.records[0]
    record_walk(ctx, "", records)
    write_cycle_table(ctx, "cycles", records, env)
    PL.plot_walks(ctx, "walk", {f"{env.name}: sensed obstacles, first cycle straight": (env, records)})
    metrics = walk_metrics(ep, env, records, (2, 4))
    metrics["first_cycle_straight"] = int(np.allclose(records[0].command, C.FIRST_STEP_STRAIGHT))
    return metrics
