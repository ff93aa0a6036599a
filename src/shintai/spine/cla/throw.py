"""Cla throws, the spine's motion started first, then the shoulder's, then the elbow's (seed 003 §5.2.3,
Figs. 5.3–5.4), on the seated whole-body Cla (:mod:`~shintai.spine.cla.body`).

§5.2.3: "手先の瞬間最大速度を大きくするためには、脊椎根元部から順に動作を開始し、肩、肘という順に動作を開始する
ことで、慣性の大きい部位が最大速度になる瞬間と手先が最大速度になる瞬間を同じくすることができ … 脊椎を利用しない
場合は肩から手先までの関節しか加速に利用できないため、脊椎を利用する場合に比べ手先の最大速度は小さくなる。"

:class:`ThrowPattern` (one Loop module, writing the muscles' length targets and the arm servos' targets):

1. **wind-up** (``windup_s``): the spine to the wind-up posture (leaning back, twisted right) and the right arm
   cocked behind the head, minimum jerk; then a hold of ``HOLD_S`` until the throw starts (``throw_at``);
2. **throw**: each part moves from its wind-up to its release posture by a minimum-jerk profile of its own
   duration (spine ``spine_s`` > shoulder ``shoulder_s`` > elbow ``elbow_s``), started so that the three
   profiles' velocity peaks coincide (a minimum-jerk move peaks at its middle): the spine starts first, then
   the shoulder, then the elbow — the thesis's order and its reason, with our durations.

The spine's postures are whole-spine uniform bends whose muscle lengths (eq. 4.25) become the L-mode targets each
tick, as :class:`~shintai.spine.cla.postures.PostureTargets` does. "Without the spine" (Fig. 5.4) is the same module
and controller with the spine locked at the wind-up posture (:meth:`ClaBody.lock_spine` when the throw starts).
"""

from __future__ import annotations

import contextlib

import mujoco
import numpy as np

from shintai.core.runtime import Loop, Module, Snapshot
from shintai.spine.cla.body import ClaBody
from shintai.spine.cla.control import spine_control
from shintai.spine.cla.keyframes import SPINE_AXES, Key, KeyframePlayer
from shintai.spine.control import SETPOINTS, encoder_targets
from shintai.spine.geometry import uniform_posture, whole_spine
from shintai.spine.robots import CLA

HOLD_S, FOLLOW_S = 0.5, 1.0  # the hold after the wind-up, the run after the throw starts [s] (chosen)
# Postures (chosen: the thesis shows photographs only). Spine whole (roll, pitch, yaw) [deg]: wind-up leaning
# back 10° and twisted right 30° (the right shoulder back), release leaning forward 15° and twisted left 30°.
SPINE_WINDUP_DEG = (0.0, -10.0, -30.0)
SPINE_RELEASE_DEG = (0.0, 15.0, 30.0)
# Right arm servo targets [rad] (cla_body's signs): cocked with the hand behind the head, released forward-down
ARM_WINDUP = {"shoulder_roll_r": 0.3, "shoulder_pitch_r": 2.9, "elbow_r": 2.0, "wrist_r": -0.3}
ARM_RELEASE = {"shoulder_roll_r": 0.3, "shoulder_pitch_r": 1.2, "elbow_r": 0.2, "wrist_r": 0.5}
SHOULDER_JOINTS = ("shoulder_roll_r", "shoulder_pitch_r")
ELBOW_JOINTS = ("elbow_r", "wrist_r")
START_ARM = {"shoulder_pitch_r": 0.0, "elbow_r": 0.3}  # the seated keyframe's arm (cla_body.SEATED_POSE)
PARTS = {"spine": SPINE_AXES, "shoulder": SHOULDER_JOINTS, "elbow": ELBOW_JOINTS}  # each on its own player


class ThrowPattern(Module):
    """The throw's timeline (module docstring); durations [s]; ``starts`` the three parts' throw starts. Each part
    (:data:`PARTS`: the whole-spine Θ, the shoulder, the elbow and wrist) is a
    :class:`~shintai.spine.cla.keyframes.KeyframePlayer` (the seqplugin player, minimum jerk) of three keys: the
    wind-up, a hold until its throw start, the release."""

    def __init__(self, zero_lengths, spine_s: float, shoulder_s: float, elbow_s: float, sequenced: bool = True,
                 windup_s: float = 1.5, name: str = "throw"):
        super().__init__(name)
        self.zero = np.asarray(zero_lengths, dtype=float)
        self.durations = {"spine": spine_s, "shoulder": shoulder_s, "elbow": elbow_s}
        self.windup_s, self.throw_at = windup_s, windup_s + HOLD_S
        peak = self.throw_at + spine_s / 2  # every part's velocity peak at the spine's
        # not sequenced (the ablation): every part starts together when the throw starts
        self.starts = {part: peak - d / 2 if sequenced else self.throw_at for part, d in self.durations.items()}
        windup = {**dict(zip(SPINE_AXES, np.radians(SPINE_WINDUP_DEG))), **ARM_WINDUP}
        release = {**dict(zip(SPINE_AXES, np.radians(SPINE_RELEASE_DEG))), **ARM_RELEASE}
        self.players = {}
        for part, names in PARTS.items():
            keys = [Key(windup_s, {n: windup[n] for n in names}, "wind-up"),
                    Key(self.starts[part] - windup_s, {}, "hold"),
                    Key(self.durations[part], {n: release[n] for n in names}, "throw")]
            self.players[part] = KeyframePlayer(names, START_ARM, keys, channel=part, name=part)

    def reset(self, snapshot: Snapshot) -> None:
        for player in self.players.values():
            player.reset(snapshot)

    def update(self, snapshot: Snapshot):
        x = {part: player.update(snapshot)[part] for part, player in self.players.items()}
        l_r = encoder_targets(CLA.model.lengths(uniform_posture(x["spine"], CLA.n)), self.zero)
        arm = {n: float(v) for part in ("shoulder", "elbow") for n, v in zip(PARTS[part], x[part])}
        return {"l_r": l_r, "l_0": l_r, **arm}


def run_throw(p: dict, with_spine: bool, camera=None, sequenced: bool = True) -> dict:
    """One throw on the seated Cla (no desk): the spine free (``with_spine``) or locked at the wind-up posture
    when the throw starts; ``sequenced`` False starts the three parts together (the ablation). Returns the time
    series (every ms): the hand's speed [m/s], the spine's whole-body
    angles [deg] and the shoulder and elbow angles [rad], and the pattern."""
    body = ClaBody("seated", desk=False)
    control, zero = spine_control(body, calibration_s=p.get("calibration_s", 1.0))
    pattern = ThrowPattern(zero, p["spine_s"], p["shoulder_s"], p["elbow_s"], sequenced, p.get("windup_s", 1.5))
    loop = Loop(body, stages=[[pattern], [control]], channels=SETPOINTS)
    rows, t0 = [], body.t
    hand = body.id("site", "hand_r")

    def sample(snap):
        v = np.zeros(6)
        mujoco.mj_objectVelocity(body.model, body.data, mujoco.mjtObj.mjOBJ_SITE, hand, v, 0)
        rows.append([snap["t"] - t0, float(np.linalg.norm(v[3:])), *np.degrees(whole_spine(snap["theta"])),
                     body.joint_qpos("shoulder_pitch_r"), body.joint_qpos("elbow_r")])

    with camera(body) if camera is not None else contextlib.nullcontext():
        loop.run(pattern.throw_at, every={1: sample})
        if not with_spine:
            body.lock_spine(True)
        loop.run(FOLLOW_S, every={1: sample})
    a = np.array(rows)
    keys = ("t", "hand_speed_mps", "spine_roll_deg", "spine_pitch_deg", "spine_yaw_deg", "shoulder_rad", "elbow_rad")
    return {**{k: a[:, i] for i, k in enumerate(keys)}, "pattern": pattern}


def throw_summary(s: dict) -> dict[str, float]:
    """The throw's peak hand speed [m/s] and when it happens [s], each part's peak speed and its time, the spine's
    yaw travel during the throw [deg]."""
    t = s["t"]
    throw = t >= s["pattern"].throw_at
    k = int(np.argmax(np.where(throw, s["hand_speed_mps"], -1.0)))
    dt = np.gradient(t)
    out = {"hand_speed_mps": float(s["hand_speed_mps"][k]), "hand_peak_t_s": float(t[k])}
    for key, name in (("spine_yaw_deg", "spine"), ("shoulder_rad", "shoulder"), ("elbow_rad", "elbow")):
        rate = np.abs(np.gradient(s[key]) / dt)
        out[f"{name}_peak_t_s"] = float(t[throw][np.argmax(rate[throw])])
        unit = "deg_s" if key.endswith("_deg") else "rad_s"
        out[f"{name}_peak_rate_{unit}"] = float(rate[throw].max())
    out["spine_yaw_travel_deg"] = float(s["spine_yaw_deg"][-1] - s["spine_yaw_deg"][throw][0])
    return out
