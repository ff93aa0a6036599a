"""Pictures of the spine's model and learning experiments: the inverse model's learning curves and errors
(cf. Figs. 4.2–4.9, Table 4.2), BeBe's view shifts, tracking and disturbances (cf. Figs. 4.53, 4.55,
4.56), and SQ43's design search (cf. Fig. 3.4).
"""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Circle, Wedge

from shintai.spine import bebe, sq43
from shintai.spine.bebe_runs import BeBeResults, push_profile
from shintai.spine.robots import BEBE_FORCE_AT_S, BEBE_PUSH_PERIOD_S, SQ43_GRID_CHECK_DEG


def plot_learning_curves(ctx, nets: dict) -> None:
    """Figs. 4.2–4.9 analogue: mean error norm on the 343 teacher postures (and the test set)."""
    with ctx.figure("inverse_learning_curves", figsize=(7.5, 4.2)) as (fig, ax):
        for (label, inv), color in zip(nets.items(), ("tab:blue", "tab:orange")):
            c = inv.curve
            ax.semilogy(c.iterations, c.train_deg, color=color, lw=1.2, label=f"{label}: 343 teacher postures")
            ax.semilogy(c.iterations, c.test_deg, color=color, lw=1, ls="--", label=f"{label}: 50 random postures")
            ax.plot(c.best_iteration, c.best_train_deg, "o", color=color, ms=5)
        ax.axhline(1.26, color="tab:blue", ls=":", lw=0.8, label="thesis 8-40-15 min 1.26° (Table 4.3)")
        ax.axhline(1.12, color="tab:orange", ls=":", lw=0.8, label="thesis 8-10-10-15 min 1.12°")
        ax.set_xlabel("iteration")
        ax.set_ylabel("mean error norm over 15 joints [deg]")
        ax.legend(fontsize=7)
        ax.set_title("learning curves on Cla's geometric model (dot: the kept network)", fontsize=9)


def plot_inverse_errors(ctx, errors: dict, table: list[dict]) -> None:
    """Per-posture error norms of the three inverses, and Table 4.2's Jacobian runs against n."""
    with ctx.figure("inverse_errors", nrows=1, ncols=2, figsize=(11.0, 4.2)) as (fig, ax):
        for label, e in errors.items():
            ax[0].semilogy(np.arange(1, len(e) + 1), np.maximum(e, 1e-3), "o-", ms=3, lw=0.8, label=label)
        ax[0].axhline(1.95, color="k", ls=":", lw=0.8, label="thesis NN 8-40-15: 1.95°")
        ax[0].set_xlabel("random uniform-bend test posture")
        ax[0].set_ylabel("error norm over 15 joints [deg]")
        ax[0].legend(fontsize=7)
        for name in sorted({r["true"] for r in table}, key=lambda s: (float(s.split("=")[1]), s)):
            rows = [r for r in table if r["true"] == name]
            ax[1].loglog([r["divisions"] for r in rows], [r["error_norm_deg"] for r in rows], "o-", ms=3, lw=0.8,
                         label=name)
        ax[1].set_xlabel("divisions n (n₀ = int|Δq| mm, 2n₀, 4n₀)")
        ax[1].set_ylabel("error norm [deg]")
        ax[1].set_title("Table 4.2 analogue (Jacobian integration)", fontsize=9)
        ax[1].legend(fontsize=6, ncol=3)


def plot_bebe_calibration(ctx, shifts: np.ndarray) -> None:
    """Fig. 4.53 analogue: the 36 view shifts v_i, coloured by span; the same-direction cone of one v."""
    with ctx.figure("bebe_calibration", figsize=(6.0, 5.6)) as (fig, ax):
        for span, color in zip(range(len(bebe.SPANS)), ("tab:blue", "tab:orange", "tab:green")):
            a, b = bebe.SPANS[span]
            block = shifts[span * len(bebe.MUSCLE_KINDS):(span + 1) * len(bebe.MUSCLE_KINDS)]
            for v in block:
                ax.annotate("", v, (0, 0), arrowprops={"arrowstyle": "->", "color": color, "lw": 1})
            ax.plot([], [], color=color, label=f"span {bebe.REGIONS[a]} – {bebe.REGIONS[b]}")
        v = np.array([1.0, 0.5]) / np.hypot(1.0, 0.5)
        half = np.degrees(np.arccos(bebe.COS_THRESHOLD))
        r = 1.1 * np.abs(shifts).max()
        centre = np.degrees(np.arctan2(v[1], v[0]))
        ax.add_patch(Wedge((0, 0), r, centre - half, centre + half, color="0.85", zorder=0,
                           label="same-direction for v (cos > 0.2)"))
        ax.annotate("v", 0.9 * r * v, (0, 0), arrowprops={"arrowstyle": "->", "color": "k", "lw": 1.5})
        ax.set_xlim(-r, r)
        ax.set_ylim(-r, r)
        ax.set_aspect("equal")
        ax.set_xlabel("view shift x [px] (right)")
        ax.set_ylabel("view shift y [px] (up)")
        ax.legend(fontsize=7, loc="lower left")
        ax.set_title("single-muscle view shifts v_i (Fig. 4.53 analogue)", fontsize=8)


def plot_bebe_tracking(ctx, res: BeBeResults, dead_zone: float) -> None:
    """Normal tracking: image error and on-muscle count, off-before-on vs the on-first ablation."""
    with ctx.figure("bebe_tracking", nrows=2, ncols=1, figsize=(8.0, 5.5), sharex=True) as (fig, ax):
        for ep, label, color in ((res.tracking, "off before on (thesis)", "tab:blue"),
                                 (res.on_first, "on before off (ablation)", "tab:red")):
            ax[0].plot(ep.t, np.linalg.norm(ep.target_px, axis=1), lw=0.8, color=color, label=label)
            ax[1].step(ep.t, ep.on_count, where="post", lw=0.9, color=color, label=label)
        ax[0].axhline(dead_zone, color="k", ls="--", lw=0.8, label="dead zone")
        ax[0].set_ylabel("|target − centre| [px]")
        ax[0].set_yscale("log")
        ax[1].axhline(bebe.same_direction_bound(res.shifts), color="k", ls=":", lw=0.8,
                      label="bound: max same-direction muscles")
        ax[1].set_ylabel("muscles on")
        ax[1].set_xlabel("t [s]")
        for a in ax:
            a.legend(fontsize=7, loc="best")


def plot_bebe_image(ctx, res: BeBeResults, untracked: np.ndarray, dead_zone: float) -> None:
    """The target in the 256 × 240 image: where it would be with the spine still, and with tracking."""
    with ctx.figure("bebe_image", figsize=(6.0, 5.4)) as (fig, ax):
        ax.plot(untracked[:, 0], untracked[:, 1], lw=0.8, color="0.6", label="spine still (no control)")
        xy = res.tracking.target_px
        ax.plot(xy[:, 0], xy[:, 1], lw=0.6, color="tab:blue", label="tracking (off before on)")
        ax.add_patch(Circle((0, 0), dead_zone, fill=False, ls="--", label="dead zone"))
        ax.set_xlim(-128, 128)
        ax.set_ylim(-120, 120)
        ax.set_aspect("equal")
        ax.set_xlabel("image x [px]")
        ax.set_ylabel("image y [px]")
        ax.legend(fontsize=7, loc="upper right")


def plot_bebe_disturbances(ctx, res: BeBeResults, dead_zone: float, push_n: float) -> None:
    """Fig. 4.55/4.56 analogue: image error under pushes and with forced-on muscles."""
    with ctx.figure("bebe_disturbances", nrows=2, ncols=1, figsize=(8.0, 6.0)) as (fig, ax):
        ep = res.disturbed
        ax[0].plot(ep.t, np.linalg.norm(ep.target_px, axis=1), lw=0.8)
        push = push_profile(push_n)
        for t in res.push_events:
            f = push(t + 0.01)[1]
            if f:
                ax[0].axvspan(t, t + BEBE_PUSH_PERIOD_S, color="tab:red" if f > 0 else "tab:green", alpha=0.12, lw=0)
        ax[0].axhline(dead_zone, color="k", ls="--", lw=0.8)
        ax[0].set_ylabel("|target − centre| [px]")
        ax[0].set_title(f"pushes of {push_n:g} N on abdomen 1 (red: +y, green: −y)", fontsize=8)
        for case, e in res.forced.items():
            ax[1].plot(e.t, np.linalg.norm(e.target_px, axis=1), lw=0.9, label=f"forced on: tilt {case}")
        ax[1].axvline(BEBE_FORCE_AT_S, color="0.4", lw=0.8)
        ax[1].axhline(dead_zone, color="k", ls="--", lw=0.8)
        ax[1].set_ylabel("|target − centre| [px]")
        ax[1].set_xlabel("t [s]")
        ax[1].legend(fontsize=7)


def plot_sq43(ctx, paths: list, prm: sq43.SQ43Params, grid_best: float) -> None:
    """Fig. 3.4 analogue (objective against step) and the paths in (a1, a2), (a2, a3)."""
    with ctx.figure("sq43_search", nrows=1, ncols=3, figsize=(13.0, 4.2)) as (fig, ax):
        for k, path in enumerate(paths):
            pts = np.array(path.points)
            ax[0].plot(path.values, "-", lw=1.2, label=f"start {k + 1} {tuple(sq43.TABLE_3_1[k])}")
            for j, (u, v) in enumerate(((0, 1), (1, 2))):
                ax[j + 1].plot(pts[:, u], pts[:, v], "-", lw=1)
                ax[j + 1].plot(pts[0, u], pts[0, v], "o", ms=4, color=ax[0].lines[-1].get_color())
                ax[j + 1].plot(pts[-1, u], pts[-1, v], "*", ms=9, color=ax[0].lines[-1].get_color())
        ax[0].axhline(grid_best, color="k", ls=":", lw=0.8, label=f"best of a {SQ43_GRID_CHECK_DEG}° grid")
        ax[0].set_xlabel("search step t")
        ax[0].set_ylabel("lifted left-front foot height [mm]")
        ax[0].legend(fontsize=7)
        for j, (u, v) in enumerate(((0, 1), (1, 2))):
            ax[j + 1].set_xlabel(f"a{u + 1} [deg]")
            ax[j + 1].set_ylabel(f"a{v + 1} [deg]")
            ax[j + 1].set_xlim(-31, 31)
            ax[j + 1].set_ylim(-31, 31)
            ax[j + 1].set_aspect("equal")
            ax[j + 1].grid(lw=0.3)
        ax[1].set_title("paths (o start, * end); |a4| ≤ 30° bounds the region", fontsize=8)


def plot_sq43_shapes(ctx, starts, ends, prm: sq43.SQ43Params) -> None:
    """Side view (y–z) of the start and end spines of each search."""
    with ctx.figure("sq43_spines", figsize=(7.5, 4.0)) as (fig, ax):
        for k, (a0, a1) in enumerate(zip(starts, ends)):
            for a, ls in ((a0, ":"), (a1, "-")):
                poly = sq43.spine_shape(a, prm).polyline
                ax.plot(1e3 * poly[:, 1], 1e3 * (poly[:, 2] - 0.03 * k), ls, lw=1.5, color=f"C{k}",
                        label=f"start {k + 1}: {'start' if ls == ':' else 'end'}")
        ax.set_xlabel("y [mm] (front →)")
        ax.set_ylabel("z [mm] (offset 30 mm per start)")
        ax.set_aspect("equal")
        ax.legend(fontsize=6, ncol=4, loc="upper center", bbox_to_anchor=(0.5, -0.2))
