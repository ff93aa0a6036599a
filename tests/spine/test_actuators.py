"""Drives and sensors: Tables 3.2–3.3, encoder, eq. 3.3 tension sensor, eq. 3.4 accelerometers, eq. 3.6."""

import numpy as np
import pytest

from shintai.core.constants import KGF_N
from shintai.spine.actuators import (
    DCMotorDrive, Encoder, TensionSensor, fsr_force, posture_from_accelerometers, pwm_duty, shunt_current, tilt,
    zmp,
)
from shintai.spine.geometry import rpy_matrix
from shintai.spine.robots import (
    CLA, CLA_MOTOR, KENTA_MOTOR_A, KENTA_MOTOR_B, KENTA_MOTOR_C, RABBIT_SERVO, TABLE_3_3_MAX_SPEED_M_S,
    TABLE_3_3_SPEED_AT_5KGF_M_S,
)

KENTA = {"A": KENTA_MOTOR_A, "B": KENTA_MOTOR_B, "C": KENTA_MOTOR_C}


@pytest.mark.parametrize("group", "ABC")
def test_motor_model_reproduces_table_3_3_speeds(group):
    """No-load pulling speed and speed at 5 kgf on the linear torque–speed line (spec §3.2)."""
    drive = DCMotorDrive([KENTA[group]])
    assert drive.no_load_speed_m_s[0] == pytest.approx(TABLE_3_3_MAX_SPEED_M_S[group], rel=2e-3)
    assert drive.speed(5 * KGF_N)[0] == pytest.approx(TABLE_3_3_SPEED_AT_5KGF_M_S[group], abs=0.25e-3)


def test_cla_drive_matches_table_3_2():
    drive = DCMotorDrive([CLA_MOTOR])
    assert drive.stall_force_n[0] == 320.0
    assert CLA_MOTOR.stall_torque_nm * CLA_MOTOR.gear_ratio / CLA_MOTOR.radius_m == pytest.approx(320, rel=0.01)
    assert 1e3 * drive.no_load_speed_m_s[0] == pytest.approx(82.9, abs=0.1)
    assert drive.force(1.0, 0.0)[0] == pytest.approx(320.0)  # stall
    assert drive.force(1.0, drive.no_load_speed_m_s)[0] == pytest.approx(0.0, abs=1e-9)  # no load
    assert drive.current(1.0, 0.0)[0] == pytest.approx(CLA_MOTOR.stall_current_a)
    assert drive.speed(320.0, duty=0.0)[0] == pytest.approx(-drive.no_load_speed_m_s[0])  # back-driven
    assert not drive.backdriven(0.5 * drive.backdrive_force_n)[0] and drive.backdriven(2 * drive.backdrive_force_n)[0]


def test_rabbit_servo_tension_from_torque():
    assert RABBIT_SERVO.max_tension_n / KGF_N == pytest.approx(12.6)  # §3.5.1


def test_pwm_duty_saturates_and_quantises():
    assert np.allclose(pwm_duty([-3.0, 3.0]), [-1.0, 1.0])
    assert abs(pwm_duty(0.3001) - 0.3001) <= 0.5 / 255


def test_encoder_quantises_to_one_count_and_zeroes():
    enc = Encoder([CLA_MOTOR])
    step = np.pi * 6e-3 / (16 * 67.49)
    assert enc.step_m[0] == pytest.approx(step)
    assert enc.read([2.4 * step])[0] == pytest.approx(2 * step)
    enc.set_zero([10 * step])
    assert enc.read([13.2 * step])[0] == pytest.approx(3 * step)


def test_tension_sensor_satisfies_eq_3_3_and_is_fine_at_low_tension():
    spec = CLA.sensor
    sensor = TensionSensor(spec)
    F = np.array([0.5, 5.0, 50.0, 300.0])
    f = sensor.fsr_force(F)
    lhs = f**2 * spec.l_m**2
    rhs = (F**2 + f**2) * (spec.b_m - f / spec.k_n_m) ** 2
    assert np.allclose(lhs, rhs, rtol=1e-3)
    assert np.all(np.diff(f) > 0) and f[-1] < spec.k_n_m * spec.b_m  # bounded: the plates close
    counts = sensor.adc(np.array([1.0, 1.1, 200.0, 210.0]))
    assert counts[1] - counts[0] >= 2 and counts[3] - counts[2] <= 5  # high resolution only at low tension
    assert sensor.read(2.0) == pytest.approx(2.0, abs=0.02)


def test_shunt_current():
    assert shunt_current(0.05) == pytest.approx(0.5)  # eq. 3.6, R = 0.1 Ω


@pytest.mark.parametrize("roll,pitch", [(0.2, 0.0), (0.0, -0.3), (0.1, 0.25)])
def test_accelerometer_tilt_recovers_roll_and_pitch(roll, pitch):
    """A static accelerometer reads +g up in its own frame; tilt() inverts R = Ry(θ) Rx(φ)."""
    R = rpy_matrix([roll, pitch, 0.4])  # yaw is unobservable
    reading = R.T @ np.array([0.0, 0.0, 9.81])
    assert np.allclose(tilt(reading), [roll, pitch])
    waist = rpy_matrix([0.0, 0.0, 0.0]).T @ np.array([0.0, 0.0, 9.81])
    assert np.allclose(posture_from_accelerometers(reading, waist), [roll, pitch])


def test_posture_fast_path_equals_the_batch_tilts():
    """The 1 ms single-reading path of eq. 3.4 gives the same angles as the array path."""
    rng = np.random.default_rng(5)
    chest, waist = rng.normal(0, 1, (2, 3)) + [0.0, 0.0, 9.0]
    batch = posture_from_accelerometers(chest[None], waist[None])[0]
    assert np.allclose(posture_from_accelerometers(chest, waist), batch, atol=1e-15)
    assert np.allclose(batch, tilt(chest) - tilt(waist))


def test_zmp_is_the_force_weighted_mean_of_the_fsr_positions():
    """Eq. 3.5 by hand: corners of a 0.1 × 0.06 m sole, three times the force on the front pair."""
    corners = np.array([[0.05, 0.03], [0.05, -0.03], [-0.05, 0.03], [-0.05, -0.03]])
    assert np.allclose(zmp(corners, [3.0, 3.0, 1.0, 1.0]), [0.025, 0.0])
    assert np.all(np.isnan(zmp(corners, np.zeros(4))))
    table_reading, table_force = np.array([0, 100, 400, 1023]), np.array([0.0, 1.0, 5.0, 20.0])
    assert fsr_force(250, table_reading, table_force) == pytest.approx(3.0)  # linear between points


def test_tension_sensor_drift_biases_the_absolute_reading_not_the_relative_one():
    """§3.6.1: drift makes the absolute value inaccurate while relative values stay usable."""
    sensor = TensionSensor(CLA.sensor)
    clean = sensor.read(np.array([5.0, 6.0]))
    sensor.drift_counts = 20.0
    drifted = sensor.read(np.array([5.0, 6.0]))
    assert np.all(drifted - clean > 0.2)  # biased upwards
    assert (drifted[1] - drifted[0]) == pytest.approx(clean[1] - clean[0], rel=0.2)  # the step survives


def test_tension_sensor_slope_falls_with_tension():
    """Fig. 3.34: high resolution at low tension — the calibration's slope is steepest at zero."""
    s = TensionSensor(CLA.sensor)
    slopes = s.slope_counts_n(np.array([0.0, 10.0, 50.0, 200.0]))
    assert slopes[0] == pytest.approx(s.zero_slope_counts_n, rel=1e-3)
    assert np.all(np.diff(slopes) < 0)
    assert s.adc(10.0) - s.adc(9.0) == pytest.approx(float(s.slope_counts_n(9.5)), abs=1.0)
