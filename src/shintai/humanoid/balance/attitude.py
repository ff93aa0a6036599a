"""The chest IMU's attitude estimate, as hrpsys-base feeds its Stabilizer (issue 26, the "apparent vertical").

hrpsys's Stabilizer computes the actual CoM ``act_cog`` by forward kinematics from the joint encoders and the
base attitude of the ``rpy`` port, which hrpsys_config connects to its KalmanFilter component; it then moves it
into the foot-origin frame (the stance feet's mid-point and yaw only), so the CoM's offset from the feet is read
through the estimated attitude. That filter (RPYKalmanFilter, per axis a state (angle, gyro bias), the gyro as
input and the accelerometer's tilt atan2(−a_x, √(a_y² + a_z²)), atan2(a_y, a_z) as the measurement; defaults
Q_angle = 0.001, Q_rate = 0.003, R_angle = 1000) trusts the accelerometer's "up", which under a sustained
acceleration a of the platform tilts by atan(a/g); so the CoM offset it reads is x − z_c·φ_est, not x.

:class:`TiltEstimate` is a complementary filter standing in for it: the estimated "up" in the chest frame is
turned by the gyro each period and pulled toward the accelerometer's direction with the time constant τ. With
hrpsys's defaults at our 4 ms period the KF's steady-state angle gain is K = 9.4×10⁻⁴ per sample (computed from its
Riccati equation), an initial rate K/Δt = 0.23 s⁻¹: τ = :data:`~shintai.humanoid.constants.ATTITUDE_TAU` = 4.3 s
(its step response matches the KF's to 0.005 up to 1 s and to 0.04 at 2 s; the bias state makes the KF's later
course overshoot, 1.16 at 10 s, which this filter lacks). Yaw is not estimated (the foot-origin frame is yaw-only
and the stabilizer takes yaw from the soles)."""

from __future__ import annotations

import math

import numpy as np

from shintai.core.geometry import cross3
from shintai.humanoid.balance.foot_attitude import quat_to_rot
from shintai.humanoid.constants import ATTITUDE_TAU, CONTROL_PERIOD

_EZ = np.eye(3)[2]  # the world's up


def rotation_between(a, b) -> np.ndarray:
    """The smallest rotation taking unit vector ``a`` onto unit vector ``b`` (Rodrigues)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    axis = cross3(a, b)
    s, c = float(np.linalg.norm(axis)), float(a @ b)
    if s < 1e-12:
        return np.eye(3)
    k = axis / s
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + s * kx + (1.0 - c) * kx @ kx


class TiltEstimate:
    """The chest's estimated "up" (module docstring) from a snapshot's ``imu_gyro``, ``imu_acc`` (chest frame) and
    ``imu_quat`` (the true attitude, used only to express the estimate's error in the world). :meth:`error` is
    the rotation R_err = R_est R_trueᵀ that turns a world vector as the forward kinematics from the estimated
    attitude would read it (R_err takes the estimated up, seen in the world, onto the true vertical)."""

    def __init__(self, tau: float = ATTITUDE_TAU, dt: float = CONTROL_PERIOD):
        if not (math.isfinite(tau) and tau > 0 and dt > 0):
            raise ValueError(f"TiltEstimate: tau and dt must be > 0, got {tau!r}, {dt!r}")
        self.tau, self.dt = float(tau), float(dt)
        self.up = None  # estimated world up in the chest frame

    def reset(self, snapshot) -> None:
        self.up = quat_to_rot(snapshot["imu_quat"]).T @ _EZ  # starts at the truth (hrpsys: reset by observation)

    def update(self, snapshot) -> np.ndarray:
        """One period: gyro, then the accelerometer's pull; returns :meth:`error`."""
        if self.up is None:
            self.reset(snapshot)
        w = np.asarray(snapshot["imu_gyro"], float)
        u = self.up - self.dt * cross3(w, self.up)  # a world-fixed vector seen from a frame turning at ω
        acc = np.asarray(snapshot["imu_acc"], float)
        n = float(np.linalg.norm(acc))
        if n > 0:
            u = u + (self.dt / self.tau) * (acc / n - u)
        self.up = u / np.linalg.norm(u)
        return self.error(snapshot)

    def error(self, snapshot) -> np.ndarray:
        return rotation_between(quat_to_rot(snapshot["imu_quat"]) @ self.up, _EZ)
