"""Figures of the quadruped scenarios: top views of walks (the paper's path figures, e.g. Figs. 18,
20, 30-35), leg and body heights per cycle (Figs. 19, 21, 34, 36), learning curves.

Every ``draw_*`` function draws into axes it is given; every ``plot_*`` function makes an experiment's
figures (``ctx.figure``) from what the experiment computed: :func:`plot_walks` is the figure pair of the walking
experiments, the others each belong to one experiment (the experiments draw nothing themselves, issue 25).
"""

from __future__ import annotations

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import replay as P
from shintai.quadruped import robot as R
from shintai.quadruped import sensing as U
from shintai.quadruped import training as T
from shintai.quadruped import world as W
from shintai.quadruped.episode import SENTINELS, Episodes

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


def plot_strategies(ctx, ours: dict, table3: dict) -> None:
    with ctx.figure("body_movement", nrows=1, ncols=2, figsize=(11, 4)) as (fig, axes):
        for ax, data, title in ((axes[0], ours, "trained action network, §5.2 environment"),
                                (axes[1], table3, "the paper's Table 3 actions (flat floor, from the stance)")):
            k = np.arange(1, len(data["fixed"]) + 1)
            for key, style in (("fixed", "o-"), ("exhaustive", "s-"), ("network", "^--")):
                ax.plot(k, data[key], style, ms=4, lw=1, label=f"{key}: Σ {np.sum(data[key]):.1f} mm")
            ax.set_xlabel("walking cycle k")
            ax.set_ylabel("Br [mm]")
            ax.set_title(title, fontsize=9)
            ax.legend(fontsize=7)


CLIMBERS = {"table3": "legs 2 and 4", "table6": "leg 1 (leg 3 steps over)", "table7": "legs 2 and 4"}


def _draw_table_obstacles(ax, env: W.Environment) -> None:
    for o in env.obstacles:
        poly = np.vstack([o.polygon, o.polygon[:1]])
        ax.fill(poly[:, 0], poly[:, 1], color="0.3" if not o.surmountable else "tab:orange", alpha=0.5)
        ax.annotate(f"{o.height:g} m", o.polygon.mean(0), fontsize=7, ha="center")


def plot_paths(ctx, replays: dict) -> None:
    from matplotlib.patches import Circle

    with ctx.figure("paths", nrows=1, ncols=3, figsize=(11, 5.0)) as (fig, axes):
        for ax, (name, rep) in zip(axes, replays.items()):
            env = P.TABLES[name][2]()
            _draw_table_obstacles(ax, env)
            body = np.array([r.body_poses[-1, :2] for r in rep.records])
            ax.plot(np.r_[0, body[:, 0]], np.r_[0, body[:, 1]], "k.-", lw=1, label="CoG after each cycle")
            for leg, color in zip(range(4), ("tab:blue", "tab:red", "tab:cyan", "tab:pink")):
                feet = np.array([r.footholds[leg] for r in rep.records])
                on = feet[:, 2] > 0
                ax.scatter(feet[~on, 0], feet[~on, 1], s=10, color=color, label=f"leg {leg + 1} ({C.LEG_NAMES[leg]})")
                ax.scatter(feet[on, 0], feet[on, 1], s=30, marker="^", color=color, edgecolors="k")
            ax.add_patch(Circle(env.destination, C.GOAL_RADIUS, fill=False, ls="--"))
            ax.set_aspect("equal")
            ax.set_title(f"{name}: climbs with {CLIMBERS[name]} (▲ = on top)", fontsize=8)
            ax.set_xlabel("x [m]")
        axes[0].set_ylabel("y [m]")
        axes[0].legend(fontsize=6, loc="lower left")


def plot_br(ctx, comparison: P.BodyMovementComparison) -> None:
    k = np.arange(1, 11)
    with ctx.figure("body_movement", nrows=1, ncols=2, figsize=(10, 4)) as (fig, (ax0, ax1)):
        for values, label, style in ((C.TABLE3_BR, "Table 3 fixed", "o-"), (C.TABLE4_BR, "Table 4 all 24", "s-"),
                                     (C.TABLE5_BR, "Table 5 RBFNN", "^-")):
            ax0.plot(k, values, style, ms=4, lw=1, label=label)
        for values, label, style in ((comparison.fixed, "fixed 4→2→3→1", "o-"),
                                     (comparison.exhaustive, "exhaustive", "s-"),
                                     (comparison.rbfnn, "paper's RBFNN orders", "^-")):
            ax1.plot(k, values, style, ms=4, lw=1, label=label)
        ax0.set_title("paper: Br per cycle", fontsize=9)
        ax1.set_title("this executor: Br of the same actions", fontsize=9)
        for ax in (ax0, ax1):
            ax.set_xlabel("walking cycle k")
            ax.set_ylabel("Br [mm]")
            ax.legend(fontsize=7)


def plot_generalisation(ctx, envs: list[W.Environment], train: Episodes, unseen: Episodes) -> None:
    ok = T.success(unseen)
    with ctx.figure("generalization", nrows=1, ncols=3, figsize=(14, 4.4)) as (fig, (ax0, ax1, ax2)):
        dest = np.array([e.destination for e in envs])
        wall_left = np.array([not e.left.surmountable for e in envs])
        limit = (unseen.limit | unseen.unstable) & ~unseen.collided
        for mask, label, marker in ((ok, "reached", "o"), (unseen.collided, "collision", "x"),
                                    (limit, "joint limit / stability", "s"),
                                    (~ok & ~unseen.collided & ~limit, "50 cycles", "d")):
            for side, colour in ((wall_left, "tab:blue"), (~wall_left, "tab:red")):
                sel = mask & side
                if not sel.any():
                    continue
                ax0.scatter(dest[sel, 0], dest[sel, 1], marker=marker, s=16, color=colour, alpha=0.7,
                            label=f"{label}, wall {'left' if colour == 'tab:blue' else 'right'}")
        ax0.set_xlabel("destination x [m]")
        ax0.set_ylabel("destination y [m]")
        ax0.legend(fontsize=6)
        ax0.set_title(f"unseen environments: {ok.mean():.0%} reached", fontsize=9)
        bins = np.arange(0.5, C.MAX_CYCLES + 1.5)
        for ep, label in ((train, "training 96"), (unseen, f"unseen {len(envs)}")):
            good = T.success(ep)
            if not good.any():
                continue
            ax1.hist(ep.cycles[good], bins=bins, alpha=0.6, density=True, label=label)
            ax2.hist(np.hypot(*ep.final_error[good].T), bins=np.linspace(0, C.GOAL_RADIUS, 21), alpha=0.6,
                     density=True, label=label)
        ax1.set_xlabel("walking cycles to the goal")
        ax2.set_xlabel("final distance error [m]")
        for ax in (ax1, ax2):
            ax.legend(fontsize=7)


def plot_shipped_curves(ctx) -> None:
    """The shipped networks' learning curves, one panel per training stage."""
    with ctx.figure("shipped_learning_curves", nrows=1, ncols=len(T.STAGES), figsize=(15, 4)) as (fig, axes):
        for ax, s in zip(axes, T.STAGES):
            best, mean, _ = T.load_curve(None, s)
            draw_curve(ax, best, mean, CURVE_TITLES[s])


POINT_STYLES = {(1, U.FORWARD): ("leg 1 forward", "tab:blue", "o"), (1, U.SIDE): ("leg 1 side", "tab:cyan", "s"),
                (0, U.FORWARD): ("leg 2 forward", "tab:red", "o"), (0, U.SIDE): ("leg 2 side", "tab:orange", "s")}


def plot_sensed_walks(ctx, walks: dict) -> None:
    """Top views of sensed walks ``{title: (env, records, perception)}`` with every echo's point."""
    with ctx.figure("sensed_walks", nrows=1, ncols=len(walks), figsize=(6.4 * len(walks), 6.4),
                    squeeze=False) as (fig, axes):
        for ax, (title, (env, records, p)) in zip(axes[0], walks.items()):
            draw_walk(ax, env, records, triangles=False)
            points, beam = p.points[0], p.beam[0]
            for (side, b), (label, colour, marker) in POINT_STYLES.items():
                pts = points[side][beam[side] == b]
                pts = pts[np.isfinite(pts[:, 0])]
                ax.scatter(pts[:, 0], pts[:, 1], s=9, marker=marker, facecolors="none", edgecolors=colour, lw=0.6,
                           label=f"echo: {label} ({len(pts)})")
            ax.set_title(title, fontsize=8)
            ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0))


def plot_features(ctx, env: W.Environment, p: U.SensedObstacles) -> None:
    """Known and sensed features per cycle of one walk (sentinels shown as gaps)."""
    known, sensed = p.known[0], p.sensed[0]
    k = np.arange(1, len(known) + 1)
    with ctx.figure("sensed_features", nrows=2, ncols=3, figsize=(13, 6.2)) as (fig, axes):
        for row, (i, side) in zip(axes, enumerate(("right", "left"))):
            for ax, (j, group) in zip(row, ((0, "x"), (2, "y"), (4, "z"))):
                for col, (f, style) in enumerate(((known, "-"), (sensed, "--"))):
                    gone = np.all(f[:, i] == SENTINELS[i], axis=-1)
                    for dj, name in ((0, "max"), (1, "min")):
                        if group == "z" and name == "min":
                            continue
                        y = np.where(gone, np.nan, f[:, i, j + dj])
                        ax.plot(k, y, style, color=f"C{dj}", marker="o" if col else "", ms=3, lw=1,
                                label=f"{'sensed' if col else 'known'} {group}_{name}")
                ax.set_title(f"{env.name}: {side} obstacle, {group} (body frame)", fontsize=8)
                ax.set_xlabel("walking cycle k")
                ax.set_ylabel("[m]")
                ax.legend(fontsize=6)


def plot_success(ctx, rates: dict, noise_curve: list, incidence_curve: list, p: dict) -> None:
    keys = ("success_rate", "collision_rate", "limit_rate", "timeout_rate")
    with ctx.figure("success", nrows=1, ncols=3, figsize=(14, 4.2)) as (fig, (ax0, ax1, ax2)):
        x = np.arange(len(keys))
        for off, name in ((-0.2, "known"), (0.2, "sensed")):
            values = [rates[name][key] for key in keys]
            bars = ax0.bar(x + off, values, width=0.4, label=f"{name} features")
            ax0.bar_label(bars, fmt="%.2f", fontsize=7)
        ax0.set_xticks(x, ["reached", "collision", "joint limit /\nstability", "50 cycles"], fontsize=8)
        ax0.set_ylim(0, 1.1)
        ax0.set_title(f"training environments (noise {p['noise_std']:g} m, incidence ≤ {p['incidence_deg']:g}°)",
                      fontsize=9)
        ax0.legend(fontsize=7)
        for ax, curve, xlabel in ((ax1, noise_curve, "range-noise std [m]"),
                                  (ax2, incidence_curve, "incidence limit [deg]")):
            xs = [c[0] for c in curve]
            ax.plot(xs, [c[1] for c in curve], "o-", label="sensed features")
            ax.axhline(rates["known"]["success_rate"], color="k", ls="--", lw=1, label="known features")
            ax.axhline(rates["blind"]["success_rate"], color="tab:red", ls=":", lw=1,
                       label="no echo at all (sentinels only)")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("success rate")
            ax.set_ylim(0, 1.05)
            ax.legend(fontsize=7)
        ax1.set_title(f"incidence ≤ {p['incidence_deg']:g}°, seed {ctx.seed}", fontsize=9)
        ax2.set_title(f"noise {p['noise_std']:g} m", fontsize=9)


def plot_learning_curves(ctx, results: dict) -> None:
    """The learning curves of a training run ``{stage: result}``, one panel per stage."""
    with ctx.figure("learning_curves", nrows=1, ncols=len(results), figsize=(5 * len(results), 4),
                    squeeze=False) as (fig, axes):
        for ax, (stage, r) in zip(axes[0], results.items()):
            draw_curve(ax, r.best, r.mean, CURVE_TITLES[stage])
