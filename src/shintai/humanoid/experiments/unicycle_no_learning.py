"""``humanoid.unicycle-no-learning``: HRP2 on the Ninebot One S2 with training wheels, the balance stack only, the
lift (the thesis's supporting hand) letting go — does the speed run away? (seed 000 §7.3.3, Figs. 7.6–7.7)."""

from __future__ import annotations

from shintai.humanoid.unicycle import plots
from shintai.humanoid.unicycle.constants import P0_M
from shintai.humanoid.unicycle.rig import P0_PARAM, summary, unicycle_rig
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment


def rig(params, variant, seed):
    return unicycle_rig(params["duration_s"], seed, params.get("p0_m", P0_M), control="stabilizer", training_wheels=True)


def metrics(runs, params):
    return summary(runs["run"])


experiment(
    "humanoid.unicycle-no-learning",
    covers=("000:fig7.7",),
    source="seed 000 §7.3.3, Figs. 7.6–7.7, App. A.1.3 (Eqs. A.5–A.9)",
    summary="HRP2 on the Ninebot One S2 with training wheels, AutoBalancer-like reference + LIP tracking only, "
            "released from the lift: does the speed diverge?",
    params=[Param("duration_s", 20.0, "simulated time after the release [s]", lo=0.5, hi=120.0), P0_PARAM],
    checks=[
        Check("speed_diverged", "==", 1, "thesis §7.3.3, Fig. 7.7: '人手のサポートを外すと … 速度をゼロとするような"
              "その場での定位が困難' (Fig. 7.7 (4) 'Divergence of Speed'); |v| > 0.3 m/s is our threshold",
              kind="reproduction"),
        Check("fallen", "==", 0, "thesis §7.3.3, Fig. 7.6: with the training wheels the vehicle stands by itself "
              "('補助輪によるハードウェアでの支持'); the robot stays on it", kind="reproduction"),
    ],
    thesis={"speed_diverged": ThesisValue(1, "seed 000 §7.3.3, Fig. 7.7 (4): 'Divergence of Speed'",
                                          "speed_diverged")},
    rig=rig, metrics=metrics, plots=plots.no_learning, video=True,
    stochastic=True,  # the sensors' noise (Table 6.1) is drawn from the run's seed
    smoke={"duration_s": 0.6},
)
