"""Figures of the quadruped scenarios: top views of walks (the paper's path figures, e.g. Figs. 18,
20, 30-35), leg and body heights per cycle (Figs. 19, 21, 34, 36), learning curves.

Every ``draw_*`` function draws into axes it is given; the experiments own the figures (``ctx.figure``);
:func:`plot_walks` is the figure pair of the walking experiments.
"""

from __future__ import annotations

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import world as W

LEG_COLOURS = ("tab:blue", "tab:red", "tab:cyan", "tab:pink")


def draw_obstacles(ax, env: W.Environment) -> None:
    """Obstacles (grey: wall, orange: surmountable, with their heights) and the goal circle."""
    from matplotlib.patches import Circle, Polygon

    for o in env.obstacles:
        colour = "0.35" if not o.surmountable else "tab:orange"
        ax.add_patch(Polygon(o.polygon, closed=True, color=colour, alpha=0.45, lw=0))
        ax.annotate(f"{o.height:g} m", o.polygon.mean(0), fontsize=7, ha="center", va="center")
    ax.add_patch(Circle(env.destination, C.GOAL_RADIUS, fill=False, ls="--", color="tab:green"))
    ax.plot(*env.destination, "+", color="tab:green")


def draw_walk(ax, env: W.Environment, records: list[R.CycleRecord], triangles: bool = True) -> None:
    """Top view: obstacles, the CoG path (every body move, dots at the end of each cycle), footholds
    coloured by leg (▲ on an obstacle top), and the support triangle and CoG at every swing."""
    draw_obstacles(ax, env)
    if not records:
        return
    path = np.vstack([r.body_poses[:, :2] for r in records])
    ends = np.array([[0.0, 0.0]] + [r.body_poses[-1, :2] for r in records])
    ax.plot(path[:, 0], path[:, 1], "k-", lw=0.6, label="CoG (every body move)")
    ax.plot(ends[:, 0], ends[:, 1], "k.", ms=5, label="CoG after each cycle")
    if triangles:
        for r in records:
            for s in range(4):
                leg = r.order[s] - 1
                tri = np.vstack([r.support_triangles[s], r.support_triangles[s][:1]])
                ax.plot(tri[:, 0], tri[:, 1], "-", color=LEG_COLOURS[leg], lw=0.4, alpha=0.5)
                ax.plot(*r.cog[s], "x", color=LEG_COLOURS[leg], ms=3, mew=0.6)
    for leg in range(4):
        feet = np.array([r.footholds[leg] for r in records])
        top = np.array([r.stands_on[leg] >= 0 for r in records])
        ax.scatter(feet[~top, 0], feet[~top, 1], s=12, color=LEG_COLOURS[leg],
                   label=f"leg {leg + 1} {C.LEG_NAMES[leg]}")
        ax.scatter(feet[top, 0], feet[top, 1], s=34, marker="^", color=LEG_COLOURS[leg], edgecolors="k", lw=0.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (right)")
    ax.set_ylabel("y [m] (forward)")


def draw_heights(ax_body, ax_feet, ax_cmd, records: list[R.CycleRecord]) -> None:
    """Per cycle: the body height Zr, every leg's landing height, and the commanded displacement."""
    k = np.array([r.k for r in records])
    ax_body.step(k, [1000 * r.zr for r in records], where="mid", color="k")
    ax_body.set_ylabel("Zr [mm]")
    for leg in range(4):
        ax_feet.plot(k, [1000 * r.footholds[leg, 2] for r in records], "o-", ms=3, lw=1, color=LEG_COLOURS[leg],
                     label=f"leg {leg + 1}")
    ax_feet.set_ylabel("landing height [mm]")
    ax_feet.legend(fontsize=7)
    cmd = np.array([r.command for r in records])
    ax_cmd.plot(k, 1000 * cmd[:, 0], "o-", ms=3, lw=1, label="ΔXr [mm]")
    ax_cmd.plot(k, 1000 * cmd[:, 1], "s-", ms=3, lw=1, label="ΔYr [mm]")
    ax_cmd.plot(k, 10 * np.degrees(cmd[:, 2]), "^-", ms=3, lw=1, label="Δθr [0.1 deg]")
    ax_cmd.legend(fontsize=7)
    for ax in (ax_body, ax_feet, ax_cmd):
        ax.set_xlabel("walking cycle k")


def draw_curve(ax, best: np.ndarray, mean: np.ndarray, title: str) -> None:
    """A GA learning curve: best and mean fitness per generation (log scale, minimised)."""
    g = np.arange(len(best))
    ax.semilogy(g, best, "-", label="best")
    ax.semilogy(g, mean, "-", lw=0.8, label="population mean")
    ax.set_xlabel("generation")
    ax.set_ylabel("fitness (minimised)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)


def plot_walks(ctx, name: str, walks: dict) -> None:
    """Top views and per-cycle heights of one or more walks ``{title: (env, records)}``."""
    n = len(walks)
    with ctx.figure(f"{name}_path", nrows=1, ncols=n, figsize=(5.2 * n, 6.2), squeeze=False) as (fig, axes):
        for ax, (title, (env, records)) in zip(axes[0], walks.items()):
            draw_walk(ax, env, records)
            ax.set_title(title, fontsize=8)
        axes[0, 0].legend(fontsize=6, loc="best")
    with ctx.figure(f"{name}_legs", nrows=n, ncols=3, figsize=(12, 3.2 * n), squeeze=False) as (fig, axes):
        for row, (title, (_, records)) in zip(axes, walks.items()):
            draw_heights(*row, records)
            row[0].set_title(title, fontsize=8)


CURVE_TITLES = {"action": "action network, fixed order: eq. (9)", "order": "swing-order network: eq. (13)",
                "free": "action network re-trained with the free gait: eq. (9)"}
