"""``spine.cla-roll-over``: Cla lying on its back tries to roll onto its front by yawing its spine together with
its shoulder and hip, and the same keys with the spine locked (seed 003 §5.2.8, Fig. 5.9). Model, keys and the
turn measure: :mod:`shintai.spine.cla.roll_over`."""

from __future__ import annotations

from shintai.scenarios.experiment import per_variant
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.cla import plots as P
from shintai.spine.cla import roll_over as RO
from shintai.spine.cla.constants import ROLL_OVER_YAW_DEG

Q_HALF = ("§5.2.8 '股関節の力・肩の力だけでは体を捻って半身を起こすことができない。脊椎を yaw 軸回りに回転させる動きと"
          "肩・股関節の動きを同時に行うことで … 半身を起こすことができる'")
Q_ROLL = "§5.2.8 'これにより、仰向けからうつぶせ、うつぶせから仰向けと、両方向の寝返りができるようになった'"


def rig(params, variant, seed):
    return RO.roll_rig(variant == "spine", fraction=params["fraction"], yaw_deg=params["yaw_deg"],
                       view={"track": "link0", "distance": 0.9, "azimuth": 120.0, "elevation": -35})


def metrics(runs, params):
    return per_variant({v: RO.outcome(r.log) for v, r in runs.items()})


experiment(
    "spine.cla-roll-over",
    source="seed 003 §5.2.8, Fig. 5.9",
    summary="Cla on its back yaws its spine with the shoulder and hip to raise half its body and roll onto its "
            "front; the same keys with the spine locked",
    params=[Param("yaw_deg", ROLL_OVER_YAW_DEG, "whole-spine twist of the keys [deg]", lo=0.0, hi=90.0),
            Param("fraction", 1.0, "run this fraction of the sequence (tests)", lo=0.05, hi=1.0)],
    checks=(
        Check("max_shoulder_turn_spine_deg", ">", "max_shoulder_turn_locked_deg", Q_HALF + ": the upper half turns "
              "further up with the spine than with the shoulder and hip alone", name="spine_raises_half_the_body",
              kind="reproduction"),
        Check("rolled_spine", "==", 1, Q_ROLL + ": with the spine Cla ends on its front", name="rolls_over_with_spine",
              kind="reproduction"),
        Check("rolled_locked", "==", 0, Q_HALF + ": with the spine locked it does not roll over",
              name="no_roll_without_spine", kind="reproduction"),
        Check("max_spine_change_locked_deg", "<", 1.5, "the lock holds the spine (cla_body's equality constraints; "
              "< 1.5° as cla_body's own test)", name="locked_spine_stays", kind="consistency"),
    ),
    thesis={"roll": ThesisValue("rolls over both ways with the spine's yaw (photographs, Fig. 5.9)",
                                "seed 003 §5.2.8 '仰向けからうつぶせ、うつぶせから仰向けと、両方向の寝返りができるよう"
                                "になった'", "rolled_spine")},
    covers=("003:fig5.9",),
    video=True,
    rig=rig, variants=RO.VARIANTS, metrics=metrics, plots=P.roll_over,
    smoke={"fraction": 0.05},
)
