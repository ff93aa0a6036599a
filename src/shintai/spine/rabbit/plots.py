"""Rabbit's pictures: the lateral stiffness against the discs' pre-compression (seed 003 §3.5.3–3.5.4, E6)."""

from __future__ import annotations


def rabbit(ctx, levels, curves: dict) -> None:
    with ctx.figure("rabbit_stiffness", 1, 1, figsize=(6.4, 4.2)) as (fig, ax):
        for label, stiff in curves.items():
            ax.plot(levels, stiff, "-o", label=label.rstrip(".").replace("_", " "))
        ax.set_xlabel("disc pre-compression the muscle lengths are computed for [mm]")
        ax.set_ylabel("lateral stiffness at the top [N/mm]")
        ax.set_yscale("log")
        ax.legend(fontsize=8)
