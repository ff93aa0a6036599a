"""Direct teaching and playback (seed 003 §4.2) and encoder zeroing in LL mode (§4.6.4).

* :func:`zero_encoders` — §4.6.4's calibration: LL mode with a "just taut" limit and short
  targets pulls every muscle in until its tension reaches the limit; with the spine held in the
  initial posture, the encoders are zeroed there.
* :class:`Recording` / :class:`Recorder` — teaching: all muscles in tension control (§4.2.1: e.g.
  all at 1 kgf) while a human moves the spine; the encoder values are logged at a fixed sampling
  period (20 ms, §5.9.2: "the muscle lengths are recorded at a 20 ms sampling period").
* :class:`Playback` — replay in L mode: the logged encoder values are sent in order as the length
  targets (§4.2.2, the ``l_r`` channel the muscle controller reads in a later stage), through the
  seqplugin posture player (:class:`~shintai.core.interpolation.SequencePlayer`), one sample per
  sampling period; ``speedup=k`` sends every k-th sample — "every other sample → 2× speed … 8× exceeded
  the motors' maximum speed" (§4.2.2). Key postures (§4.2.2 (a)) are replayed with interpolation, each
  commanded on the ``l_goal`` channel.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from shintai.core.interpolation import SequencePlayer
from shintai.core.runtime import SET, Channel, Loop, Module, Snapshot
from shintai.spine.control import Mode, MuscleControl
from shintai.spine.robots import SAMPLE_PERIOD_S

# A key posture to replay: the encoder lengths the playback moves to (minimum jerk), written by a schedule.
L_GOAL = Channel("l_goal", SET, doc="encoder lengths of the next key posture [m]")


def zero_encoders(body, control: MuscleControl, limit_n: float, theta0=None, seconds: float = 1.0,
                  pull_m: float = 0.01) -> np.ndarray:
    """§4.6.4 encoder zero calibration; returns the tensions the muscles settled at.

    A hand holds the spine at ``theta0`` (default: the basic posture) while every muscle runs LL
    with T_l = ``limit_n`` ("just taut") and a target ``pull_m`` shorter than where it is, so each
    winds in until its tension reaches the limit; then the encoders are zeroed and the targets set
    to zero (the muscle lengths of ``theta0``). The hand stays until the next loop's first tick
    without a ``hand`` writer.
    """
    hand = np.zeros(3 * body.robot.n) if theta0 is None else np.asarray(theta0, dtype=float)
    saved_limit = control.gains.T_l
    control.set_gains(T_l=limit_n)
    control.set_modes(Mode.LL)
    control.set_targets(l_r=np.asarray(body.snapshot()["encoder"]) + pull_m)
    Loop(body, [control], base={"hand": hand}).run(seconds)
    tension = body.wire_tension()
    body.zero_encoders()
    control.set_gains(T_l=saved_limit)
    control.set_targets(l_r=np.zeros(control.m), l_0=np.zeros(control.m))
    control.reset(body.snapshot())
    return tension


@dataclass
class Recording:
    """A taught motion: encoder samples (k, m) [m] every ``period`` seconds, and the true postures
    (k, 3n) the spine had (for evaluation only; the thesis had no model of them)."""

    period: float
    encoder: list = field(default_factory=list)
    theta: list = field(default_factory=list)

    @property
    def samples(self) -> np.ndarray:
        return np.asarray(self.encoder)

    @property
    def postures(self) -> np.ndarray:
        return np.asarray(self.theta)

    def decimated(self, speedup: int) -> np.ndarray:
        """Every ``speedup``-th sample (and the last), replayed at the same period: k× speed."""
        if int(speedup) != speedup or speedup < 1:
            raise ValueError(f"speedup must be a positive integer, got {speedup!r}")
        samples = self.samples
        index = np.arange(0, len(samples), int(speedup))
        if index[-1] != len(samples) - 1:
            index = np.append(index, len(samples) - 1)
        return samples[index]


class Recorder(Module):
    """Teaching: logs the encoder values (and the true posture) every sampling period; contributes
    nothing to the command (the muscles hold their tension meanwhile)."""

    def __init__(self, period: float = SAMPLE_PERIOD_S, name: str = "teach"):
        super().__init__(name, period)
        self.recording = Recording(period)

    def update(self, snapshot: Snapshot):
        self.recording.encoder.append(np.asarray(snapshot["encoder"], dtype=float).copy())
        self.recording.theta.append(np.asarray(snapshot["theta"], dtype=float).copy())
        return None


class Playback(Module):
    """Replays encoder targets in L mode through a SequencePlayer, for a :class:`MuscleControl` in a
    later stage.

    :meth:`play` queues samples one ``period`` apart ("linear": the recorded stream as encoder
    targets); :meth:`play_postures` queues taught key postures with minimum-jerk interpolation, as
    does a key posture arriving on the ``l_goal`` channel (reached in ``key_move_s``). Each tick the
    player's current vector is written to ``l_r``; on its first tick it also sets every muscle to L
    (``mode``).
    """

    def __init__(self, start, period: float | None = None, name: str = "playback", key_move_s: float = 1.0):
        super().__init__(name, period)
        self.player = SequencePlayer(np.asarray(start, dtype=float), method="linear", channel="l_r")
        self.length_mode = np.full(self.player.x.size, float(Mode.L))
        self.key_move_s = key_move_s
        self._first = True

    def play(self, samples, sample_period: float = SAMPLE_PERIOD_S) -> None:
        self.player.switch("linear")
        for sample in np.asarray(samples, dtype=float):
            self.player.push(sample, sample_period)

    def play_postures(self, postures, durations) -> None:
        self.player.switch("minjerk")
        for posture, duration in zip(np.asarray(postures, dtype=float), np.broadcast_to(durations, (len(postures),))):
            self.player.push(posture, float(duration))

    @property
    def busy(self) -> bool:
        return self.player.busy

    def reset(self, snapshot: Snapshot) -> None:
        self.player.reset(snapshot)
        self._first = True

    def update(self, snapshot: Snapshot):
        goal = snapshot.get("l_goal")
        if goal is not None:
            self.play_postures([goal], self.key_move_s)
        out = self.player.update(snapshot)
        if self._first:
            out["mode"] = self.length_mode
            self._first = False
        return out
