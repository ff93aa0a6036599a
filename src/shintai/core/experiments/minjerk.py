"""``core.minjerk``: the minimum-jerk interpolator and the seqplugin sequence player (seed 003 §6.3.4,
App. C.2.2; spec 003-part2 §2.3.5–2.3.6) — boundary conditions, re-targeting, queue, Hoff–Arbib. Pure
interpolation, no body: a compute experiment."""

from __future__ import annotations

import numpy as np

from shintai.core.interpolation import Segment, SequencePlayer, hoff_arbib_jerk
from shintai.core.plots import plot_minjerk
from shintai.scenarios.registry import Check, Param, scenario

def _random_boundary(rng, dof):
    return [rng.uniform(-1, 1, dof) for _ in range(6)] + [rng.uniform(0.2, 3.0)]


def boundary_error(rng, trials: int, dof: int = 3) -> float:
    """Largest deviation of a quintic from its boundary x, v, a at t = 0 and t = T."""
    worst = 0.0
    for _ in range(trials):
        x0, v0, a0, xf, vf, af, T = _random_boundary(rng, dof)
        seg = Segment.minjerk(x0, v0, a0, xf, vf, af, T)
        for got, want in zip(seg.state(0.0) + seg.state(T), (x0, v0, a0, xf, vf, af)):
            worst = max(worst, float(np.abs(got - want).max()))
    return worst


def retarget_jumps(rng, method: str, retargets: int, dt: float, recorder=None):
    """Re-target a player mid-motion ``retargets`` times; return the largest jump in (x, v, a)
    between the state just before and just after each re-target, and the sampled trajectory."""
    player = SequencePlayer(np.zeros(2), method=method)
    player.push(rng.uniform(-1, 1, 2), 1.0)
    jumps = np.zeros(3)
    t, samples = 0.0, []
    for _ in range(retargets):
        for _ in range(int(rng.uniform(0.2, 0.8) / dt)):
            t += dt
            player.advance(dt)
            samples.append((t, *player.state))
        before = player.state
        player.push(rng.uniform(-1, 1, 2), rng.uniform(0.5, 1.5), clear=True)
        after = player.segment.state(0.0)
        if method == "linear":
            after = (after[0], player.segment.coeffs[1], np.zeros(2))
        jumps = np.maximum(jumps, [np.abs(b - a).max() for b, a in zip(before, after)])
    while player.busy:
        t += dt
        player.advance(dt)
        samples.append((t, *player.state))
    return jumps, samples


def queue_arrival_error(rng, dt: float) -> float:
    """Queue three postures at once: each must be reached at its scheduled time (seqplugin queue)."""
    player = SequencePlayer(np.zeros(3))
    targets = [rng.uniform(-1, 1, 3) for _ in range(3)]
    durations = [0.25, 0.1, 0.25]  # Fig. C.1 spacing, in seconds
    for x, T in zip(targets, durations):
        player.push(x, T)
    worst = 0.0
    for x, T in zip(targets, durations):
        steps = int(round(T / dt))
        for _ in range(steps):
            player.advance(dt)
        worst = max(worst, float(np.abs(player.x - x).max()))
    return worst


def hoff_arbib_deviation(rng, dt: float) -> float:
    """Integrate the online Hoff–Arbib jerk law (RK4) and compare with the closed-form quintic."""
    x0, v0, a0 = rng.uniform(-1, 1, 3)
    xf, T = rng.uniform(-1, 1), 1.0
    seg = Segment.minjerk(x0, v0, a0, xf, 0.0, 0.0, T)
    s = np.array([x0, v0, a0])

    def f(state, t):
        return np.array([state[1], state[2], hoff_arbib_jerk(state[0], state[1], state[2], xf, T - t)])

    t, worst = 0.0, 0.0
    while T - t > 2 * dt:
        k1 = f(s, t)
        k2 = f(s + dt / 2 * k1, t + dt / 2)
        k3 = f(s + dt / 2 * k2, t + dt / 2)
        k4 = f(s + dt * k3, t + dt)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t += dt
        worst = max(worst, abs(s[0] - seg.state(t)[0]))
    return worst


@scenario(
    "core.minjerk",
    source="seed 003 §6.3.4, App. C.2.2 (seqplugin)",
    summary="minimum-jerk interpolation: boundary conditions, continuous re-targeting, queue, Hoff–Arbib",
    params=[
        Param("trials", 200, "random boundary-condition segments", lo=1, hi=100000),
        Param("retargets", 20, "mid-motion re-targets", lo=1, hi=10000),
        Param("dt", 0.001, "sample period [s] (seqplugin runs at the sensor period)", lo=1e-5, hi=0.05),
    ],
    checks=[
        Check("max_boundary_error", "<=", 1e-9, "issue 2: boundary conditions within 1e-9", kind="consistency"),
        Check("max_jump_pos", "<=", 1e-9, "re-planning from the current state keeps position continuous", kind="consistency"),
        Check("max_jump_vel", "<=", 1e-9, "… and velocity", kind="consistency"),
        Check("max_jump_acc", "<=", 1e-9, "… and acceleration", kind="consistency"),
        Check("linear_max_jump_vel", ">", 1e-3, "sanity: the jump metric sees the velocity step of linear interpolation", kind="consistency"),
        Check("queue_arrival_error", "<=", 1e-9, "seqplugin: each queued posture reached at its time", kind="consistency"),
        Check("hoff_arbib_max_dev", "<=", 1e-6, "the online Hoff–Arbib law integrates to the same quintic (RK4 at dt)", kind="consistency"),
    ],
    demo=True,
    estimate_s=1.0,
    smoke={"trials": 20, "retargets": 3},
)
def minjerk_scenario(ctx):
    p = ctx.params
    rng = ctx.rng
    jumps, samples = retarget_jumps(rng, "minjerk", p["retargets"], p["dt"])
    lin_jumps, _ = retarget_jumps(rng, "linear", p["retargets"], p["dt"])
    for t, x, v, a in samples:
        ctx.recorder.record(t, x=x, v=v, a=a)
    ctx.sim_time_s = samples[-1][0]
    plot_minjerk(ctx, samples)
    return {
        "max_boundary_error": boundary_error(rng, p["trials"]),
        "max_jump_pos": float(jumps[0]),
        "max_jump_vel": float(jumps[1]),
        "max_jump_acc": float(jumps[2]),
        "linear_max_jump_vel": float(lin_jumps[1]),
        "queue_arrival_error": queue_arrival_error(rng, p["dt"]),
        "hoff_arbib_max_dev": hoff_arbib_deviation(rng, p["dt"]),
    }
