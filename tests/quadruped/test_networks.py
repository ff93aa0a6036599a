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


@pytest.mark.parametrize("normalise", [True, False])
def test_forward_is_equations_7_and_8_on_the_scaled_or_raw_inputs(normalise):
    net = N.ActionNetwork(normalise=normalise)
    rng = np.random.default_rng(1)
    g = net.random_genomes(rng, 2)
    x = rng.normal(size=(2, 5, 24))
    out = net.forward(g, x)
    c, s, w = net.decode(g)
    seen = 2 * (x - N.ACTION_LOW) / (N.ACTION_HIGH - N.ACTION_LOW) - 1 if normalise else x
    for k in range(2):
        for n in range(5):
            phi = np.exp(-np.sum((seen[k, n] - c[k]) ** 2, axis=1) / s[k] ** 2)
            assert np.allclose(out[k, n], phi @ w[k])


def test_action_inputs_scale_to_their_spans_and_the_gene_ranges_follow():
    spans = np.array(C.ACTION_INPUT_SPANS)
    assert spans.shape == (24, 2) and np.all(spans[:, 0] < spans[:, 1])
    assert np.allclose(N.scale_action_inputs(spans[:, 0]), -1) and np.allclose(N.scale_action_inputs(spans[:, 1]), 1)
    lo, hi = N.ActionNetwork().bounds()
    assert np.all(lo[:2400] == C.ACTION_CENTRE_RANGE[0]) and np.all(hi[:2400] == C.ACTION_CENTRE_RANGE[1])
    assert np.array_equal(hi[2500:2503], [r[1] for r in C.ACTION_WEIGHT_RANGE])  # per output: ΔXr, ΔYr, Δθr
    raw_lo, _ = N.ActionNetwork(normalise=False).bounds()
    assert np.all(raw_lo[:2400] == C.ACTION_RAW_CENTRE_RANGE[0])
    assert np.all(raw_lo[2500:] == C.ACTION_RAW_WEIGHT_RANGE[0])


def test_genomes_on_data_put_every_centre_on_a_given_input():
    net = N.ActionNetwork()
    inputs = N.ACTION_LOW + np.random.default_rng(3).uniform(0.1, 0.9, size=(7, 24)) * (N.ACTION_HIGH - N.ACTION_LOW)
    g = net.genomes_on_data(np.random.default_rng(0), 3, inputs)
    centres, sigmas, weights = net.decode(g)
    scaled = N.scale_action_inputs(inputs)
    assert np.all(np.min(np.abs(centres[:, :, None, :] - scaled[None, None]).max(-1), axis=-1) < 1e-12)
    assert np.all((sigmas >= C.ACTION_INIT_SIGMA_RANGE[0]) & (sigmas <= C.ACTION_INIT_SIGMA_RANGE[1]))
    assert np.all(np.abs(weights) <= np.array(C.ACTION_INIT_WEIGHT))
    assert np.array_equal(g, net.genomes_on_data(np.random.default_rng(0), 3, inputs))


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
