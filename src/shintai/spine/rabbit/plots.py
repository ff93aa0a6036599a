"""Rabbit's pictures: the lateral stiffness against the discs' pre-compression (seed 003 §3.5.3–3.5.4, E6) and the
yaw turn carrying the upper body (§3.5.4, Fig. 3.27)."""

from __future__ import annotations


def rabbit(ctx, levels, curves: dict) -> None:
    with ctx.figure("rabbit_stiffness", 1, 1, figsize=(6.4, 4.2)) as (fig, ax):
        for label, stiff in curves.items():
            ax.plot(levels, stiff, "-o", label=label.rstrip(".").replace("_", " "))
        ax.set_xlabel("disc pre-compression the muscle lengths are computed for [mm]")
        ax.set_ylabel("lateral stiffness at the top [N/mm]")
        ax.set_yscale("log")
        ax.legend(fontsize=8)


def yaw_turn(ctx, runs: dict) -> None:
    """Fig. 3.27: the top's yaw against the commanded turn, and the top's tilt, per run ({name: log})."""
    with ctx.figure("rabbit_yaw_turn", 1, 2, figsize=(11.0, 4.2)) as (fig, ax):
        for name, log in runs.items():
            step = range(len(log.values("yaw_deg")))
            ax[0].plot(step, log.values("yaw_deg"), "-o", ms=3, label=f"top yaw, {name}")
            ax[1].plot(step, log.values("tilt_deg"), "-o", ms=3, label=name)
        ax[0].plot(step, runs[next(iter(runs))].values("command_deg"), "k--", lw=0.8, label="commanded")
        ax[0].set_xlabel("sweep step (one equilibrium each)")
        ax[0].set_ylabel("yaw [deg]")
        ax[0].legend(fontsize=7)
        ax[1].set_xlabel("sweep step")
        ax[1].set_ylabel("top part's tilt from vertical [deg]")
        ax[1].legend(fontsize=7)
        fig.suptitle("Rabbit's spine turning in yaw (§3.5.4, Fig. 3.27), quasi-static", fontsize=9)
