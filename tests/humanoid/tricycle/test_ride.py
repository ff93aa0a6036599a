"""Steering and pedalling together (seed 000 §3.5.2 E3, §3.5.4 E5–E7): the joystick scripts, the
swap counts Eq. 3.19 predicts, and shortened rides of humanoid.tricycle-slalom and
humanoid.outdoor-run."""

import math

import numpy as np
import pytest

from shintai.humanoid.constants import D_THETA_C, D_THETA_H, DEG, F_TRG_PASSIVE_LEG_IMPROVED, THETA_C_INIT
from shintai.humanoid.tricycle.operation import OperationSchedule
from shintai.humanoid.tricycle.ride import (
    expected_swaps,
    handle_crossings,
    leg_gains,
    route_goals,
    signed_travel,
    slalom_goals,
)


def test_slalom_script_is_two_curves_then_fig_3_21():
    goals = slalom_goals(math.pi, 25 * DEG)  # the default slalom: one revolution
    handle = [h / DEG for h, _ in goals]
    crank = [c / DEG for _, c in goals]
    assert handle == pytest.approx([-25, -25, 25, 25, -25, -25, 25, 25])
    # the slalom: −25° while θ_c goes 360° → 540°, +25° while it goes 540° → 720° (Fig. 3.21, one revolution)
    assert crank == pytest.approx([0, 180, 180, 360, 360, 540, 540, 720])


def test_route_visits_both_limits_and_returns_straight():
    goals = route_goals(1.0, 25 * DEG)
    assert [h / DEG for h, _ in goals] == pytest.approx([-25, 25, 0])
    assert goals[-1][1] == pytest.approx(2 * math.pi)


def test_expected_swaps_count_switching_angles_crossed():
    assert expected_swaps(0.0, 2 * math.pi, THETA_C_INIT) == 2  # 110° and 290°
    assert expected_swaps(0.0, 100 * DEG, THETA_C_INIT) == 0
    assert expected_swaps(0.0, 4 * math.pi, THETA_C_INIT) == 4


def test_handle_crossings_count_sign_changes_through_zero():
    assert handle_crossings(np.array([-5, -25, -20, 0, 5, 25, 0, -5]) * DEG) == 2
    assert handle_crossings(np.array([0, -5, -10]) * DEG) == 0


def test_signed_travel_counts_backward_rolling_negative():
    x = np.array([0.0, 1.0, 0.5])
    assert signed_travel(x, np.zeros(3), np.zeros(3)) == pytest.approx(0.5)
    # heading +90°: moving along +y is forward
    assert signed_travel(np.zeros(3), np.array([0.0, 2.0, 3.0]), np.full(3, math.pi / 2)) == pytest.approx(3.0)


def test_improved_settings_lower_only_the_passive_target():
    gains = leg_gains(F_TRG_PASSIVE_LEG_IMPROVED)
    assert gains["passive"].f_trg == (0.0, 0.0, 50.0)
    assert gains["active"].f_trg == (0.0, 0.0, 150.0)
    assert gains["passive"].k == 300.0 and gains["active"].k == 3000.0  # Table 3.4 otherwise


def test_simultaneous_improved_schedule_is_shorter_on_the_route():
    goals = route_goals(1.0, 25 * DEG)
    original = OperationSchedule(0.0, 0.0, goals, 0.8, D_THETA_H, D_THETA_C)
    improved = OperationSchedule(0.0, 0.0, goals, 0.8, D_THETA_H, D_THETA_C, simultaneous=True, wait_fraction=0.8)
    assert len(original.samples) == 5 + 9 + 10 + 18 + 5 + 9  # steer, then pedal, for each goal
    assert len(improved.samples) == 9 + 18 + 9
    assert original.duration / improved.duration == pytest.approx(56 / 36 / 0.8)


def test_slalom_short_ride_steers_pedals_and_swaps_roles(smoke):
    """E3's smoke run: ±10°, 40° of crank per curve, a 60° slalom, Δt = 0.2 s; no fall, every swap
    Eq. 3.19 predicts (one leg swap at 110°, three arm swaps)."""
    out = smoke("humanoid.tricycle-slalom").result
    assert out.get("error") is None, out.get("error")
    m = out["metrics"]
    assert m["falls"] == 0 and m["unreachable_ticks"] == 0
    assert m["leg_role_swaps"] == m["leg_role_swaps_expected"] == 1
    assert m["arm_role_swaps"] == m["arm_role_swaps_expected"] == 3
    assert m["max_handle_error_deg"] <= 5.0
    lo, hi = m["heading_range_deg"]
    assert lo < -3.0 and m["heading_change_deg"] > lo + 3.0  # turned right (θ_h < 0), then back left
    assert m["distance_m"] > 0.5


def test_outdoor_short_run_improved_is_faster_with_a_wider_force_gap(smoke):
    """The smoke run: a fifth of a revolution at ±10°, Δt = 0.2 s."""
    out = smoke("humanoid.outdoor-run").result
    assert out.get("error") is None, out.get("error")
    m = out["metrics"]
    assert m["speed_ratio"] > 1.25
    assert m["falls_original"] == m["falls_improved"] == 0
    assert m["passive_force_mean_improved_n"] < m["passive_force_mean_original_n"]
