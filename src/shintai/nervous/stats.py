"""Timing of nervous's loop: the period between packets, each tick's cost against the packet period (an
overrun: a tick that took longer than a period), and each plugin's cost per packet (last / mean / max µs).

The thesis gives no timing instrument for nervous; §6.4.2 says only that a plugin's "実行周期を見積もること
が可能" (its execution period can be estimated). ros2_control's controller manager keeps the same
numbers per update (period and execution-time statistics); ``stats`` prints them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass
class Timing:
    """last / mean / max of a duration, in seconds."""

    n: int = 0
    last: float = 0.0
    total: float = 0.0
    max: float = 0.0

    def add(self, seconds: float) -> None:
        self.n += 1
        self.last = seconds
        self.total += seconds
        self.max = max(self.max, seconds)

    @property
    def mean(self) -> float:
        return self.total / self.n if self.n else 0.0

    def us(self) -> str:
        """``last/mean/max`` in µs."""
        return f"{1e6 * self.last:.1f}/{1e6 * self.mean:.1f}/{1e6 * self.max:.1f}"


@dataclass
class LoopStats:
    """Per tick: the wall time between tick starts (``period``) and the tick's own cost (``cost``);
    ``overruns`` counts ticks whose cost exceeded the packet period; ``late`` counts real-time ticks that
    started more than one period after their packet was due."""

    packet_period: float
    period: Timing = None
    cost: Timing = None
    overruns: int = 0
    late: int = 0
    ticks: int = 0
    _last_start: float = math.nan

    def __post_init__(self):
        self.period = Timing() if self.period is None else self.period
        self.cost = Timing() if self.cost is None else self.cost

    def tick(self, start: float, end: float, lateness: float = 0.0) -> None:
        if math.isfinite(self._last_start):
            self.period.add(start - self._last_start)
        self._last_start = start
        self.cost.add(end - start)
        self.ticks += 1
        if end - start > self.packet_period:
            self.overruns += 1
        if lateness > self.packet_period:
            self.late += 1
