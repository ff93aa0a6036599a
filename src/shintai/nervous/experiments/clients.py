"""``nervous.clients``: several client programs command and stream at once on one nervous server running the
simulated HRP2 humanoid in real time (seed 003 §6.3.3, App. C.2.2). A compute experiment: a server and nine
client threads, not one loop."""

from __future__ import annotations

import re
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from shintai.nervous import crowd
from shintai.nervous.client import NerveClient
from shintai.nervous.nerve import Nerve
from shintai.nervous.plots import plot_clients
from shintai.nervous.server import ServerThread
from shintai.scenarios.registry import REPRODUCTION, Check, Param, ThesisValue, scenario

RC = ["load-plugin seqplugin", "create-plugin sequence sequence", "start sequence"]
WATCHERS = 4


def postures(description, count: int) -> list[np.ndarray]:
    """Arm swings (shoulder pitch ±30°, elbow −20…−50°) from the standing posture, the legs kept."""
    base = description.initial
    out = []
    for k in range(count):
        v = base.copy()
        for i, name in enumerate(description.names):
            if name.endswith("shoulder_pitch"):
                v[i] = 30.0 * (-1) ** k
            elif name.endswith("elbow_pitch"):
                v[i] = -20.0 - 30.0 * (k % 2)
        out.append(v)
    return out


@scenario(
    "nervous.clients",
    source="seed 003 §6.3.3, App. C.2.2",
    summary="nine clients at once on the real-time HRP2: two command, four stream, one hangs, one sends junk, "
            "one drops its connection again and again",
    params=[Param("seconds", 3.0, "how long the streaming clients stay [s]", lo=0.5, hi=60.0),
            Param("postures", 8, "postures the commander queues", lo=1, hi=100),
            Param("move_ms", 250.0, "time to each posture [ms]", lo=10.0, hi=5000.0)],
    checks=[
        Check("replies_per_line", "==", 1.0, "DESIGN.md contract: every non-empty, non-comment line gets exactly one "
              "ok/error line", kind="consistency"),
        Check("both_commanders_served", "==", 1, "spec 003-part2 §10 check 6 / §6.3.3: two programs command at once "
              "and both are accepted ('マルチコネクションを受け入れ')", kind=REPRODUCTION),
        Check("watcher_received_fraction_min", ">=", 0.95, "§6.3.3: the state is sent 'センサ周期と同じ周期で' to "
              "each connection — every streaming client gets ≥ 95 % of the packets", kind=REPRODUCTION),
        Check("sleeper_dropped", ">", 0, "consistency: a client that never reads loses stream lines…",
              kind="consistency"),
        Check("outbox_max", "<=", "max_queue_plus_one", "consistency: …and its queue stays bounded",
              kind="consistency"),
        Check("pest_error_fraction", "==", 1.0, "consistency: every malformed line, NaN vector and shell command "
              "is one error", kind="consistency"),
        Check("period_mean_ms", "<=", 4.2, "consistency: the 4 ms packet loop keeps its pace under the load",
              kind="consistency"),
    ],
    thesis={"connections": ThesisValue("several sockets on one nervous, one reader thread each", "seed 003 C.2.2"),
            "stream": ThesisValue("state sent at the sensor period to each connection", "seed 003 §6.3.3")},
    video=False,
    smoke={"seconds": 0.5, "postures": 2},
)
def clients(ctx):
    p = ctx.params
    nerve = Nerve("hrp2", "sim", realtime=True)
    # a 64 KiB kernel send buffer per client (chosen): the sleeper's socket fills within the run
    with ServerThread(nerve, send_buffer=65536) as server:
        with NerveClient(port=server.port) as setup:
            for line in RC + ["sequence switch minjerksequence"]:
                setup.command(line)
        poses = postures(nerve.description, p["postures"])
        start = threading.Barrier(9)
        s = p["seconds"]
        roles = {
            "commander": lambda: crowd.commander(server.port, poses, p["move_ms"], start),
            "overrider": lambda: crowd.overrider(server.port, nerve.description.initial, 500.0,
                                                 0.5 * p["postures"] * p["move_ms"] / 1e3, start),
            **{f"watcher{i}": (lambda: crowd.watcher(server.port, s, start)) for i in range(WATCHERS)},
            "sleeper": lambda: crowd.sleeper(server.port, s, start),
            "pest": lambda: crowd.pest(server.port, s, start),
            "flaky": lambda: crowd.flaky(server.port, s, start),
        }
        outbox = []
        probe = threading.Thread(target=lambda: _watch_outboxes(server, s, outbox), daemon=True)
        probe.start()
        with ThreadPoolExecutor(len(roles)) as pool:
            futures = {name: pool.submit(fn) for name, fn in roles.items()}
            seen = {name: f.result(timeout=120 + 10 * s) for name, f in futures.items()}
        probe.join(timeout=10)
        with NerveClient(port=server.port) as last:
            stats = last.command("stats")
        ctx.sim_time_s = nerve.interface.state.t
    numbers = dict(re.findall(r"(\w+)=([\d./]+)", stats))
    period = [float(x) for x in numbers["period_ms"].split("/")]
    lines = sum(v["lines"] for v in seen.values() if v["replies"] is not None)
    replies = sum(v["replies"] for v in seen.values() if v["replies"] is not None)
    watchers = [seen[f"watcher{i}"] for i in range(WATCHERS)]
    outcomes = seen["commander"]["outcomes"]
    plot_clients(ctx, seen, WATCHERS)
    return {
        "replies_per_line": replies / lines,
        "both_commanders_served": int(seen["overrider"]["outcome"] == "b:done"
                                      and all(o in ("done", "cleared") for o in outcomes)),
        "commander_done": outcomes.count("done"), "commander_cleared": outcomes.count("cleared"),
        "command_round_trip_mean_ms": float(np.mean(seen["commander"]["round_trip_ms"])),
        "command_round_trip_max_ms": float(np.max(seen["commander"]["round_trip_ms"])),
        "watcher_received_fraction_min": min(w["received"] / max(w["span"], 1) for w in watchers),
        "watcher_gaps_total": sum(w["gaps"] for w in watchers),
        "sleeper_dropped": int(numbers["dropped"]),
        "outbox_max": max(outbox) if outbox else 0, "max_queue_plus_one": server.server.max_queue + 1,
        "pest_error_fraction": seen["pest"]["errors"] / seen["pest"]["lines"],
        "pest_lines": seen["pest"]["lines"], "flaky_connections": seen["flaky"]["connections"],
        "packets": int(numbers["packets"]), "period_mean_ms": period[1], "period_max_ms": period[2],
        "overruns": int(numbers["overruns"]), "late": int(numbers["late"]),
    }


def _watch_outboxes(server, seconds, out) -> None:
    end = threading.Event()
    for _ in range(int(seconds / 0.05)):
        out.append(server.call(lambda: max((len(c.outbox) for c in server.server.connections), default=0)))
        end.wait(0.05)
