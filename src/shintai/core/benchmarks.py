"""Benchmark of the runtime: what the Loop costs per module tick over calling the modules by hand."""

from __future__ import annotations

import time

import numpy as np

from shintai.core.runtime import Body, Loop, Module, add_into, declare
from shintai.scenarios.registry import benchmark


class NullBody(Body):
    """A body that costs (almost) nothing, so the timing is the runtime's own."""

    channels = declare("u")

    def __init__(self, dt=0.001):
        self.dt, self.t = dt, 0.0
        self.snap = {"t": 0.0, "x": np.zeros(8)}

    def snapshot(self):
        self.snap["t"] = self.t
        return self.snap

    def apply(self, command):
        self.command = command

    def step(self):
        self.t += self.dt


class Gain(Module):
    """A proportional correction of the kind every body runs: u = −k x."""

    def update(self, snapshot):
        return {"u": -0.5 * snapshot["x"]}


def direct(body: NullBody, modules: list[Module], steps: int) -> float:
    """The naive form: the same calls written out by hand, no timing, no multi-rate bookkeeping."""
    t0 = time.perf_counter()
    for _ in range(steps):
        snap = body.snapshot()
        command: dict = {}
        for m in modules:
            add_into(command, m.update(snap))
        body.apply(command)
        body.step()
    return time.perf_counter() - t0


def looped(body: NullBody, modules: list[Module], steps: int) -> float:
    loop = Loop(body, modules)
    loop.start()
    t0 = time.perf_counter()
    for _ in range(steps):
        loop.step()
    return time.perf_counter() - t0


@benchmark("core.loop-overhead", "Loop cost per module tick vs calling the module functions directly")
def loop_overhead(steps: int = 20000, n_modules: int = 4) -> dict:
    modules = [Gain(f"m{i}") for i in range(n_modules)]
    direct(NullBody(), modules, 1000)  # warm-up
    t_direct = min(direct(NullBody(), modules, steps) for _ in range(3))
    t_loop = min(looped(NullBody(), modules, steps) for _ in range(3))
    ticks = steps * n_modules
    return {
        "direct_us_per_module_tick": 1e6 * t_direct / ticks,
        "loop_us_per_module_tick": 1e6 * t_loop / ticks,
        "overhead_us_per_module_tick": 1e6 * (t_loop - t_direct) / ticks,
        "ratio_loop_vs_direct": t_loop / t_direct,
        "modules": n_modules,
        "steps": steps,
    }
