"""The one runtime every body runs in: Body, Module, Loop and Switcher.

Two theses describe this architecture from two sides:

* seed 000 §7.2 — online search indices processed *in parallel* (they coexist in one loop, each
  updating its own ρ from a shared sensor snapshot) or by *switching* (independent systems of which
  exactly one runs at a time, moving on sensor guards, §7.4);
* seed 003 §6.3.4 — the middle layer "nervous": autonomous plugins whose processing routine runs
  once per sensor packet and modifies the command sent to the body.

Here a :class:`Module` reads the snapshot and returns its *contribution* to the command (a dict of
named arrays). The :class:`Loop` combines the contributions of all modules and holds each module's
last contribution between its updates (multi-rate, zero-order hold). A :class:`Switcher` is itself a
module that runs exactly one of its children (switching processing).

Composition rules (DESIGN.md):

* every command goes to a declared :class:`Channel` — the body's (``Body.channels``) or the loop's
  own (``Loop(channels=...)``, set-points and references that modules pass to each other); anything
  else is a :class:`ChannelError`, the one error type of channel misuse;
* a channel is **additive** (contributions sum: corrections added to a trajectory, seed 000 §7.3) or
  **set** (exactly one writer per tick: a wheel mask, a contact code, a chosen order);
* several modules that must be switched in and out together form a :class:`Group`;
* modules run in **stages**: what an earlier stage writes to a loop channel is in the snapshot the
  later stages see in the same tick, so a set-point feeds a controller without a hidden delay; a
  loop channel with ``delay=d`` is seen ``d`` ticks later instead (a declared delay).
"""

from __future__ import annotations

import math
import time
from abc import ABC, abstractmethod
from collections import deque
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from shintai.core.recorder import Recorder

Snapshot = dict  # name -> np.ndarray (or float); always holds "t", the body time in seconds
_F64 = np.dtype(float)
Command = dict  # channel name -> np.ndarray

ADD, SET = "add", "set"


class SimulationDiverged(RuntimeError):
    """The simulated state became non-finite or the physics engine reported an instability."""


class ChannelError(ValueError):
    """A command to an undeclared channel, a second writer of a set channel, or a bad declaration."""


@dataclass(frozen=True)
class Channel:
    """A declared command channel.

    ``kind``: :data:`ADD` (contributions of all writers sum) or :data:`SET` (exactly one writer per
    tick). For a loop's own channels: ``delay`` ticks before readers see the value (0: later stages
    of the same tick), and ``default``, what readers see while no module writes it (``None``: the
    name is absent from the snapshot).
    """

    name: str
    kind: str = ADD
    delay: int = 0
    default: Any = None
    doc: str = ""

    def __post_init__(self):
        if self.kind not in (ADD, SET):
            raise ChannelError(f"channel {self.name!r}: kind must be {ADD!r} or {SET!r}, got {self.kind!r}")
        if int(self.delay) != self.delay or self.delay < 0:
            raise ChannelError(f"channel {self.name!r}: delay must be a whole number of ticks >= 0, got {self.delay!r}")


def declare(*names: str, kind: str = ADD, **options) -> dict[str, Channel]:
    """Declare several channels of one kind: ``{name: Channel(name, kind, **options)}``."""
    return {n: Channel(n, kind, **options) for n in names}


class Body(ABC):
    """A simulated robot: a sensor snapshot out, a command in, time advances by ``dt``.

    ``channels`` declares the command channels the body takes (name -> :class:`Channel`); the
    :class:`Loop` checks every contribution against it, so :meth:`apply` only ever sees declared
    channels.
    """

    dt: float
    t: float = 0.0
    channels: Mapping[str, Channel] = {}

    @abstractmethod
    def snapshot(self) -> Snapshot:
        """Current sensor values (must include ``"t"``)."""

    @abstractmethod
    def apply(self, command: Command) -> None:
        """Take the combined command of this tick (declared channels only)."""

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
    return whole_multiple(period, dt, f"module {name!r}: period")


def is_multiple(span: float, dt: float) -> bool:
    """Whether ``span`` is a whole multiple (≥ 1) of ``dt``."""
    ratio = span / dt
    n = int(round(ratio))
    return n >= 1 and math.isclose(ratio, n, rel_tol=1e-9, abs_tol=1e-9)


def whole_multiple(span: float, dt: float, what: str) -> int:
    """``span / dt`` as an integer ≥ 1; a :class:`ValueError` naming ``what`` if it is not whole."""
    if not is_multiple(span, dt):
        raise ValueError(f"{what} {span} s is not a whole multiple of the body step {dt} s")
    return int(round(span / dt))


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
    ``(t, from, to)``. Children run at the Switcher's own rate. A child with no transition leaving
    it is a final phase. ``chain=True``: after a transition the guards leaving the new child are
    tested again, so transitions whose guards hold at the same instant all happen in one update
    (seed 001 §4.2.4: a front shift and the rear shift it allows are one instant); a cycle of guards
    that keep holding is an error.
    """

    def __init__(self, modules: Sequence[Module], transitions: Sequence[tuple[str, str, Callable]],
                 initial: str | None = None, name: str = "switcher", period: float | None = None,
                 chain: bool = False):
        super().__init__(name, period)
        self.chain = chain
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
        for _ in range(len(self.transitions) + 1 if self.chain else 1):
            for src, dst, guard in self.transitions:
                if src == self.active and guard(snapshot):
                    self.switch_to(dst, snapshot)
                    break
            else:
                break
        else:
            if self.chain:
                raise RuntimeError(f"switcher {self.name!r}: its guards keep switching at t = {snapshot['t']} "
                                   f"(a cycle of transitions that all hold)")
        return self.modules[self.active].update(snapshot)


class Group(Module):
    """Several modules run as one (their contributions add): a :class:`Switcher` child made of more
    than one module (seed 000 §7.4.1: the sitting recovery with the legs' IK is one switched system).

    The group runs every ``period`` seconds; a member runs every ``member.period / period`` group
    updates (``None``: every one), counted from the group's last :meth:`reset` — so a switched-in
    group starts all its members on its first tick, as a fresh system would, and holds each member's
    last contribution between its updates (as the :class:`Loop` does).
    """

    def __init__(self, name: str, modules: Sequence[Module], period: float):
        super().__init__(name, period)
        self.modules = list(modules)
        self.every = [ticks_per_period(m.period, period, m.name) for m in self.modules]
        self._tick = 0
        self._held: list[Command | None] = [None] * len(self.modules)

    def attach(self, recorder: Recorder | None) -> None:
        super().attach(recorder)
        for m in self.modules:
            m.attach(recorder)

    def reset(self, snapshot: Snapshot) -> None:
        for m in self.modules:
            m.reset(snapshot)
        self._tick = 0
        self._held = [None] * len(self.modules)

    def update(self, snapshot: Snapshot) -> Command | None:
        total: Command = {}
        for i, m in enumerate(self.modules):
            if self._tick % self.every[i] == 0:
                self._held[i] = m.update(snapshot)
            add_into(total, self._held[i])
        self._tick += 1
        return total


Hook = Callable[[Snapshot], None]


class Loop:
    """Parallel processing (seed 000 §7.3, seed 003 §6.3.4): multi-rate modules in stages.

    Each body step: take the snapshot (with the loop channels due to be seen, see :class:`Channel`);
    for each stage, run its modules that are due (tick index a multiple of their ticks-per-period),
    then combine the latest contribution of *every* module of the stage (a slow module's
    contribution is held between its updates) into the command — additive channels sum, a set
    channel takes its one writer's value — and show the stage's undelayed loop channels to the later
    stages; apply the body's channels; step the body. ``base`` is a command added each tick (e.g. a
    posture the modules correct). Per-module wall time is kept in ``timing``.

    ``Loop(body, modules)`` runs the modules as one stage; ``Loop(body, stages=[[...], [...]])`` in
    stages. ``channels``: the loop's own channels (set-points, references), never sent to the body.
    """

    def __init__(self, body: Body, modules: Sequence[Module] | None = None, recorder: Recorder | None = None,
                 base: Command | None = None, *, stages: Sequence[Sequence[Module]] | None = None,
                 channels: Iterable[Channel] = ()):
        if (modules is None) == (stages is None):
            raise ValueError("loop: give the modules (one stage) or stages=, not both")
        self.body = body
        self.stages = [list(s) for s in stages] if stages is not None else [list(modules)]
        self.modules = [m for stage in self.stages for m in stage]
        names = [m.name for m in self.modules]
        if len(set(names)) != len(names):
            raise ValueError(f"loop: module names must be unique, got {names}")
        self.channels = self._declare(body, channels)
        self.internal = {n: c for n, c in self.channels.items() if n not in body.channels}
        # the body's additive channels: a Python float contributed to one is summed as a float, the same
        # IEEE double sums as on 0-d arrays without building them (a joint servo target per channel)
        self._body_scalars = {n for n, c in body.channels.items() if c.kind == ADD}
        self.recorder = recorder
        self.base = {k: np.asarray(v, dtype=float) for k, v in (base or {}).items()}
        for k in self.base:
            self._channel(k, "base")
        self.every = [ticks_per_period(m.period, body.dt, m.name) for m in self.modules]
        self.held: list[Command | None] = [None] * len(self.modules)
        self.timing = {m.name: ModuleTiming() for m in self.modules}
        self.tick = 0
        self.command: Command = {}
        self._plan = self._stage_plan()
        self._base_writers = {k: "base" for k in self.base if self.channels[k].kind == SET}
        self._now = [c for c in self.internal.values() if c.delay == 0]
        self._now_names = frozenset(c.name for c in self._now)
        self._now_defaults = [(c.name, c.default) for c in self._now if c.default is not None]  # what view() shows
        self._later = {n: deque([c.default] * c.delay, maxlen=c.delay) for n, c in self.internal.items() if c.delay}
        self._started = False
        for m in self.modules:
            m.attach(recorder)

    @staticmethod
    def _declare(body: Body, extra: Iterable[Channel]) -> dict[str, Channel]:
        declared = getattr(body, "channels", None)
        if declared is None:
            raise ChannelError(f"{type(body).__name__} declares no command channels (Body.channels)")
        table = dict(declared)
        for c in extra:
            if c.name in table:
                raise ChannelError(f"loop channel {c.name!r} is declared twice (or is also a body channel)")
            table[c.name] = c
        return table

    def _channel(self, name: str, writer: str) -> Channel:
        c = self.channels.get(name)
        if c is None:
            body = ", ".join(sorted(self.body.channels)[:30]) or "none"
            own = ", ".join(sorted(self.internal)) or "none"
            raise ChannelError(f"{writer} writes undeclared channel {name!r} (body channels: {body}; "
                               f"loop channels: {own})")
        return c

    def view(self, snapshot: Snapshot) -> Snapshot:
        """The snapshot modules see at the start of a tick: the body's, plus the loop channels whose
        (delayed) value is due and those with a default."""
        if not self.internal:
            return snapshot
        view = snapshot.copy()  # a MujocoBody's Snapshot stays a lazy one (sim.body)
        for name, default in self._now_defaults:
            view[name] = default
        for name, queue in self._later.items():
            value = queue[0]
            if value is not None:
                view[name] = value
        return view

    def start(self) -> None:
        snap = self.view(self.body.snapshot())
        for m in self.modules:
            m.reset(snap)
        self._started = True

    def restage(self, stages: Sequence[Sequence[Module]]) -> None:
        """Replace the modules between two ticks (seed 003 §6.3.4: nervous's plugins are started,
        stopped and unloaded while the loop runs). A module that stays keeps its state, its held
        contribution and its timing; a new one is reset with the current view if the loop has
        started (the others are not reset again)."""
        stages = [list(s) for s in stages]
        modules = [m for stage in stages for m in stage]
        names = [m.name for m in modules]
        if len(set(names)) != len(names):
            raise ValueError(f"loop: module names must be unique, got {names}")
        every = [ticks_per_period(m.period, self.body.dt, m.name) for m in modules]
        old = {id(m): i for i, m in enumerate(self.modules)}
        self.held = [self.held[old[id(m)]] if id(m) in old else None for m in modules]
        self.timing = {m.name: self.timing[m.name] if id(m) in old else ModuleTiming() for m in modules}
        self.stages, self.modules, self.every = stages, modules, every
        self._plan = self._stage_plan()
        fresh = [m for m in modules if id(m) not in old]
        for m in fresh:
            m.attach(self.recorder)
        if self._started and fresh:
            snap = self.view(self.body.snapshot())
            for m in fresh:
                m.reset(snap)

    def _stage_plan(self) -> list[list[tuple[int, Module, int, ModuleTiming]]]:
        """Per stage, (index, module, ticks per period, timing record) of each module: what a tick walks."""
        plan, i = [], 0
        for stage in self.stages:
            plan.append([(i + k, m, self.every[i + k], self.timing[m.name]) for k, m in enumerate(stage)])
            i += len(stage)
        return plan

    def _combine(self, command: Command, stage: list, set_writers: dict) -> list:
        """Add the held contributions of the ``stage``'s modules into ``command``; returns the channels they wrote."""
        written = []
        channels, scalars, held, ndarray = self.channels, self._body_scalars, self.held, np.ndarray
        for i, m, _, _ in stage:
            part = held[i]
            if not part:
                continue
            written += part
            for channel, value in part.items():
                c = channels.get(channel)
                if c is None:
                    self._channel(channel, f"module {m.name!r}")
                if type(value) is float and channel in scalars:  # a float stays one (no copy to make)
                    command[channel] = command[channel] + value if channel in command else value
                    continue
                if c.kind == SET:
                    if channel in set_writers:
                        raise ChannelError(f"set channel {channel!r} has two writers in one tick: "
                                           f"{set_writers[channel]!r} and {m.name!r}")
                    set_writers[channel] = m.name
                elif channel in command:
                    command[channel] = command[channel] + np.asarray(value, dtype=float)
                    continue
                # a float array the loop owns (the module keeps its own): np.asarray(value, float).copy(), a float64
                # array copied by its own method (NumPy's constructor parses its arguments first)
                command[channel] = (value.copy() if type(value) is ndarray and value.dtype is _F64
                                    else np.array(value, dtype=float, order="C"))
        return written

    def step(self) -> Snapshot:
        """Run one body step; returns the snapshot the first stage saw (later stages also saw the
        earlier stages' loop channels, written into it)."""
        if not self._started:
            self.start()
        snap = self.view(self.body.snapshot())
        command = {k: v.copy() for k, v in self.base.items()} if self.base else {}
        set_writers = dict(self._base_writers)
        written = list(self.base)  # shown with what the first stage writes
        tick, held, now, clock = self.tick, self.held, self._now_names, time.perf_counter
        for stage in self._plan:
            for i, m, every, rec in stage:
                if tick % every == 0:
                    t0 = clock()
                    held[i] = m.update(snap)
                    rec.total_s += clock() - t0
                    rec.calls += 1
            written += self._combine(command, stage, set_writers)
            if now:
                for name in written:
                    if name in now:  # what this stage wrote to an undelayed loop channel
                        snap[name] = command[name]
            written = []
        self.command = command
        if self.internal:
            for name, queue in self._later.items():
                queue.append(command.get(name, self.internal[name].default))
            command = {k: v for k, v in command.items() if k not in self.internal}
        self.body.apply(command)
        self.body.step()
        self.tick += 1
        return snap

    def run(self, duration: float | None = None, until: float | Callable[[Snapshot], bool] | None = None,
            every: Mapping[int, Hook] | None = None, progress: Callable[[float], None] | None = None) -> int:
        """Step for ``duration`` seconds of body time, or up to body time ``until`` (a number), and/or
        until the predicate ``until(snapshot)`` holds after a step.

        ``every`` maps ``n`` to a hook called with the snapshot of every ``n``-th step of this run
        (the 0th, the nth, ...), for decimated recording. Returns the number of steps taken.
        :class:`SimulationDiverged` propagates; whatever the recorder holds up to then is kept.
        """
        stop = until if callable(until) else None
        if duration is None and until is not None and not callable(until):
            duration = float(until) - self.body.t
        if duration is None:
            raise ValueError("loop.run: give a duration or until= (a time or a predicate with a duration)")
        n = int(round(duration / self.body.dt))
        hooks = [(int(k), hook) for k, hook in (every or {}).items()]
        for k, _ in hooks:
            if k < 1:
                raise ValueError(f"loop.run: every= needs periods of at least one step, got {k}")
        report_every = max(1, n // 100)
        for k in range(n):
            snap = self.step()
            for period, hook in hooks:
                if k % period == 0:
                    hook(snap)
            if stop is not None and stop(snap):
                return k + 1
            if progress is not None and k % report_every == 0:
                progress(k / n)
        if progress is not None:
            progress(1.0)
        return n
