"""[55]'s error system under Eq. 26 and seed 000 Eq. 7.2's correction after the LIP tracking (balance/stabilizer.py)."""

import numpy as np
import pytest

from shintai.humanoid.balance.stabilizer import closed_loop_poles, error_system
from shintai.humanoid.constants import LIP_K, ZMP_DELAY_T


def test_the_characteristic_polynomial_is_the_one_the_docstring_states():
    k1, k2, k3 = LIP_K
    zc, tp = 0.83, ZMP_DELAY_T
    a, _ = error_system(LIP_K, zc, tp)
    w2 = 9.80665 / zc
    expected = [1.0, (1 + k3) / tp, -w2 * (1 + k2 / tp), -w2 * (1 + k1 + k3) / tp]
    assert np.allclose(np.poly(a), expected, rtol=1e-3)


def test_every_stabilising_gain_set_puts_a_correction_after_the_lip_tracking_backwards():
    """Routh–Hurwitz: 1 + k1 + k3 < 0 for every gain set that stabilises the error system, so Eq. 7.2's
    p^{d**} = p^{d*} + c settles the mass centre at c/(1 + k1 + k3), behind a forward c (issue 26 item 6)."""
    rng = np.random.default_rng(0)
    gains = rng.uniform([-6.0, -3.0, -3.0], [3.0, 2.0, 2.0], size=(4000, 3))
    stable = [k for k in gains if np.all(closed_loop_poles(k, 0.83).real < 0)]
    assert len(stable) > 200  # the draw covers the stabilising region, not a sliver of it
    for k in stable:
        a, b = error_system(k, 0.83)
        e = np.linalg.solve(a, -b * 0.01)  # equilibrium under c = +1 cm
        assert 1 + k[0] + k[2] < 0
        assert e[0] == pytest.approx(0.01 / (1 + k[0] + k[2])) and e[0] < 0 and e[2] == pytest.approx(e[0])
    # and gains with 1 + k1 + k3 > 0 are never stable
    assert not any(1 + k[0] + k[2] > 0 for k in stable)
    assert any(1 + k[0] + k[2] > 0 for k in gains)


def test_the_support_polygon_and_the_zmp_truncation():
    from shintai.humanoid.balance.stabilizer import support_polygon, truncate_zmp
    from shintai.humanoid.constants import HRP2_LINKS as L

    soles = [(0.0, 0.1, 0.0), (0.0, -0.1, 0.0)]
    left = support_polygon(soles, "l")
    assert len(left) == 4 and np.allclose(left.mean(axis=0), (L.foot_forward, 0.1 + L.foot_outward))
    both = support_polygon(soles, "lr")
    assert len(both) == 4  # the two rectangles side by side: one hull of 4 corners
    inside = np.array([0.01, 0.0])
    assert np.array_equal(truncate_zmp(inside, both), inside)
    behind = truncate_zmp([-0.3, 0.1], left)  # 0.19 m behind the heel, as the boarding asked
    assert behind == pytest.approx([L.foot_forward - L.foot_length / 2, 0.1])
    corner = truncate_zmp([1.0, 1.0], left)
    assert corner == pytest.approx([L.foot_forward + L.foot_length / 2, 0.1 + L.foot_outward + L.foot_width / 2])
