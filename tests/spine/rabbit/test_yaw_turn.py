"""Rabbit's yaw turn carrying its upper body (spine/rabbit/yaw_turn.py, seed 003 §3.5.4, Fig. 3.27)."""

import numpy as np

from shintai.scenarios.experiment import run_rig
from shintai.spine.rabbit.yaw_turn import YawTurn, yaw_turn_metrics, yaw_turn_rig


def test_the_turn_goes_out_both_ways_and_back():
    np.testing.assert_allclose(YawTurn(yaw_deg=10.0, step_deg=5.0).commands_deg(),
                               [0, 5, 10, 5, 0, -5, -10, -5, 0])


def test_the_stiffened_spine_turns_and_the_forward_load_tilts_it_a_little():
    carrying = yaw_turn_metrics(run_rig(yaw_turn_rig(YawTurn(yaw_deg=5.0, step_deg=5.0))).log)
    assert carrying["yaw_reach"] > 0.8
    assert 0.05 < carrying["max_tilt_deg"] < 5.0  # the centre 30 mm ahead of the axis bends it forward
    assert carrying["tension_share_of_servo"] < 1.0
