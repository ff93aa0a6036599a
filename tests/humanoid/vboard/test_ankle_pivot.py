"""The commanded foot pitch as an ankle joint angle (issue 26's candidate (e), shintai.humanoid.vboard.ankle_pivot)."""

import math

import numpy as np
import pytest

from shintai.humanoid.balance.stabilizer import StabilizerModule
from shintai.humanoid.constants import HRP2_LINKS
from shintai.humanoid.vboard.ankle_pivot import pivot_soles
from shintai.humanoid.vboard.ride import VboardRide


def ankle(sole, pitch, h=HRP2_LINKS.ankle_height):
    return np.asarray(sole) + h * np.array([math.sin(pitch), 0.0, math.cos(pitch)])


def test_a_pitch_about_the_ankle_keeps_the_ankle_and_swings_the_sole_back():
    soles = np.array([[0.0, 0.1, 0.2], [0.0, -0.1, 0.2]])  # left, right
    pitch0, pitch = (-0.03, -0.035), (0.02, -0.035)  # (R, L): only the right foot turns, toes down
    moved = pivot_soles(soles, pitch, pitch0)
    np.testing.assert_allclose(ankle(moved[1], pitch[0]), ankle(soles[1], pitch0[0]), atol=1e-12)
    np.testing.assert_allclose(moved[0], soles[0], atol=1e-15)  # the left's pitch did not change
    assert moved[1, 0] < soles[1, 0]  # toes down about the ankle: the sole goes back under it


def test_the_option_needs_the_ankle_foot_origin_and_the_lift():
    with pytest.raises(ValueError, match="foot_origin='ankle'"):
        VboardRide(level=2, foot_pitch_about="ankle")
    with pytest.raises(ValueError, match="'sole' or 'ankle'"):
        VboardRide(level=2, foot_pitch_about="knee")
    with pytest.raises(ValueError, match="foot_origin='ankle'"):
        StabilizerModule.__init__(object.__new__(StabilizerModule), None, ref_ankle_pitch=(0.0, 0.0))
