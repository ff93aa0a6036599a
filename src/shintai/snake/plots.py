"""Plots of the two-point experiments of seed 001 ch. 3 (Figs. 3.6–3.17 analogues): bodies in top view with
grounded (filled red) and lifted (hollow blue) wheels, paths against targets, errors, singular values and mode
timelines; the caging box, the handcart and the door."""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Rectangle

from shintai.core.recorder import Recorder
from shintai.snake.constants import CAGING, CAGING_BOX, CH3_GAINS, CH3_ROBOT, DOOR, HANDCART
from shintai.snake.door_operator import LOG, PHASES, DoorRun
from shintai.snake.model import body_points, configuration, wheel_poses
from shintai.snake.tracking import TrackingRun


def draw_body(ax, w_h, phi, grounded, alpha=1.0, label=None):
    cfg = configuration(w_h, phi, CH3_ROBOT.l)
    pts = body_points(cfg)
    wheels = wheel_poses(cfg)
    ax.plot(pts[:, 0], pts[:, 1], "-", color="0.35", lw=1.5, alpha=alpha, label=label)
    ax.plot(*pts[0], "k^", ms=6, alpha=alpha)
    draw_wheels(ax, wheels, grounded, alpha)


def draw_wheels(ax, wheels, grounded, alpha=1.0, size=28):
    """Wheels (rows x, y, ...) coloured by mode: grounded filled red, lifted hollow blue."""
    grounded = np.asarray(grounded, dtype=bool)
    ax.scatter(wheels[grounded, 0], wheels[grounded, 1], s=size, c="tab:red", zorder=3, alpha=alpha)
    ax.scatter(wheels[~grounded, 0], wheels[~grounded, 1], s=size, facecolors="white", edgecolors="tab:blue",
               zorder=3, alpha=alpha)


def draw_link_points(ax, points, grounded, alpha=1.0, size=22) -> None:
    """A simulated body as logged by MujocoSnake.link_points (head tip, link origins, tail tip; wheel i at row
    2i): the polyline, the head ▲ and the wheels coloured by mode (:func:`draw_wheels`)."""
    ax.plot(points[:, 0], points[:, 1], "-", color="0.3", lw=2, alpha=alpha)
    ax.plot(*points[0], "^", color="tab:orange", alpha=alpha)
    draw_wheels(ax, points[2::2], grounded, alpha, size)


def draw_track(ax, actual, target, color, label, target_label) -> None:
    """A control point's path (solid) against its target (dashed), both (N, 2)."""
    ax.plot(target[:, 0], target[:, 1], "--", color=color, lw=1, label=target_label)
    ax.plot(actual[:, 0], actual[:, 1], "-", color=color, lw=2, alpha=0.6, label=label)


def wheel_legend(ax, size=28, lifted="lifted wheel") -> None:
    """Legend entries for :func:`draw_wheels`."""
    ax.scatter([], [], c="tab:red", s=size, label="grounded wheel")
    ax.scatter([], [], facecolors="white", edgecolors="tab:blue", s=size, label=lifted)


def shade_stopped(ax, t, stopped, dt=CH3_GAINS.dt) -> None:
    """Red bands over the control periods stopped by the input limit (3.20)."""
    for k in np.flatnonzero(stopped):
        ax.axvspan(t[k], t[k] + dt, color="tab:red", alpha=0.15, lw=0)


def plot_top_view(ctx, run: TrackingRun, name: str = "top_view") -> None:
    """Fig. 3.6(a)(b) analogue: bodies at a few times (wheels red = grounded, hollow blue = lifted), paths vs targets."""
    with ctx.figure(name, figsize=(8.5, 5.0)) as (fig, ax):
        ax.plot(run.c_d[:, 0], run.c_d[:, 1], "--", color="tab:orange", lw=1, label="head target")
        ax.plot(run.c_d[:, 3], run.c_d[:, 4], "--", color="tab:green", lw=1, label="tail target")
        ax.plot(run.c[:, 0], run.c[:, 1], "-", color="tab:orange", lw=2, alpha=0.6, label="head")
        ax.plot(run.c[:, 3], run.c[:, 4], "-", color="tab:green", lw=2, alpha=0.6, label="tail wheel")
        picks = np.unique(np.linspace(0, len(run.mode) - 1, 5).astype(int))
        labelled = []
        for j, k in enumerate(picks):
            draw_body(ax, run.c[k, :3], run.phi[k], run.grounded[k], alpha=0.3 + 0.7 * j / max(len(picks) - 1, 1))
            if all(np.hypot(*(run.c[k, :2] - p)) > 0.02 for p in labelled):  # no overlapping labels at a stall
                ax.annotate(f"{run.t[k]:.0f} s", run.c[k, :2], fontsize=7, xytext=(3, 3), textcoords="offset points")
                labelled.append(run.c[k, :2])
        wheel_legend(ax)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.legend(fontsize=7, loc="best")
        ax.set_title("top view (head ▲); dashed: targets (3.21)", fontsize=9)


def plot_time_series(ctx, run: TrackingRun, name: str = "errors") -> None:
    """Fig. 3.6(c) analogue: errors e_1..e_6, V_m and σ_min(A_c), σ_min(B_c); stopped periods shaded."""
    t, tc = run.t, run.t[:-1]
    with ctx.figure(name, nrows=3, ncols=1, figsize=(7.5, 7.5), sharex=True) as (fig, ax):
        e = run.error
        for i, lab in zip((0, 1, 3, 4), ("e1 head x", "e2 head y", "e4 tail x", "e5 tail y")):
            ax[0].plot(t, 1e3 * e[:, i], lw=1, label=lab)
        ax[0].set_ylabel("position error [mm]")
        ax[1].plot(t, e[:, 2], lw=1, label="e3 head θ")
        ax[1].plot(t, e[:, 5], lw=1, label="e6 tail θ")
        ax[1].set_ylabel("heading error [rad]")
        ax[2].semilogy(tc, run.V_m, lw=1, label="V_m (3.19) = σ_min(B_c,σ)")
        ax[2].semilogy(tc, run.sigma_a, lw=1, label="σ_min(A_c,σ)")
        ax[2].set_ylabel("singular values")
        ax[2].set_xlabel("t [s]")
        for a in ax:
            shade_stopped(a, tc, run.stopped)
            a.legend(fontsize=7, ncol=2, loc="best")
        ax[0].set_title(f"{run.name}: red bands = stopped by the input limit (3.20)", fontsize=9)


def plot_modes(ctx, run: TrackingRun, name: str = "modes") -> None:
    """Mode timeline (Fig. 3.6(c) bottom): grounded (red) / lifted wheels per control period, and the joints (Fig. 3.7)."""
    tc = run.t[:-1]
    with ctx.figure(name, nrows=2, ncols=1, figsize=(7.5, 6.0), sharex=True) as (fig, ax):
        n = run.grounded.shape[1]
        ax[0].imshow(run.grounded.T, aspect="auto", cmap="Reds", vmin=0, vmax=1.4, interpolation="nearest",
                     extent=(tc[0], tc[-1] + CH3_GAINS.dt, n + 0.5, 0.5))
        ax[0].set_ylabel("wheel")
        ax[0].set_yticks(range(1, n + 1))
        ax[0].set_title(f"grounded wheels (red); {len(np.unique(run.mode))} distinct modes of "
                        f"{run.candidates} candidates", fontsize=9)
        for i in range(run.phi.shape[1]):
            ax[1].plot(run.t, run.phi[:, i], lw=1, label=f"φ{i + 1}")
        for s in (-1, 1):
            ax[1].axhline(s * CH3_ROBOT.joint_limit, ls=":", color="k", lw=1)
            ax[1].axhline(s * CH3_GAINS.phi_th, ls="--", color="0.6", lw=0.8)
        ax[1].set_ylabel("yaw joints [rad]")
        ax[1].set_xlabel("t [s]")
        ax[1].legend(fontsize=6, ncol=5, loc="best")


def plot_ablation(ctx, runs: dict[str, TrackingRun]) -> None:
    """Position error and cumulative stopped time of each run (switching vs. frozen mode)."""
    with ctx.figure("ablation", nrows=2, ncols=1, figsize=(7.5, 6.0), sharex=True) as (fig, ax):
        for label, run in runs.items():
            ax[0].semilogy(run.t, np.maximum(run.pos_error, 1e-9), lw=1, label=f"{label}: position error")
            ax[1].plot(run.t[:-1], np.cumsum(run.stopped) * CH3_GAINS.dt, lw=1, label=f"{label}: time stopped")
        ax[0].set_ylabel("max(head, tail) error [m]")
        ax[1].set_ylabel("cumulative stopped time [s]")
        ax[1].set_xlabel("t [s]")
        for a in ax:
            a.legend(fontsize=7)


def plot_caging(ctx, run: TrackingRun, track: dict) -> None:
    """Top view (Figs. 3.8–3.9 analogue): bodies at a few times with the box where it was then."""
    hx, hy, _ = CAGING_BOX.half
    with ctx.figure("top_view", figsize=(8.5, 5.5)) as (fig, ax):
        ax.plot(run.c_d[:, 0], run.c_d[:, 1], "--", color="tab:orange", lw=1, label="head target (3.22)–(3.23)")
        ax.plot(run.c_d[:, 3], run.c_d[:, 4], "--", color="tab:green", lw=1, label="tail target")
        ax.plot(run.c[:, 0], run.c[:, 1], "-", color="tab:orange", lw=2, alpha=0.6, label="head")
        ax.plot(run.c[:, 3], run.c[:, 4], "-", color="tab:green", lw=2, alpha=0.6, label="tail wheel")
        ax.plot(track["pos"][:, 0], track["pos"][:, 1], "-", color="tab:brown", lw=1, label="box centre")
        picks = np.unique(np.linspace(0, len(run.mode) - 1, 4).astype(int))
        for j, k in enumerate(picks):
            alpha = 0.3 + 0.7 * j / max(len(picks) - 1, 1)
            draw_body(ax, run.c[k, :3], run.phi[k], run.grounded[k], alpha=alpha)
            x, y = track["pos"][k, :2]
            ax.add_patch(Rectangle((x - hx, y - hy), 2 * hx, 2 * hy, fill=False, ec="tab:brown", alpha=alpha))
            ax.annotate(f"{run.t[k]:.0f} s", run.c[k, :2], fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        wheel_legend(ax)
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title("caging transport (box: brown squares at the bodies' times)", fontsize=9)


def plot_box(ctx, run: TrackingRun, track: dict) -> None:
    """The box's displacement and whether it stayed inside the body's loop."""
    with ctx.figure("box", figsize=(7.5, 3.8)) as (fig, ax):
        moved = track["pos"] - track["pos"][0]
        ax.plot(run.t[:-1], moved[:, 0], label="box Δx")
        ax.plot(run.t[:-1], moved[:, 1], label="box Δy")
        ax.plot(run.t, run.c[:, 0] - run.c[0, 0], "--", lw=1, label="head Δx")
        lost = np.flatnonzero(~track["caged"])
        if len(lost):
            ax.scatter(run.t[lost], moved[lost, 0], s=8, c="tab:red", label="box outside the loop", zorder=3)
        ax.axvline(CAGING.t_s1, color="0.6", ls=":", lw=1)
        ax.set_xlabel("t [s] (dotted: end of stage 1, t_s1)")
        ax.set_ylabel("displacement [m]")
        ax.legend(fontsize=7)


def plot_handcart(ctx, run: dict) -> None:
    """Top view with the cart, and the tracking errors, head–tail drift and cart travel over time."""
    t, body, cart = run["t"], run["body"], run["cart"]
    hx, hy, _ = HANDCART.cart_half
    with ctx.figure("top_view", figsize=(7.5, 6.0)) as (fig, ax):
        picks = np.unique(np.linspace(0, len(t) - 1, 4).astype(int))
        for j, k in enumerate(picks):
            alpha = 0.25 + 0.75 * j / max(len(picks) - 1, 1)
            g = np.zeros(HANDCART.n, bool) if k >= len(run["grounded"]) else run["grounded"][k]
            draw_link_points(ax, body[k], g, alpha)
            ax.add_patch(Rectangle((cart[k, 0] - hx, cart[k, 1] - hy), 2 * hx, 2 * hy, fill=False, ec="tab:blue",
                                   alpha=alpha))
            ax.annotate(f"{t[k]:.0f} s", body[k, 0], fontsize=7, xytext=(3, 3), textcoords="offset points")
        draw_track(ax, run["c"][:, :2], run["c_d"][:, :2], "tab:orange", "head", "head target (3.26)")
        draw_track(ax, run["c"][:, 6:8], run["c_d"][:, 6:8], "tab:green", "tail tip", "tail target")
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        wheel_legend(ax, 22, "lifted (base mode or arm)")
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title("handcart: double-arm model, head and tail raised (cart: blue)", fontsize=9)
    e, c = run["error"], run["c"]
    offset = c[:, :3] - c[:, 6:9]
    with ctx.figure("errors", nrows=3, ncols=1, figsize=(7.5, 7.0), sharex=True) as (fig, ax):
        ax[0].plot(t, 1e3 * np.linalg.norm(e[:, :3], axis=1), label="head position error")
        ax[0].plot(t, 1e3 * np.linalg.norm(e[:, 6:9], axis=1), label="tail position error")
        ax[0].set_ylabel("[mm]")
        ax[1].plot(t, 1e3 * np.linalg.norm(offset - offset[0], axis=1), label="head–tail offset drift")
        ax[1].set_ylabel("[mm]")
        ax[2].plot(t, cart[:, 0] - cart[0, 0], label="cart Δx")
        ax[2].plot(t, c[:, 0] - c[0, 0], "--", label="head Δx")
        ax[2].set_ylabel("[m]")
        ax[2].set_xlabel("t [s]")
        for a in ax:
            shade_stopped(a, t, run["stopped"])
            a.legend(fontsize=7)
        ax[0].set_title("red bands: stopped by the input limit (3.20)", fontsize=9)


def door_series(recorder: Recorder, key: str) -> tuple[np.ndarray, np.ndarray]:
    """(times, values) of ``<controller>.<key>`` over phases 1 and 2 (controllers ``raise`` then ``tail``), the
    values cut to their common columns (the head's 6D pose first in both)."""
    parts = [(recorder.times(f"{name}.{key}"), np.atleast_2d(recorder.values(f"{name}.{key}").T).T)
             for name in ("raise", "tail") if f"{name}.{key}" in recorder.names()]
    if not parts:
        return np.zeros(0), np.zeros((0, 6))
    width = min(v.shape[1] for _, v in parts)
    t = np.concatenate([tt for tt, _ in parts])
    order = np.argsort(t, kind="stable")
    return t[order], np.concatenate([v[:, :width] for _, v in parts])[order]


def plot_door(ctx, recorder: Recorder, run: DoorRun) -> None:
    """Top view (bodies at the phase changes with wheels by mode, the leaf, head and tail-wheel paths against
    their targets), the errors / V_m / door angle over time with the phases marked, and the mode timeline."""
    d = DOOR
    t = recorder.times(f"{LOG}.phase")
    body, angle = recorder.values(f"{LOG}.body"), recorder.values(f"{LOG}.angle")
    grounded, phase = recorder.values(f"{LOG}.grounded").astype(bool), recorder.values(f"{LOG}.phase").astype(int)
    head, tail = recorder.values(f"{LOG}.head"), recorder.values(f"{LOG}.tail")
    tc, c_d = door_series(recorder, "c_d")
    has_tail = "tail.c_d" in recorder.names()
    with ctx.figure("top_view", figsize=(8.5, 7.0)) as (fig, ax):
        for x0, y0, y1 in ((0.0, -0.8, 0.0), (0.0, d.width, d.width + 0.8)):
            ax.add_patch(Rectangle((x0, y0), d.thickness, y1 - y0, color="0.6"))
        picks = np.unique(np.r_[0, np.searchsorted(t, [e for e, _ in run.events]), len(t) - 1].clip(0, len(t) - 1))
        labels = []
        for j, k in enumerate(picks):
            alpha = 0.25 + 0.75 * j / max(len(picks) - 1, 1)
            draw_link_points(ax, body[k], grounded[k], alpha)
            leaf = d.width * np.array([-np.sin(angle[k]), np.cos(angle[k])])
            ax.plot([0, leaf[0]], [0, leaf[1]], "-", color="tab:brown", lw=3, alpha=alpha)
            text = f"{t[k]:.0f} s {PHASES[phase[k]]}"
            near = [label for label in labels if np.hypot(*(label[0] - body[k, -1])) < 0.05]
            if near:  # bodies that barely moved between phase changes share one label
                near[0][1] += f", {text}"
            else:
                labels.append([body[k, -1], text])
        for point, text in labels:
            ax.annotate(text, point, fontsize=7, xytext=(3, -8), textcoords="offset points")
        draw_track(ax, head[:, :2], c_d[:, :2], "tab:orange", "head tip", "head target (phases 1–2)")
        held = phase <= PHASES.index("tail")  # the estimate is used (and meaningful) in phases 1–2 only
        ax.plot(*recorder.values(f"{LOG}.estimate")[held, :2].T, ":", color="tab:red", lw=1,
                label="head: internal-model estimate (phases 1–2)")
        tail_target = recorder.values("tail.c_d")[:, 6:8] if has_tail else np.zeros((0, 2))
        draw_track(ax, tail[:, :2], tail_target, "tab:green", "tail wheel", "tail-wheel target (phase 2)")
        wheel_legend(ax, 22)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m] (wall at x = 0; inside: x > 0)")
        ax.set_ylabel("y [m]")
        ax.legend(fontsize=7, loc="best")
        ax.set_title(f"door: phase reached {run.phase_reached}, passed = {int(run.passed)} "
                     "(leaf brown, head ▲, bodies at the start and the phase changes)", fontsize=9)
    events = [(e, name) for e, name in run.events]
    with ctx.figure("phases", nrows=4, ncols=1, figsize=(7.5, 9.0), sharex=True) as (fig, ax):
        ax[0].step(t, phase, where="post")
        ax[0].set_yticks(range(len(PHASES)), PHASES, fontsize=7)
        ax[0].set_title("phases (operator); red bands: stopped by the input limit (3.20)", fontsize=9)
        ax[1].plot(t, np.degrees(angle), label="door angle")
        ax[1].set_ylabel("door angle [deg]")
        if len(tc):
            _, error = door_series(recorder, "error")
            ax[2].plot(tc, 1e3 * np.linalg.norm(error[:, :3], axis=1), lw=1,
                       label="head: target − internal-model estimate (controller's e)")
            k = np.searchsorted(t, tc).clip(0, len(t) - 1)
            ax[2].plot(tc, 1e3 * np.linalg.norm(c_d[:, :3] - head[k, :3], axis=1), lw=1, label="head: target − true")
        if has_tail:
            e = recorder.values("tail.error")
            ax[2].plot(recorder.times("tail.error"), 1e3 * np.hypot(e[:, 6], e[:, 7]), lw=1,
                       label="tail wheel: target − true")
        ax[2].set_ylabel("position error [mm]")
        ts, V_m = door_series(recorder, "V_m")
        if len(ts):
            ax[3].semilogy(ts, V_m[:, 0], lw=1, label="V_m = σ_min(B_σ) of the mode in use (3.19)")
        ax[3].set_ylabel("singular value")
        ax[3].set_xlabel("t [s]")
        ts, stopped = door_series(recorder, "stopped")
        for a in ax:
            shade_stopped(a, ts, stopped[:, 0].astype(bool))
            for e, _ in events:
                a.axvline(e, color="0.5", ls=":", lw=0.8)
        for a in ax[1:]:
            if a.get_legend_handles_labels()[0]:
                a.legend(fontsize=7, loc="best")
    with ctx.figure("modes", figsize=(7.5, 4.0)) as (fig, ax):
        n = grounded.shape[1]
        ax.imshow(grounded.T, aspect="auto", cmap="Reds", vmin=0, vmax=1.4, interpolation="nearest",
                  extent=(t[0], t[-1] + CH3_GAINS.dt, n + 0.5, 0.5))
        for e, name in events:
            ax.axvline(e, color="k", ls=":", lw=0.8)
            ax.annotate(name, (e, 0.5), fontsize=7, rotation=90, va="top", xytext=(2, -2), textcoords="offset points")
        ax.set_ylabel("wheel (1 = head)")
        ax.set_xlabel("t [s]")
        ax.set_title("grounded wheels (red) / lifted (white): the raised head part, base modes, the lifted tail "
                     "wheel in phase 2", fontsize=8)
