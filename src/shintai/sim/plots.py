"""The figures of the sim experiments (``sim.wall-force``), drawn with ``ctx.figure``."""

from __future__ import annotations

import numpy as np

from shintai.sim.corner import AXES


def plot_wall_force(ctx, errors, refs, f_trg, n) -> None:
    """``sim.wall-force``: the reaction on the hand and the reference change per update (dashed: the x wall moves)."""
    k = np.arange(len(errors))
    with ctx.figure("wall_force", 1, 2, figsize=(11, 4)) as (fig, ax):
        for i, a in enumerate(AXES):
            ax[0].plot(k, errors[:, i] + f_trg[i], label=f"f_{a} (target {f_trg[i]:g} N)")
            ax[0].axhline(f_trg[i], color=f"C{i}", ls=":", lw=0.8)
            ax[1].plot(k, 1000 * (refs[:, i] - refs[0, i]), label=f"ρ_{a}")
        for axis in ax:
            axis.axvline(n - 0.5, color="k", lw=0.8, ls="--")
            axis.set_xlabel("update k (dashed: the x wall moves toward the hand)")
            axis.legend(fontsize=8)
        ax[0].set_ylabel("reaction on the hand [N]")
        ax[1].set_ylabel("reference change [mm]")
