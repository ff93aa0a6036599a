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
and controller with the spine locked at the wind-up posture when the throw starts (:class:`LockAtThrow`).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.cla.body import ClaBody
from shintai.spine.cla.constants import FOLLOW_S, HOLD_S, SPINE_RELEASE_DEG, SPINE_WINDUP_DEG
from shintai.spine.cla.control import spine_control
from shintai.spine.cla.keyframes import SPINE_AXES, Key, KeyframePlayer
from shintai.spine.control import SETPOINTS, encoder_targets
from shintai.spine.geometry import uniform_posture, whole_spine
from shintai.spine.robots import CLA

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


class LockAtThrow(Module):
    """Writes ``spine_lock`` from the ``at_tick``-th tick on: the spine locked at the wind-up when the throw starts
    ("without the spine", Fig. 5.4)."""

    def __init__(self, at_tick: int):
        super().__init__("lock")
        self.at_tick, self.tick = at_tick, 0

    def update(self, snapshot: Snapshot):
        self.tick += 1
        return {"spine_lock": 1.0} if self.tick > self.at_tick else None


@dataclass
class Throw:
    """What a throw rig leaves for its metrics: the pattern and the start time."""

    pattern: ThrowPattern
    t0: float


def throw_rig(with_spine: bool, spine_s: float, shoulder_s: float, elbow_s: float, windup_s: float = 1.5,
              calibration_s: float = 1.0, sequenced: bool = True, view=None) -> Rig:
    """One throw on the seated Cla (no desk): the spine free (``with_spine``) or locked at the wind-up posture
    when the throw starts; ``sequenced`` False starts the three parts together (the ablation). Records every ms
    the hand's speed [m/s], the spine's whole-body angles [deg] and the shoulder and elbow angles [rad]
    (:func:`throw_series`); runs ``FOLLOW_S`` past the throw's start."""
    body = ClaBody("seated", desk=False)
    control, zero = spine_control(body, calibration_s=calibration_s)
    pattern = ThrowPattern(zero, spine_s, shoulder_s, elbow_s, sequenced, windup_s)
    at_throw = round(pattern.throw_at / body.dt)
    first = [pattern] if with_spine else [pattern, LockAtThrow(at_throw)]
    hand = body.id("site", "hand_r")

    def sample(snap):
        v = np.zeros(6)
        mujoco.mj_objectVelocity(body.model, body.data, mujoco.mjtObj.mjOBJ_SITE, hand, v, 0)
        return {"hand_speed_mps": float(np.linalg.norm(v[3:])), "spine_deg": np.degrees(whole_spine(snap["theta"])),
                "shoulder_rad": body.joint_qpos("shoulder_pitch_r"), "elbow_rad": body.joint_qpos("elbow_r")}

    steps = at_throw + round(FOLLOW_S / body.dt)
    return Rig(body, stages=[first, [control]], channels=SETPOINTS, duration=steps * body.dt, record={1: sample},
               view=view or {}, state=Throw(pattern, body.t))


def throw_series(log, run: Throw) -> dict:
    """The recorded series, ``t`` from the throw rig's start, and the pattern."""
    spine = log.values("spine_deg")
    s = {"t": log.times("hand_speed_mps") - run.t0, "hand_speed_mps": log.values("hand_speed_mps")}
    s |= {f"spine_{a}_deg": spine[:, i] for i, a in enumerate(("roll", "pitch", "yaw"))}
    return s | {"shoulder_rad": log.values("shoulder_rad"), "elbow_rad": log.values("elbow_rad"),
                "pattern": run.pattern}


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
