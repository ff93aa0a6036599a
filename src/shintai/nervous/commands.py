"""The registered commands of nervous (App. C.2.1 rule 3) and the s-expression forms (rule 2).

C.1.4: "ヘルプを見るには、``nervous>`` のプロンプトが出てから、``?`` リターン"; C.2.2 names ``load-plugin``,
``create-plugin``, ``start`` and (C.1.4) ``set-interface``; the thesis lists no others. Here every command's
reply is one line starting ``ok`` or ``error:`` (``help`` lists them all). Rule 2's forms are the ones the
thesis's EusLisp client sends (§6.3.3, §6.5.1, C.2.1–C.2.2): ``(send *ns* :angle-vector #f(…) [ms]
[:overwrite t])`` (EusLisp turns it into ``sequence propocmd #f(…) ms [:clear]``), ``(send *ns*
:angle-vector)`` (the robot's measured vector), ``(send *ns* :state [:tension-vector])``, ``(send *ns*
:interpolation-method [name])`` (``sequence switch``). They are recognised, never evaluated.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from shintai.nervous.motions import Motion
from shintai.nervous.plugins import PluginNotFound, canonical
from shintai.nervous.protocol import Keyword, ProtocolError, Symbol, fmt, name, number

SEQUENCE = "sequence"  # the instance EusLisp's :angle-vector talks to ("sequence propocmd …", C.2.1)
MAX_WAIT_MS = 3_600_000.0  # chosen: an hour
DEFAULT_WAIT_MS = 60_000.0  # chosen: a wait without a timeout gives up after a minute rather than hang


class Client:
    """Who sent a line and receives unsolicited lines (``state``, ``done``, ``event``). This base keeps
    them in :attr:`received` (the start-up file, tests); the server's connections queue them."""

    def __init__(self, name: str = "local"):
        self.name = name
        self.received: list[str] = []
        self.stream_every = 0
        self.stream_keys: list[str] | None = None
        self.dropped = 0

    def send(self, line: str, droppable: bool = False) -> None:
        self.received.append(line)


@dataclass
class Reply:
    """What one line gets: ``text`` (the ok/error line; None for a comment or an empty line), or a
    ``wait`` on motions, answered ``ok <ids>`` when they end or ``error:`` at ``deadline`` (monotonic
    seconds); lines to send after the reply (``after``)."""

    text: str | None
    wait: list[Motion] | None = None
    wait_for: str = ""
    deadline: float | None = None
    after: list[str] = field(default_factory=list)


class Call:
    """The context of one command: its client, ``@ID`` and trust (the start-up file is trusted);
    :meth:`motion` registers the motion it queues, announced ``done ID`` when it ends."""

    def __init__(self, nerve, client: Client, id: str | None, trusted: bool = False):
        self.nerve, self.client, self.id, self.trusted = nerve, client, id, trusted
        self.motions: list[Motion] = []

    def motion(self) -> Motion:
        motion = self.nerve.motions.new(self.client, self.id)
        if self.id is not None:
            client, id = self.client, self.id
            motion.when_finished(lambda m: client.send(f"done {id}" if m.status == "done" else f"done {id} {m.status}"))
        self.motions.append(motion)
        return motion


@dataclass(frozen=True)
class Command:
    usage: str
    help: str
    fn: Callable


COMMANDS: dict[str, Command] = {}


def command(names: str, usage: str, help: str):
    def register(fn):
        for n in names.split():
            COMMANDS[n] = Command(usage, help, fn)
        return fn
    return register


def _instance(nerve, token, what: str):
    inst = nerve.instances.get(str(token))
    if inst is None:
        raise ProtocolError(f"{what}: no plugin instance {str(token)[:40]!r} (instances: "
                            f"{', '.join(nerve.instances) or 'none'})")
    return inst


def _arity(args, lo: int, hi: int, usage: str) -> None:
    if not lo <= len(args) <= hi:
        raise ProtocolError(f"usage: {usage}")


@command("help ?", "help [COMMAND]", "list the commands, or one command's usage")
def _help(nerve, args, call):
    if args:
        c = COMMANDS.get(str(args[0]))
        if c is None:
            raise ProtocolError(f"help: no command {str(args[0])[:40]!r}")
        return f"{c.usage} — {c.help}"
    names = sorted(set(COMMANDS))
    return ("commands: " + " ".join(names) + "; INSTANCE METHOD ARGS… goes to a plugin instance; "
            "(send *ns* :angle-vector|:state|:interpolation-method …) forms are read, not evaluated; "
            "anything else is an error, never a shell command; end a command with @ID for done ID")


@command("dof", "dof", "the DOF: ok N name1 … nameN")
def _dof(nerve, args, call):
    _arity(args, 0, 0, "dof")
    return f"{nerve.description.n} " + " ".join(nerve.description.names)


@command("describe", "describe", "the robot's description as one line of JSON")
def _describe(nerve, args, call):
    _arity(args, 0, 0, "describe")
    return nerve.description.to_json()


def _keys(nerve, args) -> list[str] | None:
    if not args:
        return None
    snap = nerve.state()
    keys = []
    for a in args:
        key = str(a).removeprefix(":").removesuffix("-vector") if str(a) not in snap else str(a)
        key = key if key in snap else key + "-vector" if key + "-vector" in snap else key
        if key not in snap or key in ("t", "seq"):
            raise ProtocolError(f"state: no key {str(a)[:40]!r} (keys: {', '.join(k for k in snap if k not in ('t', 'seq'))})")
        keys.append(key)
    return keys


@command("state", "state [KEY…]", "the latest sensor packet: ok t=… seq=… key=v1,v2 …")
def _state(nerve, args, call):
    return nerve.state_text(_keys(nerve, args))


@command("stream", "stream on [PERIOD_MS] [KEY…] | stream off",
         "state lines ('state t=… …') to this client every PERIOD_MS (default every packet); dropped, never "
         "queued without bound, when the client reads slower")
def _stream(nerve, args, call):
    if not args or str(args[0]) not in ("on", "off"):
        raise ProtocolError("usage: stream on [PERIOD_MS] [KEY…] | stream off")
    client = call.client
    if str(args[0]) == "off":
        _arity(args, 1, 1, "stream off")
        client.stream_every = 0
        return "stream off"
    rest = list(args[1:])
    period = nerve.interface.period
    every = 1
    if rest and _is_number(rest[0]):
        ms = number(rest.pop(0), "stream period [ms]", 0.0, 3_600_000.0)
        every = max(1, round(ms / 1e3 / period))
    client.stream_keys = _keys(nerve, rest)
    client.stream_every = every
    return f"stream every {every} packets ({fmt(every * period * 1e3)} ms)"


def _is_number(token) -> bool:
    try:
        return math.isfinite(float(token)) if isinstance(token, str) else False
    except ValueError:
        return False


@command("set-interface", "set-interface sim|dummy",
         "switch the robot interface (C.1.4); running plugins restart on the new one")
def _set_interface(nerve, args, call):
    _arity(args, 1, 1, "set-interface sim|dummy")
    kind = str(args[0])
    if kind == nerve.interface.name:
        return kind
    try:
        nerve.set_interface(kind)
    except KeyError as exc:
        raise ProtocolError(f"set-interface: {exc.args[0]}") from None
    return kind


@command("interface", "interface", "the interface: name, pacing, packet period")
def _interface(nerve, args, call):
    i = nerve.interface
    return (f"{i.name} robot={nerve.robot} {'realtime' if i.realtime else 'fast'} "
            f"period_ms={fmt(1e3 * i.period)} t={i.state.t:.6f} seq={i.state.seq}"
            + (f" halted={nerve.halted}" if nerve.halted else ""))


@command("load-plugin", "load-plugin NAME", "load a plugin by name (entry point, shintai's own, or NAME.py in a "
         "--plugin-dir); a .py path only in the start-up file")
def _load(nerve, args, call):
    _arity(args, 1, 1, "load-plugin NAME")
    try:
        cls = nerve.load(str(args[0]), trusted=call.trusted)
    except PluginNotFound as exc:
        raise ProtocolError(f"load-plugin: {exc}") from None
    return f"{canonical(str(args[0]))} ({cls.kind}): {cls.summary}"


@command("unload-plugin", "unload-plugin NAME", "stop and delete every instance of a plugin, then unload it")
def _unload(nerve, args, call):
    _arity(args, 1, 1, "unload-plugin NAME")
    gone = nerve.unload(str(args[0]))
    return f"unloaded {args[0]}" + (f", deleted {' '.join(gone)}" if gone else "")


@command("create-plugin", "create-plugin INSTANCE PLUGIN [ARG…]", "create a named instance of a loaded plugin")
def _create(nerve, args, call):
    if len(args) < 2:
        raise ProtocolError("usage: create-plugin INSTANCE PLUGIN [ARG…]")
    inst = nerve.create(name(args[0], "create-plugin INSTANCE"), str(args[1]), list(args[2:]))
    return f"{inst.name} ({inst.plugin_name})"


@command("delete-plugin", "delete-plugin INSTANCE", "stop (if running) and delete an instance")
def _delete(nerve, args, call):
    _arity(args, 1, 1, "delete-plugin INSTANCE")
    nerve.delete(_instance(nerve, args[0], "delete-plugin"))
    return f"deleted {args[0]}"


@command("start", "start INSTANCE", "run the instance's constructor, then its routine every packet")
def _start(nerve, args, call):
    _arity(args, 1, 1, "start INSTANCE")
    nerve.start_instance(_instance(nerve, args[0], "start"))
    return f"started {args[0]}"


@command("stop", "stop INSTANCE", "stop the instance's routine and run its destructor")
def _stop(nerve, args, call):
    _arity(args, 1, 1, "stop INSTANCE")
    nerve.stop_instance(_instance(nerve, args[0], "stop"))
    return f"stopped {args[0]}"


@command("plugins", "plugins", "loaded plugins and instances (status, µs per packet last/mean/max)")
def _plugins(nerve, args, call):
    loaded = " ".join(sorted(nerve.loaded)) or "none"
    parts = [f"loaded: {loaded};"]
    for inst in nerve.instances.values():
        parts.append(f"{inst.name}({inst.plugin_name},{inst.status},{inst.plugin.kind},"
                     f"us={inst.module.timing.us()}) {inst.plugin.describe()}".strip() + ";")
    return " ".join(parts).rstrip(";")


@command("stats timeprint", "stats",
         "loop timing: packets, period and cost per packet (ms, last/mean/max), overruns (cost > period), "
         "late packets, drops, µs per packet of each running plugin")
def _stats(nerve, args, call):
    s = nerve.stats
    period = f"{1e3 * s.period.last:.3f}/{1e3 * s.period.mean:.3f}/{1e3 * s.period.max:.3f}"
    cost = f"{1e3 * s.cost.last:.3f}/{1e3 * s.cost.mean:.3f}/{1e3 * s.cost.max:.3f}"
    dropped = nerve.dropped_gone + sum(c.dropped for c in nerve.clients)
    plugins = " ".join(f"{i.name}={i.module.timing.us()}" for i in nerve.instances.values() if i.running)
    return (f"packets={s.ticks} packet_ms={fmt(1e3 * s.packet_period)} period_ms={period} cost_ms={cost} "
            f"overruns={s.overruns} late={s.late} resyncs={nerve.interface.resyncs} clients={len(nerve.clients)} "
            f"dropped={dropped}" + (f" plugins_us {plugins}" if plugins else ""))


@command("events", "events", "the last events (plugin faults, interface failures)")
def _events(nerve, args, call):
    return " | ".join(nerve.events[-10:]) or "none"


@command("wait", "wait [ID|all] [TIMEOUT_MS]", "reply when the motion queued with @ID (or all of this "
         "connection's) has ended: ok ID STATUS; error after TIMEOUT_MS (default 60000)")
def _wait(nerve, args, call):
    _arity(args, 0, 2, "wait [ID|all] [TIMEOUT_MS]")
    which = str(args[0]) if args else "all"
    ms = number(args[1], "wait timeout [ms]", 0.0, MAX_WAIT_MS) if len(args) > 1 else DEFAULT_WAIT_MS
    if which == "all":
        motions = nerve.motions.pending(call.client)
    else:
        motions = [nerve.motions.get(call.client, which.removeprefix("@"))]
    return Reply(None, wait=motions, wait_for=which.removeprefix("@"), deadline=time.monotonic() + ms / 1e3)


@command("quit exit", "quit", "close this connection")
def _quit(nerve, args, call):
    return "bye"


# -- rule 2: the s-expression forms -------------------------------------------------------------

def _plist(nerve, keys=None) -> str:
    snap = nerve.state()
    parts = [f":time {snap['t']:.6f}", f":seq {snap['seq']}"]
    for k in (x for x in snap if x not in ("t", "seq")) if keys is None else keys:
        parts.append(f":{k} #f({' '.join(fmt(v) for v in np.ravel(snap[k]))})")
    return "(" + " ".join(parts) + ")"


def sexpr_form(nerve, form, call):
    """``(send RECEIVER :METHOD ARGS…)`` — the forms of the thesis's EusLisp client, read not evaluated."""
    usage = ("s-expression: understood are (send *ns* :angle-vector [#f(…) [ms] [:overwrite t]]), "
             "(send *ns* :state [:KEY]), (send *ns* :interpolation-method [NAME]); nothing is evaluated")
    if (not isinstance(form, list) or len(form) < 3 or form[0] != Symbol("send")
            or not isinstance(form[1], Symbol) or not isinstance(form[2], Keyword)):
        raise ProtocolError(usage)
    method, args = form[2].name, form[3:]
    if method == "angle-vector":
        if not args:
            return "#f(" + " ".join(fmt(v) for v in nerve.state()["angle-vector"]) + ")"
        return _angle_vector(nerve, args, call)
    if method == "state":
        if len(args) > 1 or (args and not isinstance(args[0], Keyword)):
            raise ProtocolError("(send *ns* :state [:KEY]): one keyword at most")
        if not args:
            return _plist(nerve)
        key = _keys(nerve, [":" + args[0].name])[0]
        return "#f(" + " ".join(fmt(v) for v in np.ravel(nerve.state()[key])) + ")"
    if method == "interpolation-method":
        seq = _sequence(nerve)
        if not args:
            return seq.plugin.method
        if len(args) != 1 or not isinstance(args[0], (Symbol, Keyword)):
            raise ProtocolError("(send *ns* :interpolation-method NAME): NAME is linear, minjerk or minjerksequence")
        return seq.plugin.command("switch", [str(args[0]).removeprefix(":")], call)
    raise ProtocolError(usage)


def _sequence(nerve):
    inst = nerve.instances.get(SEQUENCE)
    if inst is None or not hasattr(inst.plugin, "push"):
        raise ProtocolError("no sequence instance: :angle-vector goes to 'sequence propocmd' (C.2.1); "
                            "load-plugin sequence, create-plugin sequence sequence, start sequence")
    return inst


def _angle_vector(nerve, args, call):
    seq = _sequence(nerve)
    target = nerve.check_vector(args[0], ":angle-vector")
    rest = list(args[1:])
    ms = 1.0  # EusLisp's default time (C.2.1: "1[ms] かけて")
    if rest and not isinstance(rest[0], Keyword):
        ms = number(rest.pop(0), ":angle-vector time [ms]", 0.0, 86_400_000.0)
        if ms <= 0:
            raise ProtocolError(":angle-vector time [ms]: must be > 0")
    clear = False
    while rest:
        key = rest.pop(0)
        if not isinstance(key, Keyword) or not rest:
            raise ProtocolError(":angle-vector: options are :overwrite t")
        value = rest.pop(0)
        if key.name in ("overwrite", "clear"):
            clear = value is True
        else:
            raise ProtocolError(f":angle-vector: unknown option :{key.name} (:overwrite t)")
    if not seq.plugin.running:
        raise ProtocolError(f"{SEQUENCE} is not running (start {SEQUENCE})")
    return seq.plugin.push(target, ms, call, clear=clear)


