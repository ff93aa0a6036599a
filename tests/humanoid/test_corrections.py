"""Ch. 4 corrections (seed 000 §4.3, §4.4.3): sitting-recovery trigger and law, Kajita's chest posture
control, the pedalling-power detection and the push-down angle."""

import math

import numpy as np
import pytest

from shintai.humanoid.constants import CONTROL_PERIOD, DEG, THETA_C_INIT
from shintai.humanoid.corrections import (
    ChestPostureControl,
    PedalLoadDetector,
    RecoveryTrigger,
    SittingRecovery,
    at_k_pi,
    hip_force,
    push_down_angle,
    recovery_due,
    recovery_index,
)


def test_recovery_trigger_only_at_k_pi():
    """§4.3.2 / Table 7.6: |θ_roll| over the threshold *and* θ_c = kπ."""
    roll = 5 * DEG
    for k in range(-2, 4):
        assert recovery_due(roll, k * math.pi)
        assert recovery_due(-roll, k * math.pi + 4 * DEG)
        assert not recovery_due(roll, k * math.pi + 10 * DEG)
        assert not recovery_due(roll, k * math.pi + math.pi / 2)
    assert not recovery_due(0.5 * DEG, math.pi)  # level trunk: nothing to recover
    assert at_k_pi(2 * math.pi - 1e-9) and not at_k_pi(math.pi / 2)


def test_trigger_fires_once_per_level_crank():
    trig = RecoveryTrigger()
    assert trig(5 * DEG, math.pi)
    assert not trig(5 * DEG, math.pi + 1 * DEG)  # same kπ: driving must resume first
    assert not trig(5 * DEG, 1.5 * math.pi)
    assert trig(5 * DEG, 2 * math.pi)


def test_hip_force_eq_4_2():
    assert hip_force(56.5, 0.0, [150, 150], [0, 0]) == pytest.approx(56.5 * 9.81 - 300)
    assert hip_force(56.5, 0.0, [320, 320], [0, 0]) < 0  # Table 7.6's 320 N per foot unloads the saddle


def test_recovery_law_eq_4_7():
    """y_g(n+1) = y_g(n) − L sgn sin(θ_roll(n) − 0), sgn = −1: Δy_g = L sin θ_roll (Eq. 4.3)."""
    L = 0.25
    index = recovery_index(0.01, L)
    assert index.update([math.sin(0.1)])[0] == pytest.approx(0.01 + L * math.sin(0.1))
    assert index.update([math.sin(-0.05)])[0] == pytest.approx(0.01 + L * (math.sin(0.1) - math.sin(0.05)))


def test_sitting_recovery_phases():
    rec = SittingRecovery(lambda s: 0.1, 0.2, base_fz=150.0, phase_s=1.0)
    rec.reset({"t": 0.0, "ref:theta_h": 0.3})
    stand = rec.update({"t": 0.99})
    shift = rec.update({"t": 1.99})
    reseat = rec.update({"t": 2.999})
    assert stand["ref:foot_fz"] == pytest.approx(170.0, rel=1e-3)  # 320 N per foot (Table 7.6)
    assert stand["ref:com_shift"] == 0.0 and stand["ref:theta_h"] == 0.3  # handle held
    assert shift["ref:com_shift"] == pytest.approx(0.2 * math.sin(0.1), rel=1e-3)
    assert reseat["ref:foot_fz"] == pytest.approx(0.0, abs=1e-3)
    assert reseat["ref:com_shift"] == pytest.approx(0.2 * math.sin(0.1))
    rec.update({"t": 3.01})
    assert rec.done
    # after the recovery the driving system holds ρ = y_g(n+1) (§7.2)
    assert rec.held({"t": 4.0}) == {"ref:com_shift": pytest.approx(0.2 * math.sin(0.1))}


def test_kajita_posture_law_against_hand_calculation():
    """Eq. 4.8 sampled exactly: for a constant error e, Δφ_C(t) = −k_C T_C e (1 − e^{−t/T_C})."""
    k_c, t_c, dt = 4.0, 1.0, CONTROL_PERIOD
    law = ChestPostureControl(lambda s: 0.0, k_c, t_c, period=dt)
    law.reset({"t": 0.0})
    e = 0.02
    for n in range(1, 501):
        delta = law.step(e)
        if n in (1, 250, 500):
            assert delta == pytest.approx(-k_c * t_c * e * (1 - math.exp(-n * dt / t_c)), rel=1e-9)
    # Euler of Eq. 4.8 agrees to first order in Δt
    d = 0.0
    for _ in range(500):
        d += dt * (k_c * (0.0 - e) - d / t_c)
    assert delta == pytest.approx(d, rel=0.01)


def test_posture_loop_levels_the_chest():
    """The closed loop φ_C = α + Δφ_C settles at α / (1 + k_C T_C) (Eq. 4.10's DC gain)."""
    law = ChestPostureControl(lambda s: 0.0, 4.0, 1.0)
    law.reset({"t": 0.0})
    alpha, phi = 2 * DEG, 2 * DEG
    for _ in range(3000):
        phi = alpha + law.step(phi)
    assert phi == pytest.approx(alpha / 5, rel=1e-3)


def test_push_down_angle():
    """§4.4.3: back to the largest θ_c^init + kπ not above θ_c (unique from any angle)."""
    assert push_down_angle(THETA_C_INIT + 0.3) == pytest.approx(THETA_C_INIT)
    assert push_down_angle(THETA_C_INIT - 0.3) == pytest.approx(THETA_C_INIT - math.pi)
    for theta in np.linspace(-7, 7, 57):
        sw = push_down_angle(theta)
        assert sw <= theta < sw + math.pi
        assert math.remainder(sw - THETA_C_INIT, math.pi) == pytest.approx(0.0, abs=1e-9)


def test_pedal_load_detector():
    det = PedalLoadDetector(0.01, rise=0.4, window_s=0.5)
    for _ in range(100):
        assert not det.step(300.0, 0.8, 0.8)
    assert not det.step(500.0, 0.8, 0.8)  # more force while the crank turns: a hill, not a stall
    assert det.step(500.0, 0.1, 0.8)  # force rise while stalled
    assert not det.step(350.0, 0.1, 0.8)  # below +40 %
