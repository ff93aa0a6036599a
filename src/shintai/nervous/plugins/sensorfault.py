"""``sensorfault`` — tension-sensor and encoder fault detection (§6.1.2: "張力センサ故障検出機能",
"エンコーダ故障検出機能").

A muscle's encoder and its tension sensor watch the same wire, so each checks the other (chosen rule; the
thesis names the functions only):

* **tension sensor** — the encoder moved more than ``move_mm`` within ``window_ms`` while the tension
  reading stayed within ``still_n`` (a wire being wound or paid out under load changes its tension), or
  the reading is pinned at the sensor's top of range;
* **encoder** — the tension changed by more than ``change_n`` within the window while the encoder stayed
  within one count and the motor was driven (|current| > ``driven_a``): the reel turned, the encoder did
  not count.

A fault is reported once per muscle; an encoder fault also switches that motor off (length control is
blind without its encoder), a tension-sensor fault only reports (length control does not read it).
Chosen: a 500 ms window, 2 mm, 0.05 N, 3 N, 0.1 A.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from shintai.nervous.plugins.base import ADD, Plugin
from shintai.nervous.plugins.diagnosis import names, parameters, require

DEFAULTS = {"window_ms": 500.0, "move_mm": 2.0, "still_n": 0.05, "change_n": 3.0, "driven_a": 0.1,
            "count_mm": 0.0175, "top_n": 300.0}
LIMITS = {"window_ms": (1.0, 1e5), "move_mm": (0.0, 100.0), "still_n": (0.0, 100.0), "change_n": (0.0, 300.0),
          "driven_a": (0.0, 100.0), "count_mm": (0.0, 10.0), "top_n": (0.0, 1e4)}


class SensorFault(Plugin):
    kind = ADD
    summary = "finds stuck tension sensors and encoders by checking one against the other (§6.1.2)"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        require(host, "sensorfault", "tension", "current")
        self.p = parameters("sensorfault", args, DEFAULTS, LIMITS)
        n = host.description.n
        self.tension_fault = np.zeros(n, dtype=bool)
        self.encoder_fault = np.zeros(n, dtype=bool)

    def start(self, state):
        self.history: deque = deque()

    def process(self, state):
        t = float(state["t"])
        l = np.asarray(state["angle-vector"], dtype=float)
        T = np.asarray(state["tension"], dtype=float)
        driven = np.abs(np.asarray(state["current"], dtype=float)) > self.p["driven_a"]
        self.history.append((t, l, T, driven))
        window = 1e-3 * self.p["window_ms"]
        while self.history and t - self.history[0][0] > window:
            self.history.popleft()
        if t - self.history[0][0] < 0.9 * window:
            return None
        ls = np.array([h[1] for h in self.history])
        Ts = np.array([h[2] for h in self.history])
        always_driven = np.all([h[3] for h in self.history], axis=0)
        l_span, T_span = np.ptp(ls, axis=0), np.ptp(Ts, axis=0)
        tension_bad = ((l_span > self.p["move_mm"]) & (T_span < self.p["still_n"])) | np.all(Ts >= self.p["top_n"], axis=0)
        encoder_bad = (T_span > self.p["change_n"]) & (l_span < self.p["count_mm"]) & always_driven
        new_t, new_e = tension_bad & ~self.tension_fault, encoder_bad & ~self.encoder_fault
        if new_t.any():
            self.tension_fault |= new_t
            self.host.event(f"{self.instance}: tension sensor fault on {names(self.host, np.flatnonzero(new_t))}")
        if new_e.any():
            self.encoder_fault |= new_e
            idx = np.flatnonzero(new_e)
            self.host.interface.set_servo("off", "", idx.tolist())
            self.host.event(f"{self.instance}: encoder fault on {names(self.host, idx)}: motor stopped")
        return None

    def cmd_status(self, args, call):
        """the muscles with a faulty tension sensor or encoder"""
        return self.describe()

    def describe(self) -> str:
        return (f"tension_faults={names(self.host, np.flatnonzero(self.tension_fault)) or '-'} "
                f"encoder_faults={names(self.host, np.flatnonzero(self.encoder_fault)) or '-'}")
