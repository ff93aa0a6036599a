"""Muscle drives and sensors (seed 003 §3.6–3.7, Tables 3.2–3.3, eqs. 3.3–3.6).

* :class:`DCMotorDrive` — DC motor + planetary gear + pulley, per muscle, vectorised: the linear
  torque–speed line of a voltage-driven DC motor, F = F_stall (o − v/v0), with o the PWM duty
  (§4.6: "o = the PWM duty sent to the motor"), v the wire speed (positive winding in), F_stall the
  table's max muscle tension and v0 its no-load speed; stall, back-drive threshold, current.
  Table 3.3's "pulling speed at 5 kgf" is this line at o = 1 (spec §3.2, derived).
* :func:`pwm_duty` — the duty actually sent: saturated to [−1, 1] (spec §2.6, assumption) and
  quantised to the PWM timer's resolution.
* :class:`Encoder` — wire length from the motor encoder, quantised to one count (16 cpr on the
  motor shaft through the gear and pulley, §3.6.1).
* :class:`TensionSensor` — Cla's parallel-plate sensor, eq. 3.3, an FSR on a 10-bit ADC, read back
  through the calibration table (high resolution at low tension, low at high tension).
* :func:`shunt_current` — eq. 3.6, I = V/R with R = 0.1 Ω.
* :func:`zmp` and :func:`fsr_force` — eq. 3.5, the ZMP from Cla's four sole FSRs read through a
  calibration table (§3.6.2).
* :func:`tilt` and :func:`posture_from_accelerometers` — eq. 3.4: pitch and roll of the shoulder
  relative to the waist from the two gravity vectors (static only; yaw is unobservable).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

import numpy as np

from shintai.spine.robots import PWM_STEPS, SHUNT_OHM, MotorSpec, TensionSensorSpec


class DCMotorDrive:
    """Linear torque–speed model of the muscle drives, one entry per muscle (see module docstring)."""

    def __init__(self, specs: Sequence[MotorSpec]):
        self.specs = tuple(specs)
        self.stall_force_n = np.array([s.max_tension_n for s in specs])
        self.no_load_speed_m_s = np.array([s.no_load_speed_m_s for s in specs])
        self.stall_current_a = np.array([s.stall_current_a for s in specs])
        self.backdrive_force_n = np.array([s.backdrive_force_n for s in specs])
        self.reflected_mass_kg = np.array([s.reflected_mass_kg for s in specs])

    @property
    def damping_n_s_m(self) -> np.ndarray:
        """Back-EMF damping at the wire, F_stall / v0 (the slope of the torque–speed line)."""
        return self.stall_force_n / self.no_load_speed_m_s

    def force(self, duty, speed_m_s) -> np.ndarray:
        """Wire pulling force [N] at duty o and winding speed v: F_stall (o − v / v0)."""
        return self.stall_force_n * (np.clip(duty, -1.0, 1.0) - np.asarray(speed_m_s) / self.no_load_speed_m_s)

    def speed(self, tension_n, duty=1.0) -> np.ndarray:
        """Steady winding speed against a tension: v0 (o − F / F_stall); negative = back-driven."""
        return self.no_load_speed_m_s * (np.clip(duty, -1.0, 1.0) - np.asarray(tension_n) / self.stall_force_n)

    def current(self, duty, speed_m_s) -> np.ndarray:
        """Motor current [A] (average over the PWM period): I_stall (o − v / v0)."""
        o = np.minimum(np.maximum(duty, -1.0), 1.0)
        return self.stall_current_a * (o - np.asarray(speed_m_s) / self.no_load_speed_m_s)

    def backdriven(self, tension_n, duty=0.0) -> np.ndarray:
        """Whether the tension overcomes the motor force at rest plus the gear friction (§4.6.4)."""
        return np.asarray(tension_n) > self.stall_force_n * np.asarray(duty) + self.backdrive_force_n


def pwm_duty(o) -> np.ndarray:
    """The duty sent to the driver: saturated to [−1, 1] and quantised to the PWM resolution."""
    return np.round(np.minimum(np.maximum(o, -1.0), 1.0) * PWM_STEPS) / PWM_STEPS


class Encoder:
    """Wire length wound in since the zero, quantised to one encoder count per muscle."""

    def __init__(self, specs: Sequence[MotorSpec]):
        self.step_m = np.array([s.encoder_step_m for s in specs])
        self.zero_m = np.zeros(len(specs))

    def set_zero(self, wound_m) -> None:
        """Encoder zero calibration (§4.6.4): the current reading becomes 0."""
        self.zero_m = np.asarray(wound_m, dtype=float).copy()

    def read(self, wound_m) -> np.ndarray:
        return np.round((np.asarray(wound_m) - self.zero_m) / self.step_m) * self.step_m


class TensionSensor:
    """Eq. 3.3 sensor + FSR + 10-bit ADC + calibration-table read-back (see :class:`TensionSensorSpec`).

    With d = b − f/k the sideways wire deflection, eq. 3.3 gives F = f √(l² − d²) / d explicitly,
    so the FSR force for a tension is found by interpolating that monotone curve; the firmware
    reads the tension back from the ADC count through the same curve (its calibration table).

    Drift (§3.6.1: "there is drift, so absolute accuracy is low; relative values are usable"):
    ``drift_counts`` is an offset of the FSR's ADC count that the calibration table does not know;
    0 (none) unless set — its size and rate are not in the text.
    """

    def __init__(self, spec: TensionSensorSpec, table_points: int = 4000):
        self.spec = spec
        f = np.linspace(0.0, spec.k_n_m * spec.b_m * (1 - 1e-4), table_points)
        d = spec.b_m - f / spec.k_n_m
        self.table_f = f
        self.table_tension = f * np.sqrt(spec.l_m**2 - d**2) / d
        self.full_scale = 2**spec.adc_bits - 1
        self.table_adc = self.full_scale * f / (f + spec.fsr_half_n)
        self.drift_counts = 0.0

    @functools.cached_property
    def zero_slope_counts_n(self) -> float:
        """The calibration's slope at zero tension [counts/N] (its steepest; the table is fixed at construction)."""
        return float((self.table_adc[1] - self.table_adc[0]) / (self.table_tension[1] - self.table_tension[0]))

    def slope_counts_n(self, tension_n) -> np.ndarray:
        """The calibration's local slope dcount/dT [counts/N] at a tension (falls as it saturates)."""
        slope = np.diff(self.table_adc) / np.diff(self.table_tension)
        return np.interp(np.maximum(tension_n, 0.0), self.table_tension[:-1], slope)

    def fsr_force(self, tension_n) -> np.ndarray:
        """Force on the pressure sensor f for wire tension F (eq. 3.3)."""
        return np.interp(np.maximum(tension_n, 0.0), self.table_tension, self.table_f)

    def adc(self, tension_n) -> np.ndarray:
        """The 10-bit ADC count for a tension."""
        count = np.interp(np.maximum(tension_n, 0.0), self.table_tension, self.table_adc)
        if self.drift_counts:
            count = np.clip(count + self.drift_counts, 0.0, self.full_scale)
        return np.round(count)

    def read(self, tension_n) -> np.ndarray:
        """Tension as the controller sees it: the ADC count converted back through the calibration."""
        return np.interp(self.adc(tension_n), self.table_adc, self.table_tension)


def shunt_current(v_drop) -> np.ndarray:
    """Motor current from the voltage across the 0.1 Ω shunt, I = V / R (eq. 3.6)."""
    return np.asarray(v_drop, dtype=float) / SHUNT_OHM


def fsr_force(reading, table_reading, table_force) -> np.ndarray:
    """An FSR's force from its ADC reading through its calibration table, linearly interpolated
    ("about 10 points measured, a table, linear interpolation", §3.6.2; the table is the robot's)."""
    return np.interp(reading, table_reading, table_force)


def zmp(positions, forces) -> np.ndarray:
    """Eq. 3.5: the ZMP from the four sole FSRs at ``positions`` (4, 2 or 3) with forces (4,),
    p_z = Σ f_i p_i / Σ f_i; NaN when the foot is unloaded."""
    f = np.maximum(np.asarray(forces, dtype=float), 0.0)
    total = f.sum()
    if total <= 0.0:
        return np.full(np.shape(positions)[-1], np.nan)
    return f @ np.asarray(positions, dtype=float) / total


def tilt(acc) -> np.ndarray:
    """(roll, pitch) [rad] of a frame from its static accelerometer reading (..., 3).

    At rest an accelerometer reads the specific force, +g along the world's up direction; for a
    frame R = Ry(θ) Rx(φ) that is g (−sin θ, cos θ sin φ, cos θ cos φ), so
    φ = atan2(a_y, a_z), θ = atan2(−a_x, √(a_y² + a_z²)).
    """
    a = np.asarray(acc, dtype=float)
    out = np.empty(a.shape[:-1] + (2,))
    out[..., 0] = np.arctan2(a[..., 1], a[..., 2])
    out[..., 1] = np.arctan2(-a[..., 0], np.hypot(a[..., 1], a[..., 2]))
    return out


def posture_from_accelerometers(acc_chest, acc_waist) -> np.ndarray:
    """Eq. 3.4, θ_s = g_c − g_h, decomposed per axis: (roll, pitch) of the shoulder as seen from the
    waist [rad]. The thesis does not say how the angle between the two gravity vectors is split
    into pitch and roll (spec §6.13): the difference of the two tilts is used, exact when the
    waist is level and the bend is about one axis, as in E11."""
    if np.ndim(acc_chest) == 1 and np.ndim(acc_waist) == 1:  # one reading each: the 1 ms path
        cx, cy, cz = acc_chest.tolist() if isinstance(acc_chest, np.ndarray) else acc_chest
        wx, wy, wz = acc_waist.tolist() if isinstance(acc_waist, np.ndarray) else acc_waist
        return np.array([math.atan2(cy, cz) - math.atan2(wy, wz),
                         math.atan2(-cx, math.hypot(cy, cz)) - math.atan2(-wx, math.hypot(wy, wz))])
    return tilt(acc_chest) - tilt(acc_waist)
