"""The one runtime every body runs in: Body, Module, Loop and Switcher.

Two theses describe this architecture from two sides:

* seed 000 §7.2 — online search indices processed *in parallel* (they coexist in one loop, each
  updating its own ρ from a shared sensor snapshot) or by *switching* (independent systems of which
  exactly one runs at a time, moving on sensor guards, §7.4);
* seed 003 §6.3.4 — the middle layer "nervous": autonomous plugins whose processing routine runs
  once per sensor packet and modifies the command sent to the body.

Here a :class:`Module` reads the snapshot and returns its *contribution* to the command (a dict of
named arrays). The :class:`Loop` sums the contributions of all modules (parallel processing) and
holds each module's last contribution between its updates (multi-rate, zero-order hold). A
:class:`Switcher` is itself a module that runs exactly one of its children (switching processing).
"""

from __future__ import annotations

import math
import time
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from shintai.core.recorder import Recorder

Snapshot = dict  # name -> np.ndarray (or float); always holds "t", the body time in seconds
Command = dict  # channel name -> np.ndarray


class SimulationDiverged(RuntimeError):
    """The simulated state became non-finite or the physics engine reported an instability."""


class Body(ABC):
    """A simulated robot: a sensor snapshot out, a command in, time advances by ``dt``."""

    dt: float
    t: float = 0.0

    @abstractmethod
    def snapshot(self) -> Snapshot:
        """Current sensor values (must include ``"t"``)."""

    @abstractmethod
    def apply(self, command: Command) -> None:
        """Take the summed command of this tick (channels the body does not know are an error)."""

    @abstractmethod
    def step(self) -> None:
        """Advance time by ``dt``; raise :class:`SimulationDiverged` on a non-finite state."""


class Module:
    """A unit of control or learning that runs at its own period.

    Subclasses override :meth:`update`. ``period`` is in seconds and must be a whole multiple of
    the body step; ``None`` means every body step. A module may hold state (filters, integrators,
    learned gains); :meth:`reset` is called once before the first update, and again when a
    :class:`Switcher` activates it.
    """

    period: float | None = None

    def __init__(self, name: str | None = None, period: float | None = None):
        self.name = name or type(self).__name__
        if period is not None:
            self.period = period
        self.recorder: Recorder | None = None

    def reset(self, snapshot: Snapshot) -> None:
        """Prepare for the first update (default: nothing)."""

    def update(self, snapshot: Snapshot) -> Command | None:
        """Return this module's contribution to the command (or None for no contribution)."""
        return None

    def log(self, t: float, **signals) -> None:
        """Record signals into the loop's recorder, if there is one."""
        if self.recorder is not None:
            self.recorder.record(t, **signals)

    def attach(self, recorder: Recorder | None) -> None:
        self.recorder = recorder


class FunctionModule(Module):
    """A module made from a plain function ``f(snapshot) -> contribution``."""

    def __init__(self, fn: Callable[[Snapshot], Command | None], name: str | None = None,
                 period: float | None = None):
        super().__init__(name or getattr(fn, "__name__", "function"), period)
        self.fn = fn

    def update(self, snapshot: Snapshot) -> Command | None:
        return self.fn(snapshot)


def ticks_per_period(period: float | None, dt: float, name: str) -> int:
    """Number of body steps per module period; the period must be a whole multiple of ``dt``."""
    if period is None:
        return 1
    ratio = period / dt
    n = int(round(ratio))
    if n < 1 or not math.isclose(ratio, n, rel_tol=1e-9, abs_tol=1e-9):
        raise ValueError(f"module {name!r}: period {period} s is not a whole multiple of the body step {dt} s")
    return n


def add_into(total: Command, part: Mapping | None) -> None:
    """Add a contribution into the running command total (parallel processing: contributions add)."""
    if not part:
        return
    for channel, value in part.items():
        value = np.asarray(value, dtype=float)
        if channel in total:
            total[channel] = total[channel] + value
        else:
            total[channel] = value.copy()


@dataclass
class ModuleTiming:
    calls: int = 0
    total_s: float = 0.0

    @property
    def mean_us(self) -> float:
        return 1e6 * self.total_s / self.calls if self.calls else 0.0


class Switcher(Module):
    """Switching processing (seed 000 §7.4, Table 7.5): exactly one child module runs at a time.

    ``transitions`` is a list of ``(from_name, to_name, guard)`` where ``guard(snapshot) -> bool``.
    At each update the guards leaving the active child are tested in order; the first that holds
    moves control to its target, whose :meth:`Module.reset` is called (the inactive child's state,
    e.g. its ρ, is held, not run). Each transition is kept in ``self.transitions_log`` as
    ``(t, from, to)``. Children run at the Switcher's own rate.
    """

    def __init__(self, modules: Sequence[Module], transitions: Sequence[tuple[str, str, Callable]],
                 initial: str | None = None, name: str = "switcher", period: float | None = None):
        super().__init__(name, period)
        self.modules = {m.name: m for m in modules}
        if len(self.modules) != len(modules):
            raise ValueError(f"switcher {name!r}: module names must be unique")
        for src, dst, _ in transitions:
            for n in (src, dst):
                if n not in self.modules:
                    raise ValueError(f"switcher {name!r}: transition names unknown module {n!r}")
        self.transitions = list(transitions)
        self.active = initial if initial is not None else modules[0].name
        if self.active not in self.modules:
            raise ValueError(f"switcher {name!r}: unknown initial module {self.active!r}")
        self.transitions_log: list[tuple[float, str, str]] = []

    def attach(self, recorder: Recorder | None) -> None:
        super().attach(recorder)
        for m in self.modules.values():
            m.attach(recorder)

    def reset(self, snapshot: Snapshot) -> None:
        self.modules[self.active].reset(snapshot)

    def switch_to(self, name: str, snapshot: Snapshot) -> None:
        self.transitions_log.append((float(snapshot["t"]), self.active, name))
        self.log(snapshot["t"], **{f"{self.name}.switch": len(self.transitions_log)})
        self.active = name
        self.modules[name].reset(snapshot)

    def update(self, snapshot: Snapshot) -> Command | None:
        for src, dst, guard in self.transitions:
            if src == self.active and guard(snapshot):
                self.switch_to(dst, snapshot)
                break
        return self.modules[self.active].update(snapshot)


class Loop:
    """Parallel processing (seed 000 §7.3, seed 003 §6.3.4): multi-rate modules, contributions add.

    Each body step: take the snapshot; run every module that is due (tick index a multiple of its
    ticks-per-period); sum the latest contribution of *every* module (a slow module's contribution
    is held between its updates); apply the sum; step the body. ``base`` is a command added to the
    sum each tick (e.g. a posture the modules correct). Per-module wall time is kept in ``timing``.
    """

    def __init__(self, body: Body, modules: Sequence[Module], recorder: Recorder | None = None,
                 base: Command | None = None):
        self.body = body
        self.modules = list(modules)
        names = [m.name for m in self.modules]
        if len(set(names)) != len(names):
            raise ValueError(f"loop: module names must be unique, got {names}")
        self.recorder = recorder
        self.base = {k: np.asarray(v, dtype=float) for k, v in (base or {}).items()}
        self.every = [ticks_per_period(m.period, body.dt, m.name) for m in self.modules]
        self.held: list[Command | None] = [None] * len(self.modules)
        self.timing = {m.name: ModuleTiming() for m in self.modules}
        self.tick = 0
        self.command: Command = {}
        self._started = False
        for m in self.modules:
            m.attach(recorder)

    def start(self) -> None:
        snap = self.body.snapshot()
        for m in self.modules:
            m.reset(snap)
        self._started = True

    def step(self) -> Snapshot:
        """Run one body step; returns the snapshot the modules saw."""
        if not self._started:
            self.start()
        snap = self.body.snapshot()
        for i, m in enumerate(self.modules):
            if self.tick % self.every[i] == 0:
                t0 = time.perf_counter()
                self.held[i] = m.update(snap)
                rec = self.timing[m.name]
                rec.total_s += time.perf_counter() - t0
                rec.calls += 1
        command = {k: v.copy() for k, v in self.base.items()}
        for part in self.held:
            add_into(command, part)
        self.command = command
        self.body.apply(command)
        self.body.step()
        self.tick += 1
        return snap

    def run(self, duration: float, until: Callable[[Snapshot], bool] | None = None,
            progress: Callable[[float], None] | None = None) -> int:
        """Step for ``duration`` seconds of body time (or until ``until(snapshot)`` holds).

        Returns the number of steps taken. :class:`SimulationDiverged` propagates; whatever the
        recorder holds up to that point is kept.
        """
        n = int(round(duration / self.body.dt))
        report_every = max(1, n // 100)
        for k in range(n):
            snap = self.step()
            if until is not None and until(snap):
                return k + 1
            if progress is not None and k % report_every == 0:
                progress(k / n)
        if progress is not None:
            progress(1.0)
        return n
