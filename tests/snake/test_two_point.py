"""Two-point controller of seed 001 ch. 3 (spec §5.4 checks 5, 7–9, 13)."""

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest

from shintai.core import Loop, Recorder
from shintai.core.geometry import wrap
from shintai.snake import model as M
from shintai.snake.constants import CAGING, CH3_GAINS, CH3_ROBOT, TRACKING
from shintai.snake.plant import KinematicSnake
from shintai.snake.targets import PiecewiseLinear
from shintai.snake.two_point import (
    TwoPointController,
    TwoPointLaw,
    candidate_modes,
    gram_det_gradient,
    joint_limit_objective,
)

L = CH3_ROBOT.l
W0, PHI0 = np.array(TRACKING.w_h0), np.array(TRACKING.phi0)


def max_lifted_run(lifted):
    best = run = 0
    for x in lifted:
        run = run + 1 if x else 0
        best = max(best, run)
    return best


# ------------------------------------------------------------------------------------- modes (check 5)

@pytest.mark.parametrize("head_end_lifted, total, n4, n5", [(True, 66, 26, 40), (False, 80, 35, 45)])
def test_candidate_counts(head_end_lifted, total, n4, n5):
    modes = candidate_modes(9, 4, 4, 2, head_end_lifted)
    sizes = modes.sum(axis=1)
    assert len(modes) == total and (sizes == 4).sum() == n4 and (sizes == 5).sum() == n5


def test_candidates_equal_brute_force_of_rules_i_ii_iii():
    expected = set()
    for g in itertools.product([False, True], repeat=9):
        lifted = [not x for x in g]
        if g[-1] or not 4 <= sum(g) <= 5 or max_lifted_run([True] + lifted) > 2:
            continue
        expected.add(g)
    got = {tuple(row) for row in candidate_modes(9, 4, 4, 2, True)}
    assert got == expected and len(got) == CH3_GAINS.candidate_count  # 66, §3.3


def test_law_uses_the_thesis_count_by_default():
    assert len(TwoPointLaw().candidates) == 66


# ---------------------------------------------------------------------------------- V_u and η (3.12)–(3.16)

def test_joint_limit_objective_is_zero_inside_threshold():
    V, grad = joint_limit_objective(np.array([0.5, -0.7, 1.0, -1.2]), math.pi / 4)
    excess = np.array([0, 0, 1.0 - math.pi / 4, 1.2 - math.pi / 4])
    assert V == pytest.approx(-(excess ** 2).sum())
    assert np.allclose(grad, [0, 0, -2 * excess[2], 2 * excess[3]])


def test_gram_det_gradient_matches_finite_differences():
    rng = np.random.default_rng(0)
    for shape in ((5, 3), (7, 9)):
        X = rng.normal(size=shape)
        det, grad = gram_det_gradient(X)
        small = X.T @ X if shape[0] > shape[1] else X @ X.T
        assert det == pytest.approx(np.linalg.det(small))
        fd = np.zeros_like(X)
        for idx in np.ndindex(*shape):
            d = np.zeros_like(X)
            d[idx] = 1e-6
            fd[idx] = (gram_det_gradient(X + d)[0] - gram_det_gradient(X - d)[0]) / 2e-6
        assert np.abs(grad - fd).max() <= 1e-6 * max(1.0, np.abs(fd).max())


@pytest.mark.parametrize("k_u", [CH3_GAINS.k_u, (0.3, 0.5, 2.0)])
def test_eta_matches_finite_differences_of_V_u(k_u):
    law = TwoPointLaw(gains=replace(CH3_GAINS, k_u=k_u))
    rng = np.random.default_rng(1)
    phi = rng.uniform(-1.3, 1.3, 9)
    grounded = law.candidates[17]
    _, eta = law.objective(W0, phi, grounded)
    fd = np.array([(law.objective(W0, phi + d, grounded)[0] - law.objective(W0, phi - d, grounded)[0]) / 2e-6
                   for d in 1e-6 * np.eye(9)])
    assert np.abs(eta - fd).max() <= 1e-6


# ------------------------------------------------------------------------------- input (3.3)–(3.6), (3.20)

def two_point_at(law, w_h, phi, grounded):
    cfg = M.configuration(w_h, phi, L)
    A, B = M.constraint_matrices(cfg)
    return M.two_point_matrices(*M.mode_matrices(A, B, grounded), *M.second_point_jacobians(cfg, 9))


def test_null_space_term_does_not_move_the_control_points():
    """Check 8: with c_d = c_c and ċ_d = 0, u = u_v lies in the null space of B_{c,σ}."""
    law = TwoPointLaw()
    mode, _ = law.select_mode(W0, PHI0)
    grounded = law.candidates[mode]
    c0 = law.controlled(M.configuration(W0, PHI0, L))
    step = law.input(W0, PHI0, grounded, c0, np.zeros(6))
    _, B_c = two_point_at(law, W0, PHI0, grounded)
    assert np.linalg.norm(step.u) > 1e-3 and np.linalg.norm(B_c @ step.u) < 1e-12


def run_loop(law, target, duration, select_period=None, w_h=W0, phi=PHI0):
    body = KinematicSnake(w_h, phi)
    rec = Recorder()
    ctrl = TwoPointController(law, target, select_period)
    Loop(body, [ctrl], rec).run(duration)
    return body, rec, ctrl


def test_null_space_motion_raises_V_u_and_keeps_control_points():
    """Check 8, (3.10): with c_d = c_c(0) the closed loop climbs V_u while c_c stays put.

    The null-space input is exact to first order; holding it over δt leaves an O(δt²) drift that the
    K_p term removes, so the control points stay within 0.1 mm while the joints move by tenths of a radian.
    """
    law = TwoPointLaw()
    c0 = law.controlled(M.configuration(W0, PHI0, L))
    body, rec, _ = run_loop(law, lambda t: (c0, np.zeros(6)), 2.0)
    V_u = rec.values("two_point.V_u")
    assert np.all(np.diff(V_u) >= -1e-9) and V_u[-1] > V_u[0]
    assert np.abs(body.phi - PHI0).max() > 0.1
    assert np.abs(rec.values("two_point.c") - c0).max() < 1e-4


def test_tracking_error_decays_like_exp_minus_Kp_t():
    """Check 7: a 1 cm head error in a fixed non-singular mode falls below 1e−4 m by t = 1.2 s (K_p = 4)."""
    law = TwoPointLaw()
    c0 = law.controlled(M.configuration(W0, PHI0, L))
    goal = c0 + np.array([0.01, 0, 0, 0, 0, 0])
    body, rec, _ = run_loop(law, lambda t: (goal, np.zeros(6)), 1.2)
    err = np.abs(rec.values("two_point.c") - goal).max(axis=1)
    final = np.abs(law.controlled(M.configuration(body.w_h, body.phi, L)) - goal).max()
    assert not rec.values("two_point.stopped").any()
    assert final < min(1e-4, 0.01 * math.exp(-CH3_GAINS.k_p * 1.2)) and np.all(np.diff(err) < 1e-12)


def test_input_limit_gives_exactly_zero():
    """Check 9, (3.20): ‖u_σ‖ > u_lim → u = 0 exactly; below the limit u passes unchanged."""
    law = TwoPointLaw()
    grounded = law.candidates[law.select_mode(W0, PHI0)[0]]
    c0 = law.controlled(M.configuration(W0, PHI0, L))
    far = law.input(W0, PHI0, grounded, c0 + np.array([0.5, 0, 0, 0, 0, 0]), np.zeros(6))
    near = law.input(W0, PHI0, grounded, c0 + np.array([0.001, 0, 0, 0, 0, 0]), np.zeros(6))
    assert far.stopped and far.u_norm > CH3_GAINS.u_lim and np.array_equal(far.u, np.zeros(9))
    assert not near.stopped and np.linalg.norm(near.u) == pytest.approx(near.u_norm)


def test_select_period_must_be_a_multiple_of_dt():
    with pytest.raises(ValueError, match="whole multiple"):
        TwoPointController(TwoPointLaw(), lambda t: None, select_period=0.07)


# ---------------------------------------------------------------------------------- angle targets (check 13)

def test_unwrapped_targets_of_the_thesis_experiments():
    law = TwoPointLaw()
    c0 = law.controlled(M.configuration(TRACKING.w_h0, TRACKING.phi0, L))
    c_e = PiecewiseLinear.ramp(c0, TRACKING.c_e, TRACKING.t_end).poses[1]
    assert c_e[2] == pytest.approx(math.pi / 2) and c_e[5] == pytest.approx(3 * math.pi / 2)
    c0_cage = law.controlled(M.configuration(CAGING.w_h0, CAGING.phi0, L))
    assert c0_cage[5] == pytest.approx(2 * math.pi)
    assert np.allclose(c0_cage[3:5], [-0.0934, -0.5878], atol=1e-4)  # spec §4.2 [derived]
    c_e1 = PiecewiseLinear.ramp(c0_cage, CAGING.c_e1, CAGING.t_s1).poses[1]
    assert c_e1[2] == pytest.approx(math.pi) and c_e1[5] == pytest.approx(2 * math.pi)


def test_wrap_angle_and_ramp():
    assert wrap(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    ramp = PiecewiseLinear.ramp(np.zeros(6), np.arange(6.0), 10.0, angles=())
    c, rate = ramp(5.0)
    assert np.allclose(c, np.arange(6.0) / 2) and np.allclose(rate, np.arange(6.0) / 10)
    c, rate = ramp(12.0)
    assert np.allclose(c, np.arange(6.0)) and not rate.any()
    with pytest.raises(ValueError):  # start and end of different sizes
        PiecewiseLinear.ramp(np.zeros(3), np.zeros(6), 10.0)
    with pytest.raises(ValueError, match="t_end"):
        PiecewiseLinear.ramp(np.zeros(6), np.zeros(6), 0.0)


def test_vectorized_mode_objectives_equal_per_candidate_evaluation():
    """(3.19) with both weights non-zero: batched V_m equals k_{m,1} σ_min(A_{c,σ}) + k_{m,2} σ_min(B_{c,σ})."""
    law = TwoPointLaw(gains=replace(CH3_GAINS, k_m=(0.7, 1.0)))
    phi = np.random.default_rng(3).uniform(-1, 1, 9)
    V = law.mode_objectives(W0, phi)
    naive = [0.7 * M.sigma_min(A_c) + M.sigma_min(B_c)
             for A_c, B_c in (two_point_at(law, W0, phi, g) for g in law.candidates)]
    assert np.allclose(V, naive, rtol=1e-12, atol=1e-15)
    assert law.select_mode(W0, phi)[0] == int(np.argmax(naive))
