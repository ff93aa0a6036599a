"""BeBe's pictures (seed 003 §4.8): view shifts of single muscles, tracking and disturbances (cf. Figs. 4.53,
4.55, 4.56)."""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Circle, Wedge

from shintai.spine.bebe import body as bebe
from shintai.spine.bebe.constants import SPANS
from shintai.spine.bebe.runs import BeBeResults, push_profile
from shintai.spine.robots import BEBE_FORCE_AT_S, BEBE_PUSH_PERIOD_S


def plot_bebe_calibration(ctx, shifts: np.ndarray) -> None:
    """Fig. 4.53 analogue: the 36 view shifts v_i, coloured by span; the same-direction cone of one v."""
    with ctx.figure("bebe_calibration", figsize=(6.0, 5.6)) as (fig, ax):
        for span, color in zip(range(len(SPANS)), ("tab:blue", "tab:orange", "tab:green")):
            a, b = SPANS[span]
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
