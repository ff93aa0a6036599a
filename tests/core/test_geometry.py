"""core.geometry: angle wrapping."""

import math

import numpy as np

from shintai.core.geometry import cross3, wrap, wrap_pi


def _angles() -> np.ndarray:
    """≥ 400k angles: multiples of π and 2π and their neighbouring floats, ±0, the smallest subnormals, and
    uniform, wide and log-spread random values up to ±1e300."""
    rng = np.random.default_rng(0)
    k = np.arange(-5000, 5001, dtype=float)
    pis = np.concatenate([k * math.pi, 2 * k * math.pi])
    edges = np.concatenate([pis, np.nextafter(pis, -np.inf), np.nextafter(pis, np.inf)])
    special = np.array([0.0, -0.0, 5e-324, -5e-324, 1e300, -1e300, math.pi, -math.pi])
    spread = 10.0 ** rng.uniform(-300, 300, 60_000) * rng.choice([-1.0, 1.0], 60_000)
    return np.concatenate([special, edges, rng.uniform(-10, 10, 200_000), rng.uniform(-1e6, 1e6, 60_000),
                           rng.normal(0, 1e15, 20_000), spread])


def test_wrap_pi_is_the_numpy_floored_modulo_bit_for_bit():
    angles = _angles()
    assert angles.size >= 400_000
    reference = np.pi - np.mod(np.pi - angles, 2 * np.pi)  # the NumPy form wrap_pi had
    got = np.array([wrap_pi(a) for a in angles.tolist()])
    assert np.array_equal(got, reference)
    assert np.array_equal(np.signbit(got), np.signbit(reference))  # the same zeros too
    assert [wrap_pi(a) for a in angles[:1000]] == got[:1000].tolist()  # np.float64 inputs as Python floats


def test_wrap_pi_keeps_plus_pi_and_lands_in_the_half_open_interval():
    assert wrap_pi(math.pi) == math.pi
    assert wrap_pi(-math.pi) == math.pi
    assert wrap_pi(3 * math.pi) == math.pi
    assert wrap_pi(0.25) == 0.25
    assert math.isclose(wrap_pi(0.25 + 4 * math.pi), 0.25, abs_tol=1e-12)
    got = np.array([wrap_pi(a) for a in np.random.default_rng(1).uniform(-50, 50, 1000)])
    assert (got > -math.pi).all() and (got <= math.pi).all()
    assert type(wrap_pi(np.float64(1.0))) is float
    assert math.isnan(wrap_pi(math.inf)) and math.isnan(wrap_pi(math.nan))


def test_wrap_is_the_other_convention():
    assert wrap(math.pi) == -math.pi
    assert np.allclose(wrap(np.array([0.5, 7.0])), [0.5, 7.0 - 2 * math.pi])


def test_cross3_is_numpys_cross_bit_for_bit_on_broadcast_shapes():
    """cross3 gives np.cross's bits (the spine's Jacobians rely on it) on the shapes the spine uses, broadcast both
    ways, and is the right-handed cross product."""
    rng = np.random.default_rng(0)
    for a_shape, b_shape in [((54, 15, 3), (54, 1, 3)), ((15, 3), (15, 3)), ((1, 15, 3), (7, 1, 3)), ((3,), (9, 3))]:
        a, b = rng.normal(size=a_shape) * 1e3, rng.normal(size=b_shape)
        assert np.array_equal(cross3(a, b), np.cross(a, b))
    assert np.array_equal(cross3(np.array([1.0, 0, 0]), np.array([0.0, 1, 0])), [0.0, 0, 1])
