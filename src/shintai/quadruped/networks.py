"""Gaussian RBF networks with flat genomes for a GA (seed §4 eqs. 7-8, §5).

φ_i(x) = exp(-||x - c_i||² / σ_i²) (7), o_j = Σ_i w_ij φ_i(x) (8): one centre vector and one width
per hidden unit, linear outputs, no bias.

* The **action network** (24 → 100 → 3) maps the state of seed §4 — feet (x, y) in the body frame,
  Zr, the right and left obstacle features, and the destination error (x_de, y_de, θ_de) — to the
  cycle's body displacement (ΔXr, ΔYr, Δθr). Inputs are fed raw in metres and radians as in the
  paper (its sentinels are in metres); outputs are metres and radians. Its genome is every design
  parameter: ``[centres (100 x 24), widths (100), weights (100 x 3)]`` (seed §4.1.2).
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
    d2 = (np.sum(x * x, -1)[..., None] - 2 * np.einsum("kNn,kmn->kNm", x, centres)
          + np.sum(centres * centres, -1)[:, None, :])
    s2 = np.maximum(np.abs(sigmas), C.SIGMA_FLOOR)[:, None, :] ** 2
    return np.exp(-np.maximum(d2, 0.0) / s2)


def as_genomes(genomes, size: int, name: str) -> np.ndarray:
    """Genomes as a ``(k, size)`` float array (one genome ``(size,)`` becomes ``(1, size)``)."""
    g = np.asarray(genomes, dtype=float)
    g = g[None] if g.ndim == 1 else g
    if g.ndim != 2 or g.shape[1] != size:
        raise ValueError(f"{name}: genomes must have {size} genes (shape (k, {size})), got {np.shape(genomes)}")
    return g


@dataclass(frozen=True)
class ActionNetwork:
    """The action RBF network of seed §4 (24 → 100 → 3) over flat genomes."""

    n_in: int = C.ACTION_INPUTS
    n_hidden: int = C.ACTION_HIDDEN
    n_out: int = C.ACTION_OUTPUTS

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
        return np.einsum("kNm,kmo->kNo", rbf_hidden(centres, sigmas, x), weights)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Per-gene ``(lo, hi)`` for initialising and mutating a population (ranges in constants)."""
        m, n = self.n_hidden, self.n_in
        parts = [(m * n, C.ACTION_CENTRE_RANGE), (m, C.ACTION_SIGMA_RANGE), (m * self.n_out, C.ACTION_WEIGHT_RANGE)]
        lo = np.concatenate([np.full(k, r[0]) for k, r in parts])
        hi = np.concatenate([np.full(k, r[1]) for k, r in parts])
        return lo, hi

    def random_genomes(self, rng: np.random.Generator, k: int) -> np.ndarray:
        """``k`` genomes uniform in :meth:`bounds`."""
        lo, hi = self.bounds()
        return rng.uniform(lo, hi, size=(k, self.size))


ORDER_LOW, ORDER_HIGH = S.TEACHER_LOW, S.TEACHER_HIGH


def scale_order_inputs(x: np.ndarray) -> np.ndarray:
    """(Zr [m], ΔXr [m], ΔYr [m], Δθr [rad]) → [-1, 1] over the teacher ranges of seed §5.1."""
    return 2 * (np.asarray(x, dtype=float) - ORDER_LOW) / (ORDER_HIGH - ORDER_LOW) - 1


@dataclass(frozen=True)
class SwingOrderNetwork:
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

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        m, n = self.n_hidden, self.n_in
        lo = np.concatenate([np.full(m * n, C.ORDER_CENTRE_RANGE[0]), np.full(m, C.ORDER_SIGMA_RANGE[0])])
        hi = np.concatenate([np.full(m * n, C.ORDER_CENTRE_RANGE[1]), np.full(m, C.ORDER_SIGMA_RANGE[1])])
        return lo, hi

    def random_genomes(self, rng: np.random.Generator, k: int) -> np.ndarray:
        lo, hi = self.bounds()
        return rng.uniform(lo, hi, size=(k, self.size))

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
