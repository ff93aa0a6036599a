"""Muscle length → posture, f of eq. (4.3), for a spine's geometric model (seed 003 §4.4.3).

Two methods, both taught by the posture → length model q = f⁻¹(θ) of eq. (4.25)
(:class:`shintai.spine.geometry.SpineModel`):

**Jacobian integration** (eqs. 4.26–4.28, rejected by the thesis). From θ₀ with lengths q₀,

    θ = θ₀ + Σ_{i=1..n} J_m(θ_{i−1})⁺ δq,   δq = (q − q₀)/n,   θ_i = θ_{i−1} + J_m(θ_{i−1})⁺ δq

with n = int(|q − q₀| [mm]) divisions (§4.4.3). Eq. (4.27) prints δq = (q − q₀)/(n − 1) with n
terms, which overshoots q by 1/(n − 1), and (4.28) is a garbled recursion on J_m; chosen: n equal
steps that end exactly at q, J_m re-evaluated at every θ_i by the thesis's numerical
differentiation (4.15) (``SpineModel.jacobian_fd``), J_m⁺ the SVD pseudo-inverse (min-norm δθ, 4.16).

The pseudo-inverse needs a rank threshold. Cla's 8 muscles run block to block, so J_m (8 × 15) has
rank ≤ 6; differenced, its "zero" singular values are ~1e-11 of noise, and a pseudo-inverse at
machine precision (NumPy's default) inverts that noise and diverges by orders of magnitude — one
plausible cause of the thesis's ±360° results (Table 4.2). :data:`PINV_RCOND` treats singular values
below 1e-6 of the largest as zero (chosen: far above the difference noise, far below the ~0.05
of the true directions); ``rcond=None`` is NumPy's default, kept to show the divergence.

**Neural network** (eqs. 4.29–4.31, adopted). Teacher: the uniform-bend postures (4.29) with
φ, θ, ψ ∈ {−15, −10, …, 15}° per joint, 7³ = 343 samples, and their lengths by (4.25). Input: the
m lengths, output: the 3n joint angles, both normalised; sigmoid units O = 1/(1 + e^{−λu}) with a
bias unit (the k = 0 term of 4.31); error E = ½ Σ (T_j − O_j)² (mean over the patterns).
Back-propagation gives ∂E/∂W through the deltas of eq. (4.31). Two trainers on that one loss:

* ``"backprop"`` — the thesis's plain update W ← W + η δ_j O_i (4.30), batch form (the pattern
  updates averaged), fixed gain η;
* ``"lbfgs"`` — scipy.optimize L-BFGS-B on the same E with the same back-propagated gradient
  (default: it reaches the thesis's accuracy in seconds, where plain back-propagation needs
  ~10⁵ epochs).

A spine of other joint ranges is taught the same way on its own 7-point grid (``grid_deg``; Kenta's: ±9°,
inside its ±10° stops, §3.7.1). As in the thesis the network kept is the one with the smallest training error norm seen during
training (Table 4.3, "minimum of the error norm"). Errors are Euclidean norms over the 3n joint
angles in degrees (§4.4.3 reasons for the norm).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize

from shintai.spine.geometry import SpineModel
from shintai.spine.robots import GRID_DEG, INPUT_RANGE, PINV_RCOND, TARGET_RANGE, TEST_LIMIT_DEG


# ------------------------------------------------------------------------------------ postures

def uniform_bend(per_joint, n: int) -> np.ndarray:
    """Eq. (4.29): every joint bends by the same (φ, θ, ψ). (..., 3) per joint → (..., 3n)."""
    return np.tile(np.asarray(per_joint, dtype=float), n)


def training_postures(n: int, grid_deg=GRID_DEG) -> np.ndarray:
    """The 7³ = 343 uniform-bend teacher postures of §4.4.3, (343, 3n) radians, φ slowest."""
    g = np.radians(np.asarray(grid_deg, dtype=float))
    per_joint = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
    return uniform_bend(per_joint, n)


def random_postures(n: int, count: int, rng: np.random.Generator, limit_deg: float = TEST_LIMIT_DEG) -> np.ndarray:
    """``count`` random uniform-bend postures, each axis uniform in ±limit per joint (§4.4.3 test)."""
    return uniform_bend(np.radians(rng.uniform(-limit_deg, limit_deg, (count, 3))), n)


def error_norm_deg(theta, truth) -> np.ndarray:
    """‖θ − θ_true‖ over the 3n joint angles, in degrees (the thesis's error measure)."""
    return np.degrees(np.linalg.norm(np.asarray(theta) - np.asarray(truth), axis=-1))


# ------------------------------------------------------------------------------------ the network

@dataclass(frozen=True)
class Normaliser:
    """Per-column affine map of [lo, hi] onto [a, b] (and back)."""

    lo: np.ndarray
    hi: np.ndarray
    a: float
    b: float

    @classmethod
    def fit(cls, data: np.ndarray, target: tuple[float, float]) -> Normaliser:
        lo, hi = data.min(axis=0), data.max(axis=0)
        if np.any(hi <= lo):
            raise ValueError("Normaliser: a column of the teacher data is constant")
        return cls(lo, hi, *target)

    def forward(self, x) -> np.ndarray:
        return self.a + (self.b - self.a) * (np.asarray(x) - self.lo) / (self.hi - self.lo)

    def inverse(self, y) -> np.ndarray:
        return self.lo + (np.asarray(y) - self.a) / (self.b - self.a) * (self.hi - self.lo)


def with_bias(x: np.ndarray) -> np.ndarray:
    """Prepend the constant unit O_0 = 1 (the k = 0 term of eq. 4.31)."""
    return np.hstack((np.ones((x.shape[0], 1)), x))


class MLP:
    """Layered sigmoid network; ``weights[l]`` is (inputs + 1, outputs), row 0 the bias weights."""

    def __init__(self, sizes, rng: np.random.Generator, slope: float = 1.0):
        self.sizes = tuple(int(s) for s in sizes)
        self.slope = slope  # λ of eq. (4.31); the thesis prints "(1.0)"
        self.weights = [rng.uniform(-1.0, 1.0, (a + 1, b)) / np.sqrt(a + 1)  # chosen: ±1/√fan-in
                        for a, b in zip(self.sizes[:-1], self.sizes[1:])]

    @property
    def name(self) -> str:
        return "-".join(map(str, self.sizes))

    def forward(self, x: np.ndarray) -> list[np.ndarray]:
        """Outputs O of every layer, input first."""
        out = [np.atleast_2d(x)]
        for W in self.weights:
            out.append(1.0 / (1.0 + np.exp(-self.slope * (with_bias(out[-1]) @ W))))
        return out

    def predict(self, x: np.ndarray) -> np.ndarray:
        return self.forward(x)[-1]

    def loss_and_gradient(self, x: np.ndarray, t: np.ndarray) -> tuple[float, list[np.ndarray]]:
        """E = ½ mean_p Σ_j (T_j − O_j)² and ∂E/∂W by back-propagation (deltas of eq. 4.31)."""
        outs = self.forward(x)
        O = outs[-1]
        delta = self.slope * O * (1.0 - O) * (t - O)  # output layer
        grads = [np.empty(0)] * len(self.weights)
        for layer in range(len(self.weights) - 1, -1, -1):
            grads[layer] = -with_bias(outs[layer]).T @ delta / len(x)
            if layer:
                hidden = outs[layer]
                delta = self.slope * hidden * (1.0 - hidden) * (delta @ self.weights[layer][1:].T)
        return 0.5 * float(np.sum((t - O) ** 2)) / len(x), grads

    def flat(self) -> np.ndarray:
        return np.concatenate([W.ravel() for W in self.weights])

    def set_flat(self, w: np.ndarray) -> None:
        i = 0
        for k, W in enumerate(self.weights):
            self.weights[k] = np.asarray(w[i:i + W.size], dtype=float).reshape(W.shape).copy()
            i += W.size


@dataclass
class LearningCurve:
    """Training error norm (and optional test error norm) [deg] against iteration/epoch."""

    iterations: list = field(default_factory=list)
    train_deg: list = field(default_factory=list)
    test_deg: list = field(default_factory=list)
    best_iteration: int = 0
    best_train_deg: float = float("inf")


def train(net: MLP, x: np.ndarray, t: np.ndarray, train_error: Callable[[MLP], float],
          method: str = "lbfgs", iterations: int = 2000, eta: float = 10.0, record_every: int = 10,
          test_error: Callable[[MLP], float] | None = None) -> LearningCurve:
    """Train ``net`` on (x, t); keep the weights with the smallest ``train_error`` (Table 4.3).

    ``method``: "lbfgs" (iterations = L-BFGS iterations) or "backprop" (iterations = epochs of eq.
    4.30 with gain ``eta``). ``train_error(net)`` is the error norm in degrees; it is recorded every
    ``record_every`` iterations, with ``test_error(net)`` if given.

    η = 10 by default (chosen: the thesis prints one "(1.0)", read here as λ; with the pattern
    updates averaged over the 343 patterns, η = 1 would learn ~10× slower than the thesis's
    per-pattern updates).
    """
    if method not in ("lbfgs", "backprop"):
        raise ValueError(f"train: method must be 'lbfgs' or 'backprop', got {method!r}")
    curve = LearningCurve()
    best = net.flat()

    def record(k: int) -> None:
        nonlocal best
        err = train_error(net)
        curve.iterations.append(k)
        curve.train_deg.append(err)
        if test_error is not None:
            curve.test_deg.append(test_error(net))
        if err < curve.best_train_deg:
            curve.best_train_deg, curve.best_iteration, best = err, k, net.flat()

    record(0)
    if method == "backprop":
        for epoch in range(1, iterations + 1):
            _, grads = net.loss_and_gradient(x, t)
            net.weights = [W - eta * g for W, g in zip(net.weights, grads)]  # (4.30): W += η δ O
            if epoch % record_every == 0:
                record(epoch)
    else:
        def fun(w):
            net.set_flat(w)
            loss, grads = net.loss_and_gradient(x, t)
            return loss, np.concatenate([g.ravel() for g in grads])

        count = [0]

        def callback(w):
            count[0] += 1
            if count[0] % record_every == 0:
                net.set_flat(w)
                record(count[0])

        minimize(fun, net.flat(), jac=True, method="L-BFGS-B", callback=callback,
                 options={"maxiter": iterations, "maxfun": 2 * iterations, "ftol": 0.0, "gtol": 0.0})
    net.set_flat(best)
    return curve


class NeuralInverse:
    """q → θ by a sigmoid network trained on the 343 uniform-bend postures of ``model`` (§4.4.3), per joint and
    axis on ``grid_deg`` (the thesis's Cla grid by default; a spine of other joint ranges passes its own)."""

    def __init__(self, model: SpineModel, hidden=(40,), rng: np.random.Generator | None = None, slope: float = 1.0,
                 grid_deg=GRID_DEG):
        self.model = model
        self.theta = training_postures(model.n, grid_deg)
        self.q = model.lengths(self.theta)
        self.x_scale = Normaliser.fit(self.q, INPUT_RANGE)
        self.y_scale = Normaliser.fit(self.theta, TARGET_RANGE)
        rng = rng if rng is not None else np.random.default_rng(0)
        self.net = MLP((model.m, *hidden, 3 * model.n), rng, slope)
        self.curve = LearningCurve()

    def posture(self, q) -> np.ndarray:
        """θ (…, 3n) [rad] from muscle lengths q (…, m) [m]."""
        q = np.asarray(q, dtype=float)
        out = self.y_scale.inverse(self.net.predict(self.x_scale.forward(q.reshape(-1, q.shape[-1]))))
        return out.reshape(q.shape[:-1] + (out.shape[-1],))

    def errors_deg(self, theta, q=None) -> np.ndarray:
        """Per-posture error norms [deg] of the network on postures ``theta`` (lengths ``q``, by 4.25 if None)."""
        return error_norm_deg(self.posture(self.model.lengths(theta) if q is None else q), theta)

    def fit(self, method: str = "lbfgs", iterations: int = 2000, eta: float = 10.0, record_every: int = 10,
            test_theta: np.ndarray | None = None) -> LearningCurve:
        """Train on the 343 postures; the learning curve records the mean error norms [deg]."""
        x, t = self.x_scale.forward(self.q), self.y_scale.forward(self.theta)
        test = None
        if test_theta is not None:
            test_q = self.model.lengths(test_theta)
            test = lambda net: float(self.errors_deg(test_theta, test_q).mean())  # noqa: E731
        self.curve = train(self.net, x, t, lambda net: float(self.errors_deg(self.theta, self.q).mean()), method,
                           iterations, eta, record_every, test)
        return self.curve

    def training_max_joint_error_deg(self) -> float:
        """Largest single-joint error on the teacher postures (thesis: < about 0.5° for 8-40-15)."""
        return float(np.degrees(np.abs(self.posture(self.q) - self.theta).max()))


# ------------------------------------------------------------------------------ Jacobian integration

@dataclass(frozen=True)
class JacobianIntegration:
    theta: np.ndarray  # (3n,) result
    divisions: int
    seconds: float  # wall time of the integration
    length_residual_m: float  # ‖q(θ) − q‖ at the result


def default_divisions(q, q0) -> int:
    """n = integer part of |q − q₀| with q in mm (§4.4.3), at least 1."""
    return max(1, int(1e3 * np.linalg.norm(np.asarray(q) - np.asarray(q0))))


def jacobian_integration(model: SpineModel, q, theta0=None, divisions: int | None = None,
                         rcond: float | None = PINV_RCOND) -> JacobianIntegration:
    """θ from lengths q by integrating J_m⁺ dq from θ₀ (default: straight), eqs. (4.26)–(4.28).

    ``rcond``: singular values of J_m below rcond·σ_max are dropped; None = NumPy's default.
    """
    t0 = time.perf_counter()
    theta = np.zeros(3 * model.n) if theta0 is None else np.array(theta0, dtype=float)
    q = np.asarray(q, dtype=float)
    q0 = model.lengths(theta)
    n = default_divisions(q, q0) if divisions is None else int(divisions)
    if n < 1:
        raise ValueError(f"jacobian_integration: divisions must be ≥ 1, got {n}")
    dq = (q - q0) / n
    pinv = np.linalg.pinv if rcond is None else (lambda J: np.linalg.pinv(J, rcond=rcond))
    for _ in range(n):
        theta = theta + pinv(model.jacobian_fd(theta)) @ dq
    seconds = time.perf_counter() - t0
    return JacobianIntegration(theta, n, seconds, float(np.linalg.norm(model.lengths(theta) - q)))
