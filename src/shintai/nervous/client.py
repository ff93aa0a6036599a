"""``NerveClient`` — a program's connection to nervous (the thesis's EusLisp ``open-nerve``, §6.3.3).

§6.3.3 shows the client side in EusLisp::

    (setq *ns* (open-nerve :io :host "host"))
    (send *ns* :state :tension-vector)
    (send *ns* :angle-vector angles)

and C.2.2 ``(send *ns* :interpolation-method newval)``. The same in Python::

    with NerveClient(port=port) as ns:
        ns.state("tension")
        ns.angle_vector(angles, 1000)
        ns.interpolation_method("minjerksequence")

Each method sends one line and reads lines until its reply (``ok …`` / ``error: …``); the unsolicited
lines met on the way are kept: ``state`` lines (a bounded deque, :attr:`states`), ``done ID``
(:attr:`done`), ``event …`` (:attr:`events`). An ``error:`` reply raises :class:`NerveError`. Every read
has a timeout, so a server that stops answering fails a program instead of hanging it.
"""

from __future__ import annotations

import socket
import time
from collections import deque

import numpy as np

from shintai.nervous.protocol import fmt

DEFAULT_TIMEOUT_S = 10.0


class NerveError(RuntimeError):
    """The server answered ``error: …`` (the message is the rest of the line)."""


def parse_state(text: str) -> dict:
    """``t=… seq=… key=v1,v2 …`` → {"t": float, "seq": int, key: array}."""
    out: dict = {}
    for token in text.split():
        key, _, value = token.partition("=")
        if key == "t":
            out[key] = float(value)
        elif key == "seq":
            out[key] = int(value)
        else:
            out[key] = np.array([float(v) for v in value.split(",")]) if value else np.zeros(0)
    return out


class NerveClient:
    """A connection to a nervous server (see the module docstring)."""

    def __init__(self, host: str = "127.0.0.1", port: int = 0, timeout: float = DEFAULT_TIMEOUT_S,
                 keep_states: int = 100_000):
        self.sock = socket.create_connection((host, port), timeout=timeout)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.timeout = timeout
        self._buffer = b""
        self.states: deque[dict] = deque(maxlen=keep_states)
        self.done: dict[str, str] = {}
        self.finished: list[str] = []  # the ids of done lines in the order they came
        self.events: list[str] = []

    def __enter__(self) -> NerveClient:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        try:
            self.sock.close()
        except OSError:
            pass

    # -- lines ----------------------------------------------------------------------------------

    def send_line(self, line: str) -> None:
        self.sock.sendall((line + "\n").encode())

    def read_line(self, timeout: float | None = None) -> str:
        """The next line from the server (any kind)."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        while b"\n" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("no line from nervous in time")
            self.sock.settimeout(left)
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionError("nervous closed the connection")
            self._buffer += chunk
        line, _, self._buffer = self._buffer.partition(b"\n")
        return line.decode()

    def _note(self, line: str) -> bool:
        """Keep an unsolicited line; False if ``line`` is a reply."""
        if line.startswith("state "):
            self.states.append(parse_state(line[6:]))
        elif line.startswith("done "):
            parts = line.split()
            self.done[parts[1]] = parts[2] if len(parts) > 2 else "done"
            self.finished.append(parts[1])
        elif line.startswith("event "):
            self.events.append(line[6:])
        else:
            return False
        return True

    def reply(self, timeout: float | None = None) -> str:
        """Read up to the next reply line (``ok …`` or ``error: …``), keeping the others."""
        while True:
            line = self.read_line(timeout)
            if not self._note(line):
                return line

    def command(self, line: str, timeout: float | None = None) -> str:
        """Send a line; its reply without ``ok``, or :class:`NerveError` for ``error:``."""
        self.send_line(line)
        answer = self.reply(timeout)
        if answer.startswith("error:"):
            raise NerveError(answer[6:].strip())
        if answer == "ok" or answer.startswith("ok "):
            return answer[3:]
        raise NerveError(f"unexpected reply {answer[:80]!r}")

    # -- the thesis's client methods ------------------------------------------------------------

    def dof(self) -> list[str]:
        parts = self.command("dof").split()
        return parts[1:1 + int(parts[0])]

    def angle_vector(self, vector=None, ms: float = 1.0, clear: bool = False, id: str | None = None):
        """With a vector: queue it, reached in ``ms`` (``sequence propocmd``; ``clear`` = EusLisp's
        ``:overwrite t``); returns the id. Without: the robot's measured angle vector."""
        if vector is None:
            return self.state("angle-vector")["angle-vector"]
        values = " ".join(fmt(v) for v in np.ravel(vector))
        line = f"sequence propocmd #f({values}) {fmt(ms)}" + (" :clear" if clear else "") + (f" @{id}" if id else "")
        self.command(line)
        return id

    def state(self, *keys: str) -> dict:
        """The latest packet (all keys, or those given, e.g. ``state("tension")``)."""
        return parse_state(self.command("state" + "".join(" " + k for k in keys)))

    def wait(self, id: str | None = None, timeout_ms: float | None = None) -> str:
        """Until the motion ``id`` (or all of this connection's) has ended."""
        line = "wait " + (id or "all") + (f" {fmt(timeout_ms)}" if timeout_ms is not None else "")
        timeout = self.timeout + (timeout_ms or 60_000.0) / 1e3
        return self.command(line, timeout=timeout)

    def interpolation_method(self, name: str | None = None) -> str:
        """Switch the sequence's interpolation (or read it)."""
        if name is None:
            return self.command("(send *ns* :interpolation-method)")
        return self.command(f"sequence switch {name}")

    def stream(self, period_ms: float | None = None, *keys: str) -> str:
        return self.command("stream on" + (f" {fmt(period_ms)}" if period_ms is not None else "")
                            + "".join(" " + k for k in keys))

    def stream_off(self) -> str:
        return self.command("stream off")

    def collect(self, count: int, timeout: float | None = None) -> list[dict]:
        """Read until ``count`` new state lines have arrived; returns them."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        got: list[dict] = []
        while len(got) < count:
            line = self.read_line(max(0.0, deadline - time.monotonic()))
            if line.startswith("state "):
                s = parse_state(line[6:])
                self.states.append(s)
                got.append(s)
            elif not self._note(line):
                raise NerveError(f"a reply nobody asked for: {line[:80]!r}")
        return got
