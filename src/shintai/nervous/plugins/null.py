"""``null`` — the test plugin (App. C.3.6 ``nullplugin.c``, "テスト用プラグイン"): it adds nothing and counts
the packets it saw; ``raise`` makes its next routine raise (to show a failing plugin is stopped and reported
while the loop goes on), ``cost US`` makes each routine spin that long (the benchmark's plugin load)."""

from __future__ import annotations

import time

from shintai.nervous.plugins.base import ADD, Plugin
from shintai.nervous.protocol import number


class PluginFault(RuntimeError):
    """What ``null raise`` makes the routine raise."""


class Null(Plugin):
    kind = ADD
    summary = "does nothing but count packets (nullplugin, App. C.3.6); raise / cost for tests"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        self.packets, self.fail, self.cost_s = 0, False, 0.0
        if args:
            self.cost_s = 1e-6 * number(args[0], "null: creation argument COST_US", 0.0, 1e6)

    def start(self, state):
        self.packets = 0

    def process(self, state):
        self.packets += 1
        if self.fail:
            self.fail = False  # one-shot: a restarted null runs again
            raise PluginFault(f"{self.instance}: raised on request at packet {state['seq']}")
        if self.cost_s:
            end = time.perf_counter() + self.cost_s
            while time.perf_counter() < end:
                pass
        return None

    def cmd_raise(self, args, call):
        """make the next routine raise"""
        self.fail = True

    def cmd_cost(self, args, call):
        """US — spin this many microseconds per packet"""
        self.cost_s = 1e-6 * number(args[0] if args else None, "cost [us]", 0.0, 1e6)

    def cmd_count(self, args, call):
        """packets seen since start"""
        return str(self.packets)

    def describe(self) -> str:
        return f"packets={self.packets}"
