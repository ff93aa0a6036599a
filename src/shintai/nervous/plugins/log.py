"""``log`` — logging (App. C.3.6 ``logplugin.c``, "ログ保存に関するプラグイン"): every N-th sensor packet as one
line of a text file a user loads with ``numpy.loadtxt(path)`` (``numpy.genfromtxt(path, names=True)`` for
the column names) — the packet's time and number, this packet's set-point ``target`` (NaN when no plugin
set one), the measured angle vector, the ``reference`` (the vector sent in answer to the previous packet),
the sensors.

``create-plugin log log FILE [EVERY]``; the file is opened by ``start`` (the constructor) and closed by
``stop`` (the destructor). FILE is a plain file name, written in the server's log directory
(``--log-dir``, default the working directory): a client chooses the name, never the path.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from shintai.nervous.plugins.base import ADD, CommandError, Plugin
from shintai.nervous.protocol import integer

FILE_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,127}")
FLUSH_LINES = 500  # chosen: written out every 500 lines (0.5 s at 1 ms packets)


class Log(Plugin):
    kind = ADD
    summary = "writes the state every N packets to a text file numpy.loadtxt reads (logplugin, App. C.3.6)"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        if not args:
            raise CommandError("log: create-plugin NAME log FILE [EVERY]")
        name = str(args[0])
        if FILE_NAME.fullmatch(name) is None or ".." in name:
            raise CommandError(f"log: {name[:60]!r} is not a plain file name (letters, digits, _ . -)")
        self.path = Path(host.log_dir) / name
        self.every = integer(args[1], "log: EVERY", 1, 1_000_000) if len(args) > 1 else 1
        self.file = None
        self.lines: list[str] = []
        self.written = 0

    def start(self, state):
        n = self.host.description.n
        keys = ["target"] + [k for k in state if k not in ("t", "seq", "target")]
        self.keys = keys
        self.blank = np.full(n, np.nan)  # no set-point this packet
        names = ["t", "seq"]
        for k in keys:
            size = np.size(state.get(k, self.blank))
            names += [f"{k}_{i}".replace("-", "_") for i in range(size)] if size > 1 else [k.replace("-", "_")]
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.file = open(self.path, "w", encoding="utf-8")  # noqa: SIM115 - closed by stop()
        self.file.write("# " + " ".join(names) + "\n")

    def process(self, state):
        if state["seq"] % self.every == 0:
            values = [float(state["t"]), float(state["seq"])]
            for k in self.keys:
                values.extend(np.ravel(state.get(k, self.blank)).tolist())
            self.lines.append(" ".join(f"{v:.12g}" for v in values))
            if len(self.lines) >= FLUSH_LINES:
                self._flush()
        return None

    def _flush(self) -> None:
        if self.file is not None and self.lines:
            self.file.write("\n".join(self.lines) + "\n")
            self.file.flush()
            self.written += len(self.lines)
            self.lines = []

    def stop(self):
        self._flush()
        if self.file is not None:
            self.file.close()
            self.file = None

    def cmd_flush(self, args, call):
        """write out the buffered lines now"""
        self._flush()
        return f"{self.written} lines in {self.path.name}"

    def describe(self) -> str:
        return f"file={self.path.name} every={self.every} lines={self.written + len(self.lines)}"
