"""Pictures of Kenta's taught postures (seed 003 §4.2.1, Fig. 4.1) and of its spine, neck and arms moving at once
(§5.2.11, Fig. 5.13)."""

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


def spine_neck_arms(ctx, s: dict) -> None:
    """Whole-spine, neck and arm angles against their commands (Fig. 5.13's run)."""
    rows = (("spine", AXES, "whole-spine"), ("neck", ("pan", "tilt"), "neck"),
            ("arms", ("shoulder pitch L", "shoulder pitch R", "elbow L", "elbow R"), "arm"))
    with ctx.figure("spine_neck_arms", 3, 1, figsize=(10, 8), sharex=True) as (fig, axes):
        for ax, (key, names, label) in zip(axes, rows):
            for k, name in enumerate(names):
                ax.plot(s["t"], s[key][:, k], color=f"C{k}", lw=1.2, label=name)
                ax.plot(s["t"], s[f"{key}_cmd"][:, k], color=f"C{k}", ls="--", lw=0.8)
            ax.set_ylabel(f"{label} [deg]")
            ax.legend(fontsize=8, ncol=4)
            ax.grid(alpha=0.3)
        axes[0].set_title("measured (solid) and commanded (dashed)", fontsize=9)
        axes[-1].set_xlabel("time since the motion started [s]")
