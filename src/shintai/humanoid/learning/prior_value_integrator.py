"""The prior-value-correcting integrator (前回値補正積分器, seed 000 §6.3.3, Eqs. 6.33–6.39), its r_sat
alternative (§6.4.2, Eq. 6.42), and the PID controller of the speed governor that uses them (Eq. 6.2).

The I action of the PID is u_I(t) = K_I(n) E(t) with the trapezoidal integral (Eqs. 6.33–6.34)

    E(t) = E(t−Δt) + Δt/2 (e(t) + e(t−Δt)).

When MLC raises the I gain K_I(n) → K_I(n+1) between two samples, the plain integrator (SW0) multiplies the
I action by K_I(n+1)/K_I(n) (Eq. 6.36) — from K_I(n) = 0 the whole error accumulated so far acts at once.
The corrected integrator switches to SW1 for that one sample only (Eq. 6.39) and scales the prior value,

    E(t) = K_I(n)/K_I(n+1) · E(t−Δt) + Δt/2 (e(t) + e(t−Δt))       (Eq. 6.37)

so that u_I(t+Δt) = u_I(t) + Δt/2 (e(t+Δt) + e(t)) K_I(n+1) (Eq. 6.38): u_I stays continuous. A decrease
(or no change) keeps SW0 (Eq. 6.33). The comparison method of §6.4.2 saturates the ratio instead:

    u_I(t+Δt) = min(K_I(n+1)/K_I(n), r_sat) u_I(t) + Δt/2 (e(t+Δt) + e(t)) K_I(n+1)   (Eq. 6.42)

Choices (thesis silent): a gain set with :meth:`PriorValueIntegrator.set_gain` takes effect at the next
sample, the "t → t+Δt" of Eqs. 6.36–6.38; before the first sample e(t−Δt) is taken equal to e(t); the D term
of Eq. 6.2 is the backward difference (e(t) − e(t−Δt))/Δt, unfiltered.
"""

from __future__ import annotations

import math

import numpy as np

from shintai.humanoid.constants import R_SAT_V
from shintai.humanoid.law_params import check_real

MODES = ("corrected", "plain", "saturated")


class PriorValueIntegrator:
    """u_I = K_I E with the switch of Eq. 6.39 (``mode="corrected"``), the plain integrator
    (``"plain"``, Eqs. 6.33–6.36) or the ratio saturation (``"saturated"``, Eq. 6.42 with ``r_sat``).

    ``switched`` is True after a sample that used SW1 (corrected) or hit r_sat (saturated).
    """

    def __init__(self, dt: float, K_I: float = 0.0, mode: str = "corrected", r_sat: float = R_SAT_V):
        if mode not in MODES:
            raise ValueError(f"mode must be one of {', '.join(MODES)}, got {mode!r}")
        self.dt = check_real("dt", dt, 0.0, low_open=True)
        self.K = check_real("K_I", K_I, 0.0)
        self.r_sat = check_real("r_sat", r_sat, 1.0) if mode == "saturated" else r_sat
        self.mode = mode
        self.E = 0.0
        self.u_I = 0.0
        self.switched = False
        self._pending: float | None = None
        self._e_prev: float | None = None

    def set_gain(self, K_I: float) -> None:
        """K_I(n) → K_I(n+1), effective from the next sample."""
        self._pending = check_real("K_I", K_I, 0.0)

    def step(self, e: float) -> float:
        e = float(e)
        e_prev = e if self._e_prev is None else self._e_prev
        trap = 0.5 * self.dt * (e + e_prev)
        K_old = self.K
        K_new = K_old if self._pending is None else self._pending
        self._pending = None
        self.switched = False
        if self.mode == "saturated":
            ratio = 1.0 if K_new == K_old else (math.inf if K_old == 0.0 else K_new / K_old)
            self.switched = ratio > self.r_sat
            self.u_I = min(ratio, self.r_sat) * self.u_I + trap * K_new  # Eq. 6.42
            self.E += trap
        else:
            if self.mode == "corrected" and K_new > K_old:  # SW1, Eq. 6.37 (K_new > 0, so no division by 0)
                self.E = K_old / K_new * self.E + trap
                self.switched = True
            else:  # SW0, Eq. 6.33
                self.E += trap
            self.u_I = K_new * self.E  # Eq. 6.34
        self.K = K_new
        self._e_prev = e
        return self.u_I


class PID:
    """u = K_P e + K_I ∫e + K_D ė (Eq. 6.2), discrete at ``dt`` with a :class:`PriorValueIntegrator`."""

    def __init__(self, dt: float, gains=(0.0, 0.0, 0.0), mode: str = "corrected", r_sat: float = R_SAT_V):
        self.dt = check_real("dt", dt, 0.0, low_open=True)
        self.gains = np.zeros(3)
        self.integrator = PriorValueIntegrator(dt, 0.0, mode, r_sat)
        self.set_gains(gains)
        self.integrator.K = self.gains[1]
        self._e_prev: float | None = None
        self.u = 0.0

    def set_gains(self, gains) -> None:
        """ρ_n = (K_P, K_I, K_D) → ρ_{n+1} (§6.3.4 step 5); the I gain goes through the integrator's switch."""
        for name, g in zip(("K_P", "K_I", "K_D"), gains, strict=True):
            check_real(name, g, 0.0)
        self.gains = np.asarray(gains, dtype=float).copy()
        self.integrator.set_gain(self.gains[1])

    def step(self, e: float) -> float:
        e = float(e)
        de = 0.0 if self._e_prev is None else (e - self._e_prev) / self.dt
        self._e_prev = e
        self.u = self.gains[0] * e + self.integrator.step(e) + self.gains[2] * de
        return self.u
