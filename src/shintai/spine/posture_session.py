"""A posture-database session on the MuJoCo Cla (seed 003 §5.9): the robot's side — pushes, teaching, history
replay and nearest-node execution in one Loop.

Stages of the Loop: [:class:`~shintai.spine.posture_person.Experimenter`] → [:class:`Supervisor`] → [MuscleControl].
The person (:mod:`~shintai.spine.posture_person`) pushes, teaches by hand and asks for replays; this module is the
robot.

* :class:`Supervisor` — the robot's upper layer: the only writer of the muscle set-points. It monitors the
  encoder lengths every 20 ms into the :class:`~shintai.spine.posture_database.PostureDatabase` in every
  mode (§5.9.3 "姿勢データベースとの兼ね合い"), feels pushes through the tensions
  (:mod:`shintai.spine.tactile`) while holding, nudges on a weak push (NN posture estimate, §4.4.3; target
  by eq. 4.25; §4.7's L + LL modes), goes limp in T mode on a strong push (§4.2.1's 1 kgf) and comes back
  to L at the taught lengths once the hand has held them still; and plays node sequences in L mode.

The muscle "lengths" of the database are the encoder values (§4.2.2: the muscle lengths are what the
motor encoders read); the posture sensor is Cla's accelerometer pair (roll, pitch, eq. 3.4).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import numpy as np

from shintai.core.interpolation import SequencePlayer
from shintai.core.runtime import Module, Snapshot
from shintai.spine.control import Mode, encoder_targets, interference_modes
from shintai.spine.geometry import SpineModel, whole_spine
from shintai.spine.posture_database import PostureDatabase
from shintai.spine.robots import (
    ARM_STILL_NM,
    BASELINE_S,
    LIMP_SETTLE_S,
    MOVE_S,
    SAMPLE_PERIOD_S,
    SETTLE_S,
    STILL_MM,
    STILL_S,
)
from shintai.spine.tactile import STRONG, Fired, PushTrigger, TriggerLevels, moment_arms, nudge_target, push_moment


HOLD, MOVE, LIMP, PLAY = "hold", "move", "limp", "play"


HOLD, MOVE, LIMP, PLAY = "hold", "move", "limp", "play"


@dataclass
class SessionLog:
    """What the session recorded: 20 ms samples, trigger events, sequences played."""

    t: list = field(default_factory=list)
    encoder: list = field(default_factory=list)
    whole: list = field(default_factory=list)  # true whole-spine angles [rad] (evaluation only)
    state: list = field(default_factory=list)
    sensor: list = field(default_factory=list)  # the posture sensor averaged over each sample (or None)
    tau: list = field(default_factory=list)  # (t, |τ̂|) while armed
    force: list = field(default_factory=list)  # (t, |F|) of the person's push
    fired: list = field(default_factory=list)  # (Fired, action index)
    nudges: list = field(default_factory=list)  # (commanded Θ' [rad], t_end)
    plays: list = field(default_factory=list)  # dicts: kind, node ids, arrival times, t0


class Supervisor(Module):
    """The upper layer (module doc). ``nn``: a length → posture model with ``posture(λ)`` (§4.4.3)."""

    def __init__(self, model: SpineModel, db: PostureDatabase, nn, levels: TriggerLevels, teach_tension_n: float,
                 use_sensor: bool = True, name: str = "supervisor"):
        super().__init__(name)
        self.model, self.db, self.nn = model, db, nn
        self.trigger = PushTrigger(levels)
        self.teach_tension_n = teach_tension_n
        self.use_sensor = use_sensor
        self.zero = model.lengths(np.zeros(3 * model.n))  # the encoders were zeroed at the basic posture
        self.state, self.arm_at, self.base, self.arms = HOLD, 0.0, None, None
        self.player: SequencePlayer | None = None
        self.log = SessionLog()
        self.next_sample = 0.0
        self.recent: deque = deque()  # the last STILL_S of 20 ms samples: encoders and tensions
        self.recent_T: deque = deque()
        self.action = -1  # index of the person's current action (for the log)

    @property
    def ready(self) -> bool:
        return self.state == HOLD and self.base is not None

    def estimate_whole(self, encoder) -> np.ndarray:
        """Θ from the NN on the path lengths λ = λ_zero − l (§4.4.3), summed over the joints."""
        return whole_spine(self.nn.posture(self.zero - np.asarray(encoder)))

    def play(self, kind: str, nodes: list[int], durations, method: str, t: float) -> None:
        """Play node lengths in L mode (``method``: "linear" at constant speed, or "minjerk")."""
        self.player = SequencePlayer(self._l_r, method=method, channel="l_r")
        for k, d in zip(nodes, durations):
            self.player.push(self.db.nodes[k].lengths, float(d))
        self.log.plays.append({"kind": kind, "nodes": list(nodes), "t0": t,
                               "arrive": (t + np.cumsum(durations)).tolist()})
        self.state, self._modes = PLAY, np.full(self.model.m, int(Mode.L))
        self._new_modes = True

    def reset(self, snapshot: Snapshot) -> None:
        self._l_r = np.asarray(snapshot["encoder"], dtype=float).copy()
        self._modes = np.full(self.model.m, int(Mode.L))
        self._new_modes = True
        self._t_prev = float(snapshot["t"])
        self.next_sample = self._t_prev
        self.arm_at = self._t_prev + LIMP_SETTLE_S  # the calibrating hand lets go on the first tick
        self._sensor_sum, self._sensor_n = np.zeros(2), 0

    def update(self, snapshot: Snapshot):
        t, enc, T = snapshot["t"], np.asarray(snapshot["encoder"]), np.asarray(snapshot["tension"])
        self._sensor_sum, self._sensor_n = self._sensor_sum + np.asarray(snapshot["posture"]), self._sensor_n + 1
        if t >= self.next_sample - 1e-9:  # the database's 20 ms monitoring sample
            self.next_sample += SAMPLE_PERIOD_S
            self._monitor(snapshot, t, enc)
        out = {}
        if self.state == HOLD and t >= self.arm_at:
            self._armed(t, enc, T)
        elif self.state in (MOVE, PLAY):
            self._l_r = self.player.advance(t - self._t_prev)
            if not self.player.busy:
                self.state, self.arm_at, self.base, self.arms = HOLD, t + SETTLE_S, None, None
        elif self.state == LIMP:
            self._limp(t, enc)
        self._t_prev = t
        out["l_r"] = self._l_r
        if self._new_modes:
            out["mode"], out["T_r"] = self._modes, np.full(self.model.m, self.teach_tension_n)
            self._new_modes = False
        return out

    # -- parts of a tick --------------------------------------------------------------------------------------

    def _monitor(self, snap, t, enc) -> None:
        sensor = self._sensor_sum / self._sensor_n if self.use_sensor else None  # averaged over the sample period
        self._sensor_sum, self._sensor_n = np.zeros(2), 0
        self.log.sensor.append(sensor)
        whole = whole_spine(snap["theta"])
        self.db.observe(enc, sensor, t, tag=self.state, truth=whole)
        lg = self.log
        lg.t.append(t)
        lg.encoder.append(enc.copy())
        lg.whole.append(whole)
        lg.state.append(self.state)
        self.recent.append(enc.copy())
        self.recent_T.append(np.asarray(snap["tension"], dtype=float).copy())
        while len(self.recent) > max(1, int(round(STILL_S / SAMPLE_PERIOD_S))) + 1:
            self.recent.popleft()
            self.recent_T.popleft()

    def _armed(self, t, enc, T) -> None:
        if self.base is None:  # arming: moment arms at the estimated posture, then wait for still tensions
            if self.arms is None:
                self.arms = moment_arms(self.model, self.estimate_whole(enc))
            window = np.array(self.recent_T)
            if len(window) <= int(round(STILL_S / SAMPLE_PERIOD_S)):
                return
            if float(np.linalg.norm((window - window[-1]) @ self.arms, axis=1).max()) >= ARM_STILL_NM:
                return
            self.base = T.copy()  # the tension the spine holds with
            self.trigger.reset()
            return
        tau = push_moment(self.arms, T, self.base)
        self.log.tau.append((t, float(np.linalg.norm(tau))))
        fired = self.trigger.update(tau, t)
        if self.trigger.start is None:  # no push under way: follow the slow drift
            self.base += (T - self.base) * min(1.0, (t - self._t_prev) / BASELINE_S)
        if fired is None:
            return
        self.log.fired.append((fired, self.action))
        if fired.level == STRONG:
            self._go_limp(enc)
        else:
            self._nudge(fired, enc, t)

    def _go_limp(self, enc) -> None:
        """§5.9.3 strong push: every muscle of the spine to T mode at the teaching tension."""
        self.state, self.limp_from = LIMP, enc.copy()
        self._modes, self._new_modes = np.full(self.model.m, int(Mode.T)), True

    def _limp(self, t, enc) -> None:
        """Teaching ends when the spine was moved (≥ d_len) and the hand has held it still: hold there in L."""
        moved = np.linalg.norm(enc - self.limp_from) >= self.db.d_len
        window = np.array(self.recent)
        still = len(window) > 1 and float(np.abs(window - window[-1]).max()) <= STILL_MM * 1e-3
        if moved and still:
            self._l_r = enc.copy()
            self._modes, self._new_modes = np.full(self.model.m, int(Mode.L)), True
            self.state, self.arm_at, self.base, self.arms = HOLD, t + LIMP_SETTLE_S, None, None

    def _nudge(self, fired: Fired, enc, t) -> None:
        """§5.9.3 weak push: NN posture + force-dependent angle → eq. 4.25 lengths; §4.7: L shortening, LL
        lengthening."""
        lengths, whole = nudge_target(self.model, self.estimate_whole(enc), fired)
        target = encoder_targets(lengths, self.zero)
        self._modes = interference_modes(self.zero - enc, lengths, Mode.LL)
        self._new_modes = True
        self.player = SequencePlayer(self._l_r, method="minjerk", channel="l_r")
        self.player.push(target, MOVE_S)
        self.state = MOVE
        self.log.nudges.append((whole, t + MOVE_S))
