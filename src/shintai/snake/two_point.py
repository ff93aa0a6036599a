"""Two-point simultaneous control with constraint switching — seed 001 ch. 3 (§3.2, eqs. (3.1)–(3.20)).

The head w̃_h and the tail wheel's axle centre w̃_t (second control point k = n, §3.2) are controlled
together through the model A_{c,σ} ċ_c = B_{c,σ} φ̇ (3.1)–(3.2). Each control period:

1. every t_σ (including t = 0, chosen, A9) the mode σ maximising V_m (3.19) over the pruned candidate
   set (§3.2.4) is selected — prediction horizon t_p = t_k, so J = V_m of each mode at the current state;
2. u_σ = u_c + u_v (3.3): pseudo-inverse tracking (3.4) plus a null-space term (3.5) climbing V_u (3.12);
3. input limit (3.20): if ‖u_σ‖ > u_lim the robot stops (u = 0) until a later selection picks a mode far
   from singular configuration II, after which it resumes (§3.2.5).

Candidate set (§3.2.4, spec §3.1, A8): the thesis states 66 candidates for n = 9, n_g = n_l = 4,
n_c = 2. Rules (i) tail wheel lifted, (ii') n_g ≤ n_σ ≤ n − n_l and (iii) runs of lifted wheels ≤ n_c give
80 when read literally; 66 results when the wheel-less head end counts as one more lifted element
(``head_end_lifted``, the default, see constants.TwoPointGains). Both are available and tested.

η (3.6) is computed analytically: V_{u,1} term directly, V_{u,2} and V_{u,3} by the chain rule through
∂A/∂φ, ∂B/∂φ, ∂J_{n,2}/∂φ (model.py's closed forms) and the gradient of a Gram determinant. The tick's
arithmetic — those matrices for one state and mode, η and (3.4)–(3.5) — is compiled in two_point_tick.py; the
SVDs stay NumPy's LAPACK calls (linalg.py). V_{u,2} uses the identity
det(A_{c,σ}^T A_{c,σ}) = det(A_σ^T A_σ) (Schur complement on the −I_3 block, spec §2.7).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import Module, whole_multiple
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, SnakeGeometry, TwoPointGains
from shintai.snake.linalg import singular_values, thin_svd
from shintai.snake.model import Configuration, check_mode, tail_pose
from shintai.snake.two_point_tick import gram_det_gradient_into, input_terms, objective_terms, stacked_matrices

_NO_SVD = np.zeros((1, 1)), np.zeros(1), np.zeros((1, 1))  # stands for the SVD of A_σ when k_{u,2} = 0 (not read)


def _vector(x, size: int, what: str) -> np.ndarray:
    """``x`` as a contiguous float64 vector of ``size`` numbers (what the compiled tick reads), or a clear error."""
    v = np.ascontiguousarray(x, dtype=float)
    if v.shape != (size,):
        raise ValueError(f"{what} ({size} numbers), got shape {v.shape}")
    return v


def candidate_modes(n: int, n_g: int, n_l: int, n_c: int, head_end_lifted: bool = True) -> np.ndarray:
    """Grounded patterns (rows, shape (m, n), True = grounded) kept by the two-stage pruning of §3.2.4.

    (i) the second control point's wheel (the tail wheel n) is lifted; (ii') n_g ≤ n_σ ≤ n − n_l;
    (iii) at most n_c adjacent wheels lifted in a row, the head end counted as a lifted element when
    ``head_end_lifted``. Rows are in increasing binary code, wheel 1 the least significant bit.
    """
    if not 1 <= n <= 20:
        raise ValueError(f"n must be in 1..20 to enumerate 2^n modes, got {n}")
    grounded = ((np.arange(2 ** n)[:, None] >> np.arange(n)) & 1).astype(bool)
    n_s = grounded.sum(axis=1)
    keep = ~grounded[:, -1] & (n_g <= n_s) & (n_s <= n - n_l)
    run = np.full(len(grounded), 1 if head_end_lifted else 0)
    longest = run.copy()
    for i in range(n):
        run = np.where(grounded[:, i], 0, run + 1)
        longest = np.maximum(longest, run)
    return grounded[keep & (longest <= n_c)]


def two_point_rows(grounded: np.ndarray) -> np.ndarray:
    """Rows of the all-grounded stacks [A, O; J_{n,1}, −I_3], [B; −J_{n,2}] that form A_{c,σ}, B_{c,σ} (2.15):
    the grounded wheels (T_σ, (2.11)), then the three rows of (2.13)."""
    n = len(grounded)
    return np.concatenate((np.flatnonzero(grounded), np.arange(n, n + 3)))


def joint_limit_objective(phi: np.ndarray, phi_th: float) -> tuple[float, np.ndarray]:
    """V_{u,1} = −Σ f(φ_th, |φ_k|) (3.13) with f (3.16), and its gradient ∂V_{u,1}/∂φ."""
    excess = np.maximum(np.abs(phi) - phi_th, 0.0)
    return -float(excess @ excess), -2.0 * excess * np.sign(phi)


def gram_det_gradient(X: np.ndarray, svd=None) -> tuple[float, np.ndarray]:
    """det of the small Gram matrix of X (X^T X if tall, X X^T if wide) and its gradient w.r.t. X.

    With X = U S V^T (thin SVD, or ``svd`` if the caller has it): det = Π s_i², ∂det/∂X =
    2 U diag(s_i Π_{j≠i} s_j²) V^T. This is 2 X adj(X^T X) (tall) or 2 adj(X X^T) X (wide), and stays
    finite at rank loss.
    """
    X = np.asarray(X, dtype=float)
    U, s, Vt = thin_svd(X) if svd is None else svd
    grad = np.empty(X.shape)
    return gram_det_gradient_into(U, s, Vt, grad), grad


@dataclass(frozen=True)
class Step:
    """What one call of :meth:`TwoPointLaw.input` computed (for logs and metrics)."""

    u: np.ndarray  # applied joint rates φ̇ after (3.20)
    u_norm: float  # ‖u_σ‖ before the limit
    stopped: bool  # (3.20) zeroed the input
    c_c: np.ndarray  # controlled variables [w̃_h; w̃_t] (3.2)
    sigma_a: float  # min singular value of A_{c,σ}
    sigma_b: float  # min singular value of B_{c,σ}
    V_m: float  # (3.19) of the current mode
    V_u: float  # (3.12)


class TwoPointLaw:
    """The control law of §3.2 for a snake ``geometry`` with ``gains``; second control point = tail wheel n."""

    def __init__(self, geometry: SnakeGeometry = CH3_ROBOT, gains: TwoPointGains = CH3_GAINS,
                 head_end_lifted: bool | None = None):
        self.geometry = geometry
        self.gains = gains
        head = gains.head_end_lifted if head_end_lifted is None else head_end_lifted
        self.candidates = candidate_modes(geometry.n, gains.n_g, gains.n_l, gains.n_c, head)
        if len(self.candidates) == 0:
            raise ValueError("no candidate mode satisfies (i), (ii') and (iii) for these n, n_g, n_l, n_c")
        # The rows of every candidate, grouped by n_σ so that all candidates of one size are evaluated by
        # one batched SVD (built once; §3.2.4's point is the cost of this search).
        n = geometry.n
        self._all_rows = two_point_rows(np.ones(n, dtype=bool))
        self._rows: dict[bytes, np.ndarray] = {}  # two_point_rows per grounded pattern, built when first used
        sizes = self.candidates.sum(axis=1)
        self._groups = []
        for size in np.unique(sizes):
            members = np.flatnonzero(sizes == size)
            self._groups.append((members, np.array([two_point_rows(self.candidates[i]) for i in members])))
        # two_point_tick's buffers: A_{c,σ}, B_{c,σ}, A_σ, ∂A_σ/∂φ, ∂B_{c,σ}/∂φ, c_c; filled again every call
        self._A_c, self._B_c, self._A_s = np.zeros((n + 3, 6)), np.zeros((n + 3, n)), np.zeros((n, 3))
        self._dA_s, self._dB_c, self._c_c = np.zeros((n, n, 3)), np.zeros((n, n + 3, n)), np.zeros(6)
        self._derivatives = (gains.k_u[1] != 0.0, gains.k_u[2] != 0.0)  # which of ∂A, ∂B η needs (3.6)
        self._k_u = np.array(gains.k_u, dtype=float)

    def controlled(self, cfg: Configuration) -> np.ndarray:
        """c_c = [w̃_h; w̃_t] (3.2); w̃_t from the forward kinematics (2.3)–(2.5)."""
        return np.concatenate((cfg.w_h, tail_pose(cfg)))

    def _state(self, w_h, phi) -> tuple[np.ndarray, np.ndarray]:
        n = self.geometry.n
        return _vector(w_h, 3, "w_h must be [x_h, y_h, theta_h]"), _vector(phi, n, "phi must hold the yaw angles")

    def _matrices(self, w_h, phi, rows, derivatives=(False, False)):
        """A_{c,σ}, B_{c,σ} (2.15) of ``rows`` (views of the buffers) and A_σ, filled by two_point_tick at (w̃_h, φ)."""
        stacked_matrices(w_h, phi, self.geometry.l, rows, self._A_c, self._B_c, self._A_s, self._dA_s, self._dB_c,
                         self._c_c, derivatives)
        r = len(rows)
        return self._A_c[:r], self._B_c[:r], self._A_s[:r - 3]

    def _mode_rows(self, grounded) -> np.ndarray:
        grounded = check_mode(grounded, self.geometry.n)
        key = grounded.tobytes()
        rows = self._rows.get(key)
        if rows is None:
            rows = self._rows[key] = two_point_rows(grounded)
        return rows

    def mode_objectives(self, w_h, phi) -> np.ndarray:
        """V_m (3.19) of every candidate at the state (w̃_h, φ), shape (len(candidates),)."""
        A_full, B_full, _ = self._matrices(*self._state(w_h, phi), self._all_rows)
        k_m1, k_m2 = self.gains.k_m
        V = np.zeros(len(self.candidates))
        for members, rows in self._groups:
            if k_m2:
                V[members] += k_m2 * singular_values(B_full[rows])[:, -1]
            if k_m1:
                V[members] += k_m1 * singular_values(A_full[rows])[:, -1]
        return V

    def select_mode(self, w_h, phi) -> tuple[int, np.ndarray]:
        """Index of the candidate maximising V_m (3.17)–(3.19) with t_p = t_k; ties go to the lowest index."""
        V = self.mode_objectives(w_h, phi)
        return int(np.argmax(V)), V

    def input(self, w_h, phi, grounded, c_d, c_d_dot) -> Step:
        """u_σ = u_c + u_v (3.3)–(3.6) for mode ``grounded``, then the input limit (3.20)."""
        g = self.gains
        w_h, phi = self._state(w_h, phi)
        A_c, B_c, A_s = self._matrices(w_h, phi, self._mode_rows(grounded), self._derivatives)
        svd_b = thin_svd(B_c)
        V_u, eta = self._objective(phi, A_s, svd_b)
        u = np.empty(len(phi))
        u_norm = input_terms(A_c, svd_b, eta, self._c_c, _vector(c_d, 6, "c_d must be [w_h; w_t]"),
                             _vector(c_d_dot, 6, "c_d_dot must be [w_h; w_t] rates"), float(g.k_p), float(g.k_v), u)
        stopped = u_norm > g.u_lim  # (3.20)
        sigma_a = float(singular_values(A_c)[-1])
        sigma_b = float(svd_b[1][-1])
        V_m = g.k_m[0] * sigma_a + g.k_m[1] * sigma_b
        return Step(np.zeros_like(u) if stopped else u, u_norm, bool(stopped), self._c_c.copy(), sigma_a, sigma_b,
                    V_m, V_u)

    def objective(self, w_h, phi, grounded) -> tuple[float, np.ndarray]:
        """V_u (3.12)–(3.16) of mode ``grounded`` at (w̃_h, φ) and its gradient η = ∂V_u/∂φ (3.6)."""
        w_h, phi = self._state(w_h, phi)
        _, B_c, A_s = self._matrices(w_h, phi, self._mode_rows(grounded), self._derivatives)
        return self._objective(phi, A_s, thin_svd(B_c))

    def _objective(self, phi, A_s, svd_b) -> tuple[float, np.ndarray]:
        eta = np.empty(len(phi))
        svd_a = thin_svd(A_s) if self._derivatives[0] else _NO_SVD
        V_u = objective_terms(phi, float(self.gains.phi_th), self._k_u, svd_a, self._dA_s, svd_b, self._dB_c, eta)
        return float(V_u), eta


_LOGGED = ("selected", "V_m_best", "c", "c_d", "mode", "grounded", "phi", "u_norm", "stopped", "sigma_a", "sigma_b",
           "V_m", "V_u", "slip")  # the controller's signals, logged as <name>.<signal>


class TwoPointController(Module):
    """The law of §3.2 as a :class:`~shintai.core.Module` running every δt (Fig. 3.2).

    Reads ``w_h``, ``phi`` from the snapshot; contributes ``{"phi_dot": u_σ, "grounded": σ}`` (lifting is a
    command). Mode selection runs at t = 0 and then every ``select_period`` s (t_σ); ``None`` freezes the
    mode chosen at t = 0 (the ablation of §3.1's claim). Logs ``<name>.*`` signals each period.
    """

    def __init__(self, law: TwoPointLaw, target, select_period: float | None = CH3_GAINS.t_sigma,
                 name: str = "two_point"):
        super().__init__(name, period=law.gains.dt)
        self.law = law
        self.target = target
        self.select_every = None if select_period is None else whole_multiple(select_period, law.gains.dt,
                                                                              "select_period")
        self.mode = 0
        self.calls = 0
        self.selections = 0
        self._keys = {k: f"{name}.{k}" for k in _LOGGED}  # signal names, built once

    def reset(self, snapshot) -> None:
        self.calls = 0
        self.selections = 0

    def update(self, snapshot):
        t = float(snapshot["t"])
        w_h, phi = snapshot["w_h"], snapshot["phi"]
        key = self._keys
        if self.calls == 0 or (self.select_every and self.calls % self.select_every == 0):
            self.mode, V_all = self.law.select_mode(w_h, phi)
            self.selections += 1
            self.log(t, **{key["selected"]: self.mode, key["V_m_best"]: V_all[self.mode]})
        self.calls += 1
        grounded = self.law.candidates[self.mode]
        c_d, c_d_dot = self.target(t)
        step = self.law.input(w_h, phi, grounded, c_d, c_d_dot)
        self.log(t, **{key["c"]: step.c_c, key["c_d"]: c_d, key["mode"]: self.mode, key["grounded"]: grounded,
                       key["phi"]: phi, key["u_norm"]: step.u_norm, key["stopped"]: step.stopped,
                       key["sigma_a"]: step.sigma_a, key["sigma_b"]: step.sigma_b, key["V_m"]: step.V_m,
                       key["V_u"]: step.V_u, key["slip"]: snapshot["slip"]})
        return {"phi_dot": step.u, "grounded": grounded.astype(float)}


class ModeSelection(Module):
    """Mode selection of §3.2.4 alone (step 1 above): the candidate maximising V_m (3.19) at t = 0 and every
    ``select_period`` s, written to the ``grounded`` set channel — for a joint-rate command from elsewhere
    (a learning agent, :mod:`shintai.gym`). ``select_period=None`` keeps the mode chosen at t = 0."""

    def __init__(self, law: TwoPointLaw, select_period: float | None = CH3_GAINS.t_sigma, name: str = "modes"):
        super().__init__(name, period=law.gains.dt)
        self.law = law
        self.select_every = None if select_period is None else whole_multiple(select_period, law.gains.dt,
                                                                              "select_period")
        self.calls, self.mode = 0, 0

    def reset(self, snapshot) -> None:
        self.calls = 0

    def update(self, snapshot):
        if self.calls == 0 or (self.select_every and self.calls % self.select_every == 0):
            self.mode, _ = self.law.select_mode(snapshot["w_h"], snapshot["phi"])
        self.calls += 1
        return {"grounded": self.law.candidates[self.mode].astype(float)}
