"""SQ43's pictures: the design search (seed 003 §3.2.3, cf. Fig. 3.4) and the levelling, crawl and trot runs
(§3.2.4, §5.6)."""

from __future__ import annotations

import numpy as np

from shintai.spine.robots import SQ43_GRID_CHECK_DEG
from shintai.spine.sq43 import design as sq43
from shintai.spine.sq43.gaits import CRAWL_ORDER


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


def levelling(ctx, runs: dict, rise_mm: float) -> None:
    """Fig. 3.6: the shoulder roll with and without the levelling against the board, and the left front leg."""
    with ctx.figure("levelling_roll") as (fig, ax):
        for v, s in runs.items():
            ax.plot(s["t"], s["roll_deg"], label=f"shoulder roll, {v} levelling")
        for a in runs["with"]["acted_s"]:
            ax.axvline(a, color="0.8", lw=0.6)
        ax2 = ax.twinx()
        ax2.plot(runs["with"]["t"], runs["with"]["board_mm"], "k--", lw=0.8, label="board height")
        ax2.set_ylabel("board under LF [mm]")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("shoulder roll [deg] (+: left side up)")
        ax.set_title(f"SQ43 levelling (Fig. 3.6): board up {rise_mm:g} mm and down; grey: controller steps", fontsize=9)
        ax.legend(fontsize=7, loc="upper right")
    with ctx.figure("levelling_leg") as (fig, ax):
        ax.plot(runs["with"]["t"], runs["with"]["lf_length_mm"], label="LF leg length (with levelling)")
        ax.plot(runs["with"]["t"], runs["with"]["acc_roll_deg"] + runs["with"]["lf_length_mm"].mean(), lw=0.6,
                label="accelerometer roll [deg] (offset)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("[mm]")
        ax.legend(fontsize=7)


def crawl(ctx, tests: dict, crawl: dict, lift_mm: float) -> None:
    """Fig. 3.7: the lift tests' swing-foot clearance, and the crawl's feet and spine twist."""
    with ctx.figure("lift_tests") as (fig, ax):
        for name, (r, legs) in tests.items():
            for leg in legs:
                ax.plot(r["t"], r["feet_z_mm"][leg], label=f"{name}: {leg}")
        ax.axhline(lift_mm, color="k", ls="--", lw=0.7, label="commanded lift")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("foot tip above floor [mm]")
        ax.set_title("SQ43 lift tests (§3.2.4–3.2.5): swing-foot clearance", fontsize=9)
        ax.legend(fontsize=6)
    with ctx.figure("crawl") as (fig, ax):
        for leg in CRAWL_ORDER:
            ax.plot(crawl["t"], crawl["feet_z_mm"][leg], label=leg)
        ax.plot(crawl["t"], crawl["twist_deg"], "k", lw=0.6, label="spine twist [deg]")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("foot tip above floor [mm]")
        ax.set_title(f"SQ43 crawl (Fig. 3.7), order {' '.join(CRAWL_ORDER)}: forward {crawl['forward_mm']:.0f} mm",
                     fontsize=9)
        ax.legend(fontsize=7)


def trot(ctx, replay: dict) -> None:
    """Fig. 5.21: the GA's best trot replayed on the body."""
    s = replay["series"]
    with ctx.figure("best_trot") as (fig, ax):
        ax.plot(s["t"], 1e3 * (s["trunk"][:, 0] - s["trunk"][0, 0]), label="trunk forward [mm]")
        ax.plot(s["t"], 1e3 * (s["trunk"][:, 1] - s["trunk"][0, 1]), label="trunk sideways [mm]")
        ax.plot(s["t"], s["twist_deg"] * 10, lw=0.7, label="spine twist [deg × 10]")
        ax.set_xlabel("gait time [s]")
        ax.set_title("SQ43: the GA's best trot replayed on the body", fontsize=9)
        ax.legend(fontsize=7)


def uneven(ctx, runs: dict, height_mm: float) -> None:
    """Fig. 3.8: shoulder and hip roll, the left front leg's offset and the feet in contact; grey: levelling pauses."""
    with ctx.figure("uneven", 2, 1, figsize=(8.0, 6.4), sharex=True) as (fig, ax):
        for v, s in runs.items():
            ax[0].plot(s["t"], s["shoulder"], lw=1, label=f"shoulder roll, {v}")
            ax[1].plot(s["t"], s["contact"] + 0.05 * list(runs).index(v), lw=0.8, label=f"feet in contact, {v}")
        ax[0].plot(runs["levelling"]["t"], runs["levelling"]["hip"], lw=0.8, label="hip roll, levelling")
        for a, b, _ in runs["levelling"]["pauses"]:
            for axis in ax:
                axis.axvspan(a, b, color="0.9")
        ax2 = ax[0].twinx()
        ax2.plot(runs["levelling"]["t"], runs["levelling"]["lf"], "k--", lw=0.8, label="LF length offset")
        ax2.set_ylabel("LF length offset [mm]")
        ax[0].set_ylabel("roll [deg] (+: left side up)")
        ax[0].legend(fontsize=6, loc="upper left")
        ax[1].set_ylabel("feet in contact")
        ax[1].set_xlabel("time [s]")
        ax[1].legend(fontsize=6)
        ax[0].set_title(f"SQ43 crawl over a {height_mm:g} mm block under the left feet (Fig. 3.8)", fontsize=9)


def standup(ctx, runs: dict, torque_nm: float) -> None:
    """Fig. 3.9: the shoulder and hip heights of each strategy, and the largest leg-servo torque against the limit."""
    with ctx.figure("standup", 2, 1, figsize=(8.0, 6.4), sharex=True) as (fig, ax):
        for i, (v, log) in enumerate(runs.items()):
            t = log.values("t_s")
            ax[0].plot(t, log.values("shoulder_z_mm"), color=f"C{i}", label=f"shoulder, {v}")
            ax[0].plot(t, log.values("hip_z_mm"), "--", color=f"C{i}", lw=0.8, label=f"hip, {v}")
            ax[1].plot(t, log.values("max_leg_torque_nm"), color=f"C{i}", lw=0.6, label=v)
        ax[1].axhline(torque_nm, color="k", ls=":", lw=0.8, label="servo limit")
        ax[0].set_ylabel("height above floor [mm]")
        ax[0].legend(fontsize=6, ncol=3)
        ax[1].set_ylabel("largest leg-servo torque [N·m]")
        ax[1].set_xlabel("time [s]")
        ax[1].legend(fontsize=6)
        ax[0].set_title(f"SQ43 standing up from its belly (Fig. 3.9), leg servos limited to {torque_nm:.3g} N·m",
                        fontsize=9)
