"""Planar kinematic model of the wheeled snake robot — seed 001 ch. 2 (§2.1–§2.4, eqs. (2.1)–(2.15)).

Frames and conventions (§2.1, spec §1.1, §2.1, errata A1–A3):

* 2n links of length l joined by 2n−1 joints; odd joints are yaw, even joints pitch. In the plane all
  pitch joints are 0 (§2.3: the small angles that lift a wheel are neglected), so the state is
  q = [w̃_h; φ] with w̃_h = [x_h, y_h, θ_{y,h}] and φ ∈ R^n the yaw joints (the text's R^{n−1} is a typo, A1).
* The head frame's x axis is coaxial with link 1 and points *backward*, toward joint 1 (§2.1), so a
  heading θ_{y,h} = π means the robot faces +x (A3).
* Along the chain: head tip –l– yaw joint 1 –l– wheel 1 –l– yaw joint 3 –l– wheel 2 … yaw joint 2n−1
  –l– wheel n. Wheel i < n sits on pitch joint 2i; wheel n is the tail tip (A2). θ_{y,i} is the yaw of
  both links next to wheel i (2.5).
* Modes (§2.3): a mode σ is a grounded/lifted pattern, here a boolean array ``grounded`` of length n.
  Lifting wheel i deletes row i of (2.8): A_σ = T_σ A, B_σ = T_σ B (2.11).

Code indices are 0-based: thesis wheel i is index i−1 and φ[k] is thesis φ_{k+1}. A :class:`Configuration`
holds the trigonometry of one state, computed once and shared by every matrix of that state.

The 3D models of §2.5 (head raised, double arm) and the wheel–plane relation of §2.6 are in
:mod:`shintai.snake.model3d`; they extend this chain with the pitch joints (ψ ∈ R^{2n−1}).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit


@dataclass(frozen=True, eq=False)
class Configuration:
    """One planar state q = [w̃_h; φ] of a snake with link length ``l``, with its trigonometry.

    ``theta[i]`` = θ_{y,i+1} (2.5); ``cos_rel[i, j]`` = cos(θ_i − θ_j), ``sin_rel[i, j]`` = sin(θ_i − θ_j).
    """

    w_h: np.ndarray
    phi: np.ndarray
    l: float
    theta: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    cos_rel: np.ndarray
    sin_rel: np.ndarray

    @property
    def n(self) -> int:
        return self.phi.shape[0]


@lru_cache(maxsize=8)
def _lower(n: int) -> np.ndarray:
    """Lower-triangular ones [j ≤ i] (read-only, shared)."""
    m = np.tri(n)
    m.flags.writeable = False
    return m


@lru_cache(maxsize=8)
def _strictly_lower(n: int) -> np.ndarray:
    """Strictly lower-triangular ones [j < i] (read-only, shared)."""
    m = np.tri(n, k=-1)
    m.flags.writeable = False
    return m


@lru_cache(maxsize=8)
def _point_weights(n: int, k: int) -> np.ndarray:
    """w_j of :func:`second_point_jacobians`: 2 (j < k), 1 (j = k), 0 (j > k), 1-based k (read-only, shared)."""
    weight = np.where(np.arange(n) < k - 1, 2.0, 0.0)
    weight[k - 1] = 1.0
    weight.flags.writeable = False
    return weight


@lru_cache(maxsize=8)
def _scaled_weights(n: int, k: int, l: float) -> tuple[np.ndarray, np.ndarray]:
    """(−w_j l, w_j l) of :func:`_point_weights` (read-only, shared)."""
    weight = _point_weights(n, k)
    minus, plus = -weight * l, weight * l
    minus.flags.writeable = plus.flags.writeable = False
    return minus, plus


@lru_cache(maxsize=8)
def _first(n: int, k: int) -> np.ndarray:
    """[j < k] over j = 0..n−1 as floats: the θ_k row of J_{k,2} (read-only, shared)."""
    first = (np.arange(n) < k).astype(float)
    first.flags.writeable = False
    return first


@lru_cache(maxsize=8)
def _b_derivative_mask(n: int) -> np.ndarray:
    """[k < m ≤ i] over (m, i, k), the support of ∂B_{i,k}/∂φ_m (read-only, shared)."""
    m, i, k = np.ogrid[:n, :n, :n]
    mask = (k < m) & (m <= i)
    mask.flags.writeable = False
    return mask


@lru_cache(maxsize=8)
def _max_index(n: int) -> np.ndarray:
    """[q, m] → max(m, q) (read-only, shared)."""
    start = np.maximum.outer(np.arange(n), np.arange(n))
    start.flags.writeable = False
    return start


def configuration(w_h, phi, l: float) -> Configuration:
    """Build the :class:`Configuration` of head pose ``w_h`` = [x_h, y_h, θ_{y,h}] and yaw angles ``phi``."""
    w_h = np.asarray(w_h, dtype=float)
    phi = np.asarray(phi, dtype=float)
    if w_h.shape != (3,):
        raise ValueError(f"w_h must be [x_h, y_h, theta_h] (3 numbers), got shape {w_h.shape}")
    if phi.ndim != 1 or phi.shape[0] < 2:
        raise ValueError(f"phi must be a 1-D array of n >= 2 yaw angles, got shape {phi.shape}")
    theta = w_h[2] + phi.cumsum()  # (2.5)
    diff = theta[:, None] - theta[None, :]
    return Configuration(w_h, phi, float(l), theta, np.cos(theta), np.sin(theta), np.cos(diff), np.sin(diff))


def wheel_poses(cfg: Configuration) -> np.ndarray:
    """Planar poses [x_i, y_i, θ_{y,i}] of the n wheel axle centres, (2.3)–(2.5), shape (n, 3).

    Unrolling the recursion (2.3): x_i = x_h + l cos θ_h + 2l Σ_{j<i} cos θ_j + l cos θ_i (same for y).
    """
    x_h, y_h, th_h = cfg.w_h
    l = cfg.l
    x = x_h + l * np.cos(th_h) + 2 * l * np.cumsum(cfg.cos) - l * cfg.cos  # 2l Σ_{j≤i} − l cos θ_i
    y = y_h + l * np.sin(th_h) + 2 * l * np.cumsum(cfg.sin) - l * cfg.sin
    return np.column_stack((x, y, cfg.theta))


def tail_pose(cfg: Configuration) -> np.ndarray:
    """Pose [x_n, y_n, θ_{y,n}] of wheel n alone: the last row of :func:`wheel_poses`, the same sums in order."""
    x_h, y_h, th_h = cfg.w_h.tolist()
    l = cfg.l
    cos, sin = cfg.cos.tolist(), cfg.sin.tolist()
    sum_c = sum_s = 0.0  # Σ_{j≤n} cos θ_j, sin θ_j, summed from the head as cumsum does
    for c, s in zip(cos, sin):
        sum_c += c
        sum_s += s
    return np.array((x_h + l * math.cos(th_h) + 2 * l * sum_c - l * cos[-1],
                     y_h + l * math.sin(th_h) + 2 * l * sum_s - l * sin[-1], cfg.theta[-1]))


def body_points(cfg: Configuration) -> np.ndarray:
    """Polyline of the body in the plane: head tip, yaw joint 1, wheel 1, yaw joint 3, …, wheel n; (2n+1, 2)."""
    headings = np.repeat(np.concatenate(([cfg.w_h[2]], cfg.theta)), 2)[1:-1]  # θ_h, θ_1, θ_1, θ_2, …, θ_n
    steps = cfg.l * np.column_stack((np.cos(headings), np.sin(headings)))
    return np.vstack((cfg.w_h[:2], cfg.w_h[:2] + np.cumsum(steps, axis=0)))


def constraint_matrices(cfg: Configuration) -> tuple[np.ndarray, np.ndarray]:
    """A ∈ R^{n×3}, B ∈ R^{n×n} of the velocity constraints A ẇ̃_h = B φ̇, (2.6)–(2.9).

    Row i is wheel i's no-side-slip constraint (2.7), v_i = A_i ẇ̃_h − B_i φ̇ = 0 (closed form of spec §2.3):
    A_i = [sin θ_i, −cos θ_i, −l(1 + cos(θ_i − θ_h) + 2 Σ_{j<i} cos(θ_i − θ_j))],
    B_{i,k} = l + 2l Σ_{j=k}^{i−1} cos(θ_i − θ_j) (k < i), B_{i,i} = l, B_{i,k} = 0 (k > i): lower-triangular
    with diagonal l (2.9), hence always invertible.
    """
    l, n = cfg.l, cfg.n
    below = cfg.cos_rel * _strictly_lower(n)  # cos(θ_i − θ_j) for j < i
    A = np.empty((n, 3))
    A[:, 0] = cfg.sin
    np.negative(cfg.cos, out=A[:, 1])
    A[:, 2] = -l * (1.0 + np.cos(cfg.theta - cfg.w_h[2]) + 2.0 * below.sum(axis=1))
    tail_sums = below[:, ::-1].cumsum(axis=1)[:, ::-1]  # Σ_{j≥k} (below)_{ij} = Σ_{j=k}^{i−1}
    B = l * _lower(n) + 2.0 * l * tail_sums
    return A, B


def constraint_terms(theta_h: float, phi: np.ndarray, l: float, phi_dot: np.ndarray):
    """A (2.8) and the product B φ̇ without forming B: the rows of :func:`constraint_rows` for all n wheels."""
    n = len(phi)
    rows = np.empty((n, 4))
    constraint_rows(float(theta_h), np.asarray(phi, dtype=float), float(l), rate_sums(np.asarray(phi_dot, dtype=float)),
                    np.ones(n, dtype=np.bool_), rows)
    return rows[:, :3], rows[:, 3]


@njit(cache=True)
def rate_sums(phi_dot: np.ndarray) -> np.ndarray:
    """Φ_j = Σ_{k≤j} φ̇_k (the rate of θ_j − θ_h by (2.5)), summed from the head starting at 0.0."""
    rates = np.empty(phi_dot.shape[0])
    total = 0.0
    for j in range(phi_dot.shape[0]):
        total += phi_dot[j]
        rates[j] = total
    return rates


@njit(cache=True)
def constraint_rows(theta_h: float, phi: np.ndarray, l: float, rates: np.ndarray, grounded: np.ndarray,
                    rows: np.ndarray) -> int:
    """Rows [A_i, (B φ̇)_i] of the grounded wheels (A_σ and B_σ φ̇ of (2.10)–(2.11)) into ``rows[:n_σ]`` (an
    (n, 4) buffer), without forming B: one O(n) pass down the chain (the plant's fast path); returns n_σ.

    ``phi`` (the yaw angles), ``rates`` (Φ_j = Σ_{k≤j} φ̇_k, :func:`rate_sums`) and ``grounded`` have length n.
    Running sums replace the double sums of :func:`constraint_matrices`: Σ_{j<i} cos(θ_i − θ_j) =
    cos θ_i Σ_{j<i} cos θ_j + sin θ_i Σ_{j<i} sin θ_j, and (B φ̇)_i = l Φ_i + 2l Σ_{j<i} cos(θ_i − θ_j) Φ_j.
    Compiled: it runs in every RK4 stage of the kinematic plant, where NumPy's per-call cost would be most of it.
    """
    cos_h, sin_h = math.cos(theta_h), math.sin(theta_h)
    theta = theta_h
    sum_c = sum_s = sum_c_rate = sum_s_rate = 0.0  # Σ_{j<i} cos θ_j, sin θ_j, cos θ_j Φ_j, sin θ_j Φ_j
    m = 0
    for i in range(phi.shape[0]):
        theta += phi[i]  # (2.5)
        c, s, rate = math.cos(theta), math.sin(theta), rates[i]
        if grounded[i]:
            rows[m, 0], rows[m, 1] = s, -c
            rows[m, 2] = -l * (1.0 + c * cos_h + s * sin_h + 2.0 * (c * sum_c + s * sum_s))
            rows[m, 3] = l * rate + 2.0 * l * (c * sum_c_rate + s * sum_s_rate)
            m += 1
        sum_c += c
        sum_s += s
        sum_c_rate += c * rate
        sum_s_rate += s * rate
    return m


def lateral_velocities(cfg: Configuration, w_h_dot, phi_dot) -> np.ndarray:
    """Axle-direction velocity v_i of every wheel (2.6) for the motion (ẇ̃_h, φ̇): v = A ẇ̃_h − B φ̇."""
    A, B = constraint_matrices(cfg)
    return A @ np.asarray(w_h_dot, dtype=float) - B @ np.asarray(phi_dot, dtype=float)


def check_mode(grounded, n: int) -> np.ndarray:
    """Validate a mode σ given as a grounded/lifted pattern: a boolean array of n wheels (§2.3.1)."""
    g = np.asarray(grounded)
    if g.shape != (n,):
        raise ValueError(f"mode must give grounded/lifted for all n = {n} wheels, got shape {g.shape}")
    if g.dtype != bool:
        if not np.all((g == 0) | (g == 1)):
            raise ValueError("mode entries must be 0/1 (lifted/grounded)")
        g = g.astype(bool)
    return g


def selection_matrix(grounded) -> np.ndarray:
    """T_σ ∈ R^{n_σ×n}: the rows of I_n of the grounded wheels (2.11)."""
    g = np.asarray(grounded, dtype=bool)
    return np.eye(g.shape[0])[g]


def mode_matrices(A: np.ndarray, B: np.ndarray, grounded) -> tuple[np.ndarray, np.ndarray]:
    """A_σ = T_σ A, B_σ = T_σ B (2.10)–(2.11): lifting wheel i deletes row i."""
    g = check_mode(grounded, A.shape[0])
    return A[g], B[g]


def redundant_solution(A_s: np.ndarray, B_s: np.ndarray, w_h_dot, l_arb) -> np.ndarray:
    """General solution φ̇ = B_σ^† A_σ ẇ̃_h + (I_n − B_σ^† B_σ) l_arb of (2.10), eq. (2.12) (B_σ typo fixed, A1)."""
    B_pinv = np.linalg.pinv(B_s)
    n = B_s.shape[1]
    return B_pinv @ A_s @ np.asarray(w_h_dot, float) + (np.eye(n) - B_pinv @ B_s) @ np.asarray(l_arb, float)


def second_point_jacobians(cfg: Configuration, k: int) -> tuple[np.ndarray, np.ndarray]:
    """J_{k,1} ∈ R^{3×3}, J_{k,2} ∈ R^{3×n} of ẇ̃_k = J_{k,1} ẇ̃_h + J_{k,2} φ̇, eq. (2.13), wheel ``k`` 1-based.

    From (2.3)–(2.5), ∂p_k/∂θ_j = w_j l [−sin θ_j, cos θ_j] with w_j = 2 (j < k), 1 (j = k), 0 (j > k), and
    ∂θ_j/∂φ_m = [m ≤ j]; so column m of J_{k,2} sums j ≥ m, and columns k+1..n are zero (§2.4.1).
    """
    n, l = cfg.n, cfg.l
    if not (isinstance(k, (int, np.integer)) and 1 <= k <= n):
        raise ValueError(f"second control point must be a wheel 1..{n}, got {k!r}")
    minus_wl, wl = _scaled_weights(n, k, l)
    gx, gy = minus_wl * cfg.sin, wl * cfg.cos
    J2 = np.empty((3, n))
    gx[::-1].cumsum(out=J2[0, ::-1])
    gy[::-1].cumsum(out=J2[1, ::-1])
    J2[2] = _first(n, k)
    th_h = cfg.w_h[2]
    J1 = np.array([[1.0, 0.0, -l * np.sin(th_h) + gx.sum()],
                   [0.0, 1.0, l * np.cos(th_h) + gy.sum()],
                   [0.0, 0.0, 1.0]])
    return J1, J2


def two_point_matrices(A_s: np.ndarray, B_s: np.ndarray, J1: np.ndarray, J2: np.ndarray):
    """A_{c,σ} ∈ R^{(n_σ+3)×6}, B_{c,σ} ∈ R^{(n_σ+3)×n} of A_{c,σ} ċ_c = B_{c,σ} φ̇, eqs. (2.14)–(2.15).

    A_{c,σ} = [[A_σ, O], [J_{k,1}, −I_3]], B_{c,σ} = [B_σ; −J_{k,2}], c_c = [w̃_h; w̃_k].
    """
    n_s = A_s.shape[0]
    A_c = np.block([[A_s, np.zeros((n_s, 3))], [J1, -np.eye(3)]])
    B_c = np.vstack((B_s, -J2))
    return A_c, B_c


def sigma_min(M: np.ndarray) -> float:
    """Smallest of the min(rows, cols) singular values of ``M``."""
    return float(np.linalg.svd(M, compute_uv=False)[-1])


def singular_configuration_I(A_s: np.ndarray, tol: float = 1e-9) -> bool:
    """Singular configuration I (§2.3.4, §3.2.2): A_σ (and so A_{c,σ}) loses column rank, rank < 3.

    Happens when all grounded axles are parallel or all grounded axle lines meet in one point (Fig. 2.6).
    """
    return A_s.shape[0] < 3 or sigma_min(A_s) < tol


def singular_configuration_II(B_c: np.ndarray, tol: float = 1e-9) -> bool:
    """Singular configuration II (§2.4.3, §3.2.2): B_{c,σ} loses row rank (no analytic characterisation).

    Always the case when n_σ + 3 > n (more rows than joints, §2.4.2).
    """
    return B_c.shape[0] > B_c.shape[1] or sigma_min(B_c) < tol


def _sin_prefix(cfg: Configuration) -> np.ndarray:
    """E[i, m] = Σ_{j<m} sin(θ_i − θ_j), shape (n, n)."""
    n = cfg.n
    E = np.zeros((n, n + 1))
    cfg.sin_rel.cumsum(axis=1, out=E[:, 1:])
    return E[:, :n]


def a_matrix_derivative(cfg: Configuration) -> np.ndarray:
    """∂A/∂φ_m for m = 1..n, shape (n, n, 3) (first axis m), from the closed form of :func:`constraint_matrices`.

    With ∂θ_i/∂φ_m = [m ≤ i] and E_{i,m} = Σ_{j<m} sin(θ_i − θ_j):
    ∂A_i/∂φ_m = [m ≤ i]·[cos θ_i, sin θ_i, l(sin(θ_i − θ_h) + 2 E_{i,m})]. Used for η (3.6) of V_{u,2}.
    """
    n, l = cfg.n, cfg.l
    m_le_i = _lower(n).T  # [m, i] = 1 where m ≤ i
    dA = np.empty((n, n, 3))
    dA[:, :, 0] = m_le_i * cfg.cos
    dA[:, :, 1] = m_le_i * cfg.sin
    dA[:, :, 2] = m_le_i * (l * (np.sin(cfg.theta - cfg.w_h[2]) + 2.0 * _sin_prefix(cfg).T))
    return dA


def b_matrix_derivative(cfg: Configuration) -> np.ndarray:
    """∂B/∂φ_m for m = 1..n, shape (n, n, n) (first axis m): ∂B_{i,k}/∂φ_m = −2l [k < m ≤ i] (E_{i,m} − E_{i,k}).

    Same notation as :func:`a_matrix_derivative`; used for η (3.6) of V_{u,3}.
    """
    n, l = cfg.n, cfg.l
    E = _sin_prefix(cfg)
    return np.where(_b_derivative_mask(n), -2.0 * l * (E.T[:, :, None] - E[None, :, :]), 0.0)


def second_point_jacobian_derivative(cfg: Configuration, k: int) -> np.ndarray:
    """∂J_{k,2}/∂φ_q for q = 1..n, shape (n, 3, n) (first axis q), wheel ``k`` 1-based.

    From :func:`second_point_jacobians`, ∂J_{k,2}[:, m]/∂φ_q = Σ_{j ≥ max(m, q)} w_j l [−cos θ_j, −sin θ_j, 0].
    """
    n, l = cfg.n, cfg.l
    minus_wl, _ = _scaled_weights(n, k, l)
    hx, hy = np.zeros(n + 1), np.zeros(n + 1)  # the sums from j = m, and 0 past the tail
    (minus_wl * cfg.cos)[::-1].cumsum(out=hx[n - 1::-1])
    (minus_wl * cfg.sin)[::-1].cumsum(out=hy[n - 1::-1])
    start = _max_index(n)  # [q, m] → max(m, q)
    dJ2 = np.zeros((n, 3, n))
    dJ2[:, 0, :] = hx[start]
    dJ2[:, 1, :] = hy[start]
    return dJ2
