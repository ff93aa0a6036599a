"""``nervous.fig-c1``: Fig. C.1 — the seqplugin's minjerksequence trace, sent over a socket to a nervous server
and played on the simulated 3-DOF arm (seed 003 App. C.2.2). A compute experiment: a server on its thread and
a client, not one loop."""

from __future__ import annotations

import numpy as np

from shintai.core.interpolation import SequencePlayer
from shintai.nervous.client import NerveClient
from shintai.nervous.nerve import Nerve
from shintai.nervous.plots import plot_fig_c1
from shintai.nervous.plugins.sequence import VIA_RULES
from shintai.nervous.server import ServerThread
from shintai.scenarios.registry import REPRODUCTION, Check, Param, ThesisValue, scenario

FIG_C1 = ((250, 60.0), (350, 120.0), (600, 60.0), (850, 0.0))  # App. C.2.2: (time [ms], position)
RUNS = {"minjerksequence": ("minjerksequence", "balanced"), "minjerk": ("minjerk", "balanced"),
        "turning": ("minjerksequence", "turning")}  # label → (method, via rule)
RC = ["load-plugin seqplugin", "create-plugin sequence sequence", "start sequence"]  # App. C.2.2's .nervousrc


def play(client: NerveClient, label: str, method: str, via: str) -> float:
    """Queue Fig. C.1's targets at once (one write, so one packet sees them all); returns the start time."""
    client.command(f"sequence switch {method}")
    client.command(f"sequence via {via}")
    lines, last = ["state"], 0
    for k, (t, x) in enumerate(FIG_C1):
        lines.append(f"sequence propocmd #f({x:g} 0 0) {t - last} @{label}{k}")
        last = t
    client.send_line("\n".join(lines + ["state"]))
    first, *queued, after = [client.reply() for _ in lines + ["state"]]
    if queued != ["ok"] * len(FIG_C1) or first.split()[1] != after.split()[1]:
        raise RuntimeError(f"Fig. C.1's targets were not queued in one packet: {first!r} … {after!r}")
    client.wait(f"{label}{len(FIG_C1) - 1}")
    client.command("sequence propocmd #f(0 0 0) 300 @back")
    client.wait("back")
    return float(first.split()[1].removeprefix("t="))


def expected(method: str, via: str, times: np.ndarray) -> np.ndarray:
    """The same queue on the interpolator alone (core.interpolation), at ``times`` after the start."""
    player = SequencePlayer(np.zeros(1), method=method, via=VIA_RULES[via])
    last = 0
    for t, x in FIG_C1:
        player.push([x], (t - last) / 1e3)
        last = t
    out, now = [], 0.0
    for t in times:
        out.append(player.advance(t - now)[0])
        now = t
    return np.array(out)


@scenario(
    "nervous.fig-c1",
    source="seed 003 App. C.2.2, Fig. C.1",
    summary="Fig. C.1 over a socket: the seqplugin plays 60 @250 ms, 120 @350, 60 @600, 0 @850 with minjerksequence",
    params=[Param("servo_kp", 40.0, "the arm's servo stiffness [N m/rad] (servo plugin)", lo=1.0, hi=1000.0)],
    checks=[
        Check("via_speed_min_minjerksequence_deg_s", ">", 50.0, "App. C.2.2: with minjerksequence a posture second "
              "or later in the queue starts 'を 0 でなく前のキューとバランスするような速度' — not zero (50 deg/s: 1/10 of "
              "the slowest segment's mean speed)", kind=REPRODUCTION),
        Check("via_speed_max_minjerk_deg_s", "<", 1.0, "App. C.2.2: 'minjerk や linear では各姿勢の境目で速度が"
              "ゼロになる' (1 deg/s: the 1 ms central difference of a zero)", kind=REPRODUCTION),
        Check("knot_error_deg", "<=", 1e-6, "consistency: each target is reached at its time (the queue honoured)",
              kind="consistency"),
        Check("end_speed_minjerksequence_deg_s", "<", 1.0, "consistency: the last posture is reached at rest",
              kind="consistency"),
        Check("played_vs_interpolator_deg", "<=", 1e-6, "consistency: the server plays exactly what the "
              "interpolator computes (sent over TCP, run per packet)", kind="consistency"),
        Check("done_in_order", "==", 1, "consistency: done ID arrives for every queued posture, in order",
              kind="consistency"),
    ],
    thesis={"targets": ThesisValue("(0, 0), (250, 60), (350, 120), (600, 60), (850, 0) — time, position (units "
                                   "not stated)", "seed 003 App. C.2.2, Fig. C.1"),
            "velocity": ThesisValue("minjerk/linear: 0 at every posture; minjerksequence: not 0 at a queued "
                                    "posture, 'balanced' with the previous entry (rule not given)",
                                    "seed 003 App. C.2.2")},
    covers=("003:figC.1",),
    video=False,
    smoke={},
)
def fig_c1(ctx):
    p = ctx.params
    nerve = Nerve("arm3", "sim", log_dir=ctx.out)
    traces, done_ok = {}, True
    with ServerThread(nerve) as server, NerveClient(port=server.port, timeout=30) as client:
        for line in RC + ["load-plugin servo", "create-plugin servo servo", f"servo set kp {p['servo_kp']}",
                          "load-plugin log", "create-plugin lg log fig_c1_log.txt", "start lg"]:
            client.command(line)
        for label, (method, via) in RUNS.items():
            start = play(client, label, method, via)
            traces[label] = start
            done_ok &= client.finished[-len(FIG_C1) - 1:-1] == [f"{label}{k}" for k in range(len(FIG_C1))]
        client.command("stop lg")
    log = np.genfromtxt(ctx.out / "fig_c1_log.txt", names=True)
    period = nerve.interface.period
    metrics, curves = {}, {}
    for label, (method, via) in RUNS.items():
        rel = log["t"] - traces[label]
        rows = (rel >= -1e-9) & (rel <= FIG_C1[-1][0] / 1e3 + 1e-9)
        t = np.round(rel[rows] / period) * period
        x, measured = log["target_0"][rows], log["angle_vector_0"][rows]
        v = np.gradient(x, t)
        knots = [int(round(k / 1e3 / period)) for k, _ in FIG_C1]
        curves[label] = (t, x, v, measured)
        via_speed = np.abs(v[knots[:-1]])
        metrics[f"via_speed_min_{label}_deg_s"] = float(via_speed.min())
        metrics[f"via_speed_max_{label}_deg_s"] = float(via_speed.max())
        metrics[f"knot_error_{label}_deg"] = float(np.abs(x[knots] - [q for _, q in FIG_C1]).max())
        metrics[f"end_speed_{label}_deg_s"] = float(abs(v[-1]))
        metrics[f"played_vs_interpolator_{label}_deg"] = float(np.abs(x - expected(method, via, t)).max())
        metrics[f"peak_{label}_deg"] = float(x.max())
        metrics[f"servo_lag_max_{label}_deg"] = float(np.abs(measured - x).max())
    metrics["knot_error_deg"] = max(metrics[f"knot_error_{k}_deg"] for k in RUNS)
    metrics["played_vs_interpolator_deg"] = max(metrics[f"played_vs_interpolator_{k}_deg"] for k in RUNS)
    metrics["done_in_order"] = int(done_ok)
    ctx.sim_time_s = float(log["t"][-1])
    for label, (t, x, v, measured) in curves.items():
        for ti, xi, vi, mi in zip(t, x, v, measured):
            ctx.recorder.record(float(ti), **{f"{label}.x": xi, f"{label}.v": vi, f"{label}.measured": mi})
    plot_fig_c1(ctx, curves, FIG_C1)
    return metrics
