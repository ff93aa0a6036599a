"""The tricycle benchmark runs on the experiments' rigs (a short run: no wall-clock assertion)."""

import math

from shintai.humanoid.benchmarks import tricycle_overhead


def test_tricycle_overhead_runs_both_configurations_for_the_same_simulated_time():
    out = tricycle_overhead(seconds=0.4)
    for name in ("pedaling", "driving"):
        assert out[f"{name}_physics_steps"] > 0
        assert out[f"{name}_sim_time_s"] > 0.0
        assert math.isfinite(out[f"{name}_overhead_ratio"]) and out[f"{name}_overhead_ratio"] > 0.0
