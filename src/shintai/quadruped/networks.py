"""Gaussian RBF networks with flat genomes for a GA (seed §4 eqs. 7-8, §5).

φ_i(x) = exp(-||x - c_i||² / σ_i²) (7), o_j = Σ_i w_ij φ_i(x) (8): one centre vector and one width
per hidden unit, linear outputs, no bias.

* The **action network** (24 → 100 → 3) maps the state of seed §4 — feet (x, y) in the body frame,
  Zr, the right and left obstacle features, and the destination error (x_de, y_de, θ_de) — to the
  cycle's body displacement (ΔXr, ΔYr, Δθr) in metres and radians. The paper feeds the inputs raw
  (its sentinels are in metres); here each is scaled to [-1, 1] over its span
  (``constants.ACTION_INPUT_SPANS``, chosen) before eq. (7), so that the few inputs that tell the
  wall's side weigh as much in ||x - c_i|| as the destination's 2 m (``normalise=False`` feeds them
  raw). Its genome is every design parameter: ``[centres (100 x 24), widths (100), weights
  (100 x 3)]`` (seed §4.1.2); :meth:`ActionNetwork.genomes_on_data` draws the GA's first population
  with the centres on inputs the robot meets.
* The **swing-order network** (4 → ORDER_HIDDEN → 24) maps (Zr, ΔXr, ΔYr, Δθr), each scaled to
  [-1, 1] over the teacher ranges of seed §5.1 (chosen: the paper gives the ranges but mixes mm and
  deg), to one output per order of Table 2; the order is the unit whose output is closest to 1. The
  paper's GA tunes only its centres and widths (seed §5.1), so its genome is
  ``[centres (h x 4), widths (h)]`` and the weights are the least-squares fit to the teacher set
  (the paper's stated reason for choosing an RBF network, seed §4).

Everything is batched over a leading axis of k genomes, so that a GA can evaluate a population in
one call.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import swing_order as S


def rbf_hidden(centres: np.ndarray, sigmas: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Eq. (7) for k networks: centres ``(k, m, n)``, widths ``(k, m)``, inputs ``(k, N, n)`` →
    ``(k, N, m)``. Widths are used as |σ| floored at ``SIGMA_FLOOR`` so any genome is finite."""
    d2 = np.einsum("kNn,kmn->kNm", x, centres)  # then in place (the operations of the formula, in its order):
    d2 *= 2  # ||x||² - 2 x.c + ||c||²
    np.subtract(np.sum(x * x, -1)[..., None], d2, out=d2)
    d2 += np.sum(centres * centres, -1)[:, None, :]
    s2 = np.maximum(np.abs(sigmas), C.SIGMA_FLOOR)[:, None, :] ** 2
    np.maximum(d2, 0.0, out=d2)  # exp(-max(d2, 0) / s2)
    np.negative(d2, out=d2)
    np.divide(d2, s2, out=d2)
    return np.exp(d2, out=d2)


def as_genomes(genomes, size: int, name: str) -> np.ndarray:
    """Genomes as a ``(k, size)`` float array (one genome ``(size,)`` becomes ``(1, size)``)."""
    g = np.asarray(genomes, dtype=float)
    g = g[None] if g.ndim == 1 else g
    if g.ndim != 2 or g.shape[1] != size:
        raise ValueError(f"{name}: genomes must have {size} genes (shape (k, {size})), got {np.shape(genomes)}")
    return g


def scale_inputs(x: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """Inputs mapped affinely so that ``low`` goes to -1 and ``high`` to +1 (per input)."""
    return 2 * (np.asarray(x, dtype=float) - low) / (high - low) - 1


class _GenomeBounds:
    """Per-gene ``(lo, hi)`` of a network's flat genome from its parts ``(count, (lo, hi))``."""

    def parts(self) -> list[tuple[int, tuple]]:
        raise NotImplementedError

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Per-gene ``(lo, hi)`` for initialising and mutating a population (ranges in constants)."""
        parts = self.parts()
        lo = np.concatenate([np.broadcast_to(np.asarray(r[0], dtype=float), (k,)) for k, r in parts])
        hi = np.concatenate([np.broadcast_to(np.asarray(r[1], dtype=float), (k,)) for k, r in parts])
        return lo, hi

    def random_genomes(self, rng: np.random.Generator, k: int) -> np.ndarray:
        """``k`` genomes uniform in :meth:`bounds`."""
        lo, hi = self.bounds()
        return rng.uniform(lo, hi, size=(k, lo.size))


ACTION_LOW = np.array([r[0] for r in C.ACTION_INPUT_SPANS])
ACTION_HIGH = np.array([r[1] for r in C.ACTION_INPUT_SPANS])


def scale_action_inputs(x: np.ndarray) -> np.ndarray:
    """The 24 action inputs [m, rad] → [-1, 1] over ``ACTION_INPUT_SPANS``."""
    return scale_inputs(x, ACTION_LOW, ACTION_HIGH)


@dataclass(frozen=True)
class ActionNetwork(_GenomeBounds):
    """The action RBF network of seed §4 (24 → 100 → 3) over flat genomes.

    With ``normalise`` (the default, ``ACTION_NORMALISE``) eq. (7) compares centres with the inputs
    scaled to [-1, 1] over ``ACTION_INPUT_SPANS``; without it, with the raw inputs as the paper feeds
    them (the gene ranges follow: ``ACTION_*_RANGE`` or ``ACTION_RAW_*_RANGE``).
    """

    n_in: int = C.ACTION_INPUTS
    n_hidden: int = C.ACTION_HIDDEN
    n_out: int = C.ACTION_OUTPUTS
    normalise: bool = C.ACTION_NORMALISE

    @property
    def size(self) -> int:
        return self.n_hidden * (self.n_in + 1 + self.n_out)

    def decode(self, genomes) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Genomes ``(k, size)`` or ``(size,)`` → centres ``(k, m, n)``, widths ``(k, m)``, weights ``(k, m, 3)``."""
        g = as_genomes(genomes, self.size, "ActionNetwork")
        m, n = self.n_hidden, self.n_in
        return (g[:, :m * n].reshape(-1, m, n), g[:, m * n:m * (n + 1)],
                g[:, m * (n + 1):].reshape(-1, m, self.n_out))

    def encode(self, centres: np.ndarray, sigmas: np.ndarray, weights: np.ndarray) -> np.ndarray:
        """One flat genome from ``centres (m, n)``, ``sigmas (m,)``, ``weights (m, 3)``."""
        return np.concatenate([np.ravel(centres), np.ravel(sigmas), np.ravel(weights)]).astype(float)

    def forward(self, genomes, x: np.ndarray) -> np.ndarray:
        """Eq. (8): outputs ``(k, N, 3)`` (ΔXr [m], ΔYr [m], Δθr [rad]) for inputs ``x (k, N, 24)``."""
        centres, sigmas, weights = self.decode(genomes)
        x = scale_action_inputs(x) if self.normalise else x
        return np.einsum("kNm,kmo->kNo", rbf_hidden(centres, sigmas, x), weights)

    def genomes_on_data(self, rng: np.random.Generator, k: int, inputs: np.ndarray) -> np.ndarray:
        """``k`` genomes with their centres on rows of ``inputs (N, 24)`` (unscaled; drawn with
        replacement), widths uniform in ``ACTION_INIT_SIGMA_RANGE`` and weights uniform in
        ±``ACTION_INIT_WEIGHT`` (the initial population of constants), clipped to :meth:`bounds`."""
        m = self.n_hidden
        points = scale_action_inputs(inputs) if self.normalise else np.asarray(inputs, dtype=float)
        centres = points[rng.integers(0, len(points), size=(k, m))]
        sigmas = rng.uniform(*C.ACTION_INIT_SIGMA_RANGE, size=(k, m))
        weights = rng.uniform(-1.0, 1.0, size=(k, m, self.n_out)) * np.array(C.ACTION_INIT_WEIGHT)
        genomes = np.concatenate([centres.reshape(k, -1), sigmas, weights.reshape(k, -1)], axis=1)
        return np.clip(genomes, *self.bounds())

    def parts(self) -> list[tuple[int, tuple]]:
        m, n = self.n_hidden, self.n_in
        centre, sigma = ((C.ACTION_CENTRE_RANGE, C.ACTION_SIGMA_RANGE) if self.normalise
                         else (C.ACTION_RAW_CENTRE_RANGE, C.ACTION_RAW_SIGMA_RANGE))
        weight = np.tile(np.array(C.ACTION_WEIGHT_RANGE, dtype=float).T, (1, m)) if self.normalise \
            else C.ACTION_RAW_WEIGHT_RANGE
        return [(m * n, centre), (m, sigma), (m * self.n_out, weight)]


ORDER_LOW, ORDER_HIGH = S.TEACHER_LOW, S.TEACHER_HIGH


def scale_order_inputs(x: np.ndarray) -> np.ndarray:
    """(Zr [m], ΔXr [m], ΔYr [m], Δθr [rad]) → [-1, 1] over the teacher ranges of seed §5.1."""
    return scale_inputs(x, ORDER_LOW, ORDER_HIGH)


@dataclass(frozen=True)
class SwingOrderNetwork(_GenomeBounds):
    """The swing-order RBF network of seed §5 (4 → h → 24); genome = centres and widths."""

    n_hidden: int = C.ORDER_HIDDEN
    n_in: int = C.ORDER_INPUTS
    n_out: int = C.ORDER_OUTPUTS

    @property
    def size(self) -> int:
        return self.n_hidden * (self.n_in + 1)

    def decode(self, genomes) -> tuple[np.ndarray, np.ndarray]:
        g = as_genomes(genomes, self.size, "SwingOrderNetwork")
        m, n = self.n_hidden, self.n_in
        return g[:, :m * n].reshape(-1, m, n), g[:, m * n:]

    def hidden(self, genomes, x: np.ndarray) -> np.ndarray:
        """Hidden outputs ``(k, N, h)`` for unscaled inputs ``x (N, 4)``."""
        centres, sigmas = self.decode(genomes)
        xs = np.broadcast_to(scale_order_inputs(x), (len(centres),) + np.shape(x))
        return rbf_hidden(centres, sigmas, xs)

    def fit_weights(self, genomes, teacher: S.TeacherSet) -> np.ndarray:
        """Least-squares output weights ``(k, h, 24)`` of each genome on the teacher set."""
        phi = self.hidden(genomes, teacher.x)
        return np.linalg.pinv(phi) @ teacher.target

    def outputs(self, genomes, teacher: S.TeacherSet, x: np.ndarray) -> np.ndarray:
        """Outputs ``(k, N, 24)`` at ``x`` with the weights fitted to ``teacher``."""
        return self.hidden(genomes, x) @ self.fit_weights(genomes, teacher)

    def parts(self) -> list[tuple[int, tuple]]:
        return [(self.n_hidden * self.n_in, C.ORDER_CENTRE_RANGE), (self.n_hidden, C.ORDER_SIGMA_RANGE)]

    def trained(self, genome, teacher: S.TeacherSet) -> SwingOrderPolicy:
        """The network of one genome with its fitted weights, as a swing-order policy."""
        centres, sigmas = self.decode(genome)
        return SwingOrderPolicy(centres[0], sigmas[0], self.fit_weights(genome, teacher)[0])


def choose_order(outputs: np.ndarray) -> np.ndarray:
    """Seed §5: the order whose output unit is closest to 1."""
    return np.argmin(np.abs(outputs - 1.0), axis=-1)


@dataclass(frozen=True)
class SwingOrderPolicy:
    """A trained swing-order network: ``policy(zr (n,), command (n, 3))`` → Table 2 numbers ``(n,)``."""

    centres: np.ndarray
    sigmas: np.ndarray
    weights: np.ndarray

    def __call__(self, zr: np.ndarray, command: np.ndarray) -> np.ndarray:
        x = scale_order_inputs(np.column_stack([zr, command]))[None]
        phi = rbf_hidden(self.centres[None], self.sigmas[None], x)[0]
        return choose_order(phi @ self.weights)
