"""``nervous.loop``: what nervous costs per sensor packet, how fast a command reaches the target, how many state
lines it streams — each measured in one run and reported against the 1 ms packet period (seed 003 §6.4.2:
the on-body control cycle is 1 ms; the thesis gives no packet period for nervous itself).

* tick cost with 0, 5 and 20 running plugins (``null``, no work of their own) besides the ``sequence`` playing a
  motion: on the dummy interface (nervous's own cost: loop, plugins, bookkeeping) against the bare interface
  calls (GetRobotState + SetAngleVector), and on the simulated Cla (the body stepped, its 1 ms muscle control
  running), each as a fraction of the 1 ms period;
* command line → first changed target: a client on a real-time 1 ms server streams the sent vector and sends
  ``sequence propocmd`` (1 ms); the wall time until a state line shows the new target;
* stream throughput: 10 clients streaming every packet from an as-fast-as-possible server, for 2 s.
"""

from __future__ import annotations

import subprocess
import sys
import time

import numpy as np

from shintai.nervous.client import NerveClient
from shintai.nervous.commands import Client
from shintai.nervous.nerve import Nerve
from shintai.nervous.server import ServerThread
from shintai.scenarios.registry import benchmark

RC = ["load-plugin seqplugin", "create-plugin sequence sequence", "start sequence", "load-plugin null"]
PERIOD_S = 1e-3


def nerve_with(robot: str, interface: str, plugins: int, realtime: bool = False) -> Nerve:
    nerve = Nerve(robot, interface, realtime=realtime)
    client = Client()
    for line in RC + [f"create-plugin n{k} null" for k in range(plugins)] + [f"start n{k}" for k in range(plugins)]:
        reply = nerve.execute(line, client)
        assert reply.text.startswith("ok"), reply.text
    target = " ".join("1" for _ in range(nerve.description.n))
    nerve.execute(f"sequence propocmd #f({target}) 60000", client)  # a motion plays the whole time
    return nerve


def tick_cost(robot: str, interface: str, plugins: int, ticks: int, repeats: int = 3) -> float:
    """Mean wall time of one packet [s] (the best of ``repeats`` runs: the machine is shared)."""
    best = float("inf")
    for _ in range(repeats):
        nerve = nerve_with(robot, interface, plugins)
        for _ in range(200):
            nerve.tick()
        t0 = time.perf_counter()
        for _ in range(ticks):
            nerve.tick()
        best = min(best, (time.perf_counter() - t0) / ticks)
    return best


def bare_cost(robot: str, interface: str, ticks: int, repeats: int = 3) -> float:
    """The interface alone: SetAngleVector + GetRobotState per packet [s] (best of ``repeats``)."""
    best = float("inf")
    for _ in range(repeats):
        i = Nerve(robot, interface).interface
        v = i.description.initial + 1.0
        t0 = time.perf_counter()
        for _ in range(ticks):
            i.set_angle_vector(v)
            i.get_robot_state()
        best = min(best, (time.perf_counter() - t0) / ticks)
    return best


def latency(trials: int) -> np.ndarray:
    """Command line → first state line showing the changed target [s], on a real-time 1 ms dummy arm."""
    nerve = nerve_with("arm3", "dummy", 0, realtime=True)
    out = []
    with ServerThread(nerve) as server, NerveClient(port=server.port, timeout=10) as c:
        c.command("sequence propocmd #f(0 0 0) 1 :clear")
        c.stream(None, "reference")
        for k in range(trials):
            value = 10.0 + k % 2
            c.collect(3)
            t0 = time.perf_counter()
            c.send_line(f"sequence propocmd #f({value:g} 0 0) 1")
            while True:
                line = c.read_line()
                if line.startswith("state ") and f"reference={value:g}," in line:
                    out.append(time.perf_counter() - t0)
                    break
    return np.array(out)


READER = """
import socket, sys, time
port, start, seconds = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
sock = socket.create_connection(("127.0.0.1", port), timeout=30)
sock.sendall(b"stream on\\n")
lines = 0
while time.time() < start:
    sock.recv(1 << 20)  # the reply and the lines before the start are not counted
while time.time() < start + seconds:
    lines += sock.recv(1 << 20).count(b"\\n")  # every line now is a state line
print(lines)
"""


def throughput(clients: int, seconds: float) -> dict:
    """``clients`` reader processes (not threads: the readers must not share the server's interpreter) stream
    every packet from an as-fast-as-possible dummy server for ``seconds``."""
    nerve = nerve_with("arm3", "dummy", 0)
    with ServerThread(nerve) as server:
        start = time.time() + 1.0  # the readers start (a bare python, no imports but socket)
        readers = [subprocess.Popen([sys.executable, "-c", READER, str(server.port), str(start), str(seconds)],
                                    stdout=subprocess.PIPE, text=True) for _ in range(clients)]
        time.sleep(max(0.0, start - time.time()))
        seq0 = nerve.interface.state.seq
        time.sleep(seconds)
        packets = nerve.interface.state.seq - seq0
        counts = [int(r.communicate(timeout=60)[0].strip() or 0) for r in readers]
        dropped = nerve.dropped_gone + sum(c.dropped for c in nerve.clients)
    total = sum(counts)
    return {"stream_clients": clients, "stream_lines_per_s_total": total / seconds,
            "stream_lines_per_s_per_client": total / seconds / clients, "stream_packets_per_s": packets / seconds,
            "stream_received_fraction": total / max(packets * clients, 1), "stream_dropped": dropped}


@benchmark("nervous.loop", "nervous per packet (0/5/20 plugins) vs the 1 ms period; command → target latency; "
           "stream throughput with 10 clients")
def nervous_loop(ticks: int = 5000, trials: int = 50, clients: int = 10, seconds: float = 2.0) -> dict:
    out: dict = {"packet_period_ms": 1e3 * PERIOD_S}
    bare = bare_cost("arm3", "dummy", ticks)
    out["dummy_bare_us"] = 1e6 * bare
    for n in (0, 5, 20):
        cost = tick_cost("arm3", "dummy", n, ticks)
        out[f"dummy_{n}_plugins_us"] = 1e6 * cost
        out[f"dummy_{n}_plugins_vs_period"] = cost / PERIOD_S
        out[f"dummy_{n}_plugins_vs_bare"] = cost / bare
    cla_bare = bare_cost("cla", "sim", ticks // 5)
    out["cla_bare_us"] = 1e6 * cla_bare
    for n in (0, 5, 20):
        cost = tick_cost("cla", "sim", n, ticks // 5)
        out[f"cla_{n}_plugins_us"] = 1e6 * cost
        out[f"cla_{n}_plugins_vs_period"] = cost / PERIOD_S
        out[f"cla_{n}_plugins_vs_bare"] = cost / cla_bare
    lat = latency(trials)
    out.update({"latency_median_ms": 1e3 * float(np.median(lat)), "latency_p90_ms": 1e3 * float(np.percentile(lat, 90)),
                "latency_max_ms": 1e3 * float(lat.max()), "latency_median_packets": float(np.median(lat)) / PERIOD_S})
    out.update(throughput(clients, seconds))
    return out
