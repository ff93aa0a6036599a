"""The V-BOARD's figures (seed 000 chs. 5–7): Figs. 5.6–5.8 (boarding), 6.3–6.4 (behaviour levels), 4.10 (B)
(chest posture), 6.9 (plant identification), 6.15–6.17 (speed governing, integrators) and 7.19–7.21 (SOLC).
Each takes the scenario's ``(ctx, runs, params)``."""

from __future__ import annotations

import math

import numpy as np

from shintai.humanoid.constants import CONTROL_PERIOD, DEG, DELTA_LIMIT, R_SAT_V
from shintai.humanoid.learning.speed_governing import lowpass
from shintai.humanoid.vboard.governed_ride import governor_series, increase_ticks, replay_integrator, unstable_intervals
from shintai.humanoid.vboard.governor import AXES
from shintai.humanoid.vboard.plant_id import identification, series, window
from shintai.humanoid.vboard.ride import theta_o, touchdown
from shintai.humanoid.vboard.constants import PROBE_AFTER
from shintai.humanoid.vboard.sign_chain import LINKS, chain_difference
from shintai.humanoid.vboard.solc import switch_times


def integrator_comparison(ctx, runs, params):
    with ctx.figure("fig6_17", 3, 1, figsize=(11, 10), sharex=True) as (_fig, ax):
        for m, style in (("corrected", "b--"), ("saturated", "g--")):
            if m not in runs:
                continue
            s = governor_series(runs[m].log, "v")
            t0 = runs[m].state.governor.t_start or 0.0
            t = s["t"] - t0
            ax[0].plot(t, s["uI"] * 1e3, style, label=f"u_I^v ×10³, {m} run (closed loop)")
            if m == "corrected":
                ax[1].plot(t, s["E"], "r", label="E_v(t), corrected integrator")
                ax[2].plot(t, s["uI"] * 1e3, "b--", label="u_I^v ×10³ corrected (Eq. 6.38)")
                ax[2].plot(t, replay_integrator(s, "saturated") * 1e3, "g--",
                           label=f"u_I^v ×10³ saturated r_sat = {R_SAT_V} on the same e_v, K_I^v(n) (Eq. 6.42)")
                for k in increase_ticks(s):
                    for a in ax:
                        a.axvline(t[k], color="0.85", lw=0.6)
        ax[0].set_title("closed-loop runs, one per integrator (grey: I-gain increases of the corrected run)")
        ax[2].set_title("Fig. 6.17: the corrected run's data replayed (the thesis's comparison)")
        for a in ax:
            a.legend(fontsize=7)
        ax[-1].set_xlabel("t [s] from the learning start")


def solc(ctx, runs, params):
    """Fig. 7.20: (a) D in the riding phase, (b) v's and (c) ω's PID gains, (d) J_v, J_ω per batch; Fig. 7.21: v, ω
    against v^d = ω^d = 0. Phases shaded: SLC grey, MLC none, DONE green."""
    run = runs["solc"]
    ride, log = run.state, run.log
    times = switch_times(ride.switcher)
    with ctx.figure("fig7_20", 4, 1, sharex=True, figsize=(9, 11)) as (_, ax):
        ax[0].plot(log.times("D_L"), log.values("D_L"), label="D (left pitch)")
        ax[0].plot(log.times("D_R"), log.values("D_R"), "--", label="D (right pitch)")
        ax[0].set_ylabel("(a) D [N·m·s/rad]")
        for j, a in enumerate(AXES):
            s = governor_series(log, a, "mlc")
            for i, (n, c) in enumerate(zip(("K_P", "K_I", "K_D"), "rgb", strict=True)):
                ax[1 + j].plot(s["t"], s["gains"][:, i] * 1e3, c, label=f"{n}^{a}")
            ax[1 + j].set_ylabel(f"({'bc'[j]}) {a} gains ×10⁻³")
            b = ride.governor.mlc[a].batches
            ax[3].semilogy([x.t_end for x in b], [max(x.J, 1e-12) for x in b], "o-", label=f"J_{a}")
        ax[3].set_ylabel("(d) J per batch")
        ax[3].set_xlabel("t [s] from the initial state on the floor")
    with ctx.figure("fig7_21", 2, 1, sharex=True, figsize=(9, 6)) as (_, ax2):
        for k, (a, key) in enumerate((("v [m/s]", "true_v"), ("ω [rad/s]", "true_omega"))):
            ax2[k].plot(log.times(key), log.values(key), "g", label="measured (truth)")
            ax2[k].axhline(0.0, color="r", label="target 0")
            ax2[k].set_ylabel(a)
        ax2[1].set_xlabel("t [s]")
    for a in list(ax) + list(ax2):
        a.axvspan(times["slc"], times["mlc"] if math.isfinite(times["mlc"]) else times["slc"], color="0.9", zorder=0)
        if math.isfinite(times["done"]):
            a.axvspan(times["done"], float(ride.body.t), color="#dfd", zorder=0)
        a.legend(fontsize=7)
        a.grid(alpha=0.3)


def _governed_run(ax, run, label: str):
    """Figs. 6.15–6.16 (b)–(f) of one run on a 5×2 grid of axes."""
    ride, log = run.state, run.log
    t0 = ride.governor.t_start or 0.0
    colors = {"K_P": "r", "K_I": "g", "K_D": "b"}
    for j, a in enumerate(AXES):
        s = governor_series(log, a)
        t = s["t"] - t0
        sym = "v" if a == "v" else "ω"
        for i, name in enumerate(("K_P", "K_I", "K_D")):
            ax[0, j].plot(t, s["gains"][:, i] * 1e3, colors[name], label=f"{name}^{sym}(n)")
        ax[0, j].set_ylabel(f"({'b1' if j == 0 else 'b2'}) gains ×10⁻³")
        ax[0, j].set_title(f"{label}: {sym}")
        tv = log.times("true_v") - t0
        ax[1, j].axhline(0.0, color="r", label=f"{sym}_d")
        ax[1, j].plot(t, -s["e"], "g--", lw=0.8, label=f"{sym} measured (Eq. 6.3 / gyro)")
        ax[1, j].plot(tv, log.values("true_v" if a == "v" else "true_omega"), color="0.5", lw=0.8, label="truth")
        ax[1, j].set_ylabel(f"(c) {sym} [{'m/s' if a == 'v' else 'rad/s'}]")
        ax[2, j].plot(t, s["E"], "r", label=f"E_{sym}(t)")
        ax[2, j].plot(t, s["uI"] * 1e3, "b--", label=f"u_I^{sym}(t) ×10³")
        ax[2, j].set_ylabel("(d) E, u_I")
        for a_, b in unstable_intervals(t, s["stable"]):
            ax[1, j].axvspan(a_, b, color="0.9")
    for j, a in enumerate(AXES):
        s = governor_series(log, a)
        style = ("m", "-") if a == "v" else ("g", "--")
        ax[3, 0].plot(s["t"] - t0, s["stable"], color=style[0], ls=style[1], label="v" if a == "v" else "ω")
        b = ride.governor.mlc[a].batches
        ax[3, 1].semilogy([x.t_end - t0 for x in b], [max(x.J, 1e-12) for x in b], color=style[0], ls=style[1],
                          marker="o", label=f"J_{'v' if a == 'v' else 'ω'}")
    ax[3, 0].set_ylabel("(e) Routh–Hurwitz (Eq. 6.41)")
    ax[3, 0].set_yticks([-1, 1])
    ax[3, 1].set_ylabel("(f) J (Eq. 6.17), per batch")
    th = log.values("foot_pitch.theta_R") if "foot_pitch.theta_R" in log.names() else None
    if th is not None:
        tt = log.times("foot_pitch.theta_R") - t0
        ax[4, 0].plot(tt, th / DEG, "r", label="Σ Δθ_R (governor + excitation)")
        ax[4, 0].plot(tt, log.values("foot_pitch.theta_L") / DEG, "b--", label="Σ Δθ_L")
    ax[4, 0].set_ylabel("commanded foot pitch [deg]")
    ax[4, 1].plot(log.times("x") - t0, log.values("x"), "k", label="scooter x [m]")
    ax[4, 1].set_ylabel("travel [m]")
    for row in ax:
        for x in row:
            x.legend(fontsize=6)
    for x in ax[-1]:
        x.set_xlabel("t [s] from the learning start")


def _boarding_run(ax, run):
    """Fig. 6.16-(a0)'s phase: the boarding before the learning — D of both foot pitches (SLC), the boards' pitch,
    the scooter's travel; t from the learning start (both feet landed)."""
    log, t0 = run.log, run.state.governor.t_start or 0.0
    for side in ("L", "R"):
        ax[0].plot(log.times(f"foot_damping.D_{side}") - t0, log.values(f"foot_damping.D_{side}")[:, 1],
                   label=f"D ({side} pitch)")
        ax[1].plot(log.times("theta_L") - t0, log.values(f"theta_{side}") / DEG, label=f"θ_{side}")
    ax[2].plot(log.times("x") - t0, log.values("x"), "k", label="scooter x")
    for a, label in zip(ax, ("D [N·m·s/rad]", "board pitch [deg]", "x [m]"), strict=True):
        a.set_ylabel(label)
        a.axvline(0.0, color="r", lw=0.6, ls=":")
        a.legend(fontsize=7)
    ax[2].set_xlabel("t [s] from the learning start (both feet landed)")


def speed_governing(ctx, runs, params):
    for name, run in runs.items():
        boarded = name.startswith("boarding")  # Fig. 6.16's self-boarded starts: "boarding", "boarding_slc"
        fig = f"fig6_16{name[len('boarding'):]}" if boarded else f"fig6_15_{name}"
        with ctx.figure(fig, 5, 2, figsize=(13, 15), sharex=True) as (_fig, ax):
            _governed_run(ax, run, f"{name} (Fig. {'6.16' if boarded else '6.15'} layout)")
        if boarded:
            with ctx.figure(f"{fig}_boarding", 3, 1, figsize=(8, 7), sharex=True) as (_fig, ax):
                _boarding_run(ax, run)


def boarding(ctx, runs, params):
    """Fig. 5.8: (a) D, (b) τᵈ and τ, (c) δ, (d) J_τ of the left-foot pitch, without (column 1) and with SLC
    (column 2); time from SLC's start (the left landing), the SLC window shaded; and the boarding itself."""
    with ctx.figure("fig5_8", 4, 2, sharex="col", figsize=(11, 10)) as (_, ax):
        for col, variant in enumerate(runs):
            log, sched = runs[variant].log, runs[variant].state.sched
            t0 = sched.t_start if sched.t_start is not None else 0.0
            t = log.times("J") - t0
            title = "without SLC (D = 22.0 fixed)" if variant == "fixed_d" else "with SLC"
            ax[0, col].plot(t, log.values("D_L"), label="D (left pitch)")
            ax[0, col].plot(t, log.values("D_R"), "--", label="D (right pitch)")
            ax[0, col].set_ylabel("D [N·m·s/rad]")
            ax[0, col].set_title(f"({'ab'[col]}) {title}")
            ax[1, col].plot(t, log.values("tau_d"), label="τᵈ")
            ax[1, col].plot(t, log.values("tau"), label="τ")
            ax[1, col].set_ylabel("left pitch torque [N·m]")
            ax[2, col].plot(t, np.degrees(log.values("delta")), label="δ")
            for s in (-1, 1):
                ax[2, col].axhline(s * math.degrees(DELTA_LIMIT), color="r", lw=0.6, ls=":")
            ax[2, col].set_ylabel("δ [deg]")
            ax[3, col].plot(t, log.values("J"), label="J_τ")
            ax[3, col].set_ylabel("J_τ")
            ax[3, col].set_xlabel("t from the left landing (SLC start) [s]")
            stop = (sched.t_stop - t0) if sched.t_stop is not None else t[-1]
            for a in ax[:, col]:
                a.axvspan(0.0, stop, color="0.9", zorder=0)
                a.legend(fontsize=7, loc="upper left")
                a.grid(alpha=0.3)
    with ctx.figure("boarding", 3, 1, sharex=True, figsize=(8, 7)) as (_, ax):
        for variant in runs:
            log = runs[variant].log
            t = log.times("J")
            ax[0].plot(t, log.values("f_Lz"), label=f"f_Lz {variant}")
            ax[0].plot(t, log.values("f_Rz"), "--", label=f"f_Rz {variant}")
            ax[1].plot(t, np.degrees(log.values("theta_l")), label=f"θ_L {variant}")
            ax[2].plot(t, log.values("scooter_x"), label=f"scooter x {variant}")
        ax[0].axhline(runs["slc"].state.params.F_thre, color="k", lw=0.6, ls=":")
        ax[0].set_ylabel("sole f_z [N]")
        ax[1].set_ylabel("left board pitch [deg]")
        ax[2].set_ylabel("scooter x [m]")
        ax[2].set_xlabel("t [s]")
        for a in ax:
            a.legend(fontsize=7)
            a.grid(alpha=0.3)


def levels(ctx, runs, params):
    level_runs = {name: runs[name] for name in ("level1", "level2")}
    with ctx.figure("zmp_and_pitch", 4, 2, figsize=(12, 11), sharex="col") as (_fig, ax):
        for j, (name, run) in enumerate(level_runs.items()):
            rec, ride = run.log, run.state
            t0 = touchdown(run)
            t = rec.times("x") - t0
            ax[0, j].set_title(f"{name} (Fig. 6.{3 + j}); t = 0 at boarding (soles loaded); lift slack at "
                               f"{ride.lift.t_release - t0:.2f} s")
            for i, (key, label) in enumerate((("zmp_x", "ZMP X [mm]"), ("zmp_y", "ZMP Y [mm]"))):
                ax[i, j].axhline(0.0, color="r", label="reference ZMP (scooter centre)")
                ax[i, j].plot(t, rec.values(key) * 1e3, "g--", label="measured ZMP (ankle F/T)")
                ax[i, j].set_ylabel(label)
            for i, (key, side, label) in enumerate((("theta_R", "r", "θ_R [deg]"), ("theta_L", "l", "θ_L [deg]"))):
                ax[2 + i, j].axhline(theta_o(side) / DEG, color="b", label="θ_O (Eq. A.1 intercept)")
                ax[2 + i, j].plot(t, rec.values(key) / DEG, "m--", label="board pitch")
                ax[2 + i, j].set_ylabel(label)
            ax[3, j].set_xlabel("t [s]")
            for a in ax[:, j]:
                a.legend(fontsize=7)
    with ctx.figure("travel", 1, 1, figsize=(8, 4)) as (_fig, ax):
        for name, run in level_runs.items():
            t0 = touchdown(run)
            ax.plot(run.log.times("x") - t0, run.log.values("x"), label=name)
        ax.set_xlabel("t [s] from boarding")
        ax.set_ylabel("scooter x [m]")
        ax.legend()
    sole_creep(ctx, {"no-slip (default)": runs["creep_noslip"], "soft contacts (sole_creep)": runs["creep"]})


def sole_creep(ctx, runs):
    """Issue 26 item 5's chain at level 2 (vboard.sole_creep), both rides: each sole on its pad, the pitch-torque
    difference beside −f̄_z (s_L − s_R), the damping's δ_R − δ_L, and the turn ω."""
    with ctx.figure("sole_creep", 4, 1, figsize=(10, 11), sharex=True) as (_fig, ax):
        for (label, run), color in zip(runs.items(), ("k", "r")):
            rec = run.log
            t = rec.times("omega")
            sl, sr = rec.values("sole_l") * 1e3, rec.values("sole_r") * 1e3
            ax[0].plot(t, sl, color=color, label=f"left, {label}")
            ax[0].plot(t, sr, color=color, ls="--", label=f"right, {label}")
            tau = rec.values("tau_diff")
            ax[1].plot(t, tau - tau[0], color=color, label=f"τ_L − τ_R, {label}")
            ax[1].plot(t, -rec.values("f_z") * ((sl - sr) - (sl[0] - sr[0])) * 1e-3, color=color, ls=":",
                       label=f"−f̄_z (s_L − s_R), {label}")
            ax[2].plot(t, rec.values("delta_diff") / DEG, color=color, label=label)
            ax[3].plot(t, rec.values("omega"), color=color, label=label)
        for a, y in zip(ax, ("sole on its pad, x [mm]", "pitch-torque difference,\nfrom the start [N·m]",
                             "δ_R − δ_L [deg]", "ω [rad/s]")):
            a.set_ylabel(y)
            a.legend(fontsize=7)
        ax[0].set_title("Level 2, D = 40: the soles' creep on the pads turns the scooter (issue 26 item 5)")
        ax[3].set_xlabel("t [s]")


def posture(ctx, runs, params):
    with ctx.figure("trunk_pitch", 3, 1, figsize=(10, 9), sharex=True) as (_fig, ax):
        for name, run in runs.items():
            rec = run.log
            t = rec.times("x") - run.state.lift.t_release
            ax[0].plot(t, rec.values("trunk_pitch") / DEG, label=f"chest pitch φ_C, {name} posture control")
            ax[1].plot(t, rec.values("x"), label=f"scooter x, {name}")
            ax[2].plot(t, rec.values("correction") / DEG, label=f"Δφ_C (Eq. 4.8), {name}")
        ax[0].set_ylabel("φ_C [deg]")
        ax[1].set_ylabel("x [m]")
        ax[2].set_ylabel("Δφ_C [deg]")
        ax[2].set_xlabel("t [s] from the lift letting go")
        for a in ax:
            a.legend(fontsize=8)


def plant_id(ctx, runs, params):
    m = identification(runs)
    with ctx.figure("identification", 3, 2, figsize=(13, 9)) as (_fig, ax):
        for j, (axis, run, u, y, yt, T, K) in enumerate((
                ("v", "v", "foot_pitch.u_v", "sensors.v", "sensors.true_v", m["T_v_s"], m["K_v"]),
                ("ω", "omega", "foot_pitch.u_omega", "sensors.omega", "sensors.true_omega", m["T_omega_s"],
                 m["K_omega"]))):
            t, s = series(runs[run])
            w = window(t)
            if w.sum() < 50:
                continue
            tt = t[w]
            ax[0, j].plot(tt, s[u][w], color="k", lw=0.8)
            ax[0, j].set_ylabel(f"u_{axis} [rad / 4 ms]")
            ax[1, j].plot(tt, s[y][w], "g--", lw=0.8, label=f"{axis} (simulated sensors)")
            ax[1, j].plot(tt, s[yt][w], color="0.5", lw=0.8, label=f"{axis} (truth)")
            ax[1, j].legend(fontsize=7)
            ydot = np.gradient(s[y][w], CONTROL_PERIOD)
            ax[2, j].plot(tt, ydot, "g--", lw=0.5, label=f"d{axis}/dt measured")
            if np.isfinite(T):
                ax[2, j].plot(tt, K * lowpass(s[u][w], T, CONTROL_PERIOD), "r", lw=1.0,
                              label=f"Eq. 6.14 model, T={T:.2f} s, K={K:.3g}")
            ax[2, j].legend(fontsize=7)
            ax[2, j].set_xlabel("t [s]")
        ax[0, 0].set_title("Fig. 6.9 (a): v")
        ax[0, 1].set_title("Fig. 6.9 (b): ω")
    if "chain" in runs and "chain_base" in runs:
        sign_chain(ctx, runs, params)


def sign_chain(ctx, runs, params):
    """Issue 26's chain: each link's difference (step run − run without) after the +1° common-mode step of the
    commanded foot pitch, one panel per link, the probe's read-out instants marked."""
    tau, diff = chain_difference(runs["chain"], runs["chain_base"])
    keep = (tau >= -0.2) & (tau <= max(PROBE_AFTER) + 0.05)
    with ctx.figure("sign_chain", 6, 2, figsize=(12, 14), sharex=True) as (_fig, ax):
        cells = ax.ravel()
        for a, (key, label, scale, unit) in zip(cells, LINKS):
            a.plot(tau[keep], diff[key][keep] * scale, color="k", lw=0.9)
            a.axhline(0.0, color="0.6", lw=0.5)
            for t in PROBE_AFTER:
                a.axvline(t, color="r", lw=0.5, ls=":")
            a.set_ylabel(f"Δ {label}\n[{unit}]", fontsize=8)
        for a in cells[len(LINKS):]:
            a.axis("off")
        for a in cells[len(LINKS) - 2:len(LINKS)]:
            a.set_xlabel("t − t_step [s]")
            a.xaxis.set_tick_params(labelbottom=True)
        cells[0].set_title("+1° common-mode commanded foot pitch, level 2 (issue 26)")
