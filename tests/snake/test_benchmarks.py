"""The snake benchmark on a short tracking run (no wall-clock assertion): the tick's split adds up and timing it
changes nothing."""

import numpy as np

from shintai.scenarios.experiment import run_rig
from shintai.snake.benchmarks import _tick_breakdown_run, tracking_speed
from shintai.snake.tracking import TrackingRun, tracking_rig


def test_tracking_speed_splits_the_tick_into_parts_that_add_up():
    out = tracking_speed(duration=1.0)
    assert out["control_periods"] == 20 and out["mode_selection_agrees"]
    parts = ("plant_step_us", "control_input_us", "mode_selection_us_per_tick", "controller_other_us", "rest_us")
    assert all(out[k] > 0.0 for k in parts)
    assert np.isclose(sum(out[k] for k in parts), out["tick_us"])


def test_the_timed_run_is_the_run():
    timed, _, _ = _tick_breakdown_run(1.0)
    plain = TrackingRun.of(run_rig(tracking_rig(1.0)))
    assert np.array_equal(timed.c, plain.c) and np.array_equal(timed.mode, plain.mode)
