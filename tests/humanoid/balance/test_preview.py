"""The ZMP preview controller (Kajita 2003): gains, optimality, tracking of a footstep plan, bad parameters."""

import math

import numpy as np
import pytest

from shintai.core.runtime import Loop, Module
from shintai.humanoid.balance.preview import (CHANNELS, CartTable, Footstep, PreviewController, PreviewModule,
    generate, hrp2_com_height, preview_gains, zmp_plan)
from shintai.humanoid.constants import CONTROL_PERIOD, PREVIEW_TIME

ZC = 0.82  # about HRP2's (test_hrp2_com_height), fixed so the other tests do not build the model


def _augmented(model):
    A, b, c = model.A, model.b, model.c
    At = np.block([[np.ones((1, 1)), (c @ A)[None, :]], [np.zeros((3, 1)), A]])
    bt = np.concatenate([[c @ b], b])[:, None]
    return At, bt


def test_hrp2_com_height_is_the_models_standing_com():
    zc = hrp2_com_height()
    assert 0.80 < zc < 0.84  # Kajita 2003 used 0.814 m for HRP-2; ours is the model's, not a copy
    assert zc == pytest.approx(ZC, abs=1e-3)


def test_riccati_solution_matches_a_fixed_point_iteration_as_hrpsys_does_it():
    """Kajita's example parameters (T = 5 ms, z_c = 0.814 m, Q_e = 1, R = 1e-6): scipy's DARE against
    the plain Riccati recursion iterated to its fixed point (hrpsys-base riccati_equation::solve)."""
    model = CartTable(0.005, 0.814)
    gains = preview_gains(model)
    At, bt = _augmented(model)
    Q, r = np.diag([1.0, 0.0, 0.0, 0.0]), 1e-6
    P = np.zeros((4, 4))
    for _ in range(20000):
        k = (bt.T @ P @ At) / (r + (bt.T @ P @ bt)[0, 0])
        nxt = At.T @ P @ At + Q - At.T @ P @ bt @ k
        if np.allclose(nxt, P, rtol=1e-13, atol=0.0):
            break
        P = nxt
    assert np.allclose(gains.P, P, rtol=1e-8)
    k = (bt.T @ P @ At)[0] / (r + (bt.T @ P @ bt)[0, 0])
    assert gains.gi == pytest.approx(k[0], rel=1e-8) and np.allclose(gains.gx, k[1:], rtol=1e-8)
    assert gains.gp[0] == -gains.gi  # G_p(1) = −G_i


def test_preview_horizon_of_1_6_s_covers_the_decayed_gains():
    gains = preview_gains(CartTable(CONTROL_PERIOD, ZC))
    assert len(gains.gp) == round(PREVIEW_TIME / CONTROL_PERIOD)
    magnitude = np.abs(gains.gp)
    peak = int(magnitude.argmax())
    assert np.all(gains.gp < 0) and peak * CONTROL_PERIOD < 0.05 and np.all(np.diff(magnitude[peak:]) < 0)
    assert magnitude[-1] < 0.01 * magnitude[peak]  # decayed below 1 % of the peak by 1.6 s
    # Standing still on a constant reference needs zero jerk: G_x[0] + Σ_j G_p(j) = 0 for an infinite
    # preview; the 1.6 s truncation leaves 0.5 % of it (corrected by the integral action).
    assert abs(gains.gx[0] + gains.gp.sum()) < 0.005 * gains.gx[0]


def test_closed_loop_equals_the_batch_optimum_of_the_same_cost():
    """With a preview covering every change of the reference, the preview servo's closed loop is the
    infinite-horizon optimum of J = Σ Q_e e² + R Δu²: solved here as one least-squares problem over
    M steps with the Riccati cost-to-go z(M)ᵀ P̃ z(M) as terminal cost (the reference is constant
    after M)."""
    dt, m = 0.01, 160
    model = CartTable(dt, ZC)
    gains = preview_gains(model, preview_time=m * dt)
    ref = np.zeros(2 * m)
    ref[20:60] = 0.05  # a 0.4 s pulse of the ZMP, within every window
    ref[60:90] = -0.03
    pattern = generate(np.stack([ref, np.zeros_like(ref)], axis=1), controller=PreviewController(model, gains))

    At, bt = _augmented(model)
    qe, r = 1.0, 1e-6
    # z(k) = (e(k), Δx(k)) = G_k Δu + h_k,  z(k+1) = Ã z(k) + b̃ Δu(k) − (Δp_ref(k+1), 0, 0, 0)
    G, h = np.zeros((4, m)), np.zeros(4)
    rows, rhs = [], []
    for k in range(m):
        G, h = At @ G, At @ h
        G[:, k] += bt[:, 0]
        h[0] -= ref[k + 1] - ref[k]
        if k + 1 < m:
            rows.append(math.sqrt(qe) * G[0])
            rhs.append(-math.sqrt(qe) * h[0])
    w, v = np.linalg.eigh(gains.P)
    root = (v * np.sqrt(np.maximum(w, 0.0))) @ v.T  # P̃^½
    rows += list(root @ G) + list(math.sqrt(r) * np.eye(m))
    rhs += list(-root @ h) + [0.0] * m
    du = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)[0]

    x, com = np.zeros(3), []
    u = 0.0
    for k in range(m):
        com.append(x[0])
        u += du[k]
        x = model.A @ x + model.b * u
    assert np.abs(np.array(com) - pattern.com[:m, 0]).max() < 1e-8
    assert np.abs(pattern.com[:m, 0]).max() > 0.01  # the comparison is not of two zeros


def test_tracks_a_footstep_plan_and_the_com_moves_before_the_zmp():
    """Boarding-like plan (§5.4: left foot first, then the right beside it): 0.2 m forward."""
    plan = zmp_plan((0.0, 0.06), (0.0, -0.06), [Footstep("l", 0.2, 0.06), Footstep("r", 0.2, -0.06)])
    pattern = generate(plan.zmp, zc=ZC)
    err = np.abs(pattern.zmp - pattern.zmp_ref).max(axis=1)
    single = np.array([s in ("l", "r") for s in plan.support])
    assert err.max() < 0.005  # a few mm at the corners of the reference
    # ≥ 0.2 s into single support and ≥ 0.2 s before its end (the ZMP leaves a corner of the
    # reference early and reaches the next late: that is what the tracking error there is)
    settled = single & np.roll(single, 50) & np.roll(single, -50)
    assert settled.sum() > 100 and err[settled].max() < 0.5e-3
    assert np.abs(pattern.com[-1] - plan.zmp[-1]).max() < 1e-3  # at rest over the final point
    # Preview: the CoM heads for the right foot (−y) before the ZMP leaves the middle
    first_move = int(np.argmax(np.abs(plan.zmp[:, 1]) > 1e-9))
    assert pattern.com[first_move, 1] < -0.002
    # … and toward the landing x while the ZMP is still on the right foot's x = 0
    first_x = int(np.argmax(plan.zmp[:, 0] > 1e-9))
    assert pattern.com[first_x, 0] > 0.01


def test_zmp_plan_phases():
    plan = zmp_plan((0.0, 0.1), (0.0, -0.1), [Footstep("r", 0.3, -0.1)], dt=0.01, single=0.5, double=0.1, hold=0.2)
    assert len(plan.zmp) == 20 + 10 + 50 + 10 + 20
    assert plan.support[:20] == ("lr",) * 20 and plan.support[30:80] == ("l",) * 50
    assert np.allclose(plan.zmp[29], (0.0, 0.1)) and np.allclose(plan.zmp[14], (0.0, 0.0))
    assert np.allclose(plan.zmp[-1], (0.15, 0.0))
    assert np.allclose(plan.zmp[84], (0.075, 0.05))  # half-way through the last double support


def test_module_writes_the_pattern_into_the_loop():
    from shintai.core.linear_plant import LinearPlant

    plan = zmp_plan((0.0, 0.06), (0.0, -0.06), [Footstep("l", 0.1, 0.06)], hold=0.4)
    body = LinearPlant(np.eye(1), np.zeros(1), np.zeros(1), dt=CONTROL_PERIOD)
    module = PreviewModule(plan, zc=ZC)
    seen = []

    class Probe(Module):  # a later stage reading what the preview wrote this tick
        def update(self, snapshot):
            seen.append((snapshot["com_ref"].copy(), snapshot["zmp_ref"].copy()))

    loop = Loop(body, stages=[[module], [Probe("probe")]], channels=list(CHANNELS.values()))
    loop.run(len(plan.zmp) * CONTROL_PERIOD)
    offline = generate(plan.zmp, zc=ZC)
    com = np.array([c for c, _ in seen])
    assert np.allclose(com[:, :2], offline.com[:len(com)], atol=1e-12) and np.all(com[:, 2] == ZC)
    assert np.allclose([z for _, z in seen], plan.zmp[:len(seen)])


@pytest.mark.parametrize("make, word", [
    (lambda: CartTable(0.0, ZC), "dt"),
    (lambda: CartTable(0.004, -0.8), "zc"),
    (lambda: CartTable(0.004, math.nan), "zc"),
    (lambda: preview_gains(CartTable(0.004, ZC), preview_time=0.001), "preview_time"),
    (lambda: preview_gains(CartTable(0.004, ZC), r=0.0), "r must"),
    (lambda: preview_gains(CartTable(0.004, ZC), qe=-1.0), "qe"),
    (lambda: preview_gains(CartTable(0.004, ZC), qx=-np.eye(3)), "qx"),
    (lambda: zmp_plan((0, 0.1), (0, -0.1), [], single=-0.8), "single"),
    (lambda: zmp_plan((0, 0.1), (0, -0.1), [Footstep("x", 0.1, 0.0)]), "side"),
    (lambda: generate(np.array([[0.0, math.nan]]), zc=ZC), "zmp_ref"),
])
def test_bad_parameters_raise_one_clear_value_error(make, word):
    with pytest.raises(ValueError, match=word):
        make()


def test_a_step_is_the_matrix_form_to_the_bit():
    """PreviewController.step (floats around BLAS's products) gives the module docstring's matrix form exactly:
    Σe += c x − p_ref(k), u = −G_i Σe − G_x x − Σ G_p p_ref(k+j), x ← A x + b u."""
    plan = zmp_plan((0.0, 0.06), (0.0, -0.06), [Footstep("l", 0.1, 0.06), Footstep("r", 0.2, -0.06)], hold=0.4)
    model = CartTable(CONTROL_PERIOD, ZC)
    ours = PreviewController(model, com0=plan.zmp[0])
    x, err = ours.x.copy(), ours.err_sum.copy()
    g, n = ours.gains, ours.horizon
    padded = np.concatenate([plan.zmp, np.repeat(plan.zmp[-1:], n + 1, axis=0)])
    for k in range(len(plan.zmp)):
        window = padded[k:k + n + 1]
        err += model.c @ x - window[0]
        u = -g.gi * err - g.gx @ x - g.gp @ window[1:]
        x = model.A @ x + np.outer(model.b, u)
        assert np.array_equal(ours.step(window), x) and np.array_equal(ours.err_sum, err)
