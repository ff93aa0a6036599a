"""Mini-batch-based closed-loop Learning Control, MLC (seed 000 §6.3.1–6.3.2, Eqs. 6.17–6.32, Tables 6.4, 6.6);
the V-BOARD's speed governor runs it with the PID of Eq. 6.2 (:mod:`shintai.humanoid.vboard.governor`).

For * = v, ω and ρ_n = (K_P(n), K_I(n), K_D(n)):

* cost over a mini-batch of T_L = 2 s (500 samples of 4 ms):  J(ρ_n) = (1/T_L) ∫ e_*² dt        (Eq. 6.17)
* gradient (IFT):  ∇J(ρ_n) = −(2/T_L) ∫ Y(t) e_*(t) dt,  Y = (∂y/∂ρ_n)ᵀ                          (Eq. 6.18)
  with Y(s) = P/(1 + P C) (∂C/∂ρ)ᵀ e(s) (Eq. 6.19); for P = K/(s(1 + T s)) and the PID C this is
  Y(s) = K [s, 1, s²]ᵀ e(s) / (T s³ + (1 + K K_D) s² + K K_P s + K K_I)                          (Eq. 6.20)
  i.e. the ODE Eq. 6.21, discretised by the backward differences Eqs. 6.22–6.24 into the recursion
  Y(t) = (C1 Y(t−Δt) + C2 Y(t−2Δt) + C3 Y(t−3Δt) + K [ė, e, ë]ᵀ) / C0                            (Eqs. 6.25–6.29)
  evaluated with the identified T_*, K_* (Table 6.2).
* update:  ρ_{n+1} = ρ_n − diag(η_P, η_I, η_D) ∇J(ρ_n) (Eq. 6.30), η = 1e-7 for v and 1e-9 for ω (Table 6.6);
  a negative gain is set to 0 and learned again from there (§6.3.2); gains start at 0 (§6.4.1).
* termination:  ‖∇J(ρ_n)‖₂ < ε ∧ J(ρ_n) < σ on k = 3 consecutive mini-batches (Eq. 6.32).
* as an online search index (Table 6.4, Eq. 6.31): x = y, x_d = y^d, W = 1/T_L, A = diag(η_P, η_I, η_D).
  ρ lives in the engine's :class:`~shintai.core.search_index.SearchIndex`, which is handed each batch's ∫ Y e dt
  and turns it into the learning index f = ∇J of Eq. 6.18.

Choices where the thesis is silent (each tested or stated next to its constant):
* ε and σ of Eq. 6.32 are "very small positive values" without numbers: chosen below per axis;
* ė and ë on the right of Eq. 6.25 are backward differences of the sampled e, like Eqs. 6.22–6.23, with
  e(t−Δt) = e(t−2Δt) = e(0) before the first sample; Y(t−mΔt) = 0 before the first sample;
* Y runs on across mini-batches (the recursion is "sequential", §6.3.2) with the coefficients of the gains in
  force; the integrals of Eqs. 6.17–6.18 are rectangle sums over the 500 samples;
* on the batch where Eq. 6.32 completes its k-th holding, learning stops and that batch's step is not applied.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.search_index import MatrixGain, SearchIndex
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    ETA_OMEGA,
    EPS_OMEGA,
    EPS_V,
    ETA_V,
    K_OMEGA,
    K_V,
    MLC_ETA_MAX,
    SIGMA_OMEGA,
    SIGMA_V,
    TERMINATION_K,
    T_L,
    T_OMEGA,
    T_V,
)
from shintai.humanoid.law_params import check_real


@dataclass(frozen=True)
class MLCParams:
    """One axis's MLC settings: identified plant (K, T), rates, termination, batch; each field checked."""

    K: float
    T: float
    eta: tuple[float, float, float]
    eps: float
    sigma: float
    k: int = TERMINATION_K
    T_L: float = T_L
    dt: float = CONTROL_PERIOD

    def __post_init__(self):
        check_real("K", self.K, 0.0, low_open=True)
        check_real("T", self.T, 0.0, low_open=True)
        if len(self.eta) != 3:
            raise ValueError(f"eta must be (eta_P, eta_I, eta_D), got {self.eta!r}")
        for name, e in zip(("eta_P", "eta_I", "eta_D"), self.eta, strict=True):
            check_real(name, e, 0.0, MLC_ETA_MAX, low_open=True)
        check_real("eps", self.eps, 0.0, low_open=True)
        check_real("sigma", self.sigma, 0.0, low_open=True)
        if int(self.k) != self.k or self.k < 1:
            raise ValueError(f"k must be a whole number >= 1, got {self.k!r}")
        check_real("dt", self.dt, 0.0, low_open=True)
        check_real("T_L", self.T_L, self.dt)
        if abs(self.T_L / self.dt - round(self.T_L / self.dt)) > 1e-9:
            raise ValueError(f"T_L must be a whole number of control periods dt={self.dt}, got {self.T_L!r}")

    @property
    def batch(self) -> int:
        return round(self.T_L / self.dt)


MLC_V = MLCParams(K=K_V, T=T_V, eta=ETA_V, eps=EPS_V, sigma=SIGMA_V)
MLC_OMEGA = MLCParams(K=K_OMEGA, T=T_OMEGA, eta=ETA_OMEGA, eps=EPS_OMEGA, sigma=SIGMA_OMEGA)


def recursion_coefficients(K: float, T: float, gains, dt: float) -> tuple[float, float, float, float]:
    """C0…C3 of Eqs. 6.26–6.29 for ρ = (K_P, K_I, K_D)."""
    KP, KI, KD = gains
    a = 1.0 + K * KD
    C0 = T / dt**3 + a / dt**2 + K * KP / dt + K * KI
    C1 = 3 * T / dt**3 + 2 * a / dt**2 + K * KP / dt
    C2 = -3 * T / dt**3 - a / dt**2
    C3 = T / dt**3
    return C0, C1, C2, C3


class Sensitivity:
    """Y(t) = (∂y(t)/∂ρ_n)ᵀ ∈ R³ by the recursion of Eq. 6.25, fed one error sample per step."""

    def __init__(self, K: float, T: float, dt: float, gains=(0.0, 0.0, 0.0)):
        self.K, self.T, self.dt = K, T, dt
        self.Y = np.zeros((3, 3))  # rows: Y(t−Δt), Y(t−2Δt), Y(t−3Δt)
        self._e: list[float] | None = None  # e(t−Δt), e(t−2Δt)
        self.set_gains(gains)

    def set_gains(self, gains) -> None:
        self.C = recursion_coefficients(self.K, self.T, gains, self.dt)

    def step(self, e: float) -> np.ndarray:
        e1, e2 = (e, e) if self._e is None else self._e
        de = (e - e1) / self.dt
        dde = (e - 2 * e1 + e2) / self.dt**2
        C0, C1, C2, C3 = self.C
        Y = (C1 * self.Y[0] + C2 * self.Y[1] + C3 * self.Y[2] + self.K * np.array([de, e, dde])) / C0
        self.Y = np.vstack([Y, self.Y[:2]])
        self._e = [e, e1]
        return Y


@dataclass
class Batch:
    """One mini-batch's outcome (for plots and the termination rule)."""

    t_end: float
    J: float
    grad: np.ndarray
    gains: np.ndarray  # ρ_{n+1} after the update (or ρ_n when learning stopped)
    clipped: np.ndarray
    holds: bool  # Eq. 6.32's two conditions on this batch


class MLC:
    """One axis (v or ω): accumulate 500 samples of e and Y, then ρ ← ρ − A ∇J (Eq. 6.30) on the engine."""

    def __init__(self, params: MLCParams, gains0=(0.0, 0.0, 0.0)):
        self.p = params
        # the engine's x is the batch's ∫ Y e dt, its learning index f = ∇J = −(2/T_L) ∫ Y e dt (Eq. 6.18)
        self.index = SearchIndex(np.asarray(gains0, dtype=float), MatrixGain(np.diag(params.eta)),
                                 gradient=lambda integral, rho: -2.0 / params.T_L * integral)
        self.sensitivity = Sensitivity(params.K, params.T, params.dt, self.gains)
        self.batches: list[Batch] = []
        self.converged = False
        self.t_converged: float | None = None
        self._streak = 0
        self._reset_batch()

    @property
    def gains(self) -> np.ndarray:
        return self.index.rho.copy()

    def _reset_batch(self) -> None:
        self._n, self._sum_e2, self._sum_Ye = 0, 0.0, np.zeros(3)

    def observe(self, e: float, t: float = 0.0) -> bool:
        """Feed e_*(t) = y^d − y; returns True when the gains changed at the end of this sample's batch."""
        if self.converged:
            return False
        Y = self.sensitivity.step(e)
        dt = self.p.dt
        self._sum_e2 += e * e * dt
        self._sum_Ye += Y * e * dt
        self._n += 1
        if self._n < self.p.batch:
            return False
        J = self._sum_e2 / self.p.T_L  # Eq. 6.17
        integral = self._sum_Ye
        grad = self.index.index(integral)  # Eq. 6.18
        self._reset_batch()
        holds = bool(np.linalg.norm(grad) < self.p.eps and J < self.p.sigma)  # Eq. 6.32
        self._streak = self._streak + 1 if holds else 0
        clipped = np.zeros(3, dtype=bool)
        if self._streak >= self.p.k:
            self.converged, self.t_converged = True, t
        else:
            rho = self.index.update(integral)  # ρ − diag(η) ∇J (Eq. 6.30)
            clipped = rho < 0
            self.index.rho = np.maximum(rho, 0.0)  # a negative gain is set to 0 and re-learned (§6.3.2)
            self.sensitivity.set_gains(self.index.rho)
        self.batches.append(Batch(t, J, grad, self.gains, clipped, holds))
        return not self.converged
