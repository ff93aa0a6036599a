"""Plots of the two-plane runs of seed 001 §4.5 (Figs. 4.5, 4.13, 4.14 analogues): the body on the two planes,
the contact of the connection's rear end, the head transition and the head's tracking, and what the null-space
term buys near the front edge."""

from __future__ import annotations


import numpy as np
from matplotlib import colormaps
from matplotlib.patches import Circle

from shintai.core.geometry import wrap
from shintai.snake.constants import CH4_ROBOT, TWO_PLANE
from shintai.snake.model3d import forward_kinematics
from shintai.snake.two_plane import FRONT, LIFTED, REAR
from shintai.snake.two_plane_runs import TwoPlaneRun


CONTACT_COLOURS = {FRONT: "tab:red", REAR: "tab:blue"}


def _event_lines(ax, run: TwoPlaneRun, kinds=("rear_shift", "release"), **kw) -> None:
    for t, kind, *_ in run.events:
        if kind in kinds:
            ax.axvline(t, ls="-.", lw=0.8, color="0.4", **kw)


def plot_motion(ctx, run: TwoPlaneRun, name: str = "motion") -> None:
    """Fig. 4.13(a)/4.14(a) analogue: the body at several times, top view and side view, on the two planes."""
    cmap = colormaps["viridis"]
    w, l = run.world, CH4_ROBOT.l
    picks = np.unique(np.r_[0, np.searchsorted(run.t, [e[0] for e in run.events if e[1] == "front_shift"]),
                            len(run.t) - 1])
    with ctx.figure(name, nrows=2, ncols=1, figsize=(10, 6.2), sharex=True) as (fig, ax):
        far = w.edge_x + w.length
        corners = [w.p_f + w.R_f @ [x, y, 0.0] for x, y in ((w.edge_x, -w.half_width), (w.edge_x, w.half_width),
                                                            (far, w.half_width), (far, -w.half_width))]
        corners = np.array(corners + corners[:1])
        ax[0].fill(corners[:, 0], corners[:, 1], color="tab:red", alpha=0.08, label="front plane")
        ax[0].axvspan(-2.0, w.rear_edge_x, color="tab:blue", alpha=0.06, label="rear plane")
        for j, k in enumerate(picks):
            colour = cmap(j / max(len(picks) - 1, 1))
            P = forward_kinematics(run.s["p_h"][k], run.s["R_h"][k], run.s["psi"][k], l).P
            contact = run.s["contact"][k].astype(int)
            wheels = run.s["wheels"][k]
            for a, (i0, i1) in zip(ax, ((0, 1), (0, 2))):
                a.plot(P[:, i0], P[:, i1], "-", color=colour, lw=1.4, label=f"{run.t[k]:.0f} s" if a is ax[0] else None)
                a.plot(P[0, i0], P[0, i1], "^", color=colour, ms=5)
                for code in (FRONT, REAR):
                    sel = contact == code
                    a.scatter(wheels[sel, i0], wheels[sel, i1], s=16, color=CONTACT_COLOURS[code], zorder=3)
                a.scatter(wheels[contact == LIFTED, i0], wheels[contact == LIFTED, i1], s=16, facecolors="white",
                          edgecolors="k", zorder=3)
        ax[0].set_ylabel("y [m]")
        ax[0].set_title("top view; wheels: red on the front plane, blue on the rear plane, white lifted; ▲ head",
                        fontsize=9)
        ax[0].legend(fontsize=6, ncol=6, loc="lower left")
        ys = run.s["wheels"][..., 1]
        xs = np.array([w.edge_x, far])
        low, high = (np.array([w.p_f + w.R_f @ [x, y - w.p_f[1], 0.0] for x in xs])
                     for y in (ys.min(), ys.max()))  # the front plane's profile at the body's extreme y
        ax[1].fill_between(low[:, 0], low[:, 2], high[:, 2], color="tab:red", alpha=0.25, lw=0,
                           label="front plane over the body's y range")
        ax[1].plot([-2.0, w.rear_edge_x], [0.0, 0.0], "-", color="tab:blue", lw=1.5)
        ax[1].set_xlim(run.s["wheels"][..., 0].min() - 0.1, run.s["wheels"][..., 0].max() + 0.3)
        ax[1].set_ylim(-0.05, 0.3)
        ax[1].set_xlabel("x [m]")
        ax[1].set_ylabel("z [m]")
        ax[1].set_title("side view", fontsize=9)
        ax[1].legend(fontsize=7, loc="upper left")
        ax[0].set_ylim(ys.min() - 0.3, ys.max() + 0.3)
        for a in ax:
            a.set_aspect("equal")


def plot_contact(ctx, run: TwoPlaneRun, name: str = "contact") -> None:
    """Fig. 4.13(d)/4.14(d) analogue: r = [d, κ, λ] of the rear end (dash-dot: rear-end shifts), and the contact
    errors of all wheels on a plane."""
    tc, r = run.c["r"]
    touching, d_err, tilt = run.on_plane()
    with ctx.figure(name, nrows=3, ncols=1, figsize=(8, 8), sharex=True) as (fig, ax):
        ax[0].plot(tc, 1e3 * (r[:, 0] - run.world.r_w), lw=1, label="d − r_w (rear end)")
        ax[0].plot(run.t, 1e3 * np.where(touching, d_err, 0.0).max(axis=1), lw=1,
                   label="max |d − r_w|, all contact wheels")
        ax[0].set_ylabel("[mm]")
        ax[1].plot(tc, r[:, 1], lw=1, label="κ (rear end)")
        ax[1].plot(tc, r[:, 2], lw=1, label="λ (rear end)")
        ax[1].plot(run.t, np.where(touching, tilt, 0.0).max(axis=1), lw=1, label="max tilt, all contact wheels")
        ax[1].set_ylabel("[rad]")
        for k in ("n_f", "n_c", "n_re"):
            ax[2].step(run.c[k][0], run.c[k][1], where="post", lw=1, label=k)
        ax[2].set_ylabel("wheels")
        ax[2].set_xlabel("t [s]")
        for a in ax:
            _event_lines(a, run)
            a.legend(fontsize=7, loc="best")
        ax[0].set_title(f"{run.cond.name}: contact of the connection's rear end with the rear plane", fontsize=9)


def plot_head(ctx, run: TwoPlaneRun, name: str = "head") -> None:
    """Fig. 4.13(b)(c) analogue: r_1 during the head transition, and the head in Σ_f against (4.36)."""
    with ctx.figure(name, nrows=3, ncols=1, figsize=(8, 8)) as (fig, ax):
        t1, r1 = run.c["r1"]
        ax[0].plot(t1, 1e3 * (r1[:, 0] - run.world.r_w), label="d_1,f − r_w [mm]")
        ax[0].plot(t1, 1e3 * r1[:, 1], label="κ_1,f [mrad]")
        ax[0].plot(t1, 1e3 * r1[:, 2], label="λ'_1,f [mrad]")
        ax[0].legend(fontsize=7)
        ax[0].set_title("head transition (4.14): r_1 → [r_w, 0, 0]", fontsize=9)
        tc, w_f = run.c["w_f"]
        _, w_d = run.c["w_d"]
        ax[1].plot(tc, w_d[:, 0], "k--", lw=1, label="targets (4.36)")
        ax[1].plot(tc, w_d[:, 1], "k--", lw=1)
        ax[1].plot(tc, w_f[:, 0], lw=1, label="^f x_h")
        ax[1].plot(tc, w_f[:, 1], lw=1, label="^f y_h")
        ax[1].set_ylabel("[m]")
        ax[1].legend(fontsize=7)
        ax[2].semilogy(tc, np.maximum(np.hypot(*(w_d[:, :2] - w_f[:, :2]).T), 1e-9), lw=1, label="position error [m]")
        ax[2].semilogy(tc, np.maximum(np.abs(wrap(w_d[:, 2] - w_f[:, 2])),
                                      1e-9), lw=1, label="heading error [rad]")
        ax[2].set_xlabel("t [s]")
        ax[2].legend(fontsize=7)
        for a in ax[1:]:
            _event_lines(a, run, kinds=("front_shift",))


def plot_edge(ctx, runs: dict, name: str = "edge", every: float = 2.0) -> None:
    """Fig. 4.5 analogue: the body near the front edge in Σ_f (x–z), every ``every`` s while something is lifted,
    with and without the null-space term; the posture of least clearance in red."""
    cmap = colormaps["viridis"]
    with ctx.figure(name, nrows=len(runs), ncols=1, figsize=(9, 3.6 * len(runs)), squeeze=False) as (fig, ax):
        for a, (label, run) in zip(ax[:, 0], runs.items()):
            w = run.world
            step = max(1, int(round(every / TWO_PLANE.dt)))
            lifted = np.flatnonzero(np.isfinite(run.s["edge_clearance"]))
            worst = lifted[np.argmin(run.s["edge_clearance"][lifted])]
            for k in np.r_[lifted[::step], worst]:
                q = w.to_front(forward_kinematics(run.s["p_h"][k], run.s["R_h"][k], run.s["psi"][k], CH4_ROBOT.l).P)
                style = dict(color="tab:red", lw=2.0, zorder=4) if k == worst else \
                    dict(color=cmap(run.t[k] / run.t[-1]), lw=0.7, alpha=0.7)
                a.plot(q[:, 0], q[:, 2], "-", **style)
                a.plot(q[2::2, 0], q[2::2, 2], "o", ms=2.5 if k != worst else 4, **style)
            a.fill_between([w.edge_x, w.edge_x + 0.5], [-0.3, -0.3], [0.0, 0.0], color="0.7", label="front plane")
            a.add_patch(Circle((w.edge_x, 0.0), w.r_w, fill=False, ls=":", color="k", label="r_w around the edge"))
            a.set_xlim(w.edge_x - 0.55, w.edge_x + 0.35)
            a.set_ylim(-0.15, 0.25)
            a.set_aspect("equal")
            a.set_xlabel("^f x [m]")
            a.set_ylabel("^f z [m]")
            a.legend(fontsize=7, loc="upper right")
            a.set_title(f"{label} (k_v = {run.k_v:g}): body every {every:g} s in Σ_f, colour = time; red: least "
                        f"clearance {1e3 * run.s['edge_clearance'][worst]:.1f} mm at {run.t[worst]:.1f} s", fontsize=9)


def plot_redundancy(ctx, runs: dict, name: str = "redundancy") -> None:
    """Edge clearance, largest joint angle and V over time, with and without the null-space term (§4.4.2)."""
    with ctx.figure(name, nrows=3, ncols=1, figsize=(8, 8), sharex=True) as (fig, ax):
        for label, run in runs.items():
            clearance = np.where(np.isfinite(run.s["edge_clearance"]), run.s["edge_clearance"], np.nan)
            ax[0].plot(run.t, 1e3 * clearance, lw=1, label=f"{label} (k_v = {run.k_v:g})")
            ax[1].plot(run.t, np.abs(run.s["psi"]).max(axis=1), lw=1, label=label)
            ax[2].plot(*run.c["V"], lw=1, label=label)
        ax[0].axhline(0.0, color="k", lw=0.8)
        ax[0].set_ylabel("edge clearance [mm]\n(none lifted: no line)")
        ax[1].axhline(CH4_ROBOT.joint_limit, color="k", ls=":", lw=1, label="ψ_lim")
        ax[1].set_ylabel("max |ψ_i| [rad]")
        ax[2].set_ylabel("V (4.33)")
        ax[2].set_xlabel("t [s]")
        first = next(iter(runs.values()))
        for a in ax:
            _event_lines(a, first, kinds=("front_shift",))
            a.legend(fontsize=7)
        ax[0].set_title("dash-dot: front shifts (with null space)", fontsize=9)


def plot_two_plane(ctx, runs: dict, null_space: bool) -> None:
    """The pictures of a §4.5 condition (the first run; both runs where they are compared), and the transition
    events of each run for the report."""
    series = {variant: TwoPlaneRun.of(run) for variant, run in runs.items()}
    main = next(iter(series.values()))
    plot_motion(ctx, main)
    plot_contact(ctx, main)
    plot_head(ctx, main)
    plot_redundancy(ctx, series)
    plot_edge(ctx, series)
    if null_space:
        plot_motion(ctx, series["no_null_space"], name="motion_no_null_space")
    ctx.extra["events"] = {variant: run.events for variant, run in series.items()}
