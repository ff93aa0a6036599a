"""The human hand of Fig. 7.12 (a6) (unicycle/hand.py): off below its catch angle, pushes toward upright past it,
lets go within its release angle."""

import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.unicycle.constants import HAND_CATCH_DEG, HAND_K, HAND_MAX_N, HAND_RELEASE_DEG
from shintai.humanoid.unicycle.hand import HumanHand
from shintai.humanoid.unicycle.ride import build_ninebot_stand
from shintai.humanoid.unicycle.vehicle import NINEBOT


@pytest.fixture(scope="module")
def body():
    return build_ninebot_stand(NINEBOT, training_wheels=False)


def _at_roll(body, deg, rate=0.0):
    body.reset("stand")
    roll = body.model.joint("ninebot_roll")
    body.data.qpos[roll.qposadr[0]] = math.radians(deg)
    body.data.qvel[roll.dofadr[0]] = rate
    mujoco.mj_forward(body.model, body.data)
    return roll.dofadr[0]


def test_the_hand_catches_past_its_angle_pushes_upright_and_lets_go(body):
    hand = HumanHand(body)
    _at_roll(body, HAND_CATCH_DEG - 1.0)
    hand()
    assert not hand.holding and not body.data.qfrc_applied.any()
    for sign in (1.0, -1.0):
        dof = _at_roll(body, sign * (HAND_CATCH_DEG + 1.0))
        hand()
        assert hand.holding
        # horizontal, against the side the vehicle's up axis leans to: it rights the unicycle
        up = body.data.xmat[body.id("body", "ninebot")].reshape(3, 3)[:, 2]
        assert np.dot(hand.force()[:2], up[:2]) < 0 and hand.force()[2] == pytest.approx(0.0)
        assert body.data.qfrc_applied.any()
        assert np.linalg.norm(hand.force()) == pytest.approx(min(HAND_K * math.radians(HAND_CATCH_DEG + 1), HAND_MAX_N))
        _at_roll(body, sign * (HAND_RELEASE_DEG + 0.5))
        hand()
        assert hand.holding  # hysteresis: still holding between release and catch
        _at_roll(body, sign * (HAND_RELEASE_DEG - 0.5))
        hand()
        assert not hand.holding and not body.data.qfrc_applied.any()
    assert hand.catches == 2 and hand.peak_n > 0


def test_the_hand_rights_a_falling_unicycle(body):
    """With the robot's servos holding its posture and no balance control, the unicycle falls past 20° within
    2 s on its own and the hand keeps it within twice its catch angle."""
    worst = {}
    for with_hand in (False, True):
        _at_roll(body, 2.0)
        hand = HumanHand(body)
        peak = 0.0
        for _ in range(int(2.0 / body.model.opt.timestep)):
            if with_hand:
                hand()
            else:
                body.data.qfrc_applied[:] = 0.0
            mujoco.mj_step(body.model, body.data)
            peak = max(peak, abs(math.degrees(body.data.joint("ninebot_roll").qpos[0])))
        worst[with_hand] = peak
    assert worst[False] > 20.0
    assert worst[True] < 2 * HAND_CATCH_DEG


def test_bad_angles_are_refused(body):
    with pytest.raises(ValueError, match="release < catch"):
        HumanHand(body, catch_deg=1.0, release_deg=2.0)
