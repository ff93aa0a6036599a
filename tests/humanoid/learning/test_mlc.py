"""MLC (seed 000 §6.3.2, Eqs. 6.17–6.32) and the speed governor (§6.3.4, Fig. 6.13)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from shintai.core.runtime import Loop
from shintai.humanoid.constants import ETA_OMEGA, ETA_V, K_V, T_V
from shintai.humanoid.learning.mlc import MLC, MLC_OMEGA, MLC_V, MLCParams, Sensitivity, recursion_coefficients
from shintai.humanoid.learning.speed_governing import IdentifiedScooterPlant, pid_loop_stable
from shintai.humanoid.vboard.governor import SpeedGovernor

DT = 0.004


def test_table_6_6_rates_and_mini_batch_of_500():
    assert MLC_V.eta == ETA_V == (1e-7,) * 3 and MLC_OMEGA.eta == ETA_OMEGA == (1e-9,) * 3
    assert MLC_V.batch == MLC_OMEGA.batch == 500
    assert (MLC_V.K, MLC_V.T, MLC_OMEGA.K, MLC_OMEGA.T) == (588.0, 1.1, 1.39e4, 0.6)


def test_recursion_is_the_backward_difference_form_of_eq_6_21():
    """Eqs. 6.25–6.29 solve T Y⁽³⁾ + (1 + K K_D) Y⁽²⁾ + K K_P Y⁽¹⁾ + K K_I Y = K [ė, e, ë] with the backward
    differences of Eqs. 6.22–6.24: put the recursion's output back into the difference equation."""
    K, T, g = K_V, T_V, (2e-3, 1e-3, 3e-4)
    C0, C1, C2, C3 = recursion_coefficients(K, T, g, DT)
    assert C3 == pytest.approx(T / DT**3) and C0 - C1 - C2 - C3 == pytest.approx(K * g[1])  # Eqs. 6.26–6.29
    rng = np.random.default_rng(6)
    e = np.cumsum(rng.normal(0, 1e-3, 200))
    s = Sensitivity(K, T, DT, g)
    Y = np.array([s.step(x) for x in e])
    k = np.arange(3, 200)
    d1 = (Y[k] - Y[k - 1]) / DT
    d2 = (Y[k] - 2 * Y[k - 1] + Y[k - 2]) / DT**2
    d3 = (Y[k] - 3 * Y[k - 1] + 3 * Y[k - 2] - Y[k - 3]) / DT**3
    lhs = T * d3 + (1 + K * g[2]) * d2 + K * g[0] * d1 + K * g[1] * Y[k]
    rhs = K * np.stack([(e[k] - e[k - 1]) / DT, e[k], (e[k] - 2 * e[k - 1] + e[k - 2]) / DT**2], axis=1)
    np.testing.assert_allclose(lhs, rhs, rtol=1e-7, atol=1e-9 * np.abs(rhs).max())


def closed_loop_output(gains, t_eval, K=K_V, T=T_V):
    """v(t) of the continuous closed loop: P = K/(s(1 + T s)), PID on e = 0 − v, a smooth input disturbance."""
    KP, KI, KD = gains

    def f(t, x):
        v, a, E = x
        u = -KP * v + KI * E - KD * a + 1e-4 * math.tanh(5 * t)
        return [a, (K * u - a) / T, -v]

    sol = solve_ivp(f, (0, t_eval[-1]), [0.0, 0.0, 0.0], t_eval=t_eval, rtol=1e-10, atol=1e-13, method="DOP853")
    return sol.y[0]


def test_sensitivity_recursion_matches_a_finite_difference_of_the_continuous_closed_loop():
    t = np.arange(0.0, 5.0 + DT / 2, DT)
    g0 = np.array([2e-3, 1e-3, 3e-4])
    e = -closed_loop_output(g0, t)
    s = Sensitivity(K_V, T_V, DT, g0)
    Y = np.array([s.step(x) for x in e])
    for i in range(3):
        h = 1e-3 * g0[i]
        up, down = g0.copy(), g0.copy()
        up[i] += h
        down[i] -= h
        fd = (closed_loop_output(up, t) - closed_loop_output(down, t)) / (2 * h)
        assert np.max(np.abs(Y[:, i] - fd)) < 0.02 * np.max(np.abs(fd)), f"gain {i}"


def feed(m, e_series, t0=0.0):
    for i, e in enumerate(e_series):
        m.observe(e, t0 + (i + 1) * DT)


def test_one_batch_is_eqs_6_17_6_18_and_6_30():
    m = MLC(MLC_V)
    rng = np.random.default_rng(17)
    e = rng.normal(0, 0.05, 500)
    s = Sensitivity(K_V, T_V, DT)
    Y = np.array([s.step(x) for x in e])
    feed(m, e)
    b = m.batches[-1]
    assert b.J == pytest.approx(np.sum(e**2) * DT / 2.0)
    np.testing.assert_allclose(b.grad, -2.0 / 2.0 * (Y * e[:, None]).sum(axis=0) * DT, rtol=1e-12)
    np.testing.assert_allclose(m.gains, np.maximum(0.0, -1e-7 * b.grad), rtol=1e-12)


def test_negative_gains_are_clipped_to_zero_and_learned_again():
    m = MLC(MLCParams(K=K_V, T=T_V, eta=(1e-3,) * 3, eps=1e-9, sigma=1e-9), gains0=(1e-6, 1e-6, 1e-6))
    feed(m, np.r_[np.full(250, 0.1), np.full(250, -0.1)])  # the error changes sign: ∫Y e < 0 for K_I
    first = m.batches[-1]
    assert first.clipped.any() and np.all(m.gains[first.clipped] == 0.0) and np.all(m.gains >= 0)
    assert m.sensitivity.C == recursion_coefficients(K_V, T_V, m.gains, DT)
    feed(m, np.full(500, 0.1), 2.0)  # a steady positive error: the I gain is learned again from 0
    assert m.gains[1] > 0


def test_termination_needs_k_consecutive_batches():
    p = MLCParams(K=K_V, T=T_V, eta=ETA_V, eps=1e3, sigma=1e-4, k=3)
    m = MLC(p)
    feed(m, np.full(1000, 1e-4))  # two quiet batches
    feed(m, np.full(500, 1.0), 4.0)  # a loud one breaks the streak
    feed(m, np.full(1000, 0.0), 6.0)
    assert not m.converged
    feed(m, np.full(500, 0.0), 10.0)
    assert m.converged and m.t_converged == pytest.approx(12.0)
    assert [b.holds for b in m.batches] == [True, True, False, True, True, True]
    assert not m.observe(0.5) and len(m.batches) == 6  # learning has stopped


@pytest.mark.parametrize("field, value", [("eta", (1e-7, 0.0, 1e-7)), ("eta", (1e-7, math.nan, 1e-7)),
                                          ("K", -588.0), ("sigma", 0.0), ("eps", math.inf), ("k", 0),
                                          ("T_L", 2.001)])
def test_bad_parameters_raise_one_clear_line(field, value):
    kw = {"K": K_V, "T": T_V, "eta": ETA_V, "eps": 10.0, "sigma": 1e-4, field: value}
    with pytest.raises(ValueError) as info:
        MLCParams(**kw)
    name = field if field != "eta" else "eta_"
    assert str(info.value).startswith(name) and "\n" not in str(info.value)


def test_mlc_from_zero_gains_meets_eq_6_32_on_the_identified_plant():
    """Table 6.2's plant with a constant board-pitch disturbance (the damping δ of Eq. 6.5, a few 1e-4);
    the thesis's robot met Eq. 6.32 after ≈38 s and ≈54 s (§6.4.1) with gains O(1e-3) for v (Fig. 6.15)."""
    body = IdentifiedScooterPlant(disturbance=(1.01e-4, 0.99e-4))
    gov = SpeedGovernor()
    Loop(body, [gov]).run(duration=120.0, until=lambda s: gov.converged)
    assert gov.converged and body.t < 120.0
    for axis, m in gov.mlc.items():
        last = m.batches[-3:]
        assert all(b.holds for b in last), axis  # Eq. 6.32, k = 3
        assert all(np.linalg.norm(b.grad) < m.p.eps and b.J < m.p.sigma for b in last)
        assert pid_loop_stable(m.p.K, m.p.T, m.gains), axis  # ends inside Eq. 6.41
        assert not pid_loop_stable(m.p.K, m.p.T, (0.0, 0.0, 0.0))  # starts outside Eq. 6.41 (K_I = 0)
        flags = [pid_loop_stable(m.p.K, m.p.T, b.gains) for b in m.batches]
        assert not all(flags) and all(flags[-3:])  # an unstable stretch while learning (Figs. 6.15–6.16 (e))
    kp, ki, kd = gov.mlc["v"].gains
    assert 1e-4 < kp < 1e-2 and 1e-4 < ki < 1e-2 and kd < min(kp, ki)  # O(1e-3); P and I dominate D
    assert abs(body.snapshot()["v"]) < 0.01


def max_ui_step(mode, seconds=20.0):
    """Largest one-tick change of u_I^v while MLC raises K_I from 0 on the identified plant."""
    body = IdentifiedScooterPlant(disturbance=(1e-4, 1e-4))
    gov = SpeedGovernor(mode=mode)
    u_I = []
    Loop(body, [gov]).run(duration=seconds, every={1: lambda s: u_I.append(gov.pid["v"].integrator.u_I)})
    return np.max(np.abs(np.diff(u_I))), gov


def test_in_closed_loop_the_corrected_integrator_removes_the_jumps_of_the_plain_one():
    plain, _ = max_ui_step("plain")
    saturated, _ = max_ui_step("saturated")
    corrected, gov = max_ui_step("corrected")
    assert any(b.gains[1] > 0 for b in gov.mlc["v"].batches)  # K_I did rise from 0
    assert corrected < 0.05 * plain  # Eq. 6.38 against Eq. 6.36
    assert corrected < 0.1 * saturated < 0.1 * plain  # r_sat = 1.5 (Eq. 6.42) still jumps (Fig. 6.17)
