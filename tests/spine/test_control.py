"""Muscle control modes (§4.6, eqs. 4.36–4.42, Table 4.6) against hand calculations, and §4.7's policy."""

import numpy as np
import pytest

from shintai.core.runtime import SET
from shintai.spine.actuators import TensionSensor
from shintai.spine.control import (
    RECOMMENDED, SETPOINTS, CountSpring, Gains, Mode, MuscleControl, encoder_targets, interference_modes, law_L, law_LL,
    law_S, law_T, software_spring, table_4_6_gains, unified_duty,
)
from shintai.spine.robots import CLA

G = Gains(K_Pl=2000.0, K_Il=1.0e4, K_Dl=3.0, K_Pt=0.1, K_Dt=1e-3, T_t=0.5, T_l=10.0, k_s=3000.0, T_r=9.8)


def test_law_L_hand_calculation():
    # l = 1 mm wound, target 1.2 mm (too long: wind in), integral 1e−5 m s, dl/dt = 2 mm/s
    o = law_L(1e-3, 1.2e-3, 1e-5, 2e-3, G)
    assert o == pytest.approx(-2000 * (-0.2e-3) - 1e4 * 1e-5 - 3.0 * 2e-3)  # 0.4 − 0.1 − 0.006
    assert o == pytest.approx(0.294)


def test_law_T_hand_calculation_and_dead_band():
    assert law_T(12.0, 9.8, 5.0, G) == pytest.approx(-0.1 * 2.2 - 1e-3 * 5.0)  # too tight: pay out
    assert law_T(9.5, 9.8, 5.0, G) == 0.0  # |T − T_r| < T_t
    assert law_T(9.3, 9.8, 0.0, G) == pytest.approx(0.05)  # on the edge of the dead band: acts


def test_software_spring_and_law_S():
    assert software_spring(1e-3, 2e-3, 3000.0) == pytest.approx(3.0)  # stretched by 1 mm → 3 N
    # T_r = 3000 (0 − (−2 mm)) = 6 N; measured 4 N: o = −0.1 (4 − 6) − 1e−3 · 1
    assert law_S(4.0, -2e-3, 0.0, 1.0, G) == pytest.approx(0.2 - 1e-3)


def test_law_LL_switches_off_at_the_limit():
    args = (1e-3, 1.2e-3, 0.0, 0.0)
    assert law_LL(*args, 9.0, G) == pytest.approx(law_L(*args, G))
    assert law_LL(*args, 10.0, G) == 0.0  # T ≥ T_l: o = 0


@pytest.mark.parametrize("mode", list(Mode))
def test_unified_law_reduces_to_each_mode(mode):
    """Eq. 4.41 with Table 4.6's parameter settings equals the mode's own law."""
    rng = np.random.default_rng(int(mode))
    for _ in range(50):
        l, l_r, integral, dl = rng.normal(0, 1e-3, 4)
        T, dT = rng.uniform(0, 20), rng.normal(0, 10)
        l_0 = rng.normal(0, 1e-3)
        g = table_4_6_gains(mode, G)
        own = {Mode.L: law_L(l, l_r, integral, dl, G), Mode.T: law_T(T, G.T_r, dT, G),
               Mode.S: law_S(T, l, l_0, dT, G), Mode.LL: law_LL(l, l_r, integral, dl, T, G)}[mode]
        assert unified_duty(l, l_r, integral, dl, T, g.T_r, dT, l_0, g) == pytest.approx(own, abs=1e-12)


def test_controller_tick_per_mode_saturation_and_sign():
    ctl = MuscleControl(4, G, period=1e-3)
    ctl.set_modes([Mode.L, Mode.T, Mode.S, Mode.LL])
    ctl.set_targets(l_r=[1e-3, 0, 0, 1e-3], T_r=[0, 5.0, 0, 0], l_0=[0, 0, 0, 0])
    ctl.reset({"encoder": np.zeros(4), "tension": np.full(4, 5.0)})
    o = ctl.duty(np.zeros(4), np.array([5.0, 5.0, 5.0, 12.0]), 1e-3)
    assert o[0] == pytest.approx(1.0)  # 1 mm too long: saturated wind-in (L)
    assert o[1] == 0.0  # at target tension (T, dead band)
    assert o[2] == pytest.approx(-0.5, abs=1 / 255)  # spring at rest, 5 N too much: pay out (S)
    assert o[3] == 0.0  # above the limit (LL)
    assert ctl.state.integral[0] == pytest.approx(-1e-6) and ctl.state.integral[3] == 0.0


def test_controller_tick_equals_the_per_mode_laws():
    """The vectorised 1 ms tick gives, muscle by muscle, the duty of eqs. 4.37–4.40 (before the PWM
    quantisation), on random readings in all four modes."""
    rng = np.random.default_rng(3)
    m = 16
    ctl = MuscleControl(m, G, period=1e-3)
    modes = np.tile([Mode.L, Mode.T, Mode.S, Mode.LL], 4)
    ctl.set_modes(modes)
    l_r, T_r, l_0 = rng.normal(0, 1e-4, m), rng.uniform(2, 15, m), rng.normal(0, 1e-4, m)
    ctl.set_targets(l_r=l_r, T_r=T_r, l_0=l_0)
    l0, T0 = rng.normal(0, 1e-4, m), rng.uniform(0, 15, m)
    ctl.reset({"encoder": l0, "tension": T0})
    l1, T1 = l0 + rng.normal(0, 2e-6, m), T0 + rng.normal(0, 0.5, m)
    o = ctl.duty(l1, T1, 1e-3)
    dl, dT = (l1 - l0) / 1e-3, (T1 - T0) / 1e-3
    integral = ctl.state.integral
    expected = np.select([modes == Mode.L, modes == Mode.T, modes == Mode.S],
                         [law_L(l1, l_r, integral, dl, G), law_T(T1, T_r, dT, G), law_S(T1, l1, l_0, dT, G)],
                         law_LL(l1, l_r, integral, dl, T1, G))
    assert np.abs(o - np.clip(expected, -1, 1)).max() <= 0.5 / 255 + 1e-12
    assert np.all(integral[(modes == Mode.T) | (modes == Mode.S)] == 0.0)  # frozen outside L / LL


def test_mode_switch_restarts_the_length_integral():
    ctl = MuscleControl(2, G)
    ctl.state.integral[:] = 1e-5
    ctl.set_modes([Mode.L, Mode.T])
    assert ctl.state.integral[0] == 1e-5  # still L
    ctl.set_modes([Mode.T, Mode.LL])
    ctl.set_modes([Mode.L, Mode.LL])
    assert ctl.state.integral[0] == 0.0 and ctl.state.integral[1] == 0.0


def test_module_contributes_duty_from_snapshot():
    ctl = MuscleControl(2, G)
    snap = {"t": 0.0, "encoder": np.zeros(2), "tension": np.zeros(2)}
    ctl.reset(snap)
    out = ctl.update(snap)
    assert set(out) == {"duty"} and out["duty"].shape == (2,)


def test_setpoints_arrive_on_channels_and_are_kept():
    """A set-point stage writes mode and targets; the controller takes them in the same tick (before
    its duty) and keeps them on ticks nobody writes them."""
    ctl = MuscleControl(2, G)
    snap = {"t": 0.0, "encoder": np.zeros(2), "tension": np.full(2, 5.0)}
    ctl.reset(snap)
    ctl.state.integral[:] = 1e-5
    out = ctl.update({**snap, "mode": np.array([float(Mode.L), float(Mode.T)]), "l_r": np.array([1e-3, 0.0]),
                      "T_r": np.array([0.0, 5.0])})
    assert list(ctl.modes) == [Mode.L, Mode.T] and ctl.l_r[0] == 1e-3 and ctl.T_r[1] == 5.0
    assert out["duty"][0] == pytest.approx(1.0) and out["duty"][1] == 0.0  # 1 mm too long: wind in; T at target
    ctl.update(snap)
    assert list(ctl.modes) == [Mode.L, Mode.T] and ctl.l_r[0] == 1e-3  # kept
    assert {c.name for c in SETPOINTS} == {"mode", "l_r", "T_r", "l_0"} and all(c.kind == SET for c in SETPOINTS)


def test_interference_policy():
    """§4.7.2: shortening muscles L, lengthening muscles the tension-limited mode."""
    modes = interference_modes([0.20, 0.20, 0.20], [0.19, 0.21, 0.20], Mode.LL)
    assert list(modes) == [Mode.L, Mode.LL, Mode.L]
    assert RECOMMENDED["normal"] == (Mode.L, Mode.LL) and RECOMMENDED["stiff"] == (Mode.L, Mode.L)


def test_encoder_targets_grow_as_the_muscle_shortens():
    assert np.allclose(encoder_targets([0.195, 0.205], [0.2, 0.2]), [0.005, -0.005])


def test_benchmark_reference_matches_the_vectorised_tick():
    """The naive per-muscle loop of the Kenta benchmark computes the same duties (before PWM quantisation)."""
    from shintai.spine.benchmarks import naive_tick

    rng = np.random.default_rng(7)
    controls = [MuscleControl(40, G), MuscleControl(40, G)]
    for c in controls:
        c.set_modes(np.arange(40) % 4)
        c.set_targets(l_r=np.linspace(-1e-3, 1e-3, 40), T_r=8.0, l_0=np.zeros(40))
        c.reset({"encoder": np.zeros(40), "tension": np.full(40, 8.0)})
    for _ in range(5):
        l, T = rng.normal(0, 1e-3, 40), np.abs(rng.normal(10, 3, 40))
        fast = controls[0].duty(l, T, 1e-3)
        slow = naive_tick(controls[1], l, T, 1e-3)
        assert np.abs(fast - slow).max() <= 0.5 / 255 + 1e-12


SENSOR = TensionSensor(CLA.sensor)
SPRING = CountSpring(SENSOR, pulse_m=1e-5, fixed_point=50.0)  # hand-calculation scale


def test_count_spring_hand_calculation():
    """Eq. 4.36 in counts (§4.5.2): k_s = 100 counts/pulse over 50, stretched 20 pulses → 40 counts,
    read back as the tension whose ADC count is 40; slack by 20 pulses → −40 counts, linear."""
    assert SPRING.counts(-2e-4, 0.0, 100.0) == pytest.approx(40.0)
    T_r = SPRING.reference(-2e-4, 0.0, 100.0)
    assert T_r == pytest.approx(np.interp(40.0, SENSOR.table_adc, SENSOR.table_tension))
    assert SENSOR.adc(T_r) == 40.0
    assert SPRING.reference(2e-4, 0.0, 100.0) == pytest.approx(-40.0 / SENSOR.zero_slope_counts_n)
    # law S on that reference (≈ 1.35 N): measured 0.5 N, outside the 0.5 N dead band, o = −K_Pt (0.5 − T_r)
    g = Gains(K_Pt=0.1, K_Dt=1e-3, T_t=0.5, k_s=100.0)
    assert law_S(0.5, -2e-4, 0.0, 0.0, g, SPRING) == pytest.approx(-0.1 * (0.5 - T_r))


def test_count_spring_hardens_in_newtons():
    """Linear in counts, so through the saturating calibration (Fig. 3.34) the newton stiffness rises
    with tension; secant and local stiffness agree."""
    k = SPRING.stiffness_n_m(np.array([0.0, 5.0, 20.0, 50.0, 100.0]), 100.0)
    assert np.all(np.diff(k) > 0) and k[-1] > 10 * k[0]
    stretch = np.linspace(0.0, 2e-3, 201)
    T = SPRING.reference(-stretch, 0.0, 100.0)
    assert np.all(np.diff(np.diff(T)) > -1e-9)  # convex: hardening
    mid = 100
    assert (T[mid + 1] - T[mid - 1]) / (stretch[mid + 1] - stretch[mid - 1]) == pytest.approx(
        SPRING.stiffness_n_m(T[mid], 100.0), rel=0.02)


def test_count_spring_matching_scale_is_the_newton_law_at_rest():
    """The chosen firmware scale: linearised at l = l_0 the count law equals k_s × (N/m per unit)."""
    spring = CountSpring.matching(SENSOR, CLA.motors[0].encoder_step_m, 30.0)
    assert spring.stiffness_n_m(0.0, 400.0) == pytest.approx(400.0 * 30.0)
    assert spring.reference(-20e-6, 0.0, 400.0) == pytest.approx(software_spring(-20e-6, 0.0, 12000.0), rel=0.02)
    assert spring.reference(-2e-3, 0.0, 400.0) > 2 * software_spring(-2e-3, 0.0, 12000.0)  # hardened


def test_controller_tick_with_count_spring_equals_law_S():
    rng = np.random.default_rng(5)
    ctl = MuscleControl(6, G, spring=SPRING)
    ctl.set_modes(Mode.S)
    l_0 = rng.normal(0, 1e-4, 6)
    ctl.set_targets(l_0=l_0)
    l0, T0 = rng.normal(0, 1e-4, 6), rng.uniform(0, 15, 6)
    ctl.reset({"encoder": l0, "tension": T0})
    l1, T1 = l0 + rng.normal(0, 2e-6, 6), T0 + rng.normal(0, 0.5, 6)
    o = ctl.duty(l1, T1, 1e-3)
    expected = law_S(T1, l1, l_0, (T1 - T0) / 1e-3, G, SPRING)
    assert np.abs(o - np.clip(expected, -1, 1)).max() <= 0.5 / 255 + 1e-12
    assert np.allclose(ctl.spring_reference(l1), SPRING.reference(l1, l_0, G.k_s))
