"""A GA's stopping rule: stop once the best fitness has stalled (issue 27, seed 004's training; issue 28, seed
003's GAs). Neither thesis prints a generation count or a stopping criterion, so a budget is a choice; this rule
makes it one declared before the run rather than a number picked after seeing a curve."""

from __future__ import annotations

import numpy as np


def stalled(best, window: int, tolerance: float, minimize: bool) -> bool:
    """Whether the best fitness per generation ``best`` (index 0 the first population) has improved by less
    than ``tolerance`` of its magnitude ``window`` generations ago: ``|b[-1] − b[-1-window]| < tolerance ×
    |b[-1-window]|`` in the improving direction (lower when ``minimize``); a best that has not moved at all has
    stalled, a best of 0 included. Never before ``window + 1`` generations; a window of 0 never stops."""
    best = np.asarray(best, dtype=float)
    if window < 1 or len(best) <= window:
        return False
    then, now = best[-1 - window], best[-1]
    gain = then - now if minimize else now - then
    return bool(gain <= 0.0 or gain < tolerance * abs(then))
