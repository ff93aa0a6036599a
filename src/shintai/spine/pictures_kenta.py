"""Pictures of Kenta's taught postures (Fig. 4.1) and of the tracking loops (Figs. 5.12, 5.14)."""

from __future__ import annotations

import numpy as np

AXES = ("roll", "pitch", "yaw")


def taught_postures(ctx, series: dict) -> None:
    """Whole-spine roll, pitch, yaw during the cyclic replay against the three taught postures."""
    with ctx.figure("replay", 3, 1, figsize=(10, 7.5), sharex=True) as (fig, axes):
        for a, ax in enumerate(axes):
            ax.plot(series["t"], series["whole"][:, a], color="k", lw=1.2, label="replayed")
            for k, taught in enumerate(series["taught"]):
                ax.axhline(taught[a], color=f"C{k}", ls="--", lw=1, label=f"taught posture {k + 1}")
            ax.set_ylabel(f"whole-spine {AXES[a]} [deg]")
            ax.grid(alpha=0.3)
        axes[0].legend(fontsize=8, ncol=4)
        axes[-1].set_xlabel("time since the replay started [s]")


def tracking(ctx, runs: dict) -> None:
    """Per robot: the target's angle from the optical axis, and each part's share of the gaze's pan."""
    with ctx.figure("tracking", len(runs), 2, figsize=(13, 3.6 * len(runs)), squeeze=False) as (fig, axes):
        for row, (robot, run) in enumerate(runs.items()):
            s = run["series"]
            ax = axes[row, 0]
            ax.plot(s["t"], np.degrees(s["image"][:, 0]), label="horizontal")
            ax.plot(s["t"], np.degrees(s["image"][:, 1]), label="vertical")
            ax.set_ylabel(f"{robot}: target off axis [deg]")
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
            ax = axes[row, 1]
            names = ("spine", "neck", "eyes")[:s["gaze"].shape[1]]
            for k, name in enumerate(names):
                ax.plot(s["t"], np.degrees(s["gaze"][:, k, 0]), label=f"{name} pan")
            ax.plot(s["t"], np.degrees(s["gaze"][:, :, 0].sum(axis=1)), "k--", lw=1, label="sum")
            ax.set_ylabel("pan [deg]")
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
        axes[-1, 0].set_xlabel("time [s]")
        axes[-1, 1].set_xlabel("time [s]")
