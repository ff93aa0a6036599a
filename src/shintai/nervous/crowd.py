"""Several client programs on one nervous server at once (seed 003 §6.3.3: "上位層のプログラムからのマルチコネク
ションを受け入れ"; C.2.2: "一つの nervous に二つ以上のソケットをつなぐ事もできる (EusLisp が二つ等)").

Each role is a function run on its own thread with its own connection; each returns what it saw:

* :func:`commander` — queues postures with ``@ID`` and waits for each (the upper layer's behaviour program);
* :func:`overrider` — a second program that, midway, replaces the first one's queue (``:clear``, EusLisp's
  ``:overwrite t``): the first hears ``done ID cleared`` for what it lost;
* :func:`watcher` — streams every packet and reads them all (a viewer, a logger);
* :func:`sleeper` — streams and never reads (a program that hung): its lines are dropped, not queued;
* :func:`pest` — sends malformed lines, NaN vectors and shell commands: each gets one ``error:`` line;
* :func:`flaky` — streams and drops its connection abruptly, again and again.
"""

from __future__ import annotations

import socket
import struct
import time

import numpy as np

from shintai.nervous.client import NerveClient, NerveError
from shintai.nervous.protocol import fmt

BAD_LINES = ("rm -rf /", "sequence propocmd #f(1 nan 3) 100", "sequence propocmd #f(1 2) 100", "(send *ns*",
             "(progn (unix:system \"reboot\"))", "sequence propocmd #f(0) -5", "\u00ff\u00fe garbage", "stream sideways")


def _vector(values) -> str:
    return "#f(" + " ".join(fmt(v) for v in values) + ")"


def commander(port: int, postures, ms: float, start) -> dict:
    with NerveClient(port=port, timeout=30) as c:
        start.wait()
        round_trips, outcomes = [], []
        for k, posture in enumerate(postures):
            t0 = time.perf_counter()
            c.command(f"sequence propocmd {_vector(posture)} {fmt(ms)} @a{k}")
            round_trips.append(time.perf_counter() - t0)
            outcomes.append(c.wait(f"a{k}").split(":")[1])
        return {"lines": 2 * len(postures), "replies": 2 * len(postures), "outcomes": outcomes,
                "round_trip_ms": 1e3 * np.array(round_trips), "done": dict(c.done)}


def overrider(port: int, posture, ms: float, after_s: float, start) -> dict:
    with NerveClient(port=port, timeout=30) as c:
        start.wait()
        time.sleep(after_s)
        c.command(f"(send *ns* :angle-vector {_vector(posture)} {fmt(ms)} :overwrite t) @b")
        outcome = c.wait("b")
        method = c.command("(send *ns* :interpolation-method)")
        return {"lines": 3, "replies": 3, "outcome": outcome, "method": method}


def watcher(port: int, seconds: float, start) -> dict:
    with NerveClient(port=port, timeout=30) as c:
        start.wait()
        c.stream()
        states = []
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            states.extend(c.collect(1))
        c.stream_off()
        seqs = np.array([s["seq"] for s in states])
        return {"lines": 2, "replies": 2, "received": len(seqs), "span": int(seqs[-1] - seqs[0] + 1) if len(seqs) else 0,
                "gaps": int(np.sum(np.diff(seqs) != 1)) if len(seqs) > 1 else 0}


def sleeper(port: int, seconds: float, start) -> dict:
    sock = socket.create_connection(("127.0.0.1", port), timeout=30)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    start.wait()
    sock.sendall(b"stream on\n")
    time.sleep(seconds)
    sock.close()
    return {"lines": 1, "replies": None}


def pest(port: int, seconds: float, start) -> dict:
    with NerveClient(port=port, timeout=30) as c:
        start.wait()
        sent = errors = 0
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            for line in BAD_LINES:
                sent += 1
                try:
                    c.command(line)
                except NerveError:
                    errors += 1
            time.sleep(0.02)
        return {"lines": sent, "replies": sent, "errors": errors}


def flaky(port: int, seconds: float, start) -> dict:
    start.wait()
    connections = 0
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        with NerveClient(port=port, timeout=30) as c:
            c.stream()
            c.collect(20)
            c.sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))  # reset, no goodbye
            connections += 1
    return {"lines": connections, "replies": connections, "connections": connections}
