"""``slack`` — muscle slack detection and take-up (§6.1.2: "筋のたるみ検出・修復機能").

A muscle whose tension sensor reads below ``slack_n`` for ``detect_ms`` while its length is controlled has
a slack wire: the wire stretched, or the spine settled under a load and left it loose (a loose muscle
controls nothing). Take-up: its encoder target is shortened at ``rate_mm_s`` (the difference is added to
the target, §6.2.4) until the tension reaches ``taut_n``; the take-up is kept (the repair) and capped at
``max_mm`` per muscle so that a broken wire is not wound in for ever. Chosen thresholds (the thesis gives
none): slack below 0.05 kgf, taut at 0.3 kgf (the encoder zeroing's "just taut", §4.6.4), 200 ms to
decide, 5 mm/s, at most 15 mm.
"""

from __future__ import annotations

import numpy as np

from shintai.nervous.plugins.base import ADD, Plugin
from shintai.nervous.plugins.diagnosis import names, parameters, require
from shintai.nervous.protocol import fmt_vector

KGF = 9.80665
DEFAULTS = {"slack_n": 0.05 * KGF, "taut_n": 0.3 * KGF, "detect_ms": 200.0, "rate_mm_s": 5.0, "max_mm": 15.0}
LIMITS = {"slack_n": (0.0, 100.0), "taut_n": (0.0, 300.0), "detect_ms": (1.0, 1e5), "rate_mm_s": (0.0, 100.0),
          "max_mm": (0.0, 200.0)}


class Slack(Plugin):
    kind = ADD
    summary = "detects slack muscles by their tension and takes the slack up (§6.1.2)"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        require(host, "slack", "tension")
        self.p = parameters("slack", args, DEFAULTS, LIMITS)
        n = host.description.n
        self.take_up = np.zeros(n)
        self.slack_since = np.full(n, np.nan)
        self.active = np.zeros(n, dtype=bool)
        self.repairs = 0

    def start(self, state):
        self.last_t = float(state["t"])

    def process(self, state):
        t = float(state["t"])
        dt, self.last_t = t - self.last_t, t
        tension = np.asarray(state["tension"], dtype=float)
        slack = tension < self.p["slack_n"]
        self.slack_since = np.where(slack, np.where(np.isnan(self.slack_since), t, self.slack_since), np.nan)
        start = slack & ~self.active & (t - np.nan_to_num(self.slack_since, nan=t) >= 1e-3 * self.p["detect_ms"])
        start &= self.take_up < self.p["max_mm"]
        if start.any():
            self.active |= start
            self.host.event(f"{self.instance}: slack {names(self.host, np.flatnonzero(start))}: taking up")
        done = self.active & ((tension >= self.p["taut_n"]) | (self.take_up >= self.p["max_mm"]))
        if done.any():
            self.active &= ~done
            self.repairs += int(done.sum())
            self.host.event(f"{self.instance}: {names(self.host, np.flatnonzero(done))} taken up by "
                            f"{fmt_vector(self.take_up[done])} mm")
        self.take_up = np.minimum(self.take_up + np.where(self.active, self.p["rate_mm_s"] * dt, 0.0), self.p["max_mm"])
        return self.take_up.copy()

    def cmd_status(self, args, call):
        """taking up now, repairs done, take-up per muscle [mm]"""
        return self.describe()

    def cmd_reset(self, args, call):
        """forget the take-up"""
        self.take_up[:] = 0.0
        self.active[:] = False

    def describe(self) -> str:
        return (f"active={names(self.host, np.flatnonzero(self.active)) or '-'} repairs={self.repairs} "
                f"take_up_mm={fmt_vector(self.take_up)}")
