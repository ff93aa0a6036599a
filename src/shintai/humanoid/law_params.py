"""One check for the real-valued parameters of the ch. 5–6 laws: a bad value is one ValueError line that
names the field and its allowed range (DESIGN.md, "Bad input")."""

from __future__ import annotations

import math


def check_real(name: str, value, low: float = -math.inf, high: float = math.inf, *,
               low_open: bool = False, high_open: bool = False) -> float:
    """Return ``value`` as a float if it is finite and inside the range, else raise ValueError naming ``name``.

    ``low_open``/``high_open`` exclude the end points: ``check_real("D0", d, 0, low_open=True)`` is D₀ > 0.
    """
    left = "(" if low_open or low == -math.inf else "["
    right = ")" if high_open or high == math.inf else "]"
    allowed = f"{left}{low:g}, {high:g}{right}"
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number in {allowed}, got {value!r}") from None
    if not math.isfinite(x) or x < low or x > high or (low_open and x == low) or (high_open and x == high):
        raise ValueError(f"{name} must be a finite number in {allowed}, got {value!r}")
    return x
