"""The person of a posture-database session on the MuJoCo Cla (seed 003 §5.9): the first stage of the session's
Loop ([:class:`Experimenter`] → [:class:`~shintai.spine.posture_session.Supervisor`] → [MuscleControl]).

:class:`Experimenter` works through a list of :class:`Action` s, each once the robot holds still
(``Supervisor.ready``): a push on the shoulder block (an external force on the top link, ramped), and if the robot
goes limp the hand takes the shoulders (the body's ``hand`` channel) and moves them to the posture to teach, holds,
and lets go; or a command to replay the history / execute a model motion (played by the supervisor).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.spine.control import encoder_targets
from shintai.spine.geometry import SpineModel, uniform_posture
from shintai.spine.posture_session import LIMP, Supervisor
from shintai.spine.robots import (
    EXEC_DWELL_S,
    EXEC_MOVE_S,
    GUIDE_HOLD_S,
    GUIDE_S,
    PAUSE_S,
    PUSH_RAMP_S,
    REPLAY_MIN_SEGMENT_S,
    REPLAY_SPEED_MM_S,
)


@dataclass(frozen=True)
class Action:
    """One step of the session. ``kind``: "push" (``force_n`` (3,) on the shoulders for ``push_s``; if the
    robot goes limp, the hand teaches ``teach_deg``, whole-spine roll/pitch/yaw), "replay" (the history so
    far) or "execute" (the model motion ``motion_deg``, (k, 3) whole-spine postures, by nearest nodes)."""

    kind: str
    force_n: tuple = (0.0, 0.0, 0.0)
    push_s: float = 0.25
    teach_deg: tuple | None = None
    motion_deg: tuple = ()
    expect: str = ""  # the level the push is meant to be (weak/strong), for the metrics


class Experimenter(Module):
    """The person (module doc): pushes through ``force`` (read by the body hook), holds through ``hand``."""

    def __init__(self, actions: list[Action], supervisor: Supervisor, model: SpineModel, name: str = "person"):
        super().__init__(name)
        self.actions, self.sup, self.model = list(actions), supervisor, model
        self.i = -1
        self.force = np.zeros(3)
        self.phase, self.t0, self.ready_since = "wait", 0.0, None
        self.hand_path = None
        self.done = False

    def update(self, snapshot: Snapshot):
        t = snapshot["t"]
        self.force = np.zeros(3)
        if self.phase == "wait":
            if not self.sup.ready:
                self.ready_since = None
                return None
            self.ready_since = t if self.ready_since is None else self.ready_since
            if t - self.ready_since < PAUSE_S:
                return None
            self._next(t, snapshot)
        if self.phase == "push":
            return self._push(t, snapshot)
        if self.phase == "guide":
            return self._guide(t)
        if self.phase == "play" and self.sup.state != "play":
            self.phase, self.ready_since = "wait", None
        return None

    def _next(self, t, snapshot) -> None:
        self.i += 1
        self.sup.action = self.i
        self.ready_since = None
        if self.i >= len(self.actions):
            self.done, self.phase = True, "done"
            return
        a = self.actions[self.i]
        self.t0 = t
        if a.kind == "push":
            self.phase = "push"
        elif a.kind == "replay":
            self.phase = "play"
            self._replay(t)
        elif a.kind == "execute":
            self.phase = "play"
            self._execute(t)
        else:
            raise ValueError(f"unknown action {a.kind!r}")

    def _push(self, t, snapshot):
        a = self.actions[self.i]
        if self.sup.state == LIMP:  # the robot went limp: the hand takes the shoulders where they are
            if a.teach_deg is None:
                self.phase = "wait"
                return None
            start = np.asarray(snapshot["theta"], dtype=float)
            goal = uniform_posture(np.radians(a.teach_deg), self.model.n)
            self.hand_path, self.phase, self.t0 = (start, goal), "guide", t
            return self._guide(t)
        s = t - self.t0
        total = a.push_s + 2 * PUSH_RAMP_S
        if s >= total:
            self.phase = "wait"
            return None
        ramp = min(1.0, s / PUSH_RAMP_S, (total - s) / PUSH_RAMP_S)
        self.force = np.asarray(a.force_n, dtype=float) * np.sin(0.5 * np.pi * ramp) ** 2
        self.sup.log.force.append((t, float(np.linalg.norm(self.force))))
        return None

    def _guide(self, t):
        start, goal = self.hand_path
        s = (t - self.t0) / GUIDE_S
        if s >= 1.0 + GUIDE_HOLD_S / GUIDE_S:
            self.phase = "wait"
            return None
        u = min(s, 1.0)
        blend = 10 * u**3 - 15 * u**4 + 6 * u**5
        return {"hand": start + blend * (goal - start)}

    def _replay(self, t) -> None:
        """§5.9.2: the history so far, at constant speed in length space."""
        db, sup = self.sup.db, self.sup
        nodes = list(db.history)
        points = np.array([sup._l_r] + [db.nodes[k].lengths for k in nodes])
        dist = np.linalg.norm(np.diff(points, axis=0), axis=1)
        durations = np.maximum(dist / (REPLAY_SPEED_MM_S * 1e-3), REPLAY_MIN_SEGMENT_S)
        sup.play("replay", nodes, durations, "linear", t)

    def _execute(self, t) -> None:
        """§5.9.1 "動作生成への利用": the model motion's lengths (eq. 4.25) → nearest nodes → played."""
        a, sup = self.actions[self.i], self.sup
        motion = np.radians(np.asarray(a.motion_deg, dtype=float))
        lengths = self.model.lengths(uniform_posture(motion, self.model.n))
        nodes = sup.db.plan(encoder_targets(lengths, sup.zero))
        durations = []
        for _ in nodes:
            durations += [EXEC_MOVE_S, EXEC_DWELL_S]
        sup.play("execute", [k for k in nodes for _ in (0, 1)], durations, "minjerk", t)
        sup.log.plays[-1]["motion"] = motion
