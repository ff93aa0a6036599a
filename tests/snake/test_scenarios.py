"""Registered snake scenarios, from their smoke runs: a 4 s snake.tracking run and the full switching ablation
(spec §5.4 #9, #10, #12)."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import shintai.snake
from shintai.scenarios import registry
from shintai.scenarios.registry import ParameterError, get
from shintai.scenarios.runner import run_scenario
from shintai.snake.constants import CH3_GAINS


@pytest.fixture
def short_tracking(smoke):
    run = smoke("snake.tracking")  # 4 s
    return run.out, run.result


@pytest.fixture
def ablation(smoke):
    run = smoke("snake.switching-ablation")  # the full 120 s
    assert run.result["params"] == get("snake.switching-ablation").resolve()
    return run.out, run.result


def test_short_tracking_run_meets_its_tracking_checks(short_tracking):
    out, result = short_tracking
    assert "error" not in result and result["sim_time_s"] == pytest.approx(4.0)
    checks = {c["name"]: c for c in result["checks"]}
    for name in ("max_pos_error_m", "max_heading_error_rad", "final_pos_error_m", "max_abs_joint_rad",
                 "grounded_wheels_max", "stopped_fraction", "min_sigma_a"):
        assert checks[name]["ok"], checks[name]
    m = result["metrics"]
    assert m["mode_selections"] == 2 and m["candidate_count"] == 66  # t = 0 and 2 s; thesis count
    assert m["grounded_wheels_min"] == m["grounded_wheels_max"] == 4
    assert m["max_slip_m_s"] < 1e-9
    # 4 s cannot show the 5–30 distinct-mode band of the full run; the check reports that honestly
    assert not checks["distinct_modes_low"]["ok"] and not result["ok"]
    assert result["thesis"]["distinct_modes"]["value"] == 14
    for png in ("top_view", "errors", "modes"):
        assert (out / f"{png}.png").stat().st_size > 10_000
    assert json.loads((out / "metrics.json").read_text())["metrics"] == m
    assert "two_point.c" in np.load(out / "log.npz")


def test_switching_reproduces_and_fixed_mode_stalls(ablation):
    _, result = ablation
    assert result["ok"], [c for c in result["checks"] if not c["ok"]]
    m = result["metrics"]
    assert m["final_pos_error_fixed_m"] >= 0.1 and m["final_pos_error_switching_m"] < 0.005
    assert m["max_pos_error_switching_m"] <= 0.005  # the full 120 s §3.3 run within 5 mm


def test_stop_holds_the_state_until_the_next_selection(ablation):
    """§3.2.5 / check 9: stopped steps leave φ unchanged; a stop only ends at a periodic mode selection,
    and with the mode frozen (no selection after t = 0) it never ends."""
    out, _ = ablation
    log = np.load(out / "log.npz")
    for name in ("switching", "fixed"):
        stopped = log[f"{name}.two_point.stopped"].astype(bool)
        phi, t = log[f"{name}.two_point.phi"], log[f"{name}.two_point.stopped_t"]
        held = np.flatnonzero(stopped[:-1])
        assert len(held) > 0 and np.abs(phi[held + 1] - phi[held]).max() == 0.0
        resumes = [t[k] for k in range(1, len(stopped)) if stopped[k - 1] and not stopped[k]]
        if name == "switching":
            assert resumes and all(math.isclose(r / CH3_GAINS.t_sigma, round(r / CH3_GAINS.t_sigma)) for r in resumes)
        else:
            first = np.argmax(stopped)
            assert not resumes and stopped[first:].all() and 40.0 < t[first] < 80.0


def test_whole_run_joint_angles_stay_inside_the_limit(ablation):
    out, _ = ablation
    assert np.abs(np.load(out / "log.npz")["switching.two_point.phi"]).max() < math.pi / 2


def test_bad_parameters_are_rejected_before_running(tmp_path):
    with pytest.raises(ParameterError, match="duration_s"):
        get("snake.tracking").resolve({"duration_s": "500"})
    with pytest.raises(ParameterError, match="plant"):
        get("snake.tracking").resolve({"plant": "bullet"})
    assert get("snake.tracking").resolve({"candidates": "80"})["candidates"] == 80
    with pytest.raises(ParameterError, match="--video"):  # the runner's: the kinematic plant has nothing to film
        run_scenario("snake.tracking", out=tmp_path, video=True)


def test_every_snake_scenario_has_its_notes_and_no_scenario_file_is_left():
    registry.load_all()
    ids = [sid for sid in registry.SCENARIOS if sid.startswith("snake.")]
    assert len(ids) == 7 and all(registry.SCENARIOS[sid].notes_path.is_file() for sid in ids)
    assert not list(Path(shintai.snake.__file__).parent.glob("*scenarios*.py"))
