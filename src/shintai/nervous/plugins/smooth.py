"""``smooth`` — "急激な指令値の変化を滑らかにするプラグイン" (App. C.3.6 ``smoothplugin.c``): the target a plugin
set this packet reaches the body rate-limited.

The thesis names the plugin and its purpose only. Chosen: a per-DOF rate limit (``rate`` in units per
second, default 90 deg/s or mm/s) on the target seen this packet; its contribution is the difference
between the limited and the raw target (§6.2.4: a difference added to the current value), so with nothing
abrupt it adds zero. ``rate 0`` turns it off (passes through).
"""

from __future__ import annotations

import numpy as np

from shintai.nervous.plugins.base import ADD, Plugin
from shintai.nervous.protocol import number

DEFAULT_RATE = 90.0  # chosen: units/s (90 deg/s: a quarter turn per second)


class Smooth(Plugin):
    kind = ADD
    summary = "rate-limits abrupt target changes (smoothplugin, App. C.3.6)"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        self.rate = number(args[0], "smooth: creation argument RATE [units/s]", 0.0, 1e9) if args else DEFAULT_RATE
        self.y: np.ndarray | None = None

    def start(self, state):
        self.y = np.asarray(state["reference"], dtype=float).copy()
        self.last_t = float(state["t"])

    def process(self, state):
        target = state.get("target")
        if target is None:
            return None
        target = np.asarray(target, dtype=float)
        dt = max(float(state["t"]) - self.last_t, 0.0)
        self.last_t = float(state["t"])
        if self.rate <= 0:
            self.y = target.copy()
            return None
        step = self.rate * dt
        self.y = self.y + np.clip(target - self.y, -step, step)
        return self.y - target

    def cmd_rate(self, args, call):
        """RATE — units per second (0: off)"""
        self.rate = number(args[0] if args else None, "rate [units/s]", 0.0, 1e9)

    def describe(self) -> str:
        return f"rate={self.rate:g}/s"
