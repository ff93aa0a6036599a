"""The spine scenarios' smoke runs (tests/smoke.py, sizes declared beside each experiment): the behaviour each is
about."""

import json
import math

import pytest

from shintai.scenarios.registry import ParameterError, get


def test_spine_scenarios_are_registered():
    for sid in ("spine.control-modes", "spine.teach-playback", "spine.software-spring", "spine.rabbit-stiffening"):
        assert get(sid).checks
    assert get("spine.control-modes").demo and get("spine.control-modes").video


def test_control_modes_smoke_run_reports_every_mode(smoke):
    """The smoke run (every mode configuration and the ablation, ±10°, short holds): the checks name Table 4.7's and
    4.8's rows, the tables carry the thesis's values beside ours, the pictures are drawn. What the modes do at
    ±20° is tested on the rigs themselves (tests/spine/cla/test_modes.py)."""
    run = smoke("spine.control-modes")
    out, result = run.out, run.result
    assert "error" not in result
    m = result["metrics"]
    assert "held_cells_agree" not in m  # only over the thesis's ±30° range
    checks = {c["name"]: c for c in result["checks"]}
    assert {c["row"] for c in checks.values() if c["kind"] == "reproduction"} == {"003:table4.7", "003:table4.8"}
    assert checks["all_l.t47_error_gap_roll_deg"]["threshold"] == 2.0 and "l_t.max_roll_held_deg" in checks
    table = result["extra"]["table_4_8"]
    assert table["all_l"]["thesis"]["mean_error_pitch_deg"] == 4.73 and "mean_current_a" in table["all_l"]["ours"]
    assert set(result["extra"]["postures"]) == set(table) | {"all_l_no_interference"}
    for png in ("table_4_8", "posture_errors", "posture_time_series", "spine_3d"):
        assert (out / f"{png}.png").stat().st_size > 10_000
    assert json.loads((out / "metrics.json").read_text())["metrics"] == m


def test_control_modes_rejects_unknown_modes():
    """A bad parameter is a parameter error before anything runs (exit 2), not a failed run."""
    with pytest.raises(ParameterError, match="unknown or repeated mode configuration"):
        get("spine.control-modes").resolve({"modes": "all_x"})
    with pytest.raises(ParameterError, match="window_s"):
        get("spine.control-modes").resolve({"hold_s": "1.0", "window_s": "2.0"})
    with pytest.raises(ParameterError, match="speedups"):
        get("spine.teach-playback").resolve({"speedups": "1,0"})


def test_teach_playback_short_run(smoke):
    result = smoke("spine.teach-playback").result
    m = result["metrics"]
    assert m["speedup_4.relative_length_error"] < 0.1 and m["speedup_4.saturated_fraction"] == 0
    assert m["speedup_8.saturated_fraction"] > 0.05
    assert m["speedup_8.relative_length_error"] > 2 * m["speedup_4.relative_length_error"]
    assert m["speedup_8.duration_s"] == pytest.approx(m["speedup_1.duration_s"] / 8, abs=0.03)
    # the band of demonstration speeds the outcome implies: 1/8 … 1/4 of the drive's no-load wire speed
    assert m["implied_band_hi_mm_s"] == pytest.approx(2 * m["implied_band_lo_mm_s"])
    assert all(c["kind"] == "consistency" for c in result["checks"])  # the outcome follows from the chosen speed


def test_software_spring_short_run(smoke):
    result = smoke("spine.software-spring").result
    assert result["ok"], [c for c in result["checks"] if not c["ok"]]
    m = result["metrics"]
    assert m["k_s_400.tension_per_length_n_mm"] > 4 * m["k_s_50.tension_per_length_n_mm"]


def test_rabbit_stiffening_short_run(smoke):
    run = smoke("spine.rabbit-stiffening")
    m = run.result["metrics"]
    assert m["stiffness_monotone"] == 1 and m["stiffness_ratio"] > 2
    assert m["pre_1.5mm.disc_compression_mm"] > m["pre_0.25mm.disc_compression_mm"]
    assert (run.out / "rabbit_stiffness.png").exists()


def test_inverse_model_short_run(smoke):
    """§4.4.3 on a short training: the NN beats Jacobian integration (Cla's rank-6 J_m lands the
    integration on another posture) and answers far faster; both networks and every metric report."""
    result = smoke("spine.inverse-model").result
    m = result["metrics"]
    assert m["nn_test_error_norm_deg"] < m["jacobian_test_error_norm_deg"]
    assert math.isfinite(m["nn4_test_error_norm_deg"]) and m["nn_train_max_joint_error_deg"] < 5.0
    assert m["nn_query_us"] * 1e-6 < m["jacobian_query_s"]


def test_bebe_tracking_short_run(smoke):
    """§4.8 on short runs: the target is mostly in the dead zone, pushes are recovered, and switching
    off before on keeps few muscles on (the on-first ablation piles them up)."""
    result = smoke("spine.bebe-tracking").result
    m = result["metrics"]
    assert "error" not in result
    assert m["dead_zone_fraction"] > 0.5 and m["disturbance_dead_zone_fraction"] > 0.5
    assert m["max_on_muscles"] < m["max_on_muscles_on_first"] / 2


def test_sq43_design_short_run(smoke):
    """§3.2.3: the four compass searches end at local optima within |a_i| ≤ 30° (consistency); the thesis's
    outcome — which start wins, which stall at once, which path start 4 joins — is reported beside ours, with no
    reproduction check (Table 3.1's row is not comparable: its FEM landscape is not printed), on values of ours
    that are well defined (whatever they are)."""
    result = smoke("spine.sq43-design").result
    checks = {c["name"]: c for c in result["checks"]}
    assert all(c["ok"] for c in checks.values() if c["kind"] == "consistency"), checks
    assert not [n for n, c in checks.items() if c["kind"] == "reproduction"]
    assert {"best_start", "stuck_immediately", "start4_joins"} <= set(result["thesis"])
    m = result["metrics"]
    assert m["best_start"] in (1, 2, 3, 4) and m["start4_joins_path"] in (0, 1, 2, 3)
    step = result["params"]["step_deg"]
    assert m["travel_deg_start1"] == step * m["steps_start1"] and m["travel_deg_start3"] == step * m["steps_start3"]
    assert m["starts_1_3_stuck"] == sum(m[f"travel_deg_start{k}"] <= 5.0 for k in (1, 3))


def test_tension_sensor_resolution_follows_the_calibration_slope(smoke):
    """Fig. 3.34's bench run: each count step's width is one count over the calibration's local slope (the sweep
    measures what the model's derivative says), and it widens with the tension."""
    from shintai.spine.actuators import TensionSensor
    from shintai.spine.robots import CLA

    m = smoke("spine.tension-sensor").result["metrics"]
    sensor = TensionSensor(CLA.sensor)
    for t in (10.0, 100.0, 300.0):
        assert m[f"step_at_{t:g}n_n"] == pytest.approx(1.0 / float(sensor.slope_counts_n(t)), rel=0.25)
    assert m["step_at_1n_n"] < m["step_at_10n_n"] < m["step_at_100n_n"] < m["step_at_300n_n"]
    assert m["readback_error_large_n"] > 10 * m["readback_error_small_n"]
