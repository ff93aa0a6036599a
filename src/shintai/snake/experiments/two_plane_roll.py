"""``snake.two-plane-roll``: seed 001 §4.5 condition 1 — head transition, straddling and connection transitions
onto a front plane rolled by −0.107 rad; the same run without the null-space term as the second variant."""

from __future__ import annotations

from shintai.scenarios.registry import experiment
from shintai.snake.constants import CONDITION_1
from shintai.snake.plots_two_plane import plot_two_plane
from shintai.snake.two_plane_runs import PARAMS, checks, condition_metrics, condition_rig, thesis_values, variants

experiment(
    "snake.two-plane-roll",
    source="seed 001 §4.5 condition 1",
    covers=("001:fig4.13",),
    summary="head transition, straddling and connection transitions onto a front plane rolled by −0.107 rad",
    params=PARAMS, checks=checks(), thesis=thesis_values(CONDITION_1, "Fig. 4.13"),
    rig=lambda params, variant, seed: condition_rig(CONDITION_1, params["duration_s"], variant),
    variants=lambda params: variants(params["null_space"]),
    metrics=lambda runs, params: condition_metrics(runs, params["null_space"]),
    plots=lambda ctx, runs, params: plot_two_plane(ctx, runs, params["null_space"]),
    smoke={"duration_s": 2.0, "null_space": False},
)
