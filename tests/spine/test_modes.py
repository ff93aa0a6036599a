"""E11's analysis (seed 003 §4.7.2–4.7.3): the hold tests and Table 4.8's summary."""

import pytest

from shintai.spine.modes import max_held, rows_until_lost, summarise_mode
from shintai.spine.postures import PostureRow
from shintai.spine.robots import HOLD_FALL_DEG


def test_e11_hold_test_looks_at_the_whole_posture():
    """A posture is lost if the spine fell > HOLD_FALL_DEG off the reference at any time while it was
    commanded (the thesis's experimenter caught it, §4.7.2), even if it was back by the measuring
    window; the earlier window-only test survives as ``*_held_window_deg``, and Table 4.8's means
    use only the postures before the first one lost."""
    def row(target, error, worst_posture, current=0.1):
        held = worst_posture <= HOLD_FALL_DEG
        return PostureRow(target, target + error, error, 2.0, 1.0, held, 0.3, current, worst_posture, True, 0.2)

    pitch = [row(-10, 1.0, 2.0), row(0, 1.0, 2.0), row(10, 2.0, 5.0), row(20, 1.0, HOLD_FALL_DEG + 1.0, 9.0),
             row(30, 5.0, 20.0, 9.0)]
    assert max_held(pitch, 30) == 10.0 and max_held(pitch, 30, "held_window") == 30.0
    assert [r.target_deg for r in rows_until_lost(pitch)] == [-10, 0, 10]
    out = summarise_mode({"pitch": pitch}, 30)
    assert out["max_pitch_held_deg"] == 10.0 and out["max_pitch_held_window_deg"] == 30.0
    assert out["collapsed"] == 1 and out["collapsed_window"] == 0
    assert out["mean_error_pitch_deg"] == pytest.approx(4.0 / 3) and out["mean_current_a"] == pytest.approx(0.1)
    assert out["mean_current_posture_a"] == pytest.approx(0.2)


