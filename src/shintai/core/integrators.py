"""Fixed-step integrators shared by the kinematic models (one place each)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def rk4_constant_rate(f: Callable, x, q, u, h: float, steps: int = 1, k1=None):
    """RK4 of ẋ = f(x, q) while q moves at the constant rate u (q(t) = q + u t is exact).

    ``steps`` sub-steps of ``h``; ``k1`` is f(x, q) if the caller already has it. Returns (x, q) after
    ``steps · h``.
    """
    for i in range(steps):
        if i or k1 is None:
            k1 = f(x, q)
        mid, end = q + 0.5 * h * u, q + h * u
        k2 = f(x + 0.5 * h * k1, mid)
        k3 = f(x + 0.5 * h * k2, mid)
        k4 = f(x + h * k3, end)
        x = x + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        q = end
    return x, q


def rk4_constant_rate_floats(f: Callable, x: list, q: list, u: list, h: float, steps: int = 1, k1=None):
    """:func:`rk4_constant_rate` on lists of Python floats, the same operations in the same order element by
    element (for a state of a few numbers, where NumPy's cost per call is most of the step). ``f(x, q)``
    takes and returns lists; returns (x, q) as lists."""
    half, sixth = 0.5 * h, h / 6.0
    for i in range(steps):
        if i or k1 is None:
            k1 = f(x, q)
        mid, end = [a + half * b for a, b in zip(q, u)], [a + h * b for a, b in zip(q, u)]
        k2 = f([a + half * b for a, b in zip(x, k1)], mid)
        k3 = f([a + half * b for a, b in zip(x, k2)], mid)
        k4 = f([a + h * b for a, b in zip(x, k3)], end)
        x = [a + sixth * (b1 + 2.0 * b2 + 2.0 * b3 + b4) for a, b1, b2, b3, b4 in zip(x, k1, k2, k3, k4)]
        q = end
    return x, q


def midpoint(f: Callable[[np.ndarray], np.ndarray], x, h: float):
    """One explicit midpoint step of ẋ = f(x): the rate at x + h/2·f(x), then the full step."""
    return x + h * f(x + 0.5 * h * f(x))
