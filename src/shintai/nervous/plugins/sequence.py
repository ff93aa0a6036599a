"""``sequence`` — the seqplugin of nervous (seed 003 §6.3.4, App. C.2.2) on
:class:`~shintai.core.interpolation.SequencePlayer`.

§6.3.4: "目標姿勢 (アクチュエータ変位の列) と目標に達するまでの時間を引数とし、指定された時間をかけて現在のアク
チュエータ状態から目標状態まで連続的にアクチュエータ変位が変わるように、目標アクチュエータ変位を更新してゆく。補間
方法は、線形補間・躍度最小補間を実装した。補間中に新たな目標値が与えられるとキューに溜まってゆき、順に実行される。
オプションとして、速度を与えられるようにしてあり、途中姿勢における速度の指定も可能になっている。指定が無ければ各途中
姿勢において速度は 0 となる。"

Methods (App. C.2.2 ``propocmd()``):

* ``propocmd #f(v1 … vN) [MS] [:clear] [:with-velocity #f(w1 … wN)]`` — queue a posture to reach in MS
  milliseconds (default 1 ms: "最後の 1 はその姿勢まで 1[ms] で移行することを指示している"); ``:clear`` empties
  the queue first (``initSequence``) and re-plans from the current state; ``:with-velocity`` gives the
  velocity at that posture (units per second: the thesis parses the option but its printed code does not
  use it and shows no format). Every value is checked (count, finite, within the DOF limits, MS > 0) before
  anything is queued.
* ``switch linear|minjerk|minjerksequence`` — the interpolation of segments planned from now on (default
  minjerk: "速度 0 で始まり速度 0 で終わる").
* ``via balanced|turning`` — minjerksequence's velocity at an intermediate posture. C.2.2: "動作中だった場合
  (その姿勢がキューの 2 番目以降になった時), その初期速度を 0 でなく前のキューとバランスするような速度にする" — not
  zero. The rule is not written out (spec 003-part2 §2.3.5); ``balanced`` (default, the thesis's "not zero"
  at every such posture): the time-weighted mean of the slopes into and out of it; ``turning``: the same but
  zero where the slope changes sign (core's :func:`~shintai.core.interpolation.via_velocity`: no overshoot
  at a peak, at the cost of a zero velocity there).
* ``clear`` — empty the queue and hold the current target; ``status``; ``angle-vector`` (the current target).

C.2.2 stores the requesting socket with each queue slot (``Mem(fds)[Mem(seq)->next]=fd``) without saying
why; here a queued posture carries its command's ``@ID`` and the server tells that client ``done ID`` when
the posture is reached.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from shintai.core.interpolation import METHODS, SequencePlayer, via_velocity
from shintai.nervous.plugins.base import SET, CommandError, Plugin
from shintai.nervous.protocol import Keyword, fmt_vector, number

DEFAULT_MS = 1.0  # App. C.2.1: "1[ms] かけて" — the time EusLisp's :angle-vector sends when none is given
MAX_MS = 86_400_000.0  # chosen: a day; a longer segment is a typo
MAX_QUEUE = 100_000  # chosen: ~30 min of 20 ms playback samples (§5.9.2); more is a runaway client


def balanced_velocity(x_prev, x_via, x_next, T_in: float, T_out: float) -> np.ndarray:
    """The velocity at an intermediate posture "balanced" between the slopes into and out of it: their mean
    weighted by the other segment's duration — never zero unless both slopes are (App. C.2.2's "0 でなく")."""
    s_in = (np.asarray(x_via, dtype=float) - x_prev) / T_in
    s_out = (np.asarray(x_next, dtype=float) - x_via) / T_out
    return (s_in * T_out + s_out * T_in) / (T_in + T_out)


VIA_RULES = {"balanced": balanced_velocity, "turning": via_velocity}


class Sequence(Plugin):
    """seqplugin: queue of postures played with linear or minimum-jerk interpolation."""

    kind = SET
    summary = "posture queue with linear / minjerk / minjerksequence interpolation (seqplugin, App. C.2.2)"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        self.method, self.via = "minjerk", "balanced"
        for arg in args:
            key, _, value = str(arg).partition("=")
            if key == "method" and value in METHODS:
                self.method = value
            elif key == "via" and value in VIA_RULES:
                self.via = value
            else:
                raise CommandError(f"sequence: unknown argument {arg!r} (method={'|'.join(METHODS)}, "
                                   f"via={'|'.join(VIA_RULES)})")
        self.player: SequencePlayer | None = None
        self.tracked: deque = deque()  # (queue entry, motion) in queue order

    def start(self, state):
        self.player = SequencePlayer(np.asarray(state["reference"], dtype=float), method=self.method,
                                     via=VIA_RULES[self.via], name=self.instance)
        self.player.reset(state)
        self.tracked.clear()

    def stop(self):
        self._end_all("stopped")
        self.player = None

    def process(self, state):
        self.player.update(state)
        self._finish_reached()
        return self.player.x.copy()

    def _finish_reached(self) -> None:
        p = self.player
        while self.tracked:
            entry, motion = self.tracked[0]
            if p.busy and (p.current is entry or any(e is entry for e in p.queue)):
                break
            self.tracked.popleft()
            motion.finish("done")

    def _end_all(self, how: str) -> None:
        while self.tracked:
            self.tracked.popleft()[1].finish(how)

    def _running(self) -> SequencePlayer:
        if self.player is None:
            raise CommandError(f"{self.instance} is not running (start {self.instance}): App. C.2.2, without a "
                               "running seqplugin :angle-vector cannot be executed")
        return self.player

    # -- methods --------------------------------------------------------------------------------

    def cmd_propocmd(self, args, call):
        """#f(v…) [MS] [:clear] [:with-velocity #f(w…)] — queue a posture reached in MS ms (default 1)"""
        player = self._running()
        if not args:
            raise CommandError("propocmd: expected #f(v1 … vN) [MS] [:clear] [:with-velocity #f(w1 … wN)]")
        target = self.host.check_vector(args[0], "propocmd target")
        rest, ms = list(args[1:]), DEFAULT_MS
        if rest and not _is_option(rest[0]):
            ms = number(rest.pop(0), "propocmd time [ms]", 0.0, MAX_MS)
            if ms <= 0:
                raise CommandError("propocmd time [ms]: must be > 0 (the thesis's default is 1 ms)")
        clear, velocity = False, None
        while rest:
            option = str(rest.pop(0)).lower()
            if option == ":clear":
                clear = True
            elif option == ":with-velocity":
                if not rest:
                    raise CommandError(":with-velocity: expected #f(w1 … wN) [units/s]")
                velocity = self.host.check_vector(rest.pop(0), ":with-velocity", limits=False)
            else:
                raise CommandError(f"propocmd: unknown option {option[:40]!r} (:clear, :with-velocity)")
        if not clear and len(player.queue) >= MAX_QUEUE:
            raise CommandError(f"propocmd: the queue is full ({MAX_QUEUE} postures)")
        return self.push(target, ms, call, clear=clear, velocity=velocity)

    def push(self, target, ms: float, call, clear: bool = False, velocity=None) -> None:
        """Queue a checked posture (also the s-expression ``:angle-vector``)."""
        player = self._running()
        player.update(self.host.state())  # the motion starts at the latest packet, not at the last routine's
        self._finish_reached()
        motion = call.motion()
        if clear:
            self._end_all("cleared")
        player.push(target, ms / 1000.0, velocity=velocity, clear=clear)  # [ms] → [s], as propocmd
        entry = player.queue[-1] if player.queue else player.current
        self.tracked.append((entry, motion))
        return None

    def cmd_switch(self, args, call):
        """linear|minjerk|minjerksequence — the interpolation from now on"""
        if len(args) != 1 or str(args[0]) not in METHODS:
            raise CommandError(f"switch: expected one of {', '.join(METHODS)}")
        self.method = str(args[0])
        if self.player is not None:
            self.player.switch(self.method)
        return self.method

    def cmd_via(self, args, call):
        """balanced|turning — minjerksequence's velocity at intermediate postures"""
        if len(args) != 1 or str(args[0]) not in VIA_RULES:
            raise CommandError(f"via: expected one of {', '.join(VIA_RULES)}")
        self.via = str(args[0])
        if self.player is not None:
            self.player.via = VIA_RULES[self.via]
        return self.via

    def cmd_clear(self, args, call):
        """empty the queue; the target holds where it is"""
        player = self._running()
        self._end_all("cleared")
        player.clear()
        return None

    def cmd_status(self, args, call):
        """busy, queued postures, method"""
        return self.describe()

    def cmd_angle_vector(self, args, call):
        """the current target"""
        return fmt_vector(self._running().x)

    def describe(self) -> str:
        p = self.player
        queued = (len(p.queue) + int(p.busy)) if p is not None else 0
        return f"busy={int(p is not None and p.busy)} queued={queued} method={self.method} via={self.via}"


def _is_option(token) -> bool:
    return isinstance(token, Keyword) or (isinstance(token, str) and token.startswith(":"))

