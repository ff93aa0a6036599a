"""Target trajectories of the two-point experiments (seed 001 §3.3, eq. (3.21)) and angle unwrapping.

The printed final headings are right only modulo 2π (spec A6): §3.3's tail −π/2 must be 3π/2 and the
caging tail 0 must be 2π, or the linear ramp winds the joints up. Every angle target is therefore moved to
the branch nearest its initial value, θ_e ← θ_0 + wrap(θ_e − θ_0) (spec §4.6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

ANGLE_INDICES = (2, 5)  # θ_{y,h} and θ_{y,t} in c_c = [x_h, y_h, θ_h, x_t, y_t, θ_t] (3.2)


def wrap_angle(a):
    """Angle(s) wrapped to [−π, π)."""
    return (np.asarray(a, dtype=float) + math.pi) % (2 * math.pi) - math.pi


def unwrap_targets(c0, c_e) -> np.ndarray:
    """``c_e`` with each heading moved to the 2π-branch nearest the same heading in ``c0`` (A6)."""
    c0 = np.asarray(c0, dtype=float)
    c_e = np.array(c_e, dtype=float)
    if c0.shape != (6,) or c_e.shape != (6,):
        raise ValueError(f"c0 and c_e must be 6-vectors [x_h, y_h, θ_h, x_t, y_t, θ_t], got {c0.shape}, {c_e.shape}")
    for i in ANGLE_INDICES:
        c_e[i] = c0[i] + wrap_angle(c_e[i] - c0[i])
    return c_e


@dataclass(frozen=True)
class Ramp:
    """c_{c,d}(t) = c_c(0) + (c_{c,e} − c_c(0)) t / t_end, eq. (3.21); ċ_{c,d} its slope.

    After t_end the target holds c_{c,e} with zero velocity (chosen; the thesis stops at t_end).
    """

    c0: np.ndarray
    c_e: np.ndarray
    t_end: float

    def __post_init__(self) -> None:
        if not self.t_end > 0:
            raise ValueError(f"t_end must be > 0 s, got {self.t_end!r}")

    def __call__(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        if t >= self.t_end:
            return np.asarray(self.c_e, float), np.zeros(6)
        rate = (np.asarray(self.c_e, float) - self.c0) / self.t_end
        return self.c0 + rate * t, rate
