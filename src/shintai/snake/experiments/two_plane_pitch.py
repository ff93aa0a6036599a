"""``snake.two-plane-pitch``: seed 001 §4.5 condition 2 — head transition, straddling and connection transitions
onto a front plane pitched by −0.0609 rad; the same run without the null-space term as the second variant."""

from __future__ import annotations

from shintai.scenarios.registry import experiment
from shintai.snake.constants import CONDITION_2
from shintai.snake.plots_two_plane import plot_two_plane
from shintai.snake.two_plane_runs import PARAMS, checks, condition_metrics, condition_rig, thesis_values, variants

experiment(
    "snake.two-plane-pitch",
    source="seed 001 §4.5 condition 2",
    covers=("001:fig4.14",),
    summary="head transition, straddling and connection transitions onto a front plane pitched by −0.0609 rad",
    params=PARAMS, checks=checks(), thesis=thesis_values(CONDITION_2, "Fig. 4.14"),
    rig=lambda params, variant, seed: condition_rig(CONDITION_2, params["duration_s"], variant),
    variants=lambda params: variants(params["null_space"]),
    metrics=lambda runs, params: condition_metrics(runs, params["null_space"]),
    plots=lambda ctx, runs, params: plot_two_plane(ctx, runs, params["null_space"]),
    smoke={"duration_s": 18.0},  # the first front shift, with and without the null space
)
