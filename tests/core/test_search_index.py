"""Online search index (seed 000 ch. 2): Eqs. 2.5, 2.10, 2.13–2.33, Table 3.3 filter."""

import numpy as np
import pytest

from shintai.core.experiments.search_index import COUPLED_C, COUPLED_G, COUPLED_XD
from shintai.core.linear_plant import run_control_index, run_learning_index
from shintai.core.search_index import (
    MatrixGain,
    QuadraticCost,
    SearchIndex,
    StabilityMonitor,
    control_index,
    control_index_coefficient,
    estimate_sign_matrix,
    finite_difference_gradient,
    first_order_gain,
    impedance_gain,
    is_decoupled,
    offline_index,
    sign_matrix,
    spsa_gradient,
)


def test_control_index_by_hand():
    sgn = sign_matrix([[-1, 0], [0, 1], [1, 1]])
    f = control_index(sgn, x=[3.0, 1.0], x_d=[1.0, 2.0])
    assert f.tolist() == [-2.0, -1.0, 1.0]  # sgn (x − x_d) with x − x_d = (2, −1)
    with pytest.raises(ValueError):
        sign_matrix([[2, 0]])


def test_sign_matrix_by_probing_force_against_a_stiff_wall():
    """Spec 000 §5.4 check 2: pushing a wall along each axis gives sgn = −E (Eq. 3.17)."""
    k_wall = 1e4
    wall = np.array([0.1, 0.2, 0.3])

    def force(xi):  # reaction force on the hand: opposes penetration, independent across axes
        return -k_wall * np.maximum(xi - wall, 0.0)

    sgn = estimate_sign_matrix(force, [wall + 0.01, wall + 0.02])
    assert np.array_equal(sgn, -np.eye(3))


def test_probing_gives_zero_when_the_sign_flips():
    """Eq. 2.7: a pedal whose effect on yaw rate flips with the steering angle gets sgn 0."""
    def yaw_rate(rho):  # rho = (pedal, steering)
        return np.array([rho[0] * rho[1]])

    sgn = estimate_sign_matrix(yaw_rate, [np.array([1.0, 0.5]), np.array([1.0, -0.5])])
    assert sgn[0, 0] == 0.0


def test_scalar_update_converges_monotonically_and_wrong_sign_grows():
    """Spec 000 §5.4 check 1 with 0 < a|g| < 1."""
    e, r, mon = run_control_index([[-2.0]], [5.0], np.array([1.0]), [0.0], [[-1.0]], [[0.3]], 30)
    assert mon.monotone and abs(e[-1, 0]) < 1e-10
    assert np.all(np.diff(np.abs(np.diff(r[:, 0]))) < 0)  # Eq. 2.28
    e_bad, _, mon_bad = run_control_index([[-2.0]], [5.0], np.array([1.0]), [0.0], [[1.0]], [[0.3]], 10)
    assert abs(e_bad[-1, 0]) > 10 * abs(e_bad[0, 0]) and mon_bad.error_increases > 0


def test_overshooting_gain_converges_but_not_monotonically():
    """1 < a|g| < 2: the error recursion factor is negative — convergent, but Eq. 2.28 still holds
    on magnitudes while the sign alternates; a|g| > 2 diverges ([DERIVED] spec §2.5)."""
    e, _, _ = run_control_index([[-2.0]], [5.0], np.array([1.0]), [0.0], [[-1.0]], [[0.75]], 40)
    assert abs(e[-1, 0]) < 1e-6 and np.any(np.diff(np.sign(e[:, 0])) != 0)
    e, _, _ = run_control_index([[-2.0]], [5.0], np.array([1.0]), [0.0], [[-1.0]], [[1.2]], 20)
    assert abs(e[-1, 0]) > abs(e[0, 0])


def test_coupled_plant_with_decoupled_sign():
    A = np.diag([0.25, 0.3])
    assert is_decoupled(A, -np.eye(2)) and not is_decoupled(A, [[-1, 1], [1, -1]])
    e, _, mon = run_control_index(COUPLED_G, COUPLED_C, COUPLED_XD, np.zeros(2), -np.eye(2), A, 60)
    assert mon.monotone and np.abs(e[-1]).max() < 1e-8


def test_learning_index_decreases_quadratic_cost():
    J, mon = run_learning_index(COUPLED_G, COUPLED_C, COUPLED_XD, np.zeros(2), np.diag([1.0, 2.0]), 0.05, 80)
    assert mon.cost_increases == 0 and J[-1] < 1e-6 * J[0]


def test_gradient_estimators_agree_with_analytic():
    cost = QuadraticCost(np.diag([1.0, 3.0]), np.array([1.0, -1.0]))
    J = lambda rho: cost(COUPLED_G @ rho + COUPLED_C)  # noqa: E731
    rho = np.array([0.3, -0.2])
    analytic = COUPLED_G.T @ cost.grad_x(COUPLED_G @ rho + COUPLED_C)
    assert np.allclose(finite_difference_gradient(J, rho), analytic, rtol=1e-6)
    rng = np.random.default_rng(0)
    mean = np.mean([spsa_gradient(J, rho, 1e-4, rng) for _ in range(4000)], axis=0)
    assert np.linalg.norm(mean - analytic) < 0.05 * np.linalg.norm(analytic)  # unbiased on a quadratic


def test_offline_index_walks_the_plan():
    plan = np.cumsum(np.ones((5, 2)), axis=0)
    law_rho = plan[0].copy()
    for f in offline_index(plan):
        law_rho = law_rho - np.eye(2) @ f
    assert np.allclose(law_rho, plan[-1])


def test_matrix_gain_must_be_symmetric_positive_definite():
    with pytest.raises(ValueError, match="symmetric"):
        MatrixGain([[1, 2], [0, 1]])
    with pytest.raises(ValueError, match="positive definite"):
        MatrixGain([[1, 0], [0, -1]])


def test_impedance_filter_static_gain_and_step_response():
    """A = (M s² + D s + K)⁻¹ with Table 3.4 passive values: static gain 1/K; ZOH matches the ODE."""
    dt = 0.004
    A = impedance_gain(10.0, 500.0, 300.0, dt)
    assert A.static_gain[0, 0] == pytest.approx(1 / 300.0)
    y = [A(np.array([1.0]))[0] for _ in range(10000)]  # 40 s: the slow pole (−0.61 /s) has settled
    assert y[-1] == pytest.approx(1 / 300.0, rel=1e-8)
    # exact solution of 10 δ'' + 500 δ' + 300 δ = 1 at t = 0.4 s, from the roots of the characteristic polynomial
    r1, r2 = np.roots([10.0, 500.0, 300.0])
    t = 100 * dt
    exact = (1 / 300.0) * (1 + (r2 * np.exp(r1 * t) - r1 * np.exp(r2 * t)) / (r1 - r2))
    assert y[99] == pytest.approx(exact, rel=1e-9)
    A.reset()
    assert np.all(A.state == 0)


def test_reference_reset_equals_filtered_update():
    """Spec 000 §5.4 check 3 on the engine: Eq. 3.14 (ξ_ref ← ξ = ξ_ref + δ) and Eq. 3.18
    (ρ ← ρ − A sgn (f_msr − f_trg), sgn = −E, A the persistent impedance filter) give one sequence."""
    dt, f_trg = 0.004, np.array([0.0, 0.0, 150.0])
    rng = np.random.default_rng(3)
    forces = [f_trg + rng.normal(0, 20, 3) for _ in range(200)]
    imp_a, imp_b = impedance_gain(10, 500, 300, dt, axes=3), impedance_gain(10, 500, 300, dt, axes=3)
    ref_a = np.zeros(3)
    law = SearchIndex(np.zeros(3), imp_b, sgn=-np.eye(3), x_d=f_trg)
    for f in forces:
        delta = imp_a(f - f_trg)  # Eq. 3.13/3.15: impedance displacement of ξ from ξ_ref
        ref_a = ref_a + delta  # Eq. 3.14: the new reference is the displaced position
        law.update(f)
    assert np.allclose(ref_a, law.rho, atol=1e-15)


def test_hold_keeps_the_reference():
    """Eq. 3.14 second branch: an unreachable proposal keeps the current reference."""
    law = SearchIndex([0.0], 0.1, sgn=[[-1.0]], x_d=[0.0], hold=lambda rho: abs(rho[0]) > 0.15)
    for _ in range(5):
        law.update([1.0])
    assert law.rho[0] == pytest.approx(0.1) and law.held_steps == 4


def test_first_order_filter_and_coefficient():
    A = first_order_gain(2.0, 0.1, 0.01)
    for _ in range(500):
        y = A(np.array([1.0]))
    assert y[0] == pytest.approx(2.0, rel=1e-9)
    coeff = control_index_coefficient(np.diag([0.5, 0.25]), -np.eye(2))
    assert np.allclose(coeff, np.diag([-2.0, -4.0]))


def test_stability_monitor_counts_violations():
    mon = StabilityMonitor()
    for e in ([1.0, 1.0], [0.5, 0.9], [0.6, 0.1]):
        mon.observe(error=e)
    assert mon.error_increases == 1 and not mon.monotone
