"""``spine.cla-poses``: the seated whole-body Cla takes side-bend and twist poses with its arms (seed 003 §3.6.3,
Fig. 3.38: postures only the spine's twist and side bend make possible; §5.2.1, Fig. 5.1: seated on a chair the
feet do not reach from, the side bend brings the hand about to the soles' height), and the same hand targets with
the spine locked.

Each pose (:data:`~shintai.spine.cla.constants.POSES_DEG`) is a key of spine posture and arm on the minimum-jerk
player (:class:`~shintai.spine.cla.keyframes.WholeBodyKeys`, the muscles in L mode), held, then back to rest. Its
hand target is where the model (:class:`~shintai.spine.cla.reach.ArmIK`) puts the hand at that spine posture: in
the side bends the arm solved to reach straight down below the shoulder to the soles' height, in the twists the
arm held out level. With the spine locked the arm is solved for the same targets with the spine straight."""

from __future__ import annotations

import numpy as np

from shintai.scenarios.experiment import Rig, per_variant
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine.cla import plots as P
from shintai.spine.cla.body import LIMB_JOINTS, SPINE_JOINTS, ClaBody, start_targets
from shintai.spine.cla.constants import (
    POSE_ARM_OUT,
    POSE_BACK_S,
    POSE_HOLD_S,
    POSE_LOW_TARGET_XY_M,
    POSE_MOVE_S,
    POSE_TOLERANCE_M,
    POSES_DEG,
    SOLE_LEVEL_TOLERANCE_M,
)
from shintai.spine.cla.control import spine_control
from shintai.spine.cla.keyframes import Key, WholeBodyKeys
from shintai.spine.cla.reach import ARM, ArmIK
from shintai.spine.cla.setup import CLA_VIEW
from shintai.spine.control import SETPOINTS
from shintai.spine.geometry import whole_spine
from shintai.spine.robots import CLA, CLA_HAND_RADIUS_M

VARIANTS = ("spine", "locked")
Q_38 = "§3.6.3 (Fig. 3.38): 'ねじりや側屈の稼働範囲により，脊椎が無ければ不可能であるような姿勢を可能にしている'"
Q_51 = "§5.2.1 (Fig. 5.1): '足が地面に着かない程度の高さの椅子に座り左右に脊椎を屈曲した時には、手先がほぼ足裏の高さと同程度の高さまで到達している'"


def side_of(pose: str) -> str:
    return "l" if pose.endswith("_left") else "r"


def sole_height(body: ClaBody) -> float:
    """The soles' lowest point [m] (the bottom of the lowest sole contact sphere) at the seated start."""
    m, d = body.model, body.data
    soles = [i for i in range(m.ngeom) if (m.geom(i).name or "").startswith("sole_")]
    return float(min(d.geom_xpos[i][2] - m.geom_size[i][0] for i in soles))


def pose_targets(ik: ArmIK, sole_z: float) -> dict[str, tuple[np.ndarray, dict]]:
    """Each pose's hand target and the arm that puts the hand there on the model with the spine (module doc)."""
    out = {}
    for pose, whole_deg in POSES_DEG.items():
        side, whole = side_of(pose), np.radians(whole_deg)
        if pose.startswith("bend"):
            sign = -1.0 if side == "r" else 1.0
            low = [POSE_LOW_TARGET_XY_M[0], sign * POSE_LOW_TARGET_XY_M[1], sole_z + CLA_HAND_RADIUS_M]
            arm, _ = ik.solve(side, whole, low)
        else:
            arm = {**{f"{j}_{side}": v for j, v in zip(ARM, POSE_ARM_OUT)}, f"wrist_{side}": 0.0}
        out[pose] = (ik.hand(side, whole, arm), arm)
    return out


def rig(params, variant, seed):
    body = ClaBody("seated", desk=False)
    sole_z = sole_height(body)
    control, zero = spine_control(body, calibration_s=params["calibration_s"])
    if variant == "locked":
        body.lock_spine(True)
    ik = ArmIK(body.model, body.data, SPINE_JOINTS, CLA.n)
    targets = pose_targets(ik, sole_z)
    start = {**start_targets("seated"), "spine_roll": 0.0, "spine_pitch": 0.0, "spine_yaw": 0.0}
    keys, gaps = [Key(0.5, {}, "rest")], {}
    for pose, (target, arm) in targets.items():
        side, whole = side_of(pose), np.radians(POSES_DEG[pose])
        if variant == "locked":
            arm, gaps[pose] = ik.solve(side, (0.0, 0.0, 0.0), target, arm)
        spine = dict(zip(("spine_roll", "spine_pitch", "spine_yaw"), (float(w) for w in whole)))
        back = {**{k: 0.0 for k in spine}, **{j: start[j] for j in arm}}
        keys += [Key(params["move_s"], {**spine, **arm}, pose), Key(POSE_HOLD_S, {}, f"{pose}_hold"),
                 Key(POSE_BACK_S, back, "rest")]
    player = WholeBodyKeys(CLA.model, zero, LIMB_JOINTS, start, keys)

    def signals(snap):
        return {"hand_r": body.site_pos("hand_r"), "hand_l": body.site_pos("hand_l"),
                "whole_deg": np.degrees(whole_spine(body.theta())), "key": float(player.step_index(snap["t"]))}

    return Rig(body, stages=[[player], [control]], channels=SETPOINTS, duration=float(player.times[-1]),
               record={20: signals}, view={**CLA_VIEW, "distance": 1.0, "azimuth": 160.0, "elevation": -5},
               state={"targets": targets, "gaps": gaps, "sole_z": sole_z, "labels": [k.label for k in keys]})


def _one(run) -> dict:
    log, st = run.log, run.state
    key, whole = log.values("key").astype(int), log.values("whole_deg")
    labels = np.array(st["labels"])[key]
    out, reached = {}, 0
    for pose, (target, _) in st["targets"].items():
        hand = log.values(f"hand_{side_of(pose)}")
        held = np.flatnonzero(labels == f"{pose}_hold")
        error = float(np.linalg.norm(hand[held[-1]] - target))
        reached += error <= POSE_TOLERANCE_M
        out |= {f"hand_error_{pose}_m": error, f"roll_{pose}_deg": float(whole[held[-1], 0]),
                f"yaw_{pose}_deg": float(whole[held[-1], 2])}
        if pose.startswith("bend"):
            during = np.isin(labels, (pose, f"{pose}_hold"))
            out[f"hand_above_soles_{pose}_m"] = float(hand[during, 2].min() - CLA_HAND_RADIUS_M - st["sole_z"])
    out["hand_above_soles_m"] = max(v for k, v in out.items() if k.startswith("hand_above_soles_"))
    out |= {f"model_gap_{pose}_m": gap for pose, gap in st["gaps"].items()}
    return out | {"poses_reached": int(reached), "max_spine_change_deg": float(np.abs(whole - whole[0]).max())}


def plots(ctx, runs, params):
    P.poses(ctx, runs, POSES_DEG)


def metrics(runs, params):
    return per_variant({v: _one(r) for v, r in runs.items()}) | {"poses": len(POSES_DEG)}


experiment(
    "spine.cla-poses",
    source="seed 003 §3.6.3, Fig. 3.38; §5.2.1, Fig. 5.1",
    summary="Seated whole-body Cla takes side-bend and twist poses with its arms: the hand where only the spine's "
            "twist and side bend put it, and down to the soles' height; the same hand targets with the spine locked",
    params=[Param("calibration_s", 1.0, "§4.6.4 encoder zeroing before the run [s]", lo=0.1, hi=5.0),
            Param("move_s", POSE_MOVE_S, "the move into each pose [s] (chosen)", lo=0.2, hi=5.0)],
    checks=(
        Check("hand_above_soles_spine_m", "<=", SOLE_LEVEL_TOLERANCE_M, Q_51 + f": in both side bends the hand's "
              f"lowest point within {SOLE_LEVEL_TOLERANCE_M * 100:g} cm of the soles' (declared before the run)",
              name="side_bend_hand_to_sole_height", kind="reproduction", row="003:fig5.1"),
        Check("poses_reached_spine", "==", "poses", Q_38 + f": with the spine every pose's hand ends within "
              f"{POSE_TOLERANCE_M * 100:g} cm of its target (declared before the run)", name="poses_possible_with_spine",
              kind="reproduction", row="003:fig3.38"),
        Check("poses_reached_locked", "==", 0, Q_38 + ": with the spine locked no pose's hand target is reached",
              name="poses_impossible_without_spine", kind="reproduction", row="003:fig3.38"),
        Check("max_spine_change_locked_deg", "<", 1.5, "the lock holds the spine (cla_body's equality constraints) — "
              "< 1.5° as cla_body's own test", name="locked_spine_stays", kind="consistency"),
    ),
    thesis={"poses": ThesisValue("twist and side-bend postures impossible without a spine (photographs)",
                                 "seed 003 " + Q_38, "poses_reached_spine"),
            "hand_height": ThesisValue("the hand about at the soles' height (photographs)", "seed 003 " + Q_51,
                                       "hand_above_soles_spine_m")},
    covers=("003:fig3.38", "003:fig5.1"),
    video=True,
    rig=rig, variants=VARIANTS, metrics=metrics, plots=plots,
    smoke={"calibration_s": 0.2, "move_s": 0.2},
)
