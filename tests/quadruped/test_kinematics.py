"""Leg kinematics of TITAN-VIII (seed §2.1, eqs. 1-2) and the joint limits (§1.3)."""

import numpy as np
import pytest

from shintai.quadruped import constants as C
from shintai.quadruped import robot as R


def grid_feet():
    """Foot positions around a shoulder at the origin over the leg's workspace: a grid of joint
    angles whose leg points at the foot (ρ = l1 cos θ1 + l2 cos θ2 > 0, the domain of eq. (2))."""
    t0, t1, t2 = np.meshgrid(np.linspace(-3.1, 3.1, 9), np.linspace(-1.4, 1.4, 15), np.linspace(-2.7, 1.6, 25))
    theta = np.column_stack([t0.ravel(), t1.ravel(), t2.ravel()])
    theta = theta[C.L1 * np.cos(theta[:, 1]) + C.L2 * np.cos(theta[:, 2]) > 1e-3]
    return R.fk(theta, np.zeros(3))


@pytest.mark.parametrize("branch", [R.KNEE_UP, R.KNEE_DOWN])
def test_fk_of_ik_is_identity_on_both_branches(branch):
    feet = grid_feet()
    theta, ok = R.ik(feet, np.zeros(3), branch)
    assert ok.all()
    assert np.max(np.abs(R.fk(theta, np.zeros(3)) - feet)) < 1e-9


def test_branches_differ_and_both_reproduce_a_bent_leg():
    shoulder = np.array([0.1, 0.275, 0.3])
    foot = R.fk(np.radians([20.0, 30.0, -70.0]), shoulder)
    up, _ = R.ik(foot, shoulder, R.KNEE_UP)
    down, _ = R.ik(foot, shoulder, R.KNEE_DOWN)
    assert np.allclose(np.degrees(up), [20.0, 30.0, -70.0])
    assert up[1] > down[1]
    assert np.allclose(R.fk(down, shoulder), foot, atol=1e-12)


def test_ik_flags_unreachable_feet():
    far = np.array([C.L0 + C.L1 + C.L2 + 0.01, 0.0, -C.L3])  # r > l1 + l2
    near = np.array([C.L0, 0.0, -C.L3 + 0.01])  # r < l2 - l1
    theta, ok = R.ik(np.stack([far, near]), np.zeros(3))
    assert not ok.any() and np.isnan(theta).all()
    edge = np.array([C.L0 + C.L1 + C.L2 - 1e-9, 0.0, -C.L3])
    assert R.ik(edge, np.zeros(3))[1]


def test_joint_limit_table_is_the_reconstruction_of_section_1_3():
    assert C.THETA0_LIMITS_DEG == ((90.0, 245.0), (-65.0, 90.0), (115.0, 270.0), (-90.0, 65.0))
    assert C.THETA1_LIMITS_DEG == (-65.0, 65.0) and C.THETA2_LIMITS_DEG == (-65.0, 90.0)
    assert all(hi - lo == 155.0 for lo, hi in C.THETA0_LIMITS_DEG)


def test_theta0_limits_wrap_for_the_left_legs():
    legs = np.arange(4)
    ok = np.radians([[180.0, 0.0, -100.0], [0.0, 0.0, -100.0], [-160.0, 0.0, -100.0], [-30.0, 0.0, -100.0]])
    assert R.within_limits(ok, legs).all()  # LR at -160 deg is 200 deg, inside 115..270
    bad = ok.copy()
    bad[:, 0] = np.radians([80.0, 100.0, 100.0, 80.0])
    assert not R.within_limits(bad, legs).any()


def stance_in_body_frame():
    stance = R.CrawlState.initial(1)
    feet = R.to_body(stance.pose, stance.feet[..., :2])[0]
    shoulder = np.column_stack([R.SHOULDER_XY, np.full(4, C.SHOULDER_DZ)])
    return np.column_stack([feet, np.full(4, -C.ZR_NOMINAL)]), shoulder


def test_theta2_limit_is_read_from_the_downward_vertical(monkeypatch):
    """The chosen reading: the printed θ2 range -65..90° is θ2 + 90° (constants.THETA2_ZERO_DEG);
    read from horizontal, no leg of the initial stance could reach the floor."""
    assert np.allclose(np.degrees(R.THETA2_LIMITS), [-155.0, 0.0])
    foot, shoulder = stance_in_body_frame()
    assert R.leg_angles(foot, shoulder, np.arange(4))[1].all()
    monkeypatch.setattr(R, "THETA2_LIMITS", np.radians(C.THETA2_LIMITS_DEG))
    assert not R.leg_angles(foot, shoulder, np.arange(4))[1].any()


def test_initial_stance_is_within_limits_at_every_teacher_height():
    stance = R.CrawlState.initial(3)
    zr = np.array([0.30, 0.36, 0.37])
    assert R.legs_within_limits(stance.pose, zr, stance.feet, np.tile(np.arange(4), (3, 1))).all()
