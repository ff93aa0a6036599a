"""The tricycle benchmark runs on the experiments' rigs (a short run: no wall-clock assertion)."""

import math

from shintai.humanoid.benchmarks import tricycle_overhead


def test_tricycle_overhead_runs_both_configurations_for_the_same_simulated_time():
    out = tricycle_overhead(seconds=0.4, pairs=2)
    for name in ("pedaling", "driving"):
        assert out[f"{name}_physics_steps"] > 0
        assert out[f"{name}_sim_time_s"] > 0.0
        assert math.isfinite(out[f"{name}_overhead_ratio"]) and out[f"{name}_overhead_ratio"] > 0.0
        assert out[f"{name}_physics_us"] > 0.0 and out[f"{name}_control_us"] > 0.0  # where the tick went
        assert out[f"{name}_overhead_ratio_min"] <= out[f"{name}_overhead_ratio"] <= out[f"{name}_overhead_ratio_max"]
        assert math.isfinite(out[f"{name}_overhead_ratio_cpu"]) and out[f"{name}_overhead_ratio_cpu"] > 0.0
        assert out[f"{name}_leg_ik_us"] > 0.0  # the feet solve every tick
        split = sum(out[f"{name}_{k}_us"] for k in ("arm_ik", "leg_ik", "angle_estimates", "control_other"))
        assert math.isclose(split, out[f"{name}_control_us"], rel_tol=1e-9)
        assert out[f"{name}_angle_estimates_us"] > 0.0 and out[f"{name}_signals_us"] > 0.0  # every tick measures, logs
        assert math.isclose(out[f"{name}_signals_us"] + out[f"{name}_rest_other_us"], out[f"{name}_rest_us"],
                            rel_tol=1e-9)
    assert out["pedaling_arm_ik_us"] == 0.0 and out["driving_arm_ik_us"] > 0.0  # only the ride has hands


def test_leg_ik_benchmark_times_both_solvers_on_the_same_targets():
    from shintai.humanoid.benchmarks import leg_ik_cost

    out = leg_ik_cost(ticks=20)
    assert out["calls"] == 20
    assert out["analytic_us_per_call"] > 0.0 and out["dls_us_per_call"] > 0.0
    assert math.isfinite(out["dls_over_analytic"])
    assert out["max_joint_difference_rad"] < 1e-3  # same branch; the DLS IK stops at its 0.1 mm / 1 mrad tolerance


def test_standing_overhead_times_the_stack_against_bare_mj_step():
    from shintai.humanoid.benchmarks import standing_overhead

    out = standing_overhead(seconds=0.2)
    assert out["ticks"] == 50 and out["physics_steps"] == 200
    assert math.isfinite(out["overhead_ratio"]) and out["overhead_ratio"] > 0.0
    for name in ("preview", "footsteps", "stabilizer", "foot_damping", "leg_ik"):
        assert out[f"{name}_us"] > 0.0
    for part in ("snapshot", "view", "combine", "apply"):  # the rest of the tick, split (standing_anatomy)
        assert out[f"rest_{part}_us"] > 0.0
    assert out["physics_check_us"] > 0.0 and out["physics_mj_step_us"] > out["physics_check_us"]
    assert math.isfinite(out["rest_loop_us"])
