"""Gaussian RBF networks and their flat genomes (seed §4 eqs. 7-8, §5)."""

import numpy as np
import pytest

from shintai.quadruped import constants as C
from shintai.quadruped import networks as N
from shintai.quadruped import swing_order as S


def test_action_genome_layout_roundtrips():
    net = N.ActionNetwork()
    assert net.size == 100 * 24 + 100 + 100 * 3
    rng = np.random.default_rng(0)
    c, s, w = rng.normal(size=(100, 24)), rng.uniform(0.1, 1, 100), rng.normal(size=(100, 3))
    dc, ds, dw = net.decode(net.encode(c, s, w))
    assert np.array_equal(dc[0], c) and np.array_equal(ds[0], s) and np.array_equal(dw[0], w)
    lo, hi = net.bounds()
    assert lo.shape == hi.shape == (net.size,) and np.all(lo < hi) and np.all(lo[2400:2500] > 0)
    with pytest.raises(ValueError, match="2800 genes"):
        net.decode(np.zeros(5))


def test_forward_is_equations_7_and_8():
    net = N.ActionNetwork()
    rng = np.random.default_rng(1)
    g = net.random_genomes(rng, 2)
    x = rng.normal(size=(2, 5, 24))
    out = net.forward(g, x)
    c, s, w = net.decode(g)
    for k in range(2):
        for n in range(5):
            phi = np.exp(-np.sum((x[k, n] - c[k]) ** 2, axis=1) / s[k] ** 2)
            assert np.allclose(out[k, n], phi @ w[k])


def test_widths_are_floored_so_any_genome_is_finite():
    net = N.ActionNetwork()
    g = np.zeros((1, net.size))
    assert np.all(np.isfinite(net.forward(g, np.ones((1, 3, 24)))))


def test_order_inputs_scale_to_the_teacher_ranges():
    assert np.allclose(N.scale_order_inputs(S.TEACHER_LOW), -1) and np.allclose(N.scale_order_inputs(S.TEACHER_HIGH), 1)


def test_swing_order_network_interpolates_its_teacher_and_picks_the_unit_closest_to_one():
    teacher = S.teacher_set(per_order=3, draws=150, seed=2)
    net = N.SwingOrderNetwork(n_hidden=len(teacher.x))
    centres = N.scale_order_inputs(teacher.x)
    genome = np.concatenate([centres.ravel(), np.full(len(teacher.x), 0.05)])
    policy = net.trained(genome, teacher)
    assert np.array_equal(policy(teacher.x[:, 0], teacher.x[:, 1:]), teacher.label)
    assert np.array_equal(N.choose_order(np.array([[0.0, 1.4, 0.8, 0.0]])), [2])
    assert net.size == len(teacher.x) * (C.ORDER_INPUTS + 1)
