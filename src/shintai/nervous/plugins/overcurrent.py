"""``overcurrent`` — over-current detection and motor stop (§6.1.2: "過電流検出・モータ停止機能").

A motor drawing more than ``limit_a`` for ``detect_ms`` (a blocked reel, a muscle pulling against an
obstacle) is stopped: its servo is switched off through the interface (``servo off`` for that DOF) and
the stop is reported; ``overcurrent reset DOF…`` switches it on again. Chosen: 0.8 A, about 70 % of Cla's
RE13 stall current (14.2 mN m / 12.9 mN m/A ≈ 1.1 A at 24 V, Table 3.2), for 200 ms — a motion's
acceleration peaks are shorter. It adds nothing to the target.
"""

from __future__ import annotations

import numpy as np

from shintai.nervous.plugins.base import ADD, CommandError, Plugin
from shintai.nervous.plugins.diagnosis import names, parameters, require

DEFAULTS = {"limit_a": 0.8, "detect_ms": 200.0}
LIMITS = {"limit_a": (0.0, 100.0), "detect_ms": (1.0, 1e5)}


class OverCurrent(Plugin):
    kind = ADD
    summary = "stops a motor that draws too much current for too long (§6.1.2)"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        require(host, "overcurrent", "current")
        self.p = parameters("overcurrent", args, DEFAULTS, LIMITS)
        n = host.description.n
        self.since = np.full(n, np.nan)
        self.stopped = np.zeros(n, dtype=bool)

    def process(self, state):
        t = float(state["t"])
        over = np.abs(np.asarray(state["current"], dtype=float)) > self.p["limit_a"]
        self.since = np.where(over, np.where(np.isnan(self.since), t, self.since), np.nan)
        trip = over & ~self.stopped & (t - np.nan_to_num(self.since, nan=t) >= 1e-3 * self.p["detect_ms"])
        if trip.any():
            idx = np.flatnonzero(trip)
            self.host.interface.set_servo("off", "", idx.tolist())
            self.stopped |= trip
            self.host.event(f"{self.instance}: over-current > {self.p['limit_a']:g} A on {names(self.host, idx)}: "
                            "motor stopped")
        return None

    def cmd_reset(self, args, call):
        """DOF… — switch stopped motors on again (all if none named)"""
        idx = self.host.dof_indices(args) if args else np.flatnonzero(self.stopped).tolist()
        if not idx:
            raise CommandError("reset: no motor is stopped")
        self.host.interface.set_servo("on", "", list(idx))
        self.stopped[idx] = False
        self.since[idx] = np.nan
        return names(self.host, idx)

    def cmd_status(self, args, call):
        """the stopped motors"""
        return self.describe()

    def describe(self) -> str:
        return f"stopped={names(self.host, np.flatnonzero(self.stopped)) or '-'} limit_a={self.p['limit_a']:g}"
