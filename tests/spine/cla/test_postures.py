"""E11's posture player and observer (seed 003 §4.7.2, Appendix A.1.3)."""

import numpy as np
import pytest

from shintai.core.runtime import Loop
from shintai.spine.control import encoder_targets
from shintai.spine.geometry import uniform_posture
from shintai.spine.cla.postures import PostureObserver, PostureTargets, axis_sequence
from shintai.spine.robots import CLA, REST_DRIFT_DEG


def test_posture_targets_follow_the_min_jerk_move_then_hold():
    """PostureTargets writes eq. 4.25's lengths of the player's posture on every tick of a move, ends at
    the commanded posture, and leaves the targets alone while idle (only the reference is written)."""
    zero = CLA.model.lengths(np.zeros(15))
    targets = PostureTargets(CLA.model, zero, move_s=1.0)
    targets.reset({"t": 0.0})
    whole = np.radians([0.0, -30.0, 0.0])
    out = targets.update({"t": 0.0, "goal": whole})
    l_r = out["l_r"]
    for k in range(1, 1100):
        l_r = out.get("l_r", l_r)  # the controller keeps the last targets it was given
        assert np.array_equal(l_r, encoder_targets(CLA.model.lengths(uniform_posture(out["whole_ref"], CLA.n)), zero))
        assert np.array_equal(out.get("l_0", l_r), l_r)
        if k == 500:
            assert 0.3 < out["whole_ref"][1] / whole[1] < 0.7  # mid-way through the move
        out = targets.update({"t": k * 1e-3})
    assert np.allclose(out["whole_ref"], whole)
    idle = targets.update({"t": 1.2})
    assert set(idle) == {"whole_ref"} and np.allclose(idle["whole_ref"], whole)  # idle: targets untouched


def test_axis_sequence_is_the_thesis_order():
    """§4.7.2: 0 → −10 → … → −max → … → +max → … → 0 in 10° steps."""
    assert axis_sequence(20) == [0, -10, -20, -10, 0, 10, 20, 10, 0]


class _StillBody:
    """A body that holds a fixed reading (encoder-free): theta bent by ``bend_deg`` about pitch, or bending on
    at ``rate_deg_s`` (a collapse)."""

    dt = 1e-3
    channels = {}

    def __init__(self, bend_deg, rate_deg_s=0.0):
        self.t, self.bend, self.rate = 0.0, bend_deg, rate_deg_s

    @property
    def theta(self):
        return np.tile(np.radians([0.0, (self.bend + self.rate * self.t) / 5, 0.0]), 5)

    def snapshot(self):
        return {"t": self.t, "theta": self.theta, "posture": np.array([0.0, self.theta[1::3].sum()]),
                "current": np.full(8, 0.02), "tension_true": np.full(8, 2.0), "whole_ref": np.zeros(3)}

    def apply(self, command):
        pass

    def step(self):
        self.t += self.dt


LIMITS = np.radians(np.full(15, 18.0))  # Cla's stops (§3.6.1)


def test_observer_measures_each_posture():
    """The window's accelerometer mean gives the error, tension and current; a spine at rest within the
    limits holds every posture under all three tests."""
    still = PostureObserver(axis=1, targets_deg=[0, 10], settle=5, moving=10, window=4, limits_rad=LIMITS)
    Loop(_StillBody(0.0), [still]).run(0.033)
    assert [r.target_deg for r in still.rows] == [0, 10] and still.stopped
    assert still.rows[0].error_deg < 1e-9 and still.rows[1].error_deg == 10.0
    assert all(r.held and r.held_fall30 and r.held_window for r in still.rows)
    assert still.rows[0].drift_deg == pytest.approx(0.0) and not still.rows[0].range_end
    assert still.rows[0].tension_kgf == pytest.approx(2.0 / 9.80665)
    assert still.rows[0].current_posture_a == pytest.approx(0.02)


def test_a_spine_at_rest_far_off_is_held_by_the_thesis_criterion_only():
    """The thesis's criterion is a collapse (the spine was caught, §4.7.2, App. A.2), not an error size: a
    spine resting 25° off its reference is held, while the window-only test and the 30° rule (error ≤ 20°)
    lose it; the sequence runs on until every test has lost a posture."""
    bent = PostureObserver(axis=1, targets_deg=[0, 10, 20], settle=5, moving=10, window=10, limits_rad=LIMITS)
    Loop(_StillBody(25.0), [bent]).run(0.2, until=lambda snap: bent.stopped)
    assert bent.rows[0].held and not bent.rows[0].held_window and not bent.rows[0].held_fall30
    assert len(bent.rows) == 3 and bent.stopped  # the thesis's test never lost one: to the end of the list


def test_a_spine_still_moving_away_or_at_its_stops_is_lost():
    """Lost by the thesis's criterion: still moving away from the reference at the end of the hold (by more
    than REST_DRIFT_DEG across the window), or a joint at its stop while the posture is commanded."""
    falling = PostureObserver(axis=1, targets_deg=[0, 10], settle=5, moving=10, window=100, limits_rad=LIMITS)
    Loop(_StillBody(1.0, rate_deg_s=4 * REST_DRIFT_DEG / 0.1), [falling]).run(0.3, until=lambda s: falling.stopped)
    assert not falling.rows[0].held and falling.rows[0].drift_deg > REST_DRIFT_DEG and not falling.rows[0].range_end
    assert falling.rows[0].held_window  # within 20° for the window: the window-only test keeps it
    creeping = PostureObserver(axis=1, targets_deg=[0], settle=5, moving=10, window=100, limits_rad=LIMITS)
    Loop(_StillBody(1.0, rate_deg_s=0.5 * REST_DRIFT_DEG / 0.1), [creeping]).run(0.2)
    assert creeping.rows[0].held  # drifts less than REST_DRIFT_DEG across the window
    stops = PostureObserver(axis=1, targets_deg=[0], settle=5, moving=10, window=10, limits_rad=LIMITS)
    Loop(_StillBody(5 * 18.0), [stops]).run(0.05)
    assert stops.rows[0].range_end and not stops.rows[0].held and stops.rows[0].range_end_joint == 1  # joint 1 pitch
