"""Fixed-step integrators: the float form of RK4 is the array form, operation for operation."""

import numpy as np

from shintai.core.integrators import rk4_constant_rate, rk4_constant_rate_floats


def rate(x, q):
    """A nonlinear ẋ(x, q) of the plant's shape: 3 states driven by 5 angles."""
    x, q = np.asarray(x), np.asarray(q)
    return np.array([np.cos(x[2] + q.sum()), np.sin(x[2] - q[0]) * q[1], x[0] * x[1] - q[4] ** 2])


def test_rk4_on_floats_is_bit_identical_to_rk4_on_arrays():
    rng = np.random.default_rng(0)
    for steps in (1, 2, 4):
        x, q, u = rng.normal(size=3), rng.normal(size=5), rng.normal(size=5)
        k1 = rate(x, q)
        xa, qa = rk4_constant_rate(rate, x, q, u, 0.025, steps, k1)
        xf, qf = rk4_constant_rate_floats(lambda x_, q_: rate(x_, q_).tolist(), x.tolist(), q.tolist(), u.tolist(),
                                          0.025, steps, k1.tolist())
        assert np.array_equal(xa, xf) and np.array_equal(qa, qf)


def test_rk4_on_floats_integrates_a_known_solution():
    """ẋ = q with q = q0 + u t: x(t) = x0 + q0 t + u t²/2, exact for RK4 (a polynomial of degree 2)."""
    x, q = rk4_constant_rate_floats(lambda x_, q_: list(q_), [1.0], [0.5], [2.0], 0.1, 5)
    assert abs(x[0] - (1.0 + 0.5 * 0.5 + 2.0 * 0.5 ** 2 / 2)) < 1e-12 and abs(q[0] - 1.5) < 1e-12
