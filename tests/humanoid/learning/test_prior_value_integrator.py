"""The prior-value-correcting integrator (seed 000 §6.3.3, Eqs. 6.33–6.39), the r_sat alternative (Eq. 6.42)
and the PID of Eq. 6.2."""

import math

import numpy as np
import pytest

from shintai.humanoid.learning.prior_value_integrator import PID, PriorValueIntegrator

DT = 0.004


def warmed(mode, K1=1e-3, r_sat=1.5, n=300):
    """An integrator that has accumulated a large error under a low gain K1 (the situation of Eq. 6.36)."""
    integ = PriorValueIntegrator(DT, K1, mode, r_sat)
    for i in range(n):
        integ.step(0.2 + 0.001 * i)
    return integ


def test_trapezoid_eq_6_33_integrates_a_ramp_exactly():
    integ = PriorValueIntegrator(DT, 2.0, "plain")
    t = np.arange(0, 251) * DT
    for ti in t:
        u = integ.step(3.0 * ti)
    assert integ.E == pytest.approx(1.5 * t[-1] ** 2, rel=1e-12) and u == pytest.approx(2.0 * integ.E)


@pytest.mark.parametrize("K1", [1e-3, 0.0])
def test_corrected_integrator_keeps_u_I_continuous_across_a_gain_increase_eq_6_38(K1):
    integ = warmed("corrected", K1)
    u_before, e_prev = integ.u_I, 0.2 + 0.001 * 299
    K2, e = 5e-3, 0.6
    integ.set_gain(K2)
    u_after = integ.step(e)
    assert integ.switched  # SW1 for this one sample (Eq. 6.39)
    assert u_after - u_before == pytest.approx(DT / 2 * (e + e_prev) * K2, rel=1e-12)  # Eq. 6.38
    integ.step(e)
    assert not integ.switched  # back to SW0 after the switching


@pytest.mark.parametrize("K1", [1e-3, 0.0])
def test_plain_integrator_jumps_by_the_gain_ratio_eq_6_36(K1):
    integ = warmed("plain", K1)
    u_before, E_before, e_prev = integ.u_I, integ.E, 0.2 + 0.001 * 299
    K2, e = 5e-3, 0.6
    integ.set_gain(K2)
    u_after = integ.step(e)
    trap = DT / 2 * (e + e_prev)
    assert u_after == pytest.approx(K2 * (E_before + trap), rel=1e-12)  # Eq. 6.36 ...
    if K1 > 0:
        assert u_after == pytest.approx(K2 / K1 * u_before + trap * K2, rel=1e-12)  # ... = (K2/K1) u_I(t) + …
    assert u_after - u_before > 50 * trap * K2  # a jump, not a step of the integral


def test_saturated_ratio_jumps_by_r_sat_minus_one_times_u_I_eq_6_43():
    integ = warmed("saturated", 1e-3, r_sat=1.5)
    u_before, e_prev, e = integ.u_I, 0.2 + 0.001 * 299, 0.6
    integ.set_gain(5e-3)  # ratio 5 > r_sat
    u_after = integ.step(e)
    slope = (u_after - u_before) / DT
    assert slope == pytest.approx((e + e_prev) / 2 * 5e-3 + (1.5 - 1) / DT * u_before, rel=1e-12)  # Eq. 6.43
    assert integ.switched
    small = warmed("saturated", 1e-3, r_sat=1.5)
    u0 = small.u_I
    small.set_gain(1.2e-3)  # ratio 1.2 ≤ r_sat: the ratio form
    assert small.step(e) == pytest.approx(1.2 * u0 + DT / 2 * (e + e_prev) * 1.2e-3, rel=1e-12)


def test_a_decrease_uses_the_normal_integrator_even_down_to_zero():
    for K2 in (5e-4, 0.0):
        a, b = warmed("corrected"), warmed("plain")
        a.set_gain(K2)
        b.set_gain(K2)
        assert a.step(0.3) == pytest.approx(b.step(0.3)) and not a.switched


def test_pid_is_eq_6_2_with_a_backward_difference_D_term():
    pid = PID(DT, (2.0, 0.5, 0.1), "corrected")
    pid.step(1.0)
    u = pid.step(1.2)
    assert u == pytest.approx(2.0 * 1.2 + 0.5 * (DT * 1.0 + DT / 2 * 2.2) + 0.1 * 0.2 / DT)


@pytest.mark.parametrize("kwargs, field", [({"mode": "clamp"}, "mode"), ({"K_I": -1.0}, "K_I"),
                                           ({"mode": "saturated", "r_sat": 0.5}, "r_sat"), ({"dt": math.nan}, "dt")])
def test_bad_parameters_name_the_field(kwargs, field):
    args = {"dt": DT, **kwargs}
    with pytest.raises(ValueError, match=f"^{field} must"):
        PriorValueIntegrator(**args)
    with pytest.raises(ValueError, match="^K_D must"):
        PID(DT, (0.0, 0.0, -1e-3))
