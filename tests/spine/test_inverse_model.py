"""Inverse model of seed 003 §4.4.3: the network against finite differences, training, the 343-posture
grid, and Jacobian integration (4.26–4.28) on Cla's geometric model."""

import numpy as np
import pytest

from shintai.spine import inverse_model as im
from shintai.spine.robots import CLA, GRID_DEG, TEST_LIMIT_DEG

MODEL = CLA.model


def test_training_grid_is_the_343_uniform_bends():
    theta = im.training_postures(MODEL.n)
    assert theta.shape == (343, 15)
    per_joint = theta.reshape(343, 5, 3)
    assert np.allclose(per_joint, per_joint[:, :1, :])  # eq. 4.29: every joint bends alike
    assert set(np.round(np.degrees(theta).ravel(), 9)) == set(GRID_DEG)
    assert len({tuple(row) for row in np.round(theta[:, :3], 12)}) == 343


def test_random_postures_are_uniform_bends_in_range():
    theta = im.random_postures(MODEL.n, 50, np.random.default_rng(0))
    assert theta.shape == (50, 15)
    assert np.allclose(theta.reshape(50, 5, 3), theta[:, None, :3])
    assert np.abs(np.degrees(theta)).max() <= TEST_LIMIT_DEG


def test_normaliser_round_trip_and_range():
    data = np.random.default_rng(1).normal(size=(20, 3))
    scale = im.Normaliser.fit(data, (0.1, 0.9))
    y = scale.forward(data)
    assert np.allclose(y.min(axis=0), 0.1) and np.allclose(y.max(axis=0), 0.9)
    assert np.allclose(scale.inverse(y), data)


def test_normaliser_rejects_a_constant_column():
    with pytest.raises(ValueError, match="constant"):
        im.Normaliser.fit(np.ones((4, 2)), (0.0, 1.0))


@pytest.mark.parametrize("sizes", [(8, 5, 15), (8, 4, 3, 15)])
def test_backprop_gradient_matches_finite_differences(sizes):
    rng = np.random.default_rng(2)
    net = im.MLP(sizes, rng, slope=1.3)
    x, t = rng.uniform(-1, 1, (7, sizes[0])), rng.uniform(0.1, 0.9, (7, sizes[-1]))
    _, grads = net.loss_and_gradient(x, t)
    analytic = np.concatenate([g.ravel() for g in grads])
    w0, h = net.flat(), 1e-6
    numeric = np.empty_like(w0)
    for k in range(w0.size):
        loss = []
        for sign in (1, -1):
            w = w0.copy()
            w[k] += sign * h
            net.set_flat(w)
            loss.append(net.loss_and_gradient(x, t)[0])
        numeric[k] = (loss[0] - loss[1]) / (2 * h)
    assert np.abs(analytic - numeric).max() <= 1e-7 * max(1.0, np.abs(analytic).max())


def test_forward_is_the_sigmoid_of_the_biased_sum():
    net = im.MLP((2, 1), np.random.default_rng(3), slope=2.0)
    net.weights = [np.array([[0.5], [1.0], [-1.0]])]  # bias row first
    out = net.predict(np.array([[0.3, 0.1]]))
    assert out[0, 0] == pytest.approx(1 / (1 + np.exp(-2.0 * (0.5 + 0.3 - 0.1))))


@pytest.mark.parametrize("method,iterations", [("lbfgs", 40), ("backprop", 300)])
def test_training_reduces_the_error_and_keeps_the_best_network(method, iterations):
    inv = im.NeuralInverse(MODEL, (10,), np.random.default_rng(4))
    curve = inv.fit(method, iterations, eta=10.0, record_every=10)
    assert curve.train_deg[-1] < 0.5 * curve.train_deg[0]
    assert curve.best_train_deg == min(curve.train_deg)
    assert inv.errors_deg(inv.theta).mean() == pytest.approx(curve.best_train_deg)


def test_train_rejects_an_unknown_method():
    inv = im.NeuralInverse(MODEL, (4,), np.random.default_rng(5))
    with pytest.raises(ValueError, match="method"):
        inv.fit("sgd", 1)


def test_posture_keeps_batch_shape():
    inv = im.NeuralInverse(MODEL, (4,), np.random.default_rng(6))
    q = MODEL.lengths(im.training_postures(MODEL.n)[:3])
    assert inv.posture(q).shape == (3, 15)
    assert inv.posture(q[0]).shape == (15,)


def test_divisions_are_the_integer_millimetres_of_the_length_change():
    q0 = np.zeros(8)
    assert im.default_divisions(q0 + 0.0037 / np.sqrt(8), q0) == 3
    assert im.default_divisions(q0, q0) == 1


def test_jacobian_integration_converges_on_an_easy_posture():
    """Yaw 1°/joint: the error shrinks as the divisions grow and the lengths are reached."""
    truth = im.uniform_bend(np.radians([0.0, 0.0, 1.0]), MODEL.n)
    q = MODEL.lengths(truth)
    runs = [im.jacobian_integration(MODEL, q, divisions=n) for n in (2, 4, 8)]
    errors = [float(im.error_norm_deg(r.theta, truth)) for r in runs]
    assert errors[0] > errors[1] > errors[2]
    assert errors[-1] < 0.01
    assert runs[-1].length_residual_m < 1e-5


def test_jacobian_integration_misses_a_roll_bend_because_jm_is_rank_deficient():
    """Cla's block-to-block muscles see only the clavicle's pose: rank J_m ≤ 6, so the min-norm path
    is not the uniform bend (the thesis's large errors, Table 4.2)."""
    truth = im.uniform_bend(np.radians([10.0, 0.0, 0.0]), MODEL.n)
    assert np.linalg.matrix_rank(MODEL.jacobian(truth), tol=1e-9) <= 6
    run = im.jacobian_integration(MODEL, MODEL.lengths(truth))
    assert im.error_norm_deg(run.theta, truth) > 10.0


def test_raw_pseudo_inverse_diverges_on_differencing_noise():
    truth = im.uniform_bend(np.radians([5.0, 0.0, 0.0]), MODEL.n)
    run = im.jacobian_integration(MODEL, MODEL.lengths(truth), rcond=None)
    assert im.error_norm_deg(run.theta, truth) > 1e3


def test_jacobian_integration_rejects_zero_divisions():
    with pytest.raises(ValueError, match="divisions"):
        im.jacobian_integration(MODEL, MODEL.lengths(np.zeros(15)), divisions=0)
