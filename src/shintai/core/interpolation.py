"""Interpolation: linear and minimum-jerk segments, re-planned from the current state, and the
sequence player of seed 003 "nervous" seqplugin (§6.3.4, Appendix C.2.2; spec
003-part2-ch5-7-appendix.md §2.3.5–2.3.6).

seqplugin semantics kept here: a target posture (one value per DOF) and a time to reach it; the
command changes continuously from the current state and arrives in that time. A target given
during a motion is *queued*; ``clear`` flushes the queue and re-plans from the current state
(``:clear``); an optional via velocity may be given per entry (``:with-velocity``); methods
``linear``, ``minjerk`` (default, zero velocity at every posture) and ``minjerksequence`` (a
non-zero velocity at intermediate postures "balanced with the previous queue entry").

The thesis prints no formula (spec §2.3.6); we use the standard quintic of Hoff–Arbib
(minimum jerk with boundary position, velocity and acceleration), as hrpsys-base's HOFFARBIB
interpolator does, re-planned from the current (x, v, a) whenever the target changes — so
re-targeting keeps position, velocity and acceleration continuous.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import Module, Snapshot

METHODS = ("linear", "minjerk", "minjerksequence")


def minimum_jerk(s: float) -> float:
    """The rest-to-rest minimum-jerk profile 10 s³ − 15 s⁴ + 6 s⁵ on s ∈ [0, 1] (the quintic of
    :func:`quintic_coefficients` with zero boundary velocity and acceleration, normalised): the fraction of a
    move done at normalised time ``s``."""
    return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)


def quintic_coefficients(x0, v0, a0, xf, vf, af, T: float) -> np.ndarray:
    """Coefficients c[0..5] (each a vector over DOF) of x(t) = Σ c_k t^k meeting x, v, a at 0 and T.

    c3, c4, c5 as in spec 003-part2 §2.3.6 (the minimum-jerk solution with boundary conditions).
    """
    if T <= 0:
        raise ValueError(f"segment duration must be positive, got {T}")
    x0, v0, a0, xf, vf, af = (np.asarray(v, dtype=float) for v in (x0, v0, a0, xf, vf, af))
    d = xf - x0
    c3 = (20 * d - (8 * vf + 12 * v0) * T - (3 * a0 - af) * T**2) / (2 * T**3)
    c4 = (-30 * d + (14 * vf + 16 * v0) * T + (3 * a0 - 2 * af) * T**2) / (2 * T**4)
    c5 = (12 * d - 6 * (vf + v0) * T - (a0 - af) * T**2) / (2 * T**5)
    return np.array([x0, v0, a0 / 2, c3, c4, c5])


@dataclass
class Segment:
    """One interpolation segment over [0, T]: a quintic (min jerk) or a straight line."""

    coeffs: np.ndarray  # (6, dof) for a quintic; (2, dof) for a line
    T: float

    @classmethod
    def minjerk(cls, x0, v0, a0, xf, vf, af, T) -> Segment:
        return cls(quintic_coefficients(x0, v0, a0, xf, vf, af, T), T)

    @classmethod
    def linear(cls, x0, xf, T) -> Segment:
        if T <= 0:
            raise ValueError(f"segment duration must be positive, got {T}")
        x0, xf = np.asarray(x0, dtype=float), np.asarray(xf, dtype=float)
        return cls(np.array([x0, (xf - x0) / T]), T)

    def state(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity, acceleration at time t (clamped to [0, T])."""
        return (self.position(t), *self.rates(t))

    def position(self, t: float) -> np.ndarray:
        """x(t) = Σ c_k t^k (t clamped to [0, T])."""
        t = min(max(t, 0.0), self.T)
        c = self.coeffs
        if c.ndim == 2:  # (terms, dof): the same products as below, without tensordot's bookkeeping
            k = _powers(len(c))[0]
            n, dof = c.shape
            return np.dot((t ** k).reshape(1, n), c).reshape(dof)
        return np.tensordot(t ** np.arange(len(c)), c, axes=1)

    def rates(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """(ẋ(t), ẍ(t)) = (Σ k c_k t^(k−1), Σ k (k−1) c_k t^(k−2)) (t clamped to [0, T])."""
        t = min(max(t, 0.0), self.T)
        c = self.coeffs
        if c.ndim == 2:
            _, k1, k1m1, k2k2m1, k2m2 = _powers(len(c))
            n, dof = c.shape
            v = np.dot((k1 * t ** k1m1).reshape(1, n - 1), c[1:]).reshape(dof)
            a = (np.dot((k2k2m1 * t ** k2m2).reshape(1, n - 2), c[2:]).reshape(dof)
                 if n > 2 else np.zeros(dof))
            return v, a
        k = np.arange(len(c))
        v = np.tensordot(k[1:] * t ** (k[1:] - 1), c[1:], axes=1)
        a = (np.tensordot(k[2:] * (k[2:] - 1) * t ** (k[2:] - 2), c[2:], axes=1)
             if len(c) > 2 else np.zeros_like(v))
        return v, a


_POWERS: dict[int, tuple] = {}


def _powers(n: int) -> tuple:
    """The integer exponent / factor arrays of :meth:`Segment.state` for ``n`` terms (cached)."""
    hit = _POWERS.get(n)
    if hit is None:
        k = np.arange(n)
        hit = _POWERS[n] = (k, k[1:], k[1:] - 1, k[2:] * (k[2:] - 1), k[2:] - 2)
    return hit


def hoff_arbib_jerk(x, v, a, xf, D: float) -> np.ndarray:
    """Hoff–Arbib online minimum-jerk law toward a resting goal with D seconds left:
    jerk = −9a/D − 36v/D² + 60(x_f − x)/D³ (spec 003-part2 §2.3.6; hrpsys HOFFARBIB)."""
    return -9 * a / D - 36 * v / D**2 + 60 * (np.asarray(xf) - x) / D**3


def via_velocity(x_prev, x_via, x_next, T_in: float, T_out: float) -> np.ndarray:
    """``minjerksequence`` velocity at an intermediate posture (thesis: "balanced with the previous
    queue entry", rule not given — spec §2.3.5 [?]). Our choice, per DOF: zero where the incoming
    and outgoing slopes differ in sign (a turning point, as with ``minjerk``), else the time-weighted
    mean of the two slopes (Catmull–Rom-like), which is continuous and never overshoots a monotone run."""
    s_in = (np.asarray(x_via, dtype=float) - x_prev) / T_in
    s_out = (np.asarray(x_next, dtype=float) - x_via) / T_out
    mean = (s_in * T_out + s_out * T_in) / (T_in + T_out)
    return np.where(s_in * s_out > 0, mean, 0.0)


@dataclass
class QueueEntry:
    target: np.ndarray
    duration: float
    velocity: np.ndarray | None = None  # via velocity at the target (":with-velocity")


class SequencePlayer(Module):
    """The seqplugin posture-sequence player as a runtime module.

    ``push(target, duration, velocity=None, clear=False)`` queues a posture; ``advance(dt)`` moves
    time; ``state`` is the current (x, v, a). As a :class:`Module` it advances by its own period
    each update and contributes the current posture to ``channel`` (nervous: the target angle
    vector, onto which other plugins add their differences).
    """

    def __init__(self, x0, method: str = "minjerk", channel: str = "target", name: str = "sequence",
                 period: float | None = None, via: Callable = via_velocity):
        super().__init__(name, period)
        self.via = via  # minjerksequence's velocity rule at an intermediate posture (see via_velocity)
        self.x = np.atleast_1d(np.asarray(x0, dtype=float)).copy()
        self._due = None  # (segment, time) whose velocity and acceleration are not formed yet
        self._rest = np.zeros_like(self.x)  # v and a while the posture is held: read-only, shared (never mutated)
        self._rest.setflags(write=False)
        self.v = np.zeros_like(self.x)
        self.a = np.zeros_like(self.x)
        self.queue: deque[QueueEntry] = deque()
        self.segment: Segment | None = None
        self.current: QueueEntry | None = None  # the entry the running segment goes to
        self.start_x = self.x.copy()  # where that segment started
        self.elapsed = 0.0
        self.channel = channel
        self.switch(method)

    # -- commands (seqplugin: propocmd, :clear, :with-velocity, switch) --

    def switch(self, method: str) -> None:
        """Change the interpolation method for segments planned from now on."""
        if method not in METHODS:
            raise ValueError(f"unknown interpolation method {method!r} (allowed: {', '.join(METHODS)})")
        self.method = method

    def push(self, target, duration: float, velocity=None, clear: bool = False) -> None:
        """Queue a posture to reach in ``duration`` seconds; ``clear`` flushes the queue and the
        current segment and re-plans from the current state (``:clear``)."""
        target = np.atleast_1d(np.asarray(target, dtype=float))
        if target.shape != self.x.shape:
            raise ValueError(f"target has {target.size} values, the player has {self.x.size} DOF")
        if not np.all(np.isfinite(target)) or not duration > 0:
            raise ValueError("target must be finite and duration positive")
        vel = None if velocity is None else np.atleast_1d(np.asarray(velocity, dtype=float))
        if clear:
            self.clear()
        self.queue.append(QueueEntry(target, float(duration), vel))
        if self.segment is None:
            self._start_next()
        elif self.method == "minjerksequence" and len(self.queue) == 1 and self.current.velocity is None:
            self._replan_current()

    def clear(self) -> None:
        """Empty the queue and stop interpolating; the current state is kept (and re-planned from)."""
        self.queue.clear()
        self.segment = None
        self.elapsed = 0.0

    @property
    def busy(self) -> bool:
        return self.segment is not None

    @property
    def state(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return self.x.copy(), self.v.copy(), self.a.copy()

    # v and a are formed when read (a re-plan, ``state``), from the segment time ``advance`` reached: most
    # ticks only need x (the tricycle's limbs advance two players every 4 ms tick)

    @property
    def v(self) -> np.ndarray:
        self._form_rates()
        return self._v

    @v.setter
    def v(self, value: np.ndarray) -> None:
        self._form_rates()
        self._v = value

    @property
    def a(self) -> np.ndarray:
        self._form_rates()
        return self._a

    @a.setter
    def a(self, value: np.ndarray) -> None:
        self._form_rates()
        self._a = value

    def _form_rates(self) -> None:
        if self._due is not None:
            segment, t = self._due
            self._due = None
            self._v, self._a = segment.rates(t)

    # -- time --

    def _end_velocity(self, entry: QueueEntry) -> np.ndarray:
        if entry.velocity is not None:
            return entry.velocity
        if self.method == "minjerksequence" and self.queue:
            nxt = self.queue[0]
            return self.via(self.start_x, entry.target, nxt.target, entry.duration, nxt.duration)
        return np.zeros_like(self.x)

    def _start_next(self) -> None:
        entry = self.queue.popleft()
        self.current, self.start_x, self.elapsed = entry, self.x.copy(), 0.0
        if self.method == "linear":
            self.segment = Segment.linear(self.x, entry.target, entry.duration)
        else:
            vf = self._end_velocity(entry)
            self.segment = Segment.minjerk(self.x, self.v, self.a, entry.target, vf, np.zeros_like(self.x),
                                           entry.duration)

    def _replan_current(self) -> None:
        """``minjerksequence``: a successor was queued behind the running segment, so its end
        posture becomes an intermediate one; re-plan the rest from the current (x, v, a) to arrive on
        time with the via velocity (continuous in x, v, a)."""
        entry, nxt = self.current, self.queue[0]
        left = self.segment.T - self.elapsed
        if left <= 0:
            return
        vf = self.via(self.start_x, entry.target, nxt.target, entry.duration, nxt.duration)
        self.segment = Segment.minjerk(self.x, self.v, self.a, entry.target, vf, np.zeros_like(self.x), left)
        self.elapsed = 0.0

    def advance(self, dt: float) -> np.ndarray:
        """Move time forward by ``dt``; returns the current position."""
        remaining = dt
        while self.segment is not None:
            left = self.segment.T - self.elapsed
            if remaining < left:
                self.elapsed += remaining
                self.x = self.segment.position(self.elapsed)
                self._due = (self.segment, self.elapsed)
                return self.x.copy()
            remaining -= left
            self.x, self.v, self.a = self.segment.state(self.segment.T)
            if self.method == "linear":
                self.v = np.zeros_like(self.x)
            self.segment = None
            if self.queue:
                self._start_next()
        self._hold()
        return self.x.copy()

    def _hold(self) -> None:
        """Idle: the posture is held, at rest (v = a = 0, the shared read-only zeros: an idle tick allocates none)."""
        self._due = None
        self._v = self._a = self._rest

    # -- as a module --

    def reset(self, snapshot: Snapshot) -> None:
        self._last_t = float(snapshot["t"])

    def update(self, snapshot: Snapshot):
        t = float(snapshot["t"])
        self.advance(t - self._last_t)
        self._last_t = t
        return {self.channel: self.x.copy()}
