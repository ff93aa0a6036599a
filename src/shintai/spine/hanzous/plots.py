"""HanzouS's brachiation pictures (seed 003 §3.3.4 Fig. 3.14, §5.7.4 Fig. 5.24, §5.7.5 Figs. 5.25–5.27)."""

from __future__ import annotations

import numpy as np

from shintai.spine.ga_run import draw_curve

COLOURS = {"stiff": "tab:red", "soft": "tab:blue", "real": "tab:green"}


def trunk_force(ctx, outcomes: dict, name: str = "trunk_root_force") -> None:
    """Fig. 5.24's counterpart: the trunk root's internal force against time, one line per stiffness, with the
    release and grasp instants marked."""
    with ctx.figure(name, figsize=(7, 4)) as (_fig, ax):
        for policy, o in outcomes.items():
            ax.plot(o.log["t"], o.log["trunk_root_force_n"], lw=0.9, color=COLOURS.get(policy), label=policy)
            if np.isfinite(o.grasp_s):
                ax.axvline(o.grasp_s, color=COLOURS.get(policy), ls=":", lw=0.8)
        ax.set_xlabel("time [s]  (dotted: right hand grasps the next bar)")
        ax.set_ylabel("trunk-root internal force [N]")
        ax.set_title("HanzouS brachiation: internal force at the trunk root (cf. seed 003 Fig. 5.24)", fontsize=9)
        ax.legend(fontsize=8)


def stiffness(ctx, outcomes: dict, name: str = "trunk_stiffness") -> None:
    """The trunk's stiffness E I / l against time (the cam's effect), and the trunk's deflection."""
    with ctx.figure(name, nrows=2, ncols=1, figsize=(7, 5.5), sharex=True) as (_fig, axes):
        for policy, o in outcomes.items():
            axes[0].plot(o.log["t"], o.log["stiffness_nm_rad"], color=COLOURS.get(policy), label=policy)
            axes[1].plot(o.log["t"], np.degrees(o.log["trunk_deflection_rad"]), color=COLOURS.get(policy), lw=0.9)
            if np.isfinite(o.release_s):
                axes[0].axvline(o.release_s, color=COLOURS.get(policy), ls="--", lw=0.6)
        axes[0].set_ylabel("trunk stiffness EI/l [N m/rad]")
        axes[0].set_title("cam-set trunk stiffness (dashed: right hand releases the rear bar)", fontsize=9)
        axes[0].legend(fontsize=8)
        axes[1].set_ylabel("trunk deflection [deg]")
        axes[1].set_xlabel("time [s]")


def ga_curves(ctx, curves: dict, name: str = "ga_curves") -> None:
    """One GA's best and mean fitness per generation for each stiffness policy, side by side."""
    with ctx.figure(name, nrows=1, ncols=len(curves), figsize=(4.5 * len(curves), 3.6), squeeze=False) as (_fig, axes):
        for ax, (policy, c) in zip(axes[0], curves.items()):
            draw_curve(ax, c["best"], c["mean"], f"GA brachiation, trunk {policy}")
