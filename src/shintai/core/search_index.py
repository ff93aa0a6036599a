"""The online search index of seed 000 ch. 2 (spec 000-part1-ch1-3.md §2.1–2.5).

A search index is the vector that says in which direction, and how far, to move a trajectory or a
gain ρ ∈ R^M so that a sensed search variable x ∈ R^N approaches its target x_d. Kinds (§2.3.2,
Fig. 2.9):

* online control index, Eq. 2.5:   f_c = sgn[ρ, x] (x − x_d)
* online learning index, Eq. 2.8:  f_l = (∂J(x)/∂ρ)ᵀ, e.g. J = (x − x_d)ᵀ W (x − x_d)  (Eq. 2.10)
* offline search index: the step between consecutive poses of a planned trajectory (§2.3.2)

and one update for all of them, the generalized trajectory-and-gain update rule (Eq. 2.13):

    ρ(t+Δt; n+1) := ρ(t; n) − A f(t; n)

with A a positive-definite symmetric matrix, or — for the passive impedance of Table 3.3, where
A = (M s² + D s + K)⁻¹ is a transfer function (spec §6 item 1) — a stateful discrete LTI filter.
The stability monitors check the conditions of Eqs. 2.22–2.33 along a run.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import expm

from shintai.core.runtime import Module, Snapshot

# --- sign matrix (Eqs. 2.5–2.7) -------------------------------------------------------------------


def sign_matrix(table: Sequence[Sequence[int]]) -> np.ndarray:
    """The declared sign matrix sgn[ρ, x] ∈ {−1, 0, +1}^{M×N} (Eq. 2.6).

    Row i, column j: +1 if x_j increases (weakly) monotonically with ρ_i, −1 if it decreases,
    0 if independent or if the monotonicity flips with another ρ (Eq. 2.7).
    """
    sgn = np.asarray(table, dtype=float)
    if sgn.ndim != 2 or not np.all(np.isin(sgn, (-1.0, 0.0, 1.0))):
        raise ValueError("sign matrix entries must be -1, 0 or +1 in an M×N table")
    return sgn


def estimate_sign_matrix(plant: Callable[[np.ndarray], np.ndarray], rho_points: Sequence[np.ndarray],
                         step: float = 1e-3, tol: float = 1e-9) -> np.ndarray:
    """Estimate sgn[ρ, x] by probing (§2.4.1: monotonicity "acquired by trial").

    For every base point ρ in ``rho_points`` and every component i, ρ_i is moved by ``step`` and the
    sign of Δx_j recorded. An entry is ±1 only when every probe that moved x_j agreed on the sign;
    it is 0 when x_j never moved (independent) or when the sign flipped between probes (the
    "unstable" case of Eq. 2.7). Weakly monotone (some probes see no change) keeps the sign.
    """
    signs = []
    for rho in rho_points:
        rho = np.asarray(rho, dtype=float)
        x0 = np.asarray(plant(rho), dtype=float)
        probe = np.empty((rho.size, x0.size))
        for i in range(rho.size):
            moved = rho.copy()
            moved[i] += step
            dx = np.asarray(plant(moved), dtype=float) - x0
            probe[i] = np.where(np.abs(dx) > tol, np.sign(dx), 0.0)
        signs.append(probe)
    signs = np.array(signs)
    pos = np.any(signs > 0, axis=0)
    neg = np.any(signs < 0, axis=0)
    return np.where(pos & ~neg, 1.0, 0.0) - np.where(neg & ~pos, 1.0, 0.0)


# --- indices (Eqs. 2.4, 2.5, 2.8) ------------------------------------------------------------------


def control_index(sgn: np.ndarray, x: np.ndarray, x_d: np.ndarray) -> np.ndarray:
    """Online control index f_c = sgn[ρ, x] (x − x_d) (Eq. 2.5); points away from the target."""
    return np.asarray(sgn) @ (np.asarray(x, dtype=float) - np.asarray(x_d, dtype=float))


@dataclass
class QuadraticCost:
    """J(x) = (x − x_d)ᵀ W (x − x_d) (Eq. 2.10) with W symmetric (diagonal positive in Eq. 2.29)."""

    W: np.ndarray
    x_d: np.ndarray

    def __call__(self, x: np.ndarray) -> float:
        e = np.asarray(x, dtype=float) - self.x_d
        return float(e @ self.W @ e)

    def grad_x(self, x: np.ndarray) -> np.ndarray:
        """∂J/∂x = 2 W (x − x_d) (W symmetric)."""
        return 2.0 * self.W @ (np.asarray(x, dtype=float) - self.x_d)


def learning_index_chain(cost: QuadraticCost, x: np.ndarray, dx_drho: np.ndarray) -> np.ndarray:
    """Online learning index f_l = (∂J/∂ρ)ᵀ = (∂x/∂ρ)ᵀ ∂J/∂x (Eq. 2.8 by the chain rule).

    ``dx_drho`` is the N×M sensitivity of the search variable to ρ, known or estimated.
    """
    return np.asarray(dx_drho).T @ cost.grad_x(x)


def finite_difference_gradient(J_of_rho: Callable[[np.ndarray], float], rho: np.ndarray,
                               h: float = 1e-6) -> np.ndarray:
    """(∂J/∂ρ)ᵀ by central differences on a cost evaluated as a function of ρ (2M evaluations)."""
    rho = np.asarray(rho, dtype=float)
    g = np.empty(rho.size)
    for i in range(rho.size):
        e = np.zeros(rho.size)
        e[i] = h
        g[i] = (J_of_rho(rho + e) - J_of_rho(rho - e)) / (2 * h)
    return g


def spsa_gradient(J_of_rho: Callable[[np.ndarray], float], rho: np.ndarray, c: float,
                  rng: np.random.Generator) -> np.ndarray:
    """Simultaneous-perturbation estimate of (∂J/∂ρ)ᵀ: two evaluations whatever M (a stochastic
    gradient for online learning, §2.3.2 "SGD"; the thesis's own SLC/MLC gradients are ch. 5–6)."""
    rho = np.asarray(rho, dtype=float)
    delta = rng.choice((-1.0, 1.0), size=rho.size)
    return (J_of_rho(rho + c * delta) - J_of_rho(rho - c * delta)) / (2 * c) * delta


def offline_index(plan: np.ndarray) -> np.ndarray:
    """Offline search index of a planned trajectory: f_k = ρ_k − ρ_{k+1} (§2.3.2, Eq. 3.9 style).

    With A = E the update rule ρ ← ρ − A f then walks the plan step by step. ``plan`` is K×M;
    the result is (K−1)×M.
    """
    plan = np.asarray(plan, dtype=float)
    return plan[:-1] - plan[1:]


# --- the weight A: a matrix or a stateful LTI filter (Eq. 2.13, Table 3.3) -------------------------


class MatrixGain:
    """A constant weight A ∈ R^{M×M}, positive-definite symmetric (Eq. 2.13)."""

    def __init__(self, A):
        A = np.atleast_2d(np.asarray(A, dtype=float))
        if A.shape[0] != A.shape[1]:
            raise ValueError(f"A must be square, got {A.shape}")
        if not np.allclose(A, A.T, atol=1e-12):
            raise ValueError("A must be symmetric (Eq. 2.13)")
        if np.linalg.eigvalsh(A).min() <= 0:
            raise ValueError("A must be positive definite (Eq. 2.13)")
        self.A = A

    @property
    def static_gain(self) -> np.ndarray:
        return self.A

    def __call__(self, f: np.ndarray) -> np.ndarray:
        return self.A @ f

    def reset(self) -> None:
        """A matrix has no state."""


class LTIGain:
    """A as a discrete LTI filter: y_k = C x_{k+1}, x_{k+1} = A_d x_k + B_d f_k (zero-order hold).

    Built from a continuous state space (A_c, B_c, C_c) sampled at ``dt`` with the exact ZOH
    (matrix exponential), so it is stable for any Δt when the continuous filter is. The output
    after input f_k is the filter state reached by holding f_k over Δt. The state persists across
    updates: this is what makes the reference-reset rule Eq. 3.14 and the filtered update Eq. 3.18
    give identical reference sequences (spec §5.4 check 3).
    """

    def __init__(self, A_c, B_c, C_c, dt: float):
        A_c, B_c, C_c = (np.atleast_2d(np.asarray(m, dtype=float)) for m in (A_c, B_c, C_c))
        n, m = A_c.shape[0], B_c.shape[1]
        big = np.zeros((n + m, n + m))
        big[:n, :n] = A_c * dt
        big[:n, n:] = B_c * dt
        phi = expm(big)
        self.A_d, self.B_d, self.C = phi[:n, :n], phi[:n, n:], C_c
        self.dt = dt
        self._A_c, self._B_c = A_c, B_c
        self.state = np.zeros(n)

    @property
    def static_gain(self) -> np.ndarray:
        """DC gain −C A_c⁻¹ B_c (for (M s² + D s + K)⁻¹ this is K⁻¹)."""
        return -self.C @ np.linalg.solve(self._A_c, self._B_c)

    def __call__(self, f: np.ndarray) -> np.ndarray:
        # ndarray.dot: the same BLAS gemv as @ for these matrix-vector shapes (the same bits, checked on 100k
        # random cases per shape), at a third of @'s call cost; a vector f is what np.atleast_1d would return
        f = f if isinstance(f, np.ndarray) and f.ndim else np.atleast_1d(f)
        self.state = self.A_d.dot(self.state) + self.B_d.dot(f)
        return self.C.dot(self.state)

    def reset(self) -> None:
        self.state[:] = 0.0


def impedance_gain(M, D, K, dt: float, axes: int = 1) -> LTIGain:
    """A = (M s² + D s + K)⁻¹ (Eq. 3.16, Table 3.3) for diagonal M, D, K given per axis.

    ``M``, ``D``, ``K`` are scalars (isotropic over ``axes`` axes — Table 3.4 gives scalars; spec §6
    item 3) or per-axis vectors. The state is [δ, δ̇] per axis, δ the impedance displacement of Eq. 3.13.
    """
    M, D, K = np.broadcast_arrays(*(np.atleast_1d(np.asarray(v, dtype=float)) for v in (M, D, K)),
                                  np.zeros(axes))[:3]
    if np.any(M <= 0) or np.any(D < 0) or np.any(K <= 0):
        raise ValueError("impedance needs M > 0, D >= 0, K > 0 (Table 3.4)")
    m = M.size
    A_c = np.zeros((2 * m, 2 * m))
    B_c = np.zeros((2 * m, m))
    C_c = np.zeros((m, 2 * m))
    for i in range(m):
        A_c[2 * i, 2 * i + 1] = 1.0
        A_c[2 * i + 1, 2 * i] = -K[i] / M[i]
        A_c[2 * i + 1, 2 * i + 1] = -D[i] / M[i]
        B_c[2 * i + 1, i] = 1.0 / M[i]
        C_c[i, 2 * i] = 1.0
    return LTIGain(A_c, B_c, C_c, dt)


def first_order_gain(k, T, dt: float) -> LTIGain:
    """A = k / (1 + T s) per axis — e.g. the real-time posture control of seed 000 §7.3.1 (A = k_C T_C/(1+T_C s)
    is this with k = k_C T_C)."""
    k, T = np.broadcast_arrays(np.atleast_1d(np.asarray(k, dtype=float)), np.atleast_1d(np.asarray(T, dtype=float)))
    if np.any(T <= 0):
        raise ValueError("first-order filter needs T > 0")
    return LTIGain(np.diag(-1.0 / T), np.diag(k / T), np.eye(k.size), dt)


def control_index_coefficient(A: np.ndarray, sgn: np.ndarray) -> np.ndarray:
    """(A sgn[ρ, x])⁺, the control-index coefficient (§2.5.1): the slope Δx/Δρ of every
    correction step in (ρ, x) space (Fig. 2.14). For a filter, pass its static gain."""
    return np.linalg.pinv(np.asarray(A) @ np.asarray(sgn))


# --- stability monitors (Eqs. 2.22–2.33) ----------------------------------------------------------


def is_decoupled(A: np.ndarray, sgn: np.ndarray) -> bool:
    """Decoupling condition Eq. 2.24: every row of −A sgn has at most one non-zero entry
    (each ρ_i is corrected by one x_j only)."""
    return bool(np.all(np.count_nonzero(np.abs(np.asarray(A) @ np.asarray(sgn)) > 1e-12, axis=1) <= 1))


@dataclass
class StabilityMonitor:
    """Counts, along a run, the steps that break the monotonicity statements of §2.5.2.

    * ``error_increases``: steps where some |{x − x_d}_j| above ``tol`` did not shrink (hypothesis Eq. 2.22);
    * ``increment_increases``: steps where some |{ρ_{k+2} − ρ_{k+1}}_i| ≥ |{ρ_{k+1} − ρ_k}_i| (Eq. 2.28),
      among components that are still moving;
    * ``cost_increases``: steps where J(x_{k+1}) ≥ J(x_k) (Eq. 2.33).
    """

    tol: float = 1e-12
    error_increases: int = 0
    increment_increases: int = 0
    cost_increases: int = 0
    steps: int = 0
    _e: np.ndarray | None = field(default=None, repr=False)
    _drho: np.ndarray | None = field(default=None, repr=False)
    _J: float | None = field(default=None, repr=False)

    def observe(self, error: np.ndarray | None = None, drho: np.ndarray | None = None,
                J: float | None = None) -> None:
        if error is not None:
            e = np.abs(np.asarray(error, dtype=float))
            if self._e is not None:
                live = self._e > self.tol  # components already at the target are exempt
                if np.any(e[live] >= self._e[live]):
                    self.error_increases += 1
            self._e = e
        if drho is not None:
            d = np.abs(np.asarray(drho, dtype=float))
            if self._drho is not None:
                moving = self._drho > self.tol
                if np.any(d[moving] >= self._drho[moving]):
                    self.increment_increases += 1
            self._drho = d
        if J is not None:
            if self._J is not None and self._J > self.tol and J >= self._J:
                self.cost_increases += 1
            self._J = float(J)
        self.steps += 1

    @property
    def monotone(self) -> bool:
        return self.error_increases == 0 and self.increment_increases == 0 and self.cost_increases == 0


# --- the update rule, and as a runtime module -----------------------------------------------------


class SearchIndex:
    """ρ ← ρ − A f (Eq. 2.13) with f an online control index (Eq. 2.14) or a learning index (Eq. 2.15).

    Give ``sgn`` and ``x_d`` for trajectory correction, or ``gradient(x, rho) -> (∂J/∂ρ)ᵀ`` for gain
    learning. ``gain`` is a :class:`MatrixGain`, an :class:`LTIGain`, or a matrix/scalar
    (made a MatrixGain). ``hold(rho_next) -> bool`` may refuse an update (e.g. the reachability gate
    of Eq. 3.14, which keeps the current reference).
    """

    def __init__(self, rho0, gain, sgn=None, x_d=None,
                 gradient: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
                 hold: Callable[[np.ndarray], bool] | None = None):
        if (sgn is None) == (gradient is None):
            raise ValueError("give either sgn and x_d (control index) or gradient (learning index)")
        self.rho = np.atleast_1d(np.asarray(rho0, dtype=float)).copy()
        self.gain = gain if hasattr(gain, "static_gain") else MatrixGain(np.atleast_2d(gain) if np.ndim(gain)
                                                                       else gain * np.eye(self.rho.size))
        self.sgn = None if sgn is None else np.atleast_2d(np.asarray(sgn, dtype=float))
        self.x_d = None if x_d is None else np.atleast_1d(np.asarray(x_d, dtype=float))
        self.gradient = gradient
        self.hold = hold
        self.last_index = np.zeros_like(self.rho)
        self.held_steps = 0

    def index(self, x: np.ndarray) -> np.ndarray:
        """The online search index f (Eq. 2.4)."""
        if self.sgn is not None:
            return control_index(self.sgn, x, self.x_d)
        return np.asarray(self.gradient(np.asarray(x, dtype=float), self.rho), dtype=float)

    def update(self, x: np.ndarray) -> np.ndarray:
        """One step of Eq. 2.13; returns the new ρ."""
        f = self.index(np.atleast_1d(np.asarray(x, dtype=float)))
        self.last_index = f
        proposal = self.rho - self.gain(f)
        if self.hold is not None and self.hold(proposal):
            self.held_steps += 1
        else:
            self.rho = proposal
        return self.rho


class SearchIndexModule(Module):
    """A :class:`SearchIndex` as a runtime module: reads x from the snapshot, writes ρ to a channel.

    ``x_of(snapshot)`` gives the search variable; ρ is contributed to ``channel`` (absolute, or as a
    difference from its initial value with ``as_difference=True`` — nervous-style modules add
    differences, seed 003 §6.3.4).
    """

    def __init__(self, index: SearchIndex, x_of: Callable[[Snapshot], np.ndarray], channel: str,
                 name: str = "search_index", period: float | None = None, as_difference: bool = False):
        super().__init__(name, period)
        self.index_law = index
        self.x_of = x_of
        self.channel = channel
        self.rho0 = index.rho.copy()
        self.as_difference = as_difference

    def update(self, snapshot: Snapshot):
        x = self.x_of(snapshot)
        rho = self.index_law.update(x)
        self.log(snapshot["t"], **{f"{self.name}.x": x, f"{self.name}.rho": rho,
                                   f"{self.name}.f": self.index_law.last_index})
        return {self.channel: rho - self.rho0 if self.as_difference else rho.copy()}
