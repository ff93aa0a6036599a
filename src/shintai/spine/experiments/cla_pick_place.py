"""``spine.cla-pick-place``: Cla, seated, picks an object from the floor by bending its spine sideways and puts it
on the desk by twisting it; the same keys solved for a locked spine (seed 003 §5.2.5–5.2.6, Fig. 5.7; Figs.
2.1–2.2). Behaviour, scene and hand: :mod:`shintai.spine.cla.pick_place`."""

from __future__ import annotations

import numpy as np

from shintai.scenarios.experiment import Rig, per_variant
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.cla import pick_place as PP
from shintai.spine.cla import plots as P
from shintai.spine.cla.constants import GRIP_TOLERANCE_M, PICK_PLACE_YAW_DEG, PLACED_TOLERANCE_M, ROLL_DEG
from shintai.spine.control import SETPOINTS
from shintai.spine.robots import CLA_DESK_HALF_M, CLA_DESK_HEIGHT_M, CLA_DESK_NEAR_M, CLA_OBJECT_HALF_M

Q_PICK = ("§5.2.5 '手を伸ばしただけでは床に手が届かず拾うことができない。脊椎の動きを利用して脊椎を側屈させればそれが"
          "可能になる'")
Q_COG = "§5.2.5 'Cla は脊椎の roll 方向の自由度を用いる事で、重心を椅子の上に置いたまま床の物を拾うことができる'"
Q_PLACE = ("§5.2.6 '座った状態では、脊椎を動かさなければ机の上に置くことができない … 脊椎をねじることで … 机の上に手を"
           "伸ばして物を机の上に置くことができた'")


def rig(params, variant, seed):
    body, player, grip, control, scene, gaps = PP.build(variant == "spine", params["roll_deg"], params["yaw_deg"])
    duration = float(player.times[-1]) * params["fraction"]
    return Rig(body, stages=[[player, grip], [control]], channels=SETPOINTS, duration=duration,
               record={20: lambda snap: PP.signals(body, grip, scene)},
               view={"track": "link0", "distance": 1.1, "azimuth": 200.0, "elevation": -20},
               state={"scene": scene, "gaps": gaps, "grip": grip, "player": player})


def _one(run) -> dict:
    log, st = run.log, run.state
    scene, grip = st["scene"], st["grip"]
    obj, whole = log.values("object"), log.values("whole_deg")
    final = obj[-1]
    on_desk = (abs(final[2] - CLA_OBJECT_HALF_M - CLA_DESK_HEIGHT_M) < PLACED_TOLERANCE_M
               and CLA_DESK_NEAR_M < final[0] < CLA_DESK_NEAR_M + 2 * CLA_DESK_HALF_M[0]
               and abs(final[1]) < CLA_DESK_HALF_M[1])
    return {"picked": int(grip.closed_at is not None and grip.gap_at_grip <= GRIP_TOLERANCE_M),
            "grip_gap_m": grip.gap_at_grip,
            "lowest_hand_above_floor_m": float(log.values("hand")[:, 2].min() - PP.CLA_HAND_RADIUS_M
                                               - scene["floor_z"]),
            "object_lift_m": float(obj[:, 2].max() - scene["object0"][2]),
            "placed": int(on_desk), "place_error_m": float(np.linalg.norm(final[:2] - scene["spot"][:2])),
            "place_reach_gap_m": float(log.values("spot_gap").min()),
            "hand_over_desk_at_release": int(grip.hand_at_release is not None and PP.over_desk(grip.hand_at_release)),
            "com_margin_min_m": float(log.values("com_margin").min()),
            "max_roll_deg": float(np.abs(whole[:, 0]).max()), "max_yaw_deg": float(np.abs(whole[:, 2]).max()),
            "max_spine_change_deg": float(np.abs(whole - whole[0]).max()),
            "solver_reach_gap_m": st["gaps"]["reach"], "solver_place_gap_m": st["gaps"]["lower"]}


def metrics(runs, params):
    return per_variant({v: _one(r) for v, r in runs.items()})


experiment(
    "spine.cla-pick-place",
    source="seed 003 §5.2.5–5.2.6, Fig. 5.7 (Figs. 2.1–2.2)",
    summary="Cla, seated with its feet off the floor, picks an object from the floor by bending its spine sideways "
            "and puts it on the desk by twisting; the same hand targets with the spine locked",
    params=[Param("roll_deg", ROLL_DEG, "whole-spine sideways bend for the pick [deg]", lo=0.0, hi=90.0),
            Param("yaw_deg", PICK_PLACE_YAW_DEG, "whole-spine twist for the place [deg]", lo=0.0, hi=90.0),
            Param("fraction", 1.0, "run this fraction of the sequence (tests)", lo=0.05, hi=1.0)],
    checks=(
        Check("picked_spine", "==", 1, Q_PICK + ": with the spine the hand reaches the object and lifts it",
              name="picks_with_spine", kind="reproduction"),
        Check("picked_locked", "==", 0, Q_PICK + ": with the spine locked the hand does not reach it",
              name="no_pick_without_spine", kind="reproduction"),
        Check("com_margin_min_spine_m", ">", 0.0, Q_COG + ": the robot's CoM projects inside the seat throughout",
              name="cog_stays_over_the_chair", kind="reproduction"),
        Check("placed_spine", "==", 1, Q_PLACE + ": the object ends resting on the desk", name="places_with_spine",
              kind="reproduction"),
        Check("hand_over_desk_at_release_locked", "==", 0, Q_PLACE + ": with the spine locked the hand, at the "
              "place keys' release, is not where an object it held would rest on the desk",
              name="no_place_without_spine", kind="reproduction"),
        Check("max_spine_change_locked_deg", "<", 1.5, "the lock holds the spine (cla_body's equality constraints; the "
              "muscles pull against it) — < 1.5° as cla_body's own test", name="locked_spine_stays",
              kind="consistency"),
    ),
    thesis={"pick": ThesisValue("picked, CoG kept over the chair (photographs, Fig. 5.7)", "seed 003 §5.2.5 '重心を"
                                "椅子の上に置いたまま床の物を拾うことができる'", "picked_spine"),
            "place": ThesisValue("placed on the desk by twisting (photographs, Fig. 5.7)", "seed 003 §5.2.6 '脊椎をね"
                                 "じることで…物を机の上に置くことができた'", "placed_spine")},
    covers=("003:fig5.7",),
    video=True,
    rig=rig, variants=PP.VARIANTS, metrics=metrics, plots=P.pick_place,
    smoke={"fraction": 0.05},
)
