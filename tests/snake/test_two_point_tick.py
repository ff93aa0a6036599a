"""The compiled tick of seed 001 §3.2 (two_point_tick.py) against model.py's NumPy forms and a pinv reference."""

import math
from dataclasses import replace

import numpy as np
import pytest

from shintai.snake import model as M
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT
from shintai.snake.two_point import TwoPointLaw, two_point_rows
from shintai.snake.two_point_tick import stacked_matrices

L, N = CH3_ROBOT.l, CH3_ROBOT.n
TOL = 1e-12  # the kernels sum in another order than NumPy: equal to rounding, not bit for bit


def random_case(rng):
    w_h = np.r_[rng.normal(size=2), rng.uniform(-math.pi, math.pi)]
    return w_h, rng.uniform(-1.2, 1.2, N)


def numpy_matrices(w_h, phi, grounded):
    """A_{c,σ}, B_{c,σ}, A_σ, ∂A_σ/∂φ, ∂B_{c,σ}/∂φ and c_c from model.py's closed forms."""
    cfg = M.configuration(w_h, phi, L)
    A, B = M.constraint_matrices(cfg)
    J1, J2 = M.second_point_jacobians(cfg, N)
    A_c, B_c = M.two_point_matrices(*M.mode_matrices(A, B, grounded), J1, J2)
    dB_c = np.concatenate((M.b_matrix_derivative(cfg)[:, grounded], -M.second_point_jacobian_derivative(cfg, N)), 1)
    c_c = np.concatenate((cfg.w_h, M.tail_pose(cfg)))
    return A_c, B_c, A[grounded], M.a_matrix_derivative(cfg)[:, grounded], dB_c, c_c


@pytest.mark.parametrize("seed", range(4))
def test_stacked_matrices_equal_model_closed_forms(seed):
    rng = np.random.default_rng(seed)
    modes = [*TwoPointLaw().candidates[rng.choice(66, 3)], np.ones(N, bool), rng.random(N) < 0.5]
    for grounded in modes:
        w_h, phi = random_case(rng)
        rows = two_point_rows(grounded)
        r, m = len(rows), int(grounded.sum())
        A_c, B_c, A_s = np.full((N + 3, 6), np.nan), np.full((N + 3, N), np.nan), np.full((N, 3), np.nan)
        dA_s, dB_c, c_c = np.full((N, N, 3), np.nan), np.full((N, N + 3, N), np.nan), np.full(6, np.nan)
        stacked_matrices(w_h, phi, L, rows, A_c, B_c, A_s, dA_s, dB_c, c_c, (True, True))
        ref = numpy_matrices(w_h, phi, grounded)
        got = A_c[:r], B_c[:r], A_s[:m], dA_s[:, :m], dB_c[:, :r], c_c
        for name, x, y in zip(("A_c", "B_c", "A_s", "dA_s", "dB_c", "c_c"), got, ref):
            assert x.shape == y.shape and np.abs(x - y).max() <= TOL, name


def test_derivatives_are_left_alone_when_not_asked():
    w_h, phi = random_case(np.random.default_rng(5))
    dA_s, dB_c = np.full((N, N, 3), 7.0), np.full((N, N + 3, N), 7.0)
    stacked_matrices(w_h, phi, L, two_point_rows(np.ones(N, bool)), np.zeros((N + 3, 6)), np.zeros((N + 3, N)),
                     np.zeros((N, 3)), dA_s, dB_c, np.zeros(6), (False, False))
    assert np.all(dA_s == 7.0) and np.all(dB_c == 7.0)


def gram_gradient(X):
    """∂det/∂X of the small Gram matrix, by the adjugate: 2 X adj(XᵀX) (tall), 2 adj(XXᵀ) X (wide)."""
    G = X.T @ X if X.shape[0] > X.shape[1] else X @ X.T
    adj = np.linalg.det(G) * np.linalg.inv(G)
    return np.linalg.det(G), 2 * (X @ adj if X.shape[0] > X.shape[1] else adj @ X)


@pytest.mark.parametrize("k_u", [CH3_GAINS.k_u, (0.6, 0.8, 0.5), (0.0, 0.0, 1.0)])
def test_input_equals_pinv_reference(k_u):
    """u_σ = B^† A ξ + k_v (I − B^†B) η (3.3)–(3.5) with η (3.6) from model.py's derivatives and the adjugate."""
    gains = replace(CH3_GAINS, k_u=k_u)
    law = TwoPointLaw(gains=gains)
    rng = np.random.default_rng(1)
    for grounded in law.candidates[rng.choice(66, 5)]:
        w_h, phi = random_case(rng)
        c_d, c_d_dot = rng.normal(size=6), rng.normal(size=6)
        A_c, B_c, A_s, dA_s, dB_c, c_c = numpy_matrices(w_h, phi, grounded)
        excess = np.maximum(np.abs(phi) - gains.phi_th, 0.0)
        V, eta = -k_u[0] * excess @ excess, -2 * k_u[0] * excess * np.sign(phi)
        for gain, X, dX in ((k_u[1], A_s, dA_s), (k_u[2], B_c, dB_c)):
            det, grad = gram_gradient(X)
            V, eta = V + gain * det, eta + gain * np.einsum("mrc,rc->m", dX, grad)
        B_pinv = np.linalg.pinv(B_c, rtol=None)  # the cutoff max(rows, cols)·ε·s_0 of the law
        u = B_pinv @ A_c @ (c_d_dot + gains.k_p * (c_d - c_c)) + gains.k_v * (np.eye(N) - B_pinv @ B_c) @ eta
        step = law.input(w_h, phi, grounded, c_d, c_d_dot)
        assert step.V_u == pytest.approx(V, rel=1e-9, abs=1e-12)
        assert np.allclose(law.objective(w_h, phi, grounded)[1], eta, rtol=1e-9, atol=1e-12)
        assert np.allclose(step.c_c, c_c, atol=TOL) and step.u_norm == pytest.approx(np.linalg.norm(u), rel=1e-9)
        assert np.allclose(step.u, 0.0 if step.stopped else u, rtol=1e-9, atol=1e-12)


def test_a_step_owns_its_arrays():
    law = TwoPointLaw()
    rng = np.random.default_rng(2)
    grounded = law.candidates[0]
    first = law.input(*random_case(rng), grounded, np.zeros(6), np.zeros(6))
    c_c, u = first.c_c.copy(), first.u.copy()
    law.input(*random_case(rng), grounded, np.zeros(6), np.zeros(6))
    assert np.array_equal(first.c_c, c_c) and np.array_equal(first.u, u)


def test_bad_state_shapes_are_refused():
    law = TwoPointLaw()
    with pytest.raises(ValueError, match="yaw angles"):
        law.input([0, 0, 0], np.zeros(8), law.candidates[0], np.zeros(6), np.zeros(6))
    with pytest.raises(ValueError, match="w_h"):
        law.select_mode([0, 0], np.zeros(N))


@pytest.mark.parametrize("bend, kept", [(0.0, False), (1e-11, True)])
def test_pinv_cutoff_on_a_straight_body(bend, kept):
    """φ ≈ 0: the x and y rows of −J_{n,2} are nearly parallel and B_{c,σ} nearly loses rank. Straight (s_min/s_0 ≈
    1e−17) the singular value is cut and the command stays finite; bent by 1e−11 rad (≈ 2e−13) it is above the
    cutoff max(rows, cols)·ε·s_0 and kept, so (3.4) commands a huge rate (which (3.20) would stop). Both equal
    pinv's with the same cutoff."""
    law = TwoPointLaw(gains=replace(CH3_GAINS, u_lim=1e30))
    w_h, phi, grounded = np.array([1.0, 2.0, 0.3]), bend * np.random.default_rng(0).normal(size=N), law.candidates[6]
    c_d, c_d_dot = np.array([1.0, 2.0, 0.3, 0.0, 0.0, 0.0]), np.ones(6)
    A_c, B_c, *_, c_c = numpy_matrices(w_h, phi, grounded)
    s = np.linalg.svd(B_c, compute_uv=False)
    assert (s[-1] > max(B_c.shape) * np.finfo(float).eps * s[0]) == kept and s[-1] / s[0] < 1e-12
    eta = law.objective(w_h, phi, grounded)[1]
    B_pinv = np.linalg.pinv(B_c, rtol=None)
    u = B_pinv @ A_c @ (c_d_dot + CH3_GAINS.k_p * (c_d - c_c)) + CH3_GAINS.k_v * (np.eye(N) - B_pinv @ B_c) @ eta
    step = law.input(w_h, phi, grounded, c_d, c_d_dot)
    assert (step.u_norm > 1e6) == kept and np.allclose(step.u, u, rtol=1e-9, atol=1e-9)


def test_tall_stack_and_both_mode_gains():
    """All wheels grounded (B_{c,σ} 12 × 9, more rows than joints) with k_m = (0.7, 1): σ's and V_m (3.19)."""
    law = TwoPointLaw(gains=replace(CH3_GAINS, k_m=(0.7, 1.0), u_lim=1e9))
    w_h, phi = random_case(np.random.default_rng(3))
    grounded = np.ones(N, bool)
    A_c, B_c, *_ = numpy_matrices(w_h, phi, grounded)
    step = law.input(w_h, phi, grounded, np.zeros(6), np.zeros(6))
    sigma_a, sigma_b = (np.linalg.svd(X, compute_uv=False)[-1] for X in (A_c, B_c))
    assert step.sigma_a == pytest.approx(sigma_a, rel=1e-9) and step.sigma_b == pytest.approx(sigma_b, rel=1e-9)
    assert step.V_m == pytest.approx(0.7 * sigma_a + sigma_b, rel=1e-9)
    V = law.mode_objectives(w_h, phi)
    k = 5
    A_k, B_k, *_ = numpy_matrices(w_h, phi, law.candidates[k])
    assert V[k] == pytest.approx(0.7 * np.linalg.svd(A_k, compute_uv=False)[-1]
                                 + np.linalg.svd(B_k, compute_uv=False)[-1], rel=1e-9)


@pytest.mark.parametrize("c_d", [np.ones(3), np.ones(7), np.ones((6, 1))])
def test_bad_target_shapes_are_refused(c_d):
    law = TwoPointLaw()
    with pytest.raises(ValueError, match="c_d"):
        law.input([0, 0, 0], np.full(N, 0.2), law.candidates[0], c_d, np.zeros(6))
