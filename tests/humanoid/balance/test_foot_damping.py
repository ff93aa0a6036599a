"""Foot torque damping control (seed 000 §5.2.2, Eqs. 5.1–5.3) and foot force difference control."""

import numpy as np
import pytest

from shintai.humanoid.balance.foot_damping import (FootDamping, ForceDifferenceControl, damping_controller_gain,
    damping_step)
from shintai.humanoid.constants import DAMPING_D_FLAT, DAMPING_T, DELTA_LIMIT

DT = 0.004


def test_euler_step_is_eq_5_1_by_hand():
    # δ + Δt (e/D − δ/T) with δ = 0.01, e = 2 N·m, D = 22, T = 1.5
    assert damping_step(0.01, 2.0, 22.0, 1.5, DT) == pytest.approx(0.01 + DT * (2.0 / 22.0 - 0.01 / 1.5), rel=1e-15)


def test_constant_error_settles_to_the_static_gain_of_eq_5_3_with_time_constant_T():
    law = FootDamping(D=[30.0, DAMPING_D_FLAT], T=DAMPING_T, dt=DT, limit=1.0)
    e = np.array([0.5, -0.4])
    n_T = round(DAMPING_T / DT)
    out = [law.step(e, np.zeros(2)) for _ in range(20 * n_T)]
    final = e * damping_controller_gain(law.D, DAMPING_T)  # T e / D
    np.testing.assert_allclose(out[-1], final, rtol=1e-6)
    # first-order lag: 1 − e⁻¹ of the way after T (Euler at Δt ≪ T: within 0.2 %)
    np.testing.assert_allclose(out[n_T - 1] / final, 1 - np.exp(-1), rtol=2e-3)


def test_sign_a_torque_below_its_reference_turns_the_foot_positive():
    law = FootDamping(dt=DT)
    assert np.all(law.step([1.0, 1.0], [0.0, 0.0]) > 0)
    np.testing.assert_allclose(law.e_tau, [1.0, 1.0])


def test_delta_is_clipped_to_the_limit_and_flagged():
    law = FootDamping(D=1.0, T=100.0, dt=DT)
    for _ in range(1000):
        d = law.step([0.0, 100.0], [0.0, 0.0])
    assert d[1] == pytest.approx(DELTA_LIMIT) and law.saturated[1] and not law.saturated[0]


@pytest.mark.parametrize("kwargs, field", [({"D": -22.0}, "D (roll)"), ({"D": [22.0, np.nan]}, "D (pitch)"),
                                           ({"T": 0.0}, "T"), ({"limit": -1}, "limit")])
def test_bad_parameters_name_the_field(kwargs, field):
    with pytest.raises(ValueError, match=f"^{field.replace('(', '[(]').replace(')', '[)]')} must"):
        FootDamping(**kwargs)


def test_force_difference_control_splits_the_correction_in_double_support_and_decays_in_single():
    law = ForceDifferenceControl(D=100.0, T=1.5, dt=DT)
    z_r, z_l = law.step(0.0, -50.0, double_support=True)  # left foot carries 50 N less than wanted
    assert z_l == pytest.approx(DT * 50.0 / 100.0 / 2) and z_r == pytest.approx(-z_l)
    before = law.z_ctrl
    law.step(0.0, -50.0, double_support=False)
    assert law.z_ctrl == pytest.approx(before * (1 - DT / 1.5))


def test_the_module_steps_both_feet_as_each_foots_law_would():
    """FootDampingModule runs Eq. 5.1 on both feet in one compiled call: the same δ, e_τ and saturation, to the bit,
    as each foot's FootDamping.step on its arrays (the clip included: the right pitch saturates)."""
    from shintai.humanoid.balance.foot_damping import FootDampingModule

    module = FootDampingModule(D=[30.0, 1.0])
    laws = {f: FootDamping(D=[30.0, 1.0]) for f in "LR"}
    rng = np.random.default_rng(0)
    for k in range(300):
        snap = {"t": k * DT, **{f"tau_d_{f}": rng.normal(0.0, 5.0, 2) for f in "LR"},
                **{f"tau_{f}": rng.normal(0.0, 5.0, 2) for f in "LR"}}
        snap["tau_d_R"][1] += 200.0
        out = module.update(snap)
        expected = np.concatenate([laws[f].step(snap[f"tau_d_{f}"], snap[f"tau_{f}"]) for f in "LR"])
        assert np.array_equal(out["foot_damping"], expected) and np.array_equal(out["damping_delta"], expected)
        assert np.array_equal(out["e_tau"], np.concatenate([laws[f].e_tau for f in "LR"]))
        for f in "LR":
            assert np.array_equal(module.feet[f].saturated, laws[f].saturated)
    assert module.feet["R"].saturated[1] and not module.feet["L"].saturated.any()
