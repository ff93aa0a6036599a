"""Pictures of Kenta's taught postures (seed 003 §4.2.1, Fig. 4.1)."""

from __future__ import annotations

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
