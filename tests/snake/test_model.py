"""Model of seed 001 ch. 2 against finite differences of the forward kinematics (spec §5.4 checks 1–4, 6)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shintai.snake import model as M
from shintai.snake.constants import CH3_ROBOT, TRACKING

L = CH3_ROBOT.l
H = 1e-6  # central-difference step; truncation ~h², round-off ~eps/h ≈ 1e-10


def random_state(rng, n=9):
    return np.r_[rng.normal(size=2), rng.uniform(-math.pi, math.pi)], rng.uniform(-1.2, 1.2, n)


def fd_wheels(w_h, phi, wrt, h=H):
    """Central differences of wheel_poses w.r.t. w_h (wrt='w') or phi (wrt='phi'): (n, 3, dim)."""
    base = w_h if wrt == "w" else phi
    cols = []
    for k in range(len(base)):
        d = np.zeros(len(base))
        d[k] = h
        args = [(w_h + d, phi), (w_h - d, phi)] if wrt == "w" else [(w_h, phi + d), (w_h, phi - d)]
        plus, minus = (M.wheel_poses(M.configuration(w, p, L)) for w, p in args)
        cols.append((plus - minus) / (2 * h))
    return np.stack(cols, axis=2)


@pytest.mark.parametrize("seed", range(5))
def test_A_B_match_finite_differences_of_the_constraint(seed):
    """Row i of A ẇ − B φ̇ is wheel i's axle-direction velocity (2.6) computed from the FK (2.3)–(2.5)."""
    rng = np.random.default_rng(seed)
    w_h, phi = random_state(rng)
    cfg = M.configuration(w_h, phi, L)
    A, B = M.constraint_matrices(cfg)
    axle = np.column_stack((np.sin(cfg.theta), -np.cos(cfg.theta)))  # v_i = ẋ_i sin θ_i − ẏ_i cos θ_i
    dw, dphi = fd_wheels(w_h, phi, "w"), fd_wheels(w_h, phi, "phi")
    A_fd = np.einsum("ic,icd->id", axle, dw[:, :2, :])
    B_fd = -np.einsum("ic,icd->id", axle, dphi[:, :2, :])
    assert np.abs(A - A_fd).max() <= 1e-6
    assert np.abs(B - B_fd).max() <= 1e-6


def test_B_is_lower_triangular_with_diagonal_l():
    w_h, phi = random_state(np.random.default_rng(1))
    _, B = M.constraint_matrices(M.configuration(w_h, phi, L))
    assert np.allclose(np.triu(B, 1), 0.0)
    assert np.allclose(np.diag(B), L)  # (2.9)


def test_constraint_meaning_for_random_motions():
    """Check 2: FK-differenced lateral velocity of every wheel equals A ẇ − B φ̇ for any (ẇ, φ̇)."""
    rng = np.random.default_rng(7)
    w_h, phi = random_state(rng)
    w_dot, phi_dot = rng.normal(size=3), rng.normal(size=9)
    h = 1e-6
    plus = M.wheel_poses(M.configuration(w_h + h * w_dot, phi + h * phi_dot, L))
    minus = M.wheel_poses(M.configuration(w_h - h * w_dot, phi - h * phi_dot, L))
    vel = (plus - minus) / (2 * h)
    th = M.configuration(w_h, phi, L).theta
    lateral = vel[:, 0] * np.sin(th) - vel[:, 1] * np.cos(th)
    assert np.abs(lateral - M.lateral_velocities(M.configuration(w_h, phi, L), w_dot, phi_dot)).max() <= 1e-6


def test_fast_constraint_terms_equal_the_matrices():
    rng = np.random.default_rng(3)
    w_h, phi = random_state(rng)
    phi_dot = rng.normal(size=9)
    A, B = M.constraint_matrices(M.configuration(w_h, phi, L))
    A_fast, b_fast = M.constraint_terms(w_h[2], phi, L, phi_dot)
    assert np.allclose(A_fast, A, atol=1e-14) and np.allclose(b_fast, B @ phi_dot, atol=1e-14)


@pytest.mark.parametrize("k", [1, 4, 9])
def test_second_point_jacobians_match_finite_differences(k):
    rng = np.random.default_rng(k)
    w_h, phi = random_state(rng)
    J1, J2 = M.second_point_jacobians(M.configuration(w_h, phi, L), k)
    assert np.abs(J1 - fd_wheels(w_h, phi, "w")[k - 1]).max() <= 1e-6
    assert np.abs(J2 - fd_wheels(w_h, phi, "phi")[k - 1]).max() <= 1e-6
    assert np.all(J2[:, k:] == 0.0)  # columns k+1..n are zero (§2.4.1)


def test_derivatives_of_A_B_J2_match_finite_differences():
    rng = np.random.default_rng(11)
    w_h, phi = random_state(rng)
    cfg = M.configuration(w_h, phi, L)
    dA, dB = M.a_matrix_derivative(cfg), M.b_matrix_derivative(cfg)
    dJ2 = M.second_point_jacobian_derivative(cfg, 9)
    for m in range(9):
        d = np.zeros(9)
        d[m] = H
        (Ap, Bp), (Am, Bm) = (M.constraint_matrices(M.configuration(w_h, phi + s * d, L)) for s in (1, -1))
        J2p = M.second_point_jacobians(M.configuration(w_h, phi + d, L), 9)[1]
        J2m = M.second_point_jacobians(M.configuration(w_h, phi - d, L), 9)[1]
        assert np.abs(dA[m] - (Ap - Am) / (2 * H)).max() <= 1e-6
        assert np.abs(dB[m] - (Bp - Bm) / (2 * H)).max() <= 1e-6
        assert np.abs(dJ2[m] - (J2p - J2m) / (2 * H)).max() <= 1e-6


def test_tracking_initial_controlled_variables():
    """Spec §4.1 [derived]: c_c(0) = [0, 0, π, −1.1253, −0.0593, 4π/3] for the §3.3 initial state."""
    tail = M.wheel_poses(M.configuration(TRACKING.w_h0, TRACKING.phi0, L))[-1]
    assert np.allclose(tail, [-1.1253, -0.0593, 4 * math.pi / 3], atol=1e-4)


def test_head_frame_points_backward():
    """A3: heading π puts the body toward −x of the head; wheel 1 is 2l behind the head along the chain."""
    cfg = M.configuration([0.0, 0.0, math.pi], np.zeros(9), L)
    wheels = M.wheel_poses(cfg)
    assert np.allclose(wheels[:, 0], -2 * L * np.arange(1, 10)) and np.allclose(wheels[:, 1], 0.0, atol=1e-15)
    pts = M.body_points(cfg)
    assert pts.shape == (19, 2) and np.allclose(pts[2::2], wheels[:, :2])


def test_singular_configuration_I_cases():
    """Check 3: parallel axles (φ = 0) and concurrent axles (all φ equal: wheels on an arc) lose rank."""
    for phi in (np.zeros(9), np.full(9, 0.3)):
        A, _ = M.constraint_matrices(M.configuration([0.1, -0.2, 0.7], phi, L))
        assert M.sigma_min(A) < 1e-9 and M.singular_configuration_I(A)
    # three grounded wheels whose two interior yaw joints are equal: their axles meet in one point
    phi = np.array([0.2, -0.5, 0.4, 0.35, 0.35, 0.1, -0.2, 0.6, 0.1])
    A, B = M.constraint_matrices(M.configuration([0.0, 0.0, 1.0], phi, L))
    grounded = np.zeros(9, bool)
    grounded[[2, 3, 4]] = True  # wheels 3, 4, 5; interior yaw joints φ_4 = φ_5
    assert M.singular_configuration_I(M.mode_matrices(A, B, grounded)[0])
    grounded[5] = True  # wheel 6 after φ_6 = 0.1 ≠ 0.35 breaks the concurrency
    assert not M.singular_configuration_I(M.mode_matrices(A, B, grounded)[0])


def test_det_identity_two_point_vs_grounded_matrix():
    """Check 4: det(A_{c,σ}^T A_{c,σ}) = det(A_σ^T A_σ) (Schur complement on −I_3)."""
    rng = np.random.default_rng(5)
    for _ in range(5):
        w_h, phi = random_state(rng)
        cfg = M.configuration(w_h, phi, L)
        A, B = M.constraint_matrices(cfg)
        grounded = rng.permutation(np.r_[np.ones(4, bool), np.zeros(5, bool)])
        A_s, B_s = M.mode_matrices(A, B, grounded)
        A_c, _ = M.two_point_matrices(A_s, B_s, *M.second_point_jacobians(cfg, 9))
        lhs, rhs = np.linalg.det(A_c.T @ A_c), np.linalg.det(A_s.T @ A_s)
        assert abs(lhs - rhs) <= 1e-10 * abs(rhs)


def test_mode_matrices_delete_rows_and_two_point_sizes():
    rng = np.random.default_rng(2)
    cfg = M.configuration(*random_state(rng), L)
    A, B = M.constraint_matrices(cfg)
    grounded = np.array([1, 0, 1, 1, 0, 0, 1, 0, 0], bool)
    A_s, B_s = M.mode_matrices(A, B, grounded)
    T = M.selection_matrix(grounded)
    assert np.array_equal(A_s, T @ A) and np.array_equal(B_s, T @ B)  # (2.11)
    A_c, B_c = M.two_point_matrices(A_s, B_s, *M.second_point_jacobians(cfg, 9))
    assert A_c.shape == (7, 6) and B_c.shape == (7, 9)  # (2.15)


def test_solvability_needs_three_lifted_wheels():
    """Check 6: with n_σ > n − 3, B_{c,σ} has more rows than joints, so it is always singular (II)."""
    cfg = M.configuration(*random_state(np.random.default_rng(4)), L)
    A, B = M.constraint_matrices(cfg)
    J = M.second_point_jacobians(cfg, 9)
    for n_s, expect in ((6, False), (7, True)):
        grounded = np.r_[np.ones(n_s, bool), np.zeros(9 - n_s, bool)]
        _, B_c = M.two_point_matrices(*M.mode_matrices(A, B, grounded), *J)
        assert M.singular_configuration_II(B_c) is expect


def test_redundant_solution_satisfies_the_mode_model_for_any_l():
    """(2.12): every φ̇ of the general solution satisfies A_σ ẇ̃_h = B_σ φ̇ (2.10)."""
    rng = np.random.default_rng(6)
    A, B = M.constraint_matrices(M.configuration(*random_state(rng), L))
    A_s, B_s = M.mode_matrices(A, B, np.array([1, 1, 0, 1, 0, 1, 1, 0, 0], bool))
    w_dot = rng.normal(size=3)
    for _ in range(3):
        phi_dot = M.redundant_solution(A_s, B_s, w_dot, rng.normal(size=9))
        assert np.abs(A_s @ w_dot - B_s @ phi_dot).max() < 1e-12


@pytest.mark.parametrize("w_h, phi, msg", [
    ([0.0, 0.0], np.zeros(9), "w_h must be"),
    ([0.0, 0.0, 0.0], np.zeros((3, 3)), "phi must be"),
])
def test_bad_state_is_one_clear_error(w_h, phi, msg):
    with pytest.raises(ValueError, match=msg):
        M.configuration(w_h, phi, L)


def test_bad_mode_and_control_point_are_clear_errors():
    cfg = M.configuration([0.0, 0.0, 0.0], np.full(9, 0.1), L)
    A, B = M.constraint_matrices(cfg)
    with pytest.raises(ValueError, match="all n = 9 wheels"):
        M.mode_matrices(A, B, np.ones(8, bool))
    with pytest.raises(ValueError, match="0/1"):
        M.mode_matrices(A, B, np.full(9, 2))
    with pytest.raises(ValueError, match="wheel 1..9"):
        M.second_point_jacobians(cfg, 10)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.lists(st.floats(-1.5, 1.5), min_size=4, max_size=12), st.floats(-math.pi, math.pi),
       st.lists(st.floats(-2, 2), min_size=12, max_size=12))
def test_constraint_terms_equal_matrices_for_any_chain(phi, theta_h, rates):
    """Property: the O(n) pass equals the closed-form matrices for any n and state."""
    phi = np.array(phi)
    phi_dot = np.array(rates[: len(phi)])
    A, B = M.constraint_matrices(M.configuration([0.0, 0.0, theta_h], phi, L))
    A_fast, b_fast = M.constraint_terms(theta_h, phi, L, phi_dot)
    assert np.allclose(A_fast, A, atol=1e-12) and np.allclose(b_fast, B @ phi_dot, atol=1e-12)
