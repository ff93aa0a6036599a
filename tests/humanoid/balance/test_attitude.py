"""The chest IMU's tilt estimate (balance.attitude) and the stabilizer's com_reading option."""

import math

import numpy as np
import pytest

from shintai.core.constants import GRAVITY
from shintai.humanoid.balance.attitude import TiltEstimate, rotation_between
from shintai.humanoid.balance.stabilizer import StabilizerModule


def still(acc=(0.0, 0.0, GRAVITY), gyro=(0.0, 0.0, 0.0)):
    return {"imu_quat": np.array([1.0, 0.0, 0.0, 0.0]), "imu_acc": np.array(acc, float), "imu_gyro": np.array(gyro, float)}


def test_rotation_between_takes_a_onto_b():
    rng = np.random.default_rng(3)
    for _ in range(20):
        a, b = rng.normal(size=3), rng.normal(size=3)
        a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
        r = rotation_between(a, b)
        assert np.allclose(r @ a, b, atol=1e-9) and np.allclose(r.T @ r, np.eye(3), atol=1e-9)


def test_standing_still_reads_the_truth():
    est = TiltEstimate(tau=1.0)
    est.reset(still())
    for _ in range(500):
        err = est.update(still())
    assert np.allclose(err, np.eye(3), atol=1e-12)


def test_a_sustained_acceleration_tilts_the_read_vertical_with_tau():
    """Forward acceleration a (specific force (a, 0, g) on an upright chest): the read CoM offset of a point z above
    the feet goes to −z·tan⁻¹(a/g)-ish behind, 1 − e^{−t/τ} of the way after t."""
    a, tau, dt = 1.0, 0.5, 0.004
    est = TiltEstimate(tau=tau, dt=dt)
    est.reset(still())
    n = 250  # 1 s = 2 τ
    for _ in range(n):
        err = est.update(still(acc=(a, 0.0, GRAVITY)))
    x_read = (err @ np.array([0.0, 0.0, 1.0]))[0]
    expect = -math.sin(math.atan(a / GRAVITY) * (1 - math.exp(-n * dt / tau)))
    assert x_read < 0 and abs(x_read - expect) < 0.05 * abs(expect)


def test_the_gyro_alone_keeps_a_turning_estimate_true():
    """A chest turning at a constant pitch rate with a consistent accelerometer: the estimate follows (no lag
    beyond the integration's)."""
    dt, rate = 0.004, 0.5
    est = TiltEstimate(tau=1e6, dt=dt)
    th = 0.0
    snap = lambda th: {"imu_quat": np.array([math.cos(th / 2), 0.0, math.sin(th / 2), 0.0]),
                       "imu_acc": np.array([-GRAVITY * math.sin(th), 0.0, GRAVITY * math.cos(th)]),
                       "imu_gyro": np.array([0.0, rate, 0.0])}
    est.reset(snap(th))
    for _ in range(100):
        th += rate * dt
        err = est.update(snap(th))
    assert np.linalg.norm(err - np.eye(3)) < 1e-3


def test_com_reading_is_named():
    with pytest.raises(ValueError, match="com_reading"):
        StabilizerModule(None, com_reading="apparent")
