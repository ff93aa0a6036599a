"""The Ninebot's figures (seed 000 §7.3.3): Figs. 7.7–7.10 (stabilizer only, learning) and 7.11–7.12 (free
riding). Each scenario figure takes ``(ctx, runs, params)``."""

from __future__ import annotations

import numpy as np

from shintai.humanoid.unicycle.constants import V_DIVERGED
from shintai.humanoid.unicycle.rig import series, zmp_errors


def draw_learning(ax, run, label: str) -> None:
    """Fig. 7.9 (b)–(e) and Fig. 7.10 of one run on 5 axes."""
    ride, log = run.state, run.log
    t0 = ride.t0
    for a, mod, sym in ((ax[0], ride.traj, "traj"), (ax[1], ride.speed, "v")):
        if mod is None:
            continue
        t, g = series(log, f"{mod.name}.gains")
        g = g.reshape(-1, 3)
        for i, (name, c) in enumerate((("K_P", "r"), ("K_I", "g"), ("K_D", "b"))):
            a.plot(t - t0, g[:, i], c, label=f"{name}^{sym}(n)")
        a.set_ylabel(f"({'b' if sym == 'traj' else 'c'}) {sym} gains")
        a.legend(fontsize=7)
    ax[0].set_title(label)
    t, v = log.times("true_v") - t0, log.values("true_v")
    tv, vd = series(log, "speed.e")
    ax[2].plot(t, v, "g--", label="act v (truth)")
    ax[2].axhline(0.0, color="r", label="ref v")
    ax[2].set_ylabel("(d) v [m/s]")
    ax[2].legend(fontsize=7)
    for mod, style in ((ride.traj, "r-o"), (ride.speed, "b-s")):
        if mod is not None and mod.mlc.batches:
            b = mod.mlc.batches
            ax[3].semilogy([x.t_end - t0 for x in b], [max(x.J, 1e-12) for x in b], style, ms=3,
                           label=f"J ({mod.name}; both see the one e_v)")
    ax[3].set_ylabel("(e) J (Eq. 6.17)")
    ax[3].legend(fontsize=7)
    _, _, tz, zd, za = zmp_errors(run, t0)
    ax[4].plot(tz, zd * 1e3, "r", label="fin ref ZMP x (p^{d**})")
    ax[4].plot(tz, za * 1e3, "g--", lw=0.8, label="act ZMP x")
    ax[4].set_ylabel("Fig. 7.10: ZMP x [mm]")
    ax[4].set_ylim(np.nanpercentile(za * 1e3, 1) - 20, np.nanpercentile(za * 1e3, 99) + 20) if za.size else None
    ax[4].legend(fontsize=7)
    ax[4].set_xlabel("t [s] from the release")


def free(ctx, runs, step_at: float, v_step: float):
    """Fig. 7.13 per variant (columns): v^d and v; the unicycle's roll, φ_C^d and the hand's force; the correction."""
    with ctx.figure("fig7_13", 3, len(runs), figsize=(8 * len(runs), 9), sharex="col", squeeze=False) as (_fig, ax):
        for j, (name, run) in enumerate(runs.items()):
            ride, log = run.state, run.log
            t = log.times("true_v") - ride.t0
            col = ax[:, j]
            col[0].plot(t, np.where(t >= step_at, v_step, 0.0), "r", label="ref v")
            col[0].plot(t, log.values("true_v"), "g--", label="act v (truth)")
            col[0].set_ylabel("v [m/s]")
            col[0].set_title(f"Fig. 7.13, {name}: no training wheels, learned gains; t = 0 at the release")
            col[1].plot(t, np.degrees(log.values("roll")), "k", label="unicycle roll")
            if ride.roll is not None and "roll.target" in log.names():
                col[1].plot(log.times("roll.target") - ride.t0, np.degrees(log.values("roll.target")), "m",
                            label="φ_C^d (Eq. 7.6)")
            col[1].set_ylabel("roll [deg]")
            if ride.hand is not None:
                hand = col[1].twinx()
                hand.fill_between(t, log.values("hand_n"), color="orange", alpha=0.3, label="hand [N]")
                hand.set_ylabel("hand force [N]")
                hand.legend(fontsize=7, loc="lower right")
            col[2].plot(t, log.values("zmp_mod") * 1e3, "b", label="correction p^{d**} − p^{d*} [mm]")
            col[2].set_xlabel("t [s] from the release")
            for a in col:
                a.legend(fontsize=7)


def learning(ctx, runs, params):
    with ctx.figure("fig7_9_7_10", 5, len(runs), figsize=(6 * len(runs), 14), sharex="col", squeeze=False) as (_f, ax):
        for j, (name, run) in enumerate(runs.items()):
            draw_learning(ax[:, j], run, f"{name} (Fig. 7.9 (b)–(e), Fig. 7.10)")


def no_learning(ctx, runs, params):
    run = runs["run"]
    ride, log = run.state, run.log
    t = log.times("true_v") - ride.t0
    with ctx.figure("speed", 3, 1, figsize=(9, 9), sharex=True) as (_fig, ax):
        ax[0].plot(t, log.values("true_v"), "g", label="v (truth)")
        for s in (1, -1):
            ax[0].axhline(s * V_DIVERGED, color="0.6", ls=":")
        ax[0].set_ylabel("v [m/s]")
        ax[0].set_title("Fig. 7.7: stabilizer only, training wheels; t = 0 at the release")
        ax[1].plot(t, log.values("zmp_act_x") * 1e3, "b", label="rider's ZMP x from p⁰ (M_y⁰/W, Eq. A.5)")
        ax[1].set_ylabel("ZMP x [mm]")
        ax[2].plot(t, log.values("x"), "k", label="unicycle x")
        ax[2].set_ylabel("travel [m]")
        ax[2].set_xlabel("t [s] from the release")
        for a in ax:
            a.legend(fontsize=7)
