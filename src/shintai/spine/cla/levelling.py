"""Cla levels its shoulders by the accelerometer while its seat is tilted (seed 003 §5.2.2, Fig. 5.2).

§5.2.2: "3 軸加速度センサにより重力方向を検出し、肩が水平でなければ、脊椎の姿勢を制御して水平になるように動作する。
動作中は、加速度センサが自分の動作に起因する加速度を検出してしまうので、姿勢の調節とセンサ情報の読み取りはフェイズ
を分けて、姿勢検出 → 脊椎調節量算出 → 動作 という作業を順に繰り返すようにした。脊椎調整量の算出時には、4.4.3節に
述べたニューラルネットワークを利用した筋長情報 → 脊椎の姿勢情報の変換を利用した。"

* :class:`SeatTilt` — the disturbance (ours: the thesis does not say what tilted Cla): the experimenter tilts the
  stool (:func:`~shintai.spine.cla.body.build_spec` ``seat_tilt``) to given (roll, pitch) with minimum jerk.
* :class:`Levelling` — the three phases, repeated: (1) **sense**: after the spine has been still for
  ``settle_s``, average the shoulder (clavicle) accelerometer over ``window_s`` and take its tilt (roll, pitch)
  from the gravity direction; (2) **compute**: if the shoulders are off level by more than ``deadband_deg``,
  the present spine posture from the muscle lengths by the neural network of §4.4.3 (the encoders give the
  lengths: λ = λ(0) − l), and the new whole-spine goal = the present one − the shoulder tilt (roll and pitch;
  the yaw kept); (3) **move**: the goal to the posture player (eq. 4.25 lengths → L mode), ``move_s``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.interpolation import minimum_jerk
from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.actuators import tilt
from shintai.spine.cla.body import ClaBody
from shintai.spine.cla.constants import SEAT_MOVE_S, TILT1_S
from shintai.spine.cla.control import CHANNELS, spine_control, spine_stages
from shintai.spine.geometry import whole_spine
from shintai.spine.inverse_model import NeuralInverse


class SeatTilt(Module):
    """Writes the seat's targets ``seat_roll``/``seat_pitch`` [rad]: at each ``(t_start, roll, pitch)`` of
    ``moves`` the seat moves from where it was to (roll, pitch) in ``move_s`` with minimum jerk."""

    def __init__(self, moves, move_s: float = 1.0, name: str = "seat"):
        super().__init__(name)
        self.moves, self.move_s = [(float(t), np.array([r, p], dtype=float)) for t, r, p in moves], move_s

    def reset(self, snapshot: Snapshot) -> None:
        self.t0 = snapshot["t"]  # the moves' times count from the loop's start

    def target(self, t: float) -> np.ndarray:
        """The seat's (roll, pitch) target at ``t`` seconds from the loop's start."""
        at = np.zeros(2)
        for start, goal in self.moves:
            if t < start:
                break
            s = min(1.0, (t - start) / self.move_s)
            at = at + (goal - at) * minimum_jerk(s)
        return at

    def update(self, snapshot: Snapshot):
        roll, pitch = self.target(snapshot["t"] - self.t0)
        return {"seat_roll": roll, "seat_pitch": pitch}


class Levelling(Module):
    """§5.2.2's sense → compute → move loop (module docstring). ``events`` keeps, per adjustment, the time,
    the shoulder tilt sensed (deg), the NN's whole-spine posture (deg) and the goal sent (deg)."""

    def __init__(self, inverse: NeuralInverse, zero_lengths, settle_s: float, window_s: float, move_s: float,
                 deadband_deg: float, gain: float = 1.0, name: str = "levelling"):
        super().__init__(name)
        self.inverse, self.zero = inverse, np.asarray(zero_lengths, dtype=float)
        self.settle_s, self.window_s, self.move_s = settle_s, window_s, move_s
        self.deadband, self.gain = np.radians(deadband_deg), gain
        self.events: list[dict] = []
        self.reset(None)

    def reset(self, snapshot: Snapshot | None) -> None:
        self.phase, self.since, self.samples = "settle", None, []

    def update(self, snapshot: Snapshot):
        t = snapshot["t"]
        if self.since is None:
            self.since = t
        if self.phase in ("settle", "move"):
            wait = self.settle_s + (self.move_s if self.phase == "move" else 0.0)
            if t - self.since >= wait:
                self.phase, self.since, self.samples = "sense", t, []
            return None
        self.samples.append(np.asarray(snapshot["acc_chest"], dtype=float))
        if t - self.since < self.window_s:
            return None
        shoulder = tilt(np.mean(self.samples, axis=0))  # (roll, pitch) of the shoulders in the world [rad]
        self.phase, self.since = "settle", t
        if np.abs(shoulder).max() <= self.deadband:
            return None
        lengths = self.zero - np.asarray(snapshot["encoder"], dtype=float)  # l = λ(0) − λ (control.py)
        now = whole_spine(self.inverse.posture(lengths))
        goal = now.copy()
        goal[:2] -= self.gain * shoulder
        self.phase = "move"
        self.events.append({"t": t, "shoulder_deg": np.degrees(shoulder), "nn_whole_deg": np.degrees(now),
                            "true_whole_deg": np.degrees(whole_spine(snapshot["theta"])), "goal_deg": np.degrees(goal)})
        return {"goal": goal}


def shoulder_tilt(body) -> np.ndarray:
    """The clavicle's true (roll, pitch) in the world [rad], from its frame (not the accelerometer)."""
    R = body.data.xmat[body.id("body", "link5")].reshape(3, 3)
    up = R.T @ np.array([0.0, 0.0, 1.0])
    return np.array([np.arctan2(up[1], up[2]), np.arctan2(-up[0], np.hypot(up[1], up[2]))])


@dataclass
class LevellingRun:
    """What a levelling rig leaves for its metrics: the law (its ``events``), whether it acted, the start time."""

    law: Levelling
    levelling: bool
    t0: float


def levelling_rig(levelling: bool, inverse: NeuralInverse, tilt1_roll_deg: float, tilt2_s: float,
                  tilt2_roll_deg: float, tilt2_pitch_deg: float, settle_s: float, window_s: float, move_s: float,
                  deadband_deg: float, duration_s: float, calibration_s: float = 1.0, view=None) -> Rig:
    """One run on the seated Cla with a tilting seat: the seat tilts to (``tilt1_roll_deg``, 0) at ``TILT1_S`` and
    to (``tilt2_roll_deg``, ``tilt2_pitch_deg``) at ``tilt2_s``; with ``levelling`` the :class:`Levelling` loop
    acts, without it the spine holds its basic posture. Records every 20 ms (:func:`levelling_series`)."""
    body = ClaBody("seated", desk=False, seat_tilt=True)
    control, zero = spine_control(body, calibration_s=calibration_s)
    seat = SeatTilt([(TILT1_S, np.radians(tilt1_roll_deg), 0.0),
                     (tilt2_s, np.radians(tilt2_roll_deg), np.radians(tilt2_pitch_deg))], SEAT_MOVE_S)
    law = Levelling(inverse, zero, settle_s, window_s, move_s, deadband_deg)
    stages = spine_stages(control, zero, move_s, first=[seat, law] if levelling else [seat])
    t0 = body.t  # times from the loop's start (after the encoder zeroing)

    def sample(snap):
        return {"shoulder_deg": np.degrees(shoulder_tilt(body)), "acc_deg": np.degrees(tilt(snap["acc_chest"])),
                "seat_deg": np.degrees(seat.target(snap["t"] - t0)),
                "spine_deg": np.degrees(whole_spine(snap["theta"]))}

    return Rig(body, stages=stages, channels=CHANNELS, duration=duration_s,
               record={max(1, round(0.02 / body.dt)): sample}, view=view or {}, state=LevellingRun(law, levelling, t0))


def levelling_series(log, run: LevellingRun) -> dict:
    """The recorded series (``t`` from the loop's start) and the adjustments (``events``)."""
    s = {"t": log.times("shoulder_deg") - run.t0}
    for signal, names in (("shoulder_deg", ("roll_deg", "pitch_deg")), ("acc_deg", ("acc_roll_deg", "acc_pitch_deg")),
                          ("seat_deg", ("seat_roll_deg", "seat_pitch_deg")),
                          ("spine_deg", ("spine_roll_deg", "spine_pitch_deg", "spine_yaw_deg"))):
        values = log.values(signal)
        s |= {name: values[:, i] for i, name in enumerate(names)}
    s["events"] = [{**e, "t": e["t"] - run.t0} for e in run.law.events] if run.levelling else []
    return s


def settled(series: dict, t0: float, t1: float) -> float:
    """The shoulders' mean tilt magnitude √(roll² + pitch²) [deg] over [t0, t1)."""
    sel = (series["t"] >= t0) & (series["t"] < t1)
    return float(np.hypot(series["roll_deg"][sel].mean(), series["pitch_deg"][sel].mean()))
