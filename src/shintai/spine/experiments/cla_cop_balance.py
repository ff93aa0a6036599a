"""``spine.cla-cop-balance``: Cla standing bends its spine slowly from side to side while an arm-swing reflex keeps
the soles' centre of pressure (eq. 3.5, four FSRs per foot) near their front–back centre; the same bends without
the reflex (seed 003 §5.2.7, Fig. 5.8). Reflex and bends: :mod:`shintai.spine.cla.cop`."""

from __future__ import annotations

import numpy as np

from shintai.core.constants import GRAVITY
from shintai.scenarios.experiment import Rig, per_variant
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.cla import cop as CB
from shintai.spine.cla import plots as P
from shintai.spine.cla.constants import BEND_DEG, FALLEN_FORCE, HALF_PERIOD_S, SETTLE_S
from shintai.spine.control import SETPOINTS

Q_REFLEX = ("§5.2.7 '常に足裏の前後方向の中心付近に重心の投影点が来るように, 両腕を前後にゆっくりと動かしながらバランス"
            "をとる … こうした反射を, 左右の側屈の動作と並列に行うことで, 立った状態での運動ができるようになった'")


def rig(params, variant, seed):
    body, player, reflex, control, centre = CB.build(variant == "swing", params["cycles"], params["bend_deg"],
                                                     params["half_period_s"])
    return Rig(body, stages=[[player, reflex], [control]], channels=SETPOINTS,
               duration=float(player.times[-1]) * params["fraction"],
               record={10: lambda snap: CB.signals(body, reflex, snap)},
               view={"track": "link0", "distance": 1.0, "azimuth": 150.0, "elevation": -10},
               state={"centre": centre, "t0": body.t})  # the keys start after the calibration


def _one(run) -> dict:
    log = run.log
    t = log.times("cop")
    bending = t >= run.state["t0"] + SETTLE_S  # from the first bend on
    cop, centre = log.values("cop")[bending], log.values("sole_centre_x")[bending]
    err = cop[:, 0] - centre
    weight = run.body.model.body_subtreemass[run.body.id("body", "link0")] * GRAVITY
    fell = bool(np.any(log.values("force")[bending] < FALLEN_FORCE * weight) or np.any(~np.isfinite(err)))
    ok = np.isfinite(err)
    arm = log.values("arm_offset_deg")
    return {"cop_excursion_m": float(np.abs(err[ok]).max()) if ok.any() else float("nan"),
            "cop_rms_m": float(np.sqrt(np.mean(err[ok] ** 2))) if ok.any() else float("nan"),
            "cop_lateral_range_m": float(np.ptp(cop[ok, 1])) if ok.any() else float("nan"),
            "fell": int(fell), "arm_swing_range_deg": float(np.ptp(arm)),
            "max_roll_deg": float(np.abs(log.values("roll_deg")).max())}


def metrics(runs, params):
    return per_variant({v: _one(r) for v, r in runs.items()})


experiment(
    "spine.cla-cop-balance",
    source="seed 003 §5.2.7, Fig. 5.8, eq. 3.5",
    summary="Cla standing bends its spine from side to side while both arms swing forward/back to keep the sole "
            "centre of pressure at the feet's front–back centre; the same bends without the arm swing",
    params=[Param("cycles", 2, "side-bend cycles (right, left)", lo=1, hi=20),
            Param("bend_deg", BEND_DEG, "whole-spine roll to each side [deg]", lo=0.0, hi=90.0),
            Param("half_period_s", HALF_PERIOD_S, "time from one side to the other [s]", lo=0.5, hi=30.0),
            Param("fraction", 1.0, "run this fraction of the sequence (tests)", lo=0.05, hi=1.0)],
    checks=(
        Check("cop_excursion_swing_m", "<", "cop_excursion_no_swing_m", Q_REFLEX + ": with the arm swing the CoP "
              "stays closer to the front–back centre", name="arm_swing_narrows_cop", kind="reproduction"),
        Check("fell_swing", "==", 0, Q_REFLEX + ": with the reflex Cla keeps standing through the bends",
              name="stands_with_arm_swing", kind="reproduction"),
    ),
    thesis={"balance": ThesisValue("stands while bending (photographs, Fig. 5.8); no CoP trace printed",
                                   "seed 003 §5.2.7 '立った状態での運動ができるようになった'",
                                   "cop_excursion_swing_m")},
    covers=("003:fig5.8",),
    video=True,
    rig=rig, variants=CB.VARIANTS, metrics=metrics, plots=P.cop_balance,
    smoke={"fraction": 0.05},
)
