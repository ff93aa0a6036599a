"""The speed-governing system of seed 000 §6.2.2: velocity filter (Eq. 6.3), mixing (Eq. 6.5), plant
(Eqs. 6.12–6.14), identification (Eqs. 6.14–6.16), Routh–Hurwitz (Eqs. 6.40–6.41)."""

import math

import numpy as np
import pytest

from shintai.humanoid.constants import K_OMEGA, K_V, T_OMEGA, T_V
from shintai.humanoid.learning.speed_governing import (IdentifiedScooterPlant, LinearVelocityFilter, SpeedPlant,
    characteristic_polynomial, foot_pitch_increments, identify_plant, pid_loop_stable, plant_inputs, routh_hurwitz,
    stability_flag)

DT = 0.004


def run_filter(v_of_t, seconds, bias=0.0, vo_noise=0.0, seed=0, T_f=0.5):
    """Feed the filter a_x = v̇ + bias at 4 ms and x_VO (+ noise) at 10 ms; return t and its v."""
    rng = np.random.default_rng(seed)
    f = LinearVelocityFilter(T_f, DT)
    ts = np.arange(1, round(seconds / DT) + 1) * DT
    out = []
    for t in ts:
        if abs(t * 100 - round(t * 100)) < 1e-6:  # every 10 ms
            x = np.trapezoid([v_of_t(s) for s in np.linspace(0, t, 200)], np.linspace(0, t, 200))
            f.vo_sample(t, x + rng.normal(0, vo_noise))
        h = 1e-6
        out.append(f.step((v_of_t(t + h) - v_of_t(t - h)) / (2 * h) + bias))
    return ts, np.array(out)


def test_complementary_filter_passes_consistent_signals_and_bounds_bias_by_T_f():
    v = lambda t: 0.3 * math.sin(1.3 * t)
    ts, est = run_filter(v, 8.0)
    late = ts > 4.0
    assert np.max(np.abs(est[late] - [v(t) for t in ts[late]])) < 0.01  # HPF + LPF = 1 (VO is 10 ms behind)
    ts, est = run_filter(lambda t: 0.2, 6.0, bias=0.05)
    assert est[-1] - 0.2 == pytest.approx(0.05 * 0.5, rel=0.05)  # accelerometer bias → error b·T_f


def test_filter_attenuates_visual_odometry_noise():
    ts, est = run_filter(lambda t: 0.1, 6.0, vo_noise=1e-3, seed=3)
    raw_sd = math.sqrt(2) * 1e-3 / 0.01  # differencing 10 ms samples
    assert np.std(est[ts > 3.0]) < 0.2 * raw_sd


def test_mixing_eq_6_5_and_its_inverse():
    np.testing.assert_allclose(foot_pitch_increments(2e-4, 5e-5, (1e-5, -1e-5)), [2.6e-4, 1.4e-4])
    np.testing.assert_allclose(plant_inputs(foot_pitch_increments(2e-4, 5e-5)), [2e-4, 5e-5])


def test_plant_step_response_is_K_over_s_1_plus_Ts():
    p = SpeedPlant(K_V, T_V, DT)
    u = 1e-4
    ys = [p.step(u) for _ in range(1000)]
    t = 1000 * DT
    assert ys[-1] == pytest.approx(K_V * u * (t - T_V * (1 - math.exp(-t / T_V))), rel=1e-9)


def test_scooter_plant_body_drives_v_by_the_mean_and_omega_by_the_half_difference():
    body = IdentifiedScooterPlant()
    body.apply({"foot_pitch": foot_pitch_increments(1e-4, 0.0)})
    for _ in range(100):
        body.step()
    s = body.snapshot()
    assert s["v"] > 0 and s["omega"] == 0.0
    body = IdentifiedScooterPlant()
    body.apply({"foot_pitch": foot_pitch_increments(0.0, 1e-5)})
    body.step()
    assert body.snapshot()["v"] == 0.0 and body.snapshot()["omega"] > 0


@pytest.mark.parametrize("K, T", [(K_V, T_V), (K_OMEGA, T_OMEGA)])
def test_identification_recovers_T_and_K_from_a_noisy_series(K, T):
    rng = np.random.default_rng(14)
    n = round(40.0 / DT)
    hold = rng.integers(100, 500, size=200)  # 0.4–2 s steps of random height
    u = np.repeat(rng.normal(0, 1e-4 * K_V / K, hold.size), hold)[:n]
    p = SpeedPlant(K, T, DT)
    y = np.array([p.step(x) for x in u])
    scale = np.std(y)
    y_meas = y + rng.normal(0, 1e-2 * scale, n)  # 1 % noise on y: ẏ_act is mostly noise
    fit = identify_plant(u, y_meas, DT)
    assert fit["T"] == pytest.approx(T, rel=0.03) and fit["K"] == pytest.approx(K, rel=0.02)
    assert fit["r2"] < 0.2  # the fit explains little of the differentiated noise, yet T and K come back


@pytest.mark.parametrize("K, T", [(K_V, T_V), (K_OMEGA, T_OMEGA)])
def test_identification_low_pass_on_both_sides_keeps_T_and_K_and_takes_the_noise_out_of_r2(K, T):
    rng = np.random.default_rng(14)
    n = round(40.0 / DT)
    hold = rng.integers(100, 500, size=200)
    u = np.repeat(rng.normal(0, 1e-4 * K_V / K, hold.size), hold)[:n]
    p = SpeedPlant(K, T, DT)
    y = np.array([p.step(x) for x in u])
    y_meas = y + rng.normal(0, 1e-2 * np.std(y), n)
    raw, filtered = identify_plant(u, y_meas, DT), identify_plant(u, y_meas, DT, cutoff_hz=2.0)
    assert filtered["T"] == pytest.approx(T, rel=0.03) and filtered["K"] == pytest.approx(K, rel=0.02)
    assert raw["r2"] < 0.2 < 0.8 < filtered["r2"]
    with pytest.raises(ValueError, match="cutoff_hz"):
        identify_plant(u, y_meas, DT, cutoff_hz=0.0)


def test_identification_rejects_mismatched_series():
    with pytest.raises(ValueError, match="same length"):
        identify_plant(np.zeros(100), np.zeros(99), DT)


def test_routh_hurwitz_agrees_with_the_roots_of_random_polynomials():
    rng = np.random.default_rng(40)
    for _ in range(400):
        c = np.r_[rng.uniform(0.1, 2.0), rng.normal(0.5, 1.0, rng.integers(2, 6))]
        roots_stable = bool(np.all(np.roots(c).real < -1e-9))
        if abs(np.max(np.roots(c).real)) < 1e-6:
            continue  # on the boundary: numerically ambiguous
        assert routh_hurwitz(c) == roots_stable, c


def test_eq_6_41_agrees_with_the_roots_of_eq_6_40():
    rng = np.random.default_rng(41)
    agree = {True: 0, False: 0}
    for K, T in ((K_V, T_V), (K_OMEGA, T_OMEGA)):
        for _ in range(300):
            g = 10.0 ** rng.uniform(-7, -2, 3) * (rng.random(3) > 0.1)  # some gains exactly 0, as after clipping
            phi = characteristic_polynomial(K, T, g)
            np.testing.assert_allclose(phi, [T, 1 + K * g[2], K * g[0], K * g[1]])
            by_roots = bool(np.all(np.roots(phi).real < 0)) and g[1] > 0
            assert pid_loop_stable(K, T, g) == by_roots == (routh_hurwitz(phi) if g[1] > 0 else False), g
            assert stability_flag(K, T, g) == (1 if by_roots else -1)
            agree[by_roots] += 1
    assert min(agree.values()) > 50  # both outcomes exercised
