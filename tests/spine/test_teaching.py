"""Direct teaching and playback (§4.2) and LL encoder zeroing (§4.6.4)."""

import numpy as np
import pytest

from shintai.core.constants import KGF_N
from shintai.core.runtime import Loop
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.control import SETPOINTS, Gains, Mode, MuscleControl
from shintai.spine.robots import CLA, CLA_ARMS_DOWN, CLA_TRUNK_LOADS, SAMPLE_PERIOD_S
from shintai.spine.teaching import Playback, Recording, zero_encoders


def test_decimation_takes_every_kth_sample_and_the_last():
    rec = Recording(SAMPLE_PERIOD_S, encoder=[np.full(2, k) for k in range(10)])
    assert rec.decimated(1).shape == (10, 2)
    assert list(rec.decimated(4)[:, 0]) == [0, 4, 8, 9]
    assert list(rec.decimated(3)[:, 0]) == [0, 3, 6, 9]
    with pytest.raises(ValueError, match="positive integer"):
        rec.decimated(0)


@pytest.fixture(scope="module")
def zeroed():
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    control = MuscleControl(CLA.m, Gains())
    tension = zero_encoders(body, control, 0.3 * KGF_N)
    return body, control, tension


def test_ll_zeroing_leaves_every_muscle_taut_near_the_limit(zeroed):
    """§4.6.4: LL with a 'just taut' limit and short targets: every muscle winds in until its
    tension reaches the limit; the encoders then read zero."""
    body, control, tension = zeroed
    assert np.all(tension > 0.5 * 0.3 * KGF_N) and np.all(tension < 2.0 * 0.3 * KGF_N)
    assert np.allclose(body.snapshot()["encoder"], 0.0)
    assert control.gains.T_l == Gains().T_l  # the limit is restored after calibration


def test_playback_drives_the_length_targets_in_l_mode(zeroed):
    """The playback writes the replayed lengths to ``l_r`` and L to ``mode``; the controller, a stage
    later, takes them in the same tick (the hand keeps holding the spine here)."""
    body, control, _ = zeroed
    playback = Playback(np.zeros(CLA.m))
    step = np.r_[0.5e-3, np.zeros(CLA.m - 1)]
    playback.play([step * k / 5 for k in range(1, 6)])  # 5 samples, 20 ms apart
    loop = Loop(body, stages=[[playback], [control]], channels=SETPOINTS, base={"hand": np.zeros(15)})
    loop.run(0.001)
    assert np.all(control.modes == Mode.L) and np.array_equal(control.l_r, loop.command["l_r"])
    loop.run(0.104)  # 5 × 20 ms (the first tick only starts the player)
    assert not playback.busy and np.allclose(control.l_r, step)
    loop.run(0.395)
    assert body.snapshot()["encoder"][0] == pytest.approx(0.5e-3, abs=3 * CLA.motors[0].encoder_step_m)
