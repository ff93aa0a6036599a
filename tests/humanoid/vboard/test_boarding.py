"""HRP2 boards the V-BOARD (seed 000 §5.4): the scene, the footsteps onto the pads, and a truncated
``humanoid.vboard-boarding`` run — the SLC window opens on the left foot's landing on its board and closes on
the right foot's, D changes inside it only, and the right pitch takes the learned D."""

import numpy as np
import pytest

from shintai.humanoid.balance.standing import settle_on_floor, stand_geometry
from shintai.humanoid.constants import VBOARD
from shintai.humanoid.vboard.boarding import BOARD_X, boarding_body, boarding_steps
from shintai.scenarios.registry import ParameterError, get

SID = "humanoid.vboard-boarding"


def test_the_scene_the_robot_on_the_floor_the_scooter_ahead_drives_off_steps_onto_the_pad_centres():
    body = boarding_body()
    settle_on_floor(body)
    soles, _ = stand_geometry(body)
    assert all(abs(soles[s][2]) < 2e-3 for s in "lr")  # on the floor
    assert body.firmware.on == {"l": False, "r": False}  # nobody on the pads: drives off
    steps = boarding_steps(soles)
    assert [s.side for s in steps] == ["l", "r"]
    for step in steps:
        pad = body.site_pos(f"board_{step.side}_top")
        assert (step.x, step.y, step.z) == pytest.approx((pad[0], pad[1], VBOARD.deck_height), abs=2e-3)
    assert body.site_pos("vboard_centre")[0] == pytest.approx(BOARD_X)


@pytest.fixture(scope="module")
def short_run(smoke):
    """The smoke run, both variants up to 3.6 s: past the right landings (≈3.31 s without SLC, ≈3.38 s with, the
    soles not creeping on the pads: vboard.constants.NOSLIP_ITERATIONS; with creep they were ≈3.12 and ≈3.22 s). The metrics and the recorded f_Rz, right pad switch of the SLC run."""
    run = smoke(SID)
    assert run.result["params"]["max_s"] == 3.6 and run.result.get("error") is None, run.result.get("error")
    with np.load(run.out / "log.npz") as log:
        signals = {k: log[f"slc.{k}"] for k in ("f_Rz", "f_Rz_t", "switch_r")}
    return run.result["metrics"], signals


def test_the_slc_window_opens_on_the_left_landing_and_closes_on_the_right_landing(short_run):
    m, log = short_run
    # the plan's left swing is 1.2–2.0 s and the right's 2.2–3.0 s; the left foot unloads through 25 N at
    # ≈1.2 s, which must not start SLC (the guard fix), nor the right's lift-off chatter at ≈2.2 s stop it
    assert 1.9 < m["t_left_landing_s"] < 2.05 and 2.9 < m["t_right_landing_s"] < 3.5
    assert m["slc_duration_s"] == pytest.approx(m["t_right_landing_s"] - m["t_left_landing_s"])
    assert 1.0 < m["window_without_slc_s"] < 1.45  # same guards, no learning: the same swing, landing ≈0.07 s earlier
    # SLC stops on the thesis's guard, f_Rz > F_thre = 25 N (§5.4.1, Table 5.2), the right foot's first placement:
    # f_Rz ≤ 25 N through the swing up to the stop, > 25 N on the stop's tick
    t, f = log["f_Rz_t"], log["f_Rz"]
    swing = (t > 2.5) & (t < m["t_right_landing_s"] - 1e-6)
    assert swing.any() and f[swing].max() <= 25.0
    assert f[np.argmin(np.abs(t - m["t_right_landing_s"]))] > 25.0
    # the scooter's own contact switches (pad force > 20 N, its firmware) are a different event: the left one turns
    # on with the guard; the right one turns on first, when the unloaded board tipping about its axle knocks the
    # descending sole (pad impulses past 20 N while the ankle sensor reads < 25 N), never after the guard
    assert m["t_left_landing_s"] == pytest.approx(m["t_left_switch_on_s"], abs=0.01)
    assert m["t_right_switch_on_s"] <= m["t_right_landing_s"]


def test_d_changes_inside_the_window_only_and_the_right_foot_takes_it(short_run):
    m, _ = short_run
    assert m["damping_rise"] > 1.0 and m["damping_change_outside_window"] == 0.0
    assert m["damping_change_without_slc"] == 0.0
    assert m["right_took_learned_d"] == 1 and m["right_pitch_damping_final"] == m["damping_final"]
    assert m["roll_damping_final"] == m["damping_initial"] == 22.0
    assert m["fell_without_slc"] == 0 and m["fell_with_slc"] == 0 and m["ik_unreachable"] == 0
    assert np.isfinite(m["delta_max_with_slc_deg"])


@pytest.mark.parametrize("key, value", [("eta", "2"), ("D0", "-22"), ("R", "nan"), ("max_s", "0")])
def test_bad_settings_are_one_line_parameter_errors(key, value):
    with pytest.raises(ParameterError) as info:
        get(SID).resolve({key: value})
    assert "\n" not in str(info.value)
