"""nervous without the network: an interface, the plugin loop, the plugins, the line interpreter.

Per sensor packet (C.2.2) one tick of a :class:`~shintai.core.runtime.Loop` over :class:`NerveBody` (the
interface as a Body: the snapshot is the packet, ``apply`` is SetAngleVector, ``step`` is GetRobotState):

* stage 1 — the running plugin of kind ``set`` (the seqplugin) writes the loop channel ``target``;
* stage 2 — :class:`Hold` sends that target (the last one when none was written) to the body channel
  ``angle-vector``, and every running plugin of kind ``add`` adds its difference to it (§6.2.4: "それらを現
  在値に足し合わせる形"); they see this packet's ``target``.

A plugin runs inside a :class:`PluginModule`, which times it and catches what it raises: a plugin that
raises, or returns a wrong-sized or non-finite vector, contributes nothing that packet, is stopped (its
destructor runs) and reported as an ``event`` line, and the loop goes on. Plugins are started, stopped and
unloaded between ticks (:meth:`~shintai.core.runtime.Loop.restage`). A failure of the interface itself (a
diverged simulation) halts the loop, reported alike; commands are still answered.

:meth:`Nerve.execute` interprets one line (rules of :mod:`shintai.nervous.protocol`; the commands are in
:mod:`shintai.nervous.commands`) and returns one :class:`Reply`.
"""

from __future__ import annotations

import time
import traceback
from pathlib import Path

import numpy as np

from shintai.core.runtime import ADD, SET, Body, Channel, Loop, Module
from shintai.nervous import hal, robots
from shintai.nervous.commands import COMMANDS, Call, Client, Reply, sexpr_form
from shintai.nervous.motions import Motions
from shintai.nervous.plugins import PluginNotFound, canonical, find, from_file
from shintai.nervous.plugins.base import Plugin
from shintai.nervous.protocol import (ProtocolError, Vector, error, fmt, fmt_vector, is_silent, ok, read_sexpr,
                                      split_id, words)
from shintai.nervous.stats import LoopStats, Timing

TARGET = "target"  # loop channel: this packet's set-point (stage 1 → stage 2)
OUTPUT = "angle-vector"  # body channel: what SetAngleVector sends


class NerveBody(Body):
    """The interface seen by the Loop: snapshot = the packet, apply = SetAngleVector, step = GetRobotState."""

    channels = {OUTPUT: Channel(OUTPUT, ADD, doc="the target vector sent to the body")}

    def __init__(self, interface: hal.Interface):
        self.interface = interface

    @property
    def dt(self) -> float:
        return self.interface.period

    @property
    def t(self) -> float:
        return self.interface.state.t

    def snapshot(self) -> dict:
        return self.interface.state.snapshot()

    def apply(self, command) -> None:
        if OUTPUT in command:
            self.interface.set_angle_vector(command[OUTPUT])

    def step(self) -> None:
        self.interface.get_robot_state()


class Hold(Module):
    """Sends this packet's target, or the last one when no plugin set it (the body keeps its target)."""

    def __init__(self):
        super().__init__("(target)")
        self.last: np.ndarray | None = None

    def reset(self, snapshot):
        self.last = np.asarray(snapshot["reference"], dtype=float).copy()

    def update(self, snapshot):
        target = snapshot.get(TARGET)
        if target is not None:
            self.last = np.asarray(target, dtype=float)
        return {OUTPUT: self.last}


class Instance:
    """A created plugin: the object, its loop module, whether it runs, why it stopped."""

    def __init__(self, name: str, plugin_name: str, plugin: Plugin, n: int):
        self.name, self.plugin_name, self.plugin = name, plugin_name, plugin
        self.module = PluginModule(self, n)
        self.status = "created"
        self.error: str | None = None

    @property
    def running(self) -> bool:
        return self.plugin.running


class PluginModule(Module):
    """Runs one plugin's routine in the loop: timed, its exceptions caught, its output checked."""

    def __init__(self, instance: Instance, n: int):
        super().__init__(instance.name)
        self.instance, self.n = instance, n
        self.channel = TARGET if instance.plugin.kind == SET else OUTPUT
        self.timing = Timing()
        self.failure: str | None = None

    def update(self, snapshot):
        if self.failure is not None:
            return None
        t0 = time.perf_counter()
        try:
            out = self.instance.plugin.process(snapshot)
            if out is not None:
                out = np.asarray(out, dtype=float)
                if out.shape != (self.n,) or not np.all(np.isfinite(out)):
                    raise ValueError(f"returned {out.shape} values ({np.count_nonzero(~np.isfinite(out))} not finite); "
                                     f"a {self.instance.plugin.kind} vector has {self.n} finite values")
        except Exception as exc:  # noqa: BLE001 - a plugin's fault is reported, the loop goes on
            self.failure = f"{type(exc).__name__}: {exc}".splitlines()[0]
            self.trace = traceback.format_exc()
            return None
        finally:
            self.timing.add(time.perf_counter() - t0)
        return None if out is None else {self.channel: out}


class Nerve:
    """The middle layer (see the module docstring)."""

    def __init__(self, robot: str, interface: str = "sim", realtime: bool = False, log_dir: str | Path = ".",
                 plugin_dirs=()):
        robots.entry(robot)
        self.robot, self.realtime = robot, realtime
        self.log_dir, self.plugin_dirs = Path(log_dir), [Path(p) for p in plugin_dirs]
        self.spine = robots.spine_of(robot)
        self.motions = Motions()
        self.loaded: dict[str, type[Plugin]] = {}
        self.instances: dict[str, Instance] = {}
        self.clients: set[Client] = set()
        self.dropped_gone = 0  # stream lines dropped for clients that have left
        self.halted: str | None = None
        self.events: list[str] = []
        self._open(interface)

    # -- the interface and the loop ---------------------------------------------------------------

    def _open(self, kind: str) -> None:
        self.interface = hal.open_interface(kind, self.robot, self.realtime)
        self.description = self.interface.description
        self.body = NerveBody(self.interface)
        self.hold = Hold()
        self.loop = Loop(self.body, stages=self._stages(), channels=[Channel(TARGET, SET)])
        self.loop.start()
        self.stats = LoopStats(self.interface.period)
        self.halted = None

    def _stages(self) -> list[list[Module]]:
        running = [i for i in self.instances.values() if i.running]
        return [[i.module for i in running if i.plugin.kind == SET],
                [self.hold] + [i.module for i in running if i.plugin.kind == ADD]]

    def restage(self) -> None:
        self.loop.restage(self._stages())

    def state(self) -> dict:
        """The latest packet as a snapshot."""
        return self.body.snapshot()

    def set_interface(self, kind: str) -> None:
        """Close the interface and open another (§5.4.5: the same software on the robot or the simulator,
        "インタフェースを切り替えるだけで"). Running plugins are restarted on the new interface's state."""
        running = [i for i in self.instances.values() if i.running]
        for inst in running:
            self._stop(inst)
        old = self.interface
        self._open(kind)
        old.close_interface()
        for inst in running:
            self.start_instance(inst)

    def tick(self) -> dict | None:
        """One sensor packet: the plugins, SetAngleVector, GetRobotState; then failed plugins are stopped
        and reported, and state lines go to streaming clients. None if the loop is halted."""
        if self.halted is not None:
            return None
        start = time.perf_counter()
        try:
            self.loop.step()
        except Exception as exc:  # noqa: BLE001 - the interface failed: halt, report, keep serving
            self.halted = f"{type(exc).__name__}: {exc}".splitlines()[0]
            self.event(f"interface {self.interface.name} failed, loop halted: {self.halted}")
            return None
        self.stats.tick(start, time.perf_counter())
        failed = [i for i in self.instances.values() if i.running and i.module.failure is not None]
        for inst in failed:
            self._stop(inst, status=f"failed: {inst.module.failure}")
            self.event(f"plugin {inst.name} raised and was stopped: {inst.module.failure}")
        if failed:
            self.restage()
        self._stream()
        return self.interface.state

    def _stream(self) -> None:
        seq = self.interface.state.seq
        line_all = None
        for client in self.clients:
            if client.stream_every and seq % client.stream_every == 0:
                if client.stream_keys is None:
                    line_all = line_all or "state " + self.state_text()
                    client.send(line_all, droppable=True)
                else:
                    client.send("state " + self.state_text(client.stream_keys), droppable=True)

    def state_text(self, keys=None) -> str:
        """The state as ``t=… seq=… key=v1,v2 …`` (all keys, or the given ones)."""
        snap = self.state()
        parts = [f"t={snap['t']:.6f}", f"seq={snap['seq']}"]
        for key in (k for k in snap if k not in ("t", "seq")) if keys is None else keys:
            parts.append(f"{key}={fmt_vector(np.ravel(snap[key]))}")
        return " ".join(parts)

    def event(self, text: str) -> None:
        """Report to every client (an ``event`` line) and keep it."""
        self.events.append(text)
        del self.events[:-100]
        for client in self.clients:
            client.send(f"event {text}")

    # -- plugins ----------------------------------------------------------------------------------

    def load(self, name: str, trusted: bool = False) -> type[Plugin]:
        """``load-plugin``: by name, or a ``.py`` path when ``trusted`` (the start-up file)."""
        if "/" in name or name.endswith(".py"):
            if not trusted:
                raise ProtocolError("load-plugin: a file path is honoured only in the start-up file (--rc) or "
                                    "as NAME from a --plugin-dir folder")
            cls = from_file(name)
            key = Path(name).stem
        else:
            cls = find(name, self.plugin_dirs)
            key = canonical(name)
        self.loaded[key] = cls
        return cls

    def create(self, instance: str, plugin_name: str, args: list) -> Instance:
        if instance in self.instances:
            raise ProtocolError(f"create-plugin: an instance named {instance!r} exists")
        if instance in COMMANDS:
            raise ProtocolError(f"create-plugin: {instance!r} is a command name (C.2.1 rule 3 would shadow it)")
        cls = self.loaded.get(plugin_name)
        if cls is None:
            raise ProtocolError(f"create-plugin: plugin {plugin_name!r} is not loaded (load-plugin {plugin_name})")
        plugin = cls(Host(self), instance, list(args))
        inst = Instance(instance, plugin_name, plugin, self.description.n)
        self.instances[instance] = inst
        return inst

    def start_instance(self, inst: Instance) -> None:
        if inst.running:
            raise ProtocolError(f"start: {inst.name} is already running")
        if inst.plugin.kind == SET:
            other = [i.name for i in self.instances.values() if i.running and i.plugin.kind == SET]
            if other:
                raise ProtocolError(f"start: {other[0]} already sets the target (one set-point plugin at a time; "
                                    f"stop {other[0]} first)")
        try:
            inst.plugin.start(self.loop.view(self.state()))
        except ProtocolError:
            raise
        except Exception as exc:  # noqa: BLE001 - a constructor's fault is the command's error
            raise ProtocolError(f"start: {inst.name}'s constructor raised {type(exc).__name__}: {exc}") from None
        inst.module.failure = None
        inst.plugin.running = True
        inst.status = "running"
        inst.error = None
        self.restage()

    def _stop(self, inst: Instance, status: str = "stopped") -> None:
        inst.plugin.running = False
        inst.status = status
        inst.error = inst.module.failure
        try:
            inst.plugin.stop()
        except Exception as exc:  # noqa: BLE001 - a destructor's fault is reported, not raised
            self.event(f"plugin {inst.name}'s destructor raised {type(exc).__name__}: {exc}")

    def stop_instance(self, inst: Instance) -> None:
        if not inst.running:
            raise ProtocolError(f"stop: {inst.name} is not running ({inst.status})")
        self._stop(inst)
        self.restage()

    def delete(self, inst: Instance) -> None:
        if inst.running:
            self._stop(inst)
            self.restage()
        del self.instances[inst.name]

    def unload(self, plugin_name: str) -> list[str]:
        """``unload-plugin``: every instance of the plugin is stopped and deleted, then the plugin."""
        if plugin_name not in self.loaded:
            raise ProtocolError(f"unload-plugin: {plugin_name!r} is not loaded (loaded: "
                                f"{', '.join(self.loaded) or 'none'})")
        gone = [i for i in self.instances.values() if i.plugin_name == plugin_name]
        for inst in gone:
            self.delete(inst)
        del self.loaded[plugin_name]
        return [i.name for i in gone]

    # -- lines ------------------------------------------------------------------------------------

    def check_vector(self, token, what: str, limits: bool = True) -> np.ndarray:
        """A #f(…) token as a DOF vector: N finite values, within the DOF limits."""
        if not isinstance(token, Vector):
            raise ProtocolError(f"{what}: expected a float vector #f(v1 … v{self.description.n}), "
                                f"got {str(token)[:40]!r}")
        v = np.array(token.values, dtype=float)
        n = self.description.n
        if v.size != n:
            raise ProtocolError(f"{what}: {v.size} values, the robot {self.robot} has {n} DOF "
                                f"({' '.join(self.description.names[:12])}{' …' if n > 12 else ''})")
        if limits:
            lo, hi = self.description.lower, self.description.upper
            bad = np.flatnonzero((v < lo) | (v > hi))
            if bad.size:
                i = int(bad[0])
                d = self.description.dofs[i]
                raise ProtocolError(f"{what}: {d.name} = {fmt(v[i])} {d.unit} is outside its limits "
                                    f"[{fmt(d.lower)}, {fmt(d.upper)}]")
        return v

    def execute(self, line: str, client: Client, trusted: bool = False) -> Reply:
        """One line → one :class:`Reply` (C.2.1's rules in order; rule 5, the shell, is refused)."""
        if is_silent(line):
            return Reply(None)
        call = None
        try:
            body, id = split_id(line.strip())
            call = Call(self, client, id, trusted)
            if body.startswith("("):
                reply = sexpr_form(self, read_sexpr(body), call)
            else:
                tokens = words(body)
                if not tokens:
                    raise ProtocolError("an @ID needs a command before it")
                head, args = tokens[0], tokens[1:]
                if isinstance(head, Vector):
                    raise ProtocolError("a line starts with a command or a plugin instance, not a vector")
                if head in COMMANDS:
                    reply = COMMANDS[head].fn(self, args, call)
                elif head in self.instances:
                    reply = self._to_plugin(self.instances[head], args, call)
                else:
                    raise ProtocolError(f"unknown command {head[:40]!r}: not a command or a plugin instance "
                                        "(lines are never passed to a shell; `help` lists the commands)")
        except ProtocolError as exc:
            self._undo(call)
            return Reply(error(str(exc)))
        except Exception as exc:  # noqa: BLE001 - a bug must not take the server down
            self._undo(call)
            return Reply(error(f"internal error: {type(exc).__name__}: {exc}".splitlines()[0]))
        if not isinstance(reply, Reply):
            reply = Reply(ok(reply or ""))
        if call.id is not None and not call.motions and reply.wait is None:
            reply.after.append(f"done {call.id}")
        return reply

    @staticmethod
    def _undo(call: Call | None) -> None:
        """A command that failed queued nothing: a motion it registered ends at once (unannounced)."""
        if call is not None:
            for m in call.motions:
                m.discard()

    def _to_plugin(self, inst: Instance, args: list, call: Call):
        if not args:
            return f"{inst.name}: {inst.plugin_name} {inst.status} {inst.plugin.describe()}".strip()
        method = args[0]
        if isinstance(method, Vector):
            raise ProtocolError(f"{inst.name}: expected a method name, got a vector")
        return inst.plugin.command(method, list(args[1:]), call)


class Host:
    """What a plugin sees of nervous."""

    def __init__(self, nerve: Nerve):
        self._nerve = nerve

    @property
    def description(self):
        return self._nerve.description

    @property
    def interface(self) -> hal.Interface:
        return self._nerve.interface

    @property
    def period_s(self) -> float:
        return self._nerve.interface.period

    @property
    def spine(self):
        """The spine robot (geometry, eq. 4.25) when the robot is one, else None."""
        return self._nerve.spine

    @property
    def log_dir(self) -> Path:
        return self._nerve.log_dir

    def state(self) -> dict:
        return self._nerve.state()

    def event(self, text: str) -> None:
        self._nerve.event(text)

    def check_vector(self, token, what: str, limits: bool = True) -> np.ndarray:
        return self._nerve.check_vector(token, what, limits)

    def dof_indices(self, tokens) -> list[int]:
        """DOF names or indices → indices (an error names the unknown one)."""
        names = self._nerve.description.names
        out = []
        for tok in tokens:
            tok = str(tok)
            if tok in names:
                out.append(names.index(tok))
            elif tok.isdigit() and int(tok) < len(names):
                out.append(int(tok))
            else:
                raise ProtocolError(f"unknown DOF {tok[:40]!r} (names {', '.join(names[:12])}… or 0–{len(names) - 1})")
        return out


__all__ = ["Call", "Client", "Host", "Nerve", "NerveBody", "PluginNotFound", "Reply"]
