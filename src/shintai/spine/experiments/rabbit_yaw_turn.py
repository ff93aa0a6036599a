"""``spine.rabbit-yaw-turn``: Rabbit's spine turns its upper body in yaw (seed 003 §3.5.4, Fig. 3.27) on the
quasi-static Rabbit (:mod:`shintai.spine.rabbit.yaw_turn`): carrying the upper body on the stiffened spine, the same
turn unloaded, and carrying it on the soft (not pre-compressed) spine."""

from __future__ import annotations

from dataclasses import replace

from shintai.scenarios.experiment import variant_metric
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.rabbit import plots as pictures
from shintai.spine.rabbit.yaw_turn import YawTurn, yaw_turn_metrics, yaw_turn_rig

VARIANTS = ("carrying", "unloaded", "soft")


def turn(params, variant) -> YawTurn:
    t = YawTurn(yaw_deg=params["yaw_deg"], step_deg=params["step_deg"], precompression_mm=params["precompression_mm"],
                forward_mm=params["forward_mm"])
    return replace(t, precompression_mm=0.0) if variant == "soft" else t


def rig(params, variant, seed):
    return yaw_turn_rig(turn(params, variant), load=variant != "unloaded")


def metrics(runs, params):
    out = {}
    for variant, run in runs.items():
        out |= {variant_metric(k, variant): v for k, v in yaw_turn_metrics(run.log).items()}
    out["load_height_drop_mm"] = out["min_top_z_unloaded_mm"] - out["min_top_z_carrying_mm"]
    return out


def plots(ctx, runs, params):
    pictures.yaw_turn(ctx, {v: r.log for v, r in runs.items()})


experiment(
    "spine.rabbit-yaw-turn",
    source="seed 003 §3.5.4, Fig. 3.27",
    covers=("003:fig3.27",),
    summary="Rabbit (quasi-static): the six muscles turn the upper body ±40° in yaw on the stiffened spine while it "
            "carries the upper body's weight; the same turn unloaded and on the soft spine",
    params=[
        Param("yaw_deg", YawTurn.yaw_deg, "turn each way [deg] (§3.5.1: ±45° range; the turn's size not in the text)",
              lo=5.0, hi=45.0),
        Param("step_deg", YawTurn.step_deg, "commanded yaw per equilibrium [deg]", lo=1.0, hi=20.0),
        Param("precompression_mm", YawTurn.precompression_mm, "disc pre-compression the lengths are computed for "
              "(§3.5.3's stiff setting; amount not in the text)", lo=0.0, hi=1.5),
        Param("forward_mm", YawTurn.forward_mm, "upper body's centre ahead of the spine axis (not in the text)",
              lo=0.0, hi=60.0),
    ],
    checks=[
        Check("yaw_reach_carrying", ">=", 0.8, "§3.5.4: '旋回を行うことができることを確認した' — the top turns through "
              "at least 80 % of the commanded range while carrying the upper body (80 % ours; the thesis shows "
              "photographs)", name="turns_carrying", kind="reproduction"),
        Check("max_tilt_carrying_deg", "<=", 5.0, "§3.5.4: '上半身の重量を十分支えて' — the upper body stays upright "
              "through the turn: its axis within 5° of vertical (5° ours)", name="upper_body_carried",
              kind="reproduction"),
        Check("tension_share_of_servo_carrying", "<=", 1.0, "§3.5.1: the muscles' maximum tension from the S9204's "
              "12.6 kgf·cm on the Ø20 mm pulley, '12.6[kgf]' — the turn needs no more", name="within_servo_tension",
              kind="consistency"),
    ],
    thesis={"turn": ThesisValue("the spine supports the upper body's weight and turns (photographs)",
                                "§3.5.4, Fig. 3.27", "yaw_reach_carrying")},
    rig=rig, variants=VARIANTS, metrics=metrics, plots=plots,
    smoke={"yaw_deg": 5.0, "step_deg": 5.0},
)
