"""Cla pulls an object on the desk towards itself, leaning with the spine (seed 003 §5.2.4, Figs. 5.5–5.6), on
the seated whole-body Cla (:mod:`~shintai.spine.cla.body`).

§5.2.4: "Cla が机の上のものを引き寄せる様子 … 脊椎を利用しないで同様の動作を行おうとすると、Fig. 5.6 に示すように、
手が対象物に届かない。脊椎の動きが必要なデモンストレーションである。なお、脊椎の姿勢は実機で調整し決定している。"

**Set-up** (ours; the thesis gives none): the object (``desk_object``, a 40-mm cube) lies in line with the right
arm with its near face ``beyond_reach_m`` beyond the farthest point the right hand reaches at the desk's height with
the spine straight (:func:`reach_at_desk`). Cla's hand has no fingers in our model (§3.6.2 lists shoulder, elbow
and wrist only), so it pulls by hooking: the hand comes down behind the object and drags it back.

**Motion** (:class:`PullPattern`; keyframes chosen, as the thesis's spine posture was tuned on the robot): the
spine leans forward ``lean_deg`` (whole-spine pitch, :class:`~shintai.spine.cla.postures.PostureTargets`) while the arm
reaches over the object, the hand comes down behind it, then the spine straightens (half, then fully) while the
arm draws the hand back along the desk to ``PULL_TO_X_M``. The arm's joint targets at each keyframe are solved by
inverse kinematics on the model with the spine at the keyframe's lean (:func:`arm_keyframes`): "without the
spine" (Fig. 5.6) is the same module, the same targets and controller, the spine locked upright.

**Tuning** ("脊椎の姿勢は実機で調整し決定している", §5.2.4): the spine's goal while it leans carries a whole-spine
yaw pre-offset ``yaw_deg`` against the twist the load gives it; its value is tuned (constants ``PULL_YAW_*``),
on the hand's lateral drift off the object's centre line (:func:`pull_summary`'s ``hand_lateral_max_m``), not on
the pulled distance.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.cla.body import ClaBody
from shintai.spine.cla.constants import CLEARANCE_M, END_S, FOLD, LIFT_XZ_M, PRESS_M, PULL_TO_X_M, SUCCESS_M
from shintai.spine.cla.control import CHANNELS, spine_control, spine_stages
from shintai.spine.cla.keyframes import Key, KeyframePlayer
from shintai.spine.geometry import uniform_posture, whole_spine
from shintai.spine.robots import CLA, CLA_DESK_HEIGHT_M, CLA_HAND_RADIUS_M, CLA_OBJECT_HALF_M, CLA_SHOULDER_M

ARM = ("shoulder_pitch_r", "elbow_r", "wrist_r")
# The timeline [s from the loop's start]: (time the arm arrives, keyframe name, spine lean fraction at it)
# "lift" first raises the hand above the desk close to the chest (the seated arm hangs under the desk's edge)
# ("fold": the elbow bent first, so that the hand rises close to the body)
TIMELINE = ((0.6, "fold", 0.0), (1.2, "lift", 0.0), (2.7, "over", 1.0), (3.9, "down", 1.0), (5.2, "half", 0.5),
            (6.2, "pulled", 0.0))
STARTS = {"fold": 0.0, "lift": 0.6, "over": 1.2, "down": 3.2, "half": 4.2, "pulled": 5.2}  # each move's start


def _set(m, d, lean: float, arm) -> None:
    d.qpos[[m.jnt_qposadr[m.joint(f"j{i + 1}_{a}").id] for i in range(CLA.n) for a in ("roll", "pitch", "yaw")]] = \
        uniform_posture(np.array([0.0, lean, 0.0]), CLA.n)
    for joint, q in zip(ARM, arm):
        d.qpos[m.jnt_qposadr[m.joint(joint).id]] = q
    mujoco.mj_kinematics(m, d)
    mujoco.mj_comPos(m, d)


def hand_at(m, lean: float, arm, d: mujoco.MjData | None = None) -> np.ndarray:
    """The right hand's centre for spine lean ``lean`` [rad] and arm joints ``arm`` (kinematics only)."""
    d = mujoco.MjData(m) if d is None else d
    _set(m, d, lean, arm)
    return d.site_xpos[m.site("hand_r").id].copy()


def solve_arm(m, lean: float, target_xz, q0=(1.5, 0.3, 0.0), iterations: int = 200) -> np.ndarray:
    """Arm joints putting the right hand at (x, z) ``target_xz`` (the arm moves in its x–z plane) with the spine
    leaning ``lean``: damped least squares within the joint limits, the wrist kept near 0."""
    d = mujoco.MjData(m)
    q = np.array(q0, dtype=float)
    dofs = [m.jnt_dofadr[m.joint(j).id] for j in ARM]
    lo = np.array([m.jnt_range[m.joint(j).id][0] for j in ARM])
    hi = np.array([m.jnt_range[m.joint(j).id][1] for j in ARM])
    jacp = np.zeros((3, m.nv))
    for _ in range(iterations):
        _set(m, d, lean, q)
        err = np.asarray(target_xz) - d.site_xpos[m.site("hand_r").id][[0, 2]]
        mujoco.mj_jacSite(m, d, jacp, None, m.site("hand_r").id)
        J = jacp[[0, 2]][:, dofs]
        W = np.diag([1.0, 1.0, 4.0])  # the wrist costs more: it moves last
        Jw = J @ np.linalg.inv(W)
        dq = np.linalg.inv(W) @ Jw.T @ np.linalg.solve(Jw @ Jw.T + 1e-4 * np.eye(2), err)
        q = np.clip(q + dq, lo, hi)
    return q


def solve_arm_best(m, lean: float, target_xz, q_prev) -> np.ndarray:
    """:func:`solve_arm` from the previous keyframe and from a few fixed starts (the solver is local and the
    joints are limited); the solution nearest the target, ties broken by nearness to the previous keyframe."""
    best, best_cost = None, np.inf
    for q0 in (q_prev, (1.5, 0.3, 0.0), (2.2, 0.3, 0.0), (1.0, 1.0, 0.0), (2.8, 0.0, 0.0)):
        q = solve_arm(m, lean, target_xz, q0)
        miss = np.linalg.norm(hand_at(m, lean, q)[[0, 2]] - np.asarray(target_xz))
        cost = round(miss, 3) + 1e-3 * np.linalg.norm(q - np.asarray(q_prev))
        if cost < best_cost:
            best, best_cost = q, cost
    return best


def reach_at_desk(m, lean: float = 0.0) -> float:
    """The farthest x [m] the right hand's centre reaches at the desk's contact height with the spine leaning
    ``lean`` (elbow and wrist straight, the shoulder swept)."""
    z = CLA_DESK_HEIGHT_M + CLA_HAND_RADIUS_M
    best, d = -np.inf, mujoco.MjData(m)
    for sp in np.linspace(0.0, 3.0, 301):
        p = hand_at(m, lean, (sp, 0.0, 0.0), d)
        if p[2] >= z:
            best = max(best, p[0])
    return float(best)


def object_x(m, beyond_reach_m: float) -> float:
    """The object's centre x: its near face ``beyond_reach_m`` past the straight-spine reach at the desk."""
    return reach_at_desk(m) + beyond_reach_m + CLA_OBJECT_HALF_M


def arm_keyframes(m, lean: float, x_obj: float) -> dict[str, np.ndarray]:
    """The arm's joint targets at each keyframe (module docstring), solved with the spine at its keyframe lean."""
    z_desk = CLA_DESK_HEIGHT_M + CLA_HAND_RADIUS_M
    behind = x_obj + CLA_OBJECT_HALF_M + CLA_HAND_RADIUS_M + CLEARANCE_M
    targets = {"lift": (LIFT_XZ_M[0], z_desk + LIFT_XZ_M[1]),
               "over": (behind, z_desk + 2 * CLA_OBJECT_HALF_M + 0.02), "down": (behind, z_desk + CLEARANCE_M),
               "half": ((behind + PULL_TO_X_M) / 2, z_desk - PRESS_M), "pulled": (PULL_TO_X_M, z_desk - PRESS_M)}
    out, q = {"fold": np.array(FOLD)}, np.array(FOLD)
    for _, name, fraction in TIMELINE[1:]:
        q = out[name] = solve_arm_best(m, fraction * lean, targets[name], q)
    return out


def arm_keys(keyframes: dict[str, np.ndarray]) -> list[Key]:
    """The arm's part of the timeline as key postures for the keyframe player: each keyframe reached at its
    arrival time from its move's start (:data:`STARTS`), a hold (a key naming no joint) where the arm waits."""
    keys, at = [], 0.0
    for arrive, name, _ in TIMELINE:
        if STARTS[name] > at:
            keys.append(Key(STARTS[name] - at, {}, "hold"))
        keys.append(Key(arrive - STARTS[name], dict(zip(ARM, keyframes[name])), name))
        at = arrive
    return keys


class PullPattern(Module):
    """The pull's timeline: the spine's goals (whole-spine pitch) on the ticks they change and the arm's targets
    every tick, joint-space minimum jerk from keyframe to keyframe (the seqplugin player,
    :class:`~shintai.spine.cla.keyframes.KeyframePlayer`)."""

    def __init__(self, keyframes: dict[str, np.ndarray], lean: float, start_arm, yaw: float = 0.0, name: str = "pull"):
        super().__init__(name)
        self.keys, self.lean, self.yaw, self.start = keyframes, lean, yaw, np.asarray(start_arm, dtype=float)
        self.player = KeyframePlayer(ARM, dict(zip(ARM, self.start)), arm_keys(keyframes), channel="arm")
        self.t0, self.sent = 0.0, set()

    def reset(self, snapshot: Snapshot) -> None:
        self.t0, self.sent = snapshot["t"], set()
        self.player.reset(snapshot)

    def update(self, snapshot: Snapshot):
        t = snapshot["t"] - self.t0
        out = dict(zip(ARM, self.player.update(snapshot)["arm"]))
        for _, name, fraction in TIMELINE:
            if t >= STARTS[name] and name not in self.sent:
                self.sent.add(name)
                out["goal"] = np.array([0.0, fraction * self.lean, self.yaw if fraction > 0 else 0.0])
        return out


@dataclass
class Pull:
    """What a pull rig leaves for its metrics: the set-up, the keyframes, the start time and object position."""

    object_x_m: float
    reach_straight_m: float
    reach_leaning_m: float
    keyframes: list
    t0: float
    x0: np.ndarray


def pull_rig(with_spine: bool, lean_deg: float, beyond_reach_m: float, move_s: float, calibration_s: float = 1.0,
             view=None, yaw_deg: float = 0.0) -> Rig:
    """One pull on the seated Cla before the desk: the spine free, or locked upright from the start, leaning
    ``lean_deg`` (with the yaw pre-offset ``yaw_deg`` while it leans) toward an object ``beyond_reach_m`` past the straight arm's reach. Records every 10 ms the hand,
    the object's displacement, the hand's gap to it and the whole spine (:func:`pull_series`)."""
    body = ClaBody("seated")
    m = body.model
    lean = np.radians(lean_deg)
    x_obj = object_x(m, beyond_reach_m)
    start = [body.joint_qpos(j) for j in ARM]
    keys = arm_keyframes(m, lean, x_obj)
    control, zero = spine_control(body, calibration_s=calibration_s)
    body.place("desk_object", [x_obj, -CLA_SHOULDER_M[1], CLA_DESK_HEIGHT_M + CLA_OBJECT_HALF_M])
    if not with_spine:
        body.lock_spine(True)
    pattern = PullPattern(keys, lean, start, np.radians(yaw_deg))
    stages = spine_stages(control, zero, move_s, first=[pattern])
    run = Pull(x_obj, reach_at_desk(m), reach_at_desk(m, lean), keys, body.t, body.object_pos("desk_object").copy())

    def sample(snap):
        hand, obj = snap["hand_r_pos"], body.object_pos("desk_object")
        gap = np.abs(hand - obj) - CLA_OBJECT_HALF_M
        return {"hand_m": hand, "object_d_m": obj - run.x0,
                "hand_gap_m": float(np.linalg.norm(np.maximum(gap, 0.0)) - CLA_HAND_RADIUS_M),
                "spine_deg": np.degrees(whole_spine(snap["theta"]))}

    return Rig(body, stages=stages, channels=CHANNELS, duration=END_S, record={10: sample}, view=view or {},
               state=run)


def pull_series(log, run: Pull) -> dict:
    """The recorded time series (``t`` from the pull's start) and the set-up."""
    hand, obj, spine = log.values("hand_m"), log.values("object_d_m"), log.values("spine_deg")
    s = {"t": log.times("hand_m") - run.t0, "hand_gap_m": log.values("hand_gap_m"),
         "hand_lateral_m": hand[:, 1] - (run.x0[1] + obj[:, 1])}
    s |= {f"hand_{a}_m": hand[:, i] for i, a in enumerate("xyz")}
    s |= {f"object_d{a}_m": obj[:, i] for i, a in enumerate("xyz")}
    s |= {f"spine_{a}_deg": spine[:, i] for i, a in enumerate(("roll", "pitch", "yaw"))}
    return s | {"object_x_m": run.object_x_m, "reach_straight_m": run.reach_straight_m,
                "reach_leaning_m": run.reach_leaning_m, "keyframes": run.keyframes}


def pull_summary(s: dict) -> dict[str, float]:
    """Pulled distance (toward Cla: −x) [m], success, the hand's closest approach to the object [m] and its
    farthest x [m], the largest spine lean [deg], the spine's largest |yaw| [deg], and the hand's largest lateral
    offset from the object's centre line from the hand's coming down behind it to the end of the drag [m]."""
    pulled = float(-s["object_dx_m"][-1])
    drag = (s["t"] >= STARTS["down"]) & (s["t"] <= TIMELINE[-1][0])
    return {"object_pulled_m": pulled, "success": int(pulled >= SUCCESS_M),
            "hand_lateral_max_m": float(np.abs(s["hand_lateral_m"][drag]).max()),
            "max_abs_yaw_deg": float(np.abs(s["spine_yaw_deg"]).max()),
            "hand_min_gap_m": float(s["hand_gap_m"].min()), "hand_max_x_m": float(s["hand_x_m"].max()),
            "max_lean_deg": float(s["spine_pitch_deg"].max())}
