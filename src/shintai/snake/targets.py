"""Piecewise-linear targets of the two-point experiments — seed 001 (3.21), (3.22)–(3.23), (3.26), and the
operator's waypoints of §3.4.3.

One class for all of them: :class:`PiecewiseLinear` goes through poses at given times and holds the last
pose (zero rate) afterwards. The ramp (3.21) is the case of two waypoints (0, t_end); the two-stage ramp
(3.22)–(3.23) the case of three, stage 2 read as (t − t_s1)/(t_end − t_s1) (spec A7).

The printed final headings are right only modulo 2π (spec A6): §3.3's tail −π/2 must be 3π/2 and the
caging tail 0 must be 2π, or the linear ramp winds the joints up. Every angle of a waypoint is therefore
moved to the 2π-branch nearest the same angle of the waypoint before it, θ_k ← θ_{k−1} + wrap(θ_k − θ_{k−1})
(spec §4.6).
"""

from __future__ import annotations

from bisect import bisect_right
from dataclasses import dataclass

import numpy as np

from shintai.core.geometry import wrap

ANGLE_INDICES = (2, 5)  # θ_{y,h} and θ_{y,t} in c_c = [x_h, y_h, θ_h, x_t, y_t, θ_t] (3.2)


@dataclass(frozen=True)
class PiecewiseLinear:
    """c_d(t) through ``poses[k]`` at ``times[k]`` (held after the last), and its slope ċ_d(t).

    Build it with :meth:`through` (angles unwrapped, A6) or :meth:`ramp` ((3.21): c(0) → c_e over t_end).
    """

    times: tuple[float, ...]
    poses: np.ndarray

    @classmethod
    def through(cls, times, poses, angles=ANGLE_INDICES) -> PiecewiseLinear:
        """Waypoints ``poses`` at strictly increasing ``times``; ``angles`` (indices into a pose) unwrapped (A6)."""
        poses = np.array(poses, dtype=float)
        if len(times) != len(poses) or len(times) < 2 or np.any(np.diff(times) <= 0):
            raise ValueError("waypoints need >= 2 strictly increasing times, one pose each")
        idx = np.asarray(angles, dtype=int)
        for k in range(1, len(poses)):
            poses[k, idx] = poses[k - 1, idx] + wrap(poses[k, idx] - poses[k - 1, idx])
        return cls(tuple(float(t) for t in times), poses)

    @classmethod
    def ramp(cls, c0, c_e, t_end: float, angles=ANGLE_INDICES) -> PiecewiseLinear:
        """(3.21): c_d(t) = c(0) + (c_e − c(0)) t / t_end, then c_e with zero rate (chosen; the thesis stops at
        t_end)."""
        if not t_end > 0:
            raise ValueError(f"t_end must be > 0 s, got {t_end!r}")
        return cls.through((0.0, t_end), (c0, c_e), angles)

    def __call__(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        if t >= self.times[-1]:
            return self.poses[-1].copy(), np.zeros(self.poses.shape[1])
        k = bisect_right(self.times, t) - 1  # np.searchsorted(side="right") on the tuple, without converting it
        rate = (self.poses[k + 1] - self.poses[k]) / (self.times[k + 1] - self.times[k])
        return self.poses[k] + rate * (t - self.times[k]), rate
