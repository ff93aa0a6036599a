"""The 50 ms tick of seed 001 §3.2 compiled: the matrices of one state and mode, and u_σ = u_c + u_v (3.3)–(3.6).

Three kernels around NumPy's LAPACK SVDs (linalg.py), called by :class:`~shintai.snake.two_point.TwoPointLaw`:

* :func:`stacked_matrices` — A_{c,σ}, B_{c,σ} (2.15) of the rows ``rows`` (the grounded wheels, then the three of
  (2.13)), A_σ and, when asked, ∂A_σ/∂φ and ∂B_{c,σ}/∂φ for η (3.6), and c_c (3.2);
* :func:`objective_terms` — V_u and η (3.12)–(3.16) from the SVDs of A_σ and B_{c,σ};
* :func:`input_terms` — u_σ = u_c + u_v (3.3)–(3.5) from the SVD of B_{c,σ} and η.

The closed forms are model.py's (constraint_matrices (2.6)–(2.9), second_point_jacobians (2.13), tail_pose,
a_matrix_derivative, b_matrix_derivative, second_point_jacobian_derivative), written here as loops over the n
wheels; model.py's NumPy functions stay the reference and tests/snake/test_two_point_tick.py holds the two equal.
The sums run in another order than NumPy's (its pairwise sums and BLAS products) and the trigonometry is libm's,
so the results agree with the NumPy form to rounding (≈1e−16 relative), not bit for bit. The equations are
repeated here rather than called from model.py because numba's disk cache is keyed on a kernel's own file: a
compiled callee in another file could go stale.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_EPS = np.finfo(float).eps


@njit(cache=True)
def stacked_matrices(w_h, phi, l, rows, A_c, B_c, A_s, dA_s, dB_c, c_c, derivatives):
    """Fill A_c[:r], B_c[:r] (r = len(rows)), A_s[:m], c_c and, for ``derivatives`` = (∂A, ∂B), dA_s[:, :m] and
    dB_c[:, :r] (first axis φ_q); m = r − 3 grounded wheels ``rows[:m]`` (0-based), second control point wheel n.

    A_{c,σ} = [[A_σ, O], [J_{n,1}, −I_3]], B_{c,σ} = [B_σ; −J_{n,2}] (2.15) of (2.14) with, for wheel i,
    A_i = [sin θ_i, −cos θ_i, −l(1 + cos(θ_i − θ_h) + 2 Σ_{j<i} cos(θ_i − θ_j))] and
    B_{i,k} = l + 2l Σ_{j=k}^{i−1} cos(θ_i − θ_j) (k ≤ i), 0 (k > i)  (2.6)–(2.9);
    J_{n,2}[:, k] = [Σ_{j≥k} w_j l (−sin θ_j), Σ_{j≥k} w_j l cos θ_j, 1] with w_j = 2 (j < n), 1 (j = n) (2.13);
    ∂A_i/∂φ_q = [q ≤ i]·[cos θ_i, sin θ_i, l(sin(θ_i − θ_h) + 2 E_{i,q})], E_{i,q} = Σ_{j<q} sin(θ_i − θ_j);
    ∂B_{i,k}/∂φ_q = −2l [k < q ≤ i](E_{i,q} − E_{i,k});
    ∂J_{n,2}[:, k]/∂φ_q = Σ_{j≥max(k,q)} w_j l [−cos θ_j, −sin θ_j, 0].
    """
    n = phi.shape[0]
    r = rows.shape[0]
    m = r - 3
    th_h = w_h[2]
    theta = np.empty(n)
    total = 0.0
    for i in range(n):  # (2.5): θ_i = θ_h + Σ_{k≤i} φ_k
        total += phi[i]
        theta[i] = th_h + total
    cos, sin = np.cos(theta), np.sin(theta)
    weight = np.full(n, 2.0 * l)  # w_j l of (2.13)
    weight[n - 1] = l
    gx, gy = np.empty(n + 1), np.empty(n + 1)  # Σ_{j≥k} w_j l (−sin θ_j), (cos θ_j); 0 past the tail
    hx, hy = np.empty(n + 1), np.empty(n + 1)  # Σ_{j≥k} w_j l (−cos θ_j), (−sin θ_j)
    gx[n] = gy[n] = hx[n] = hy[n] = 0.0
    for k in range(n - 1, -1, -1):
        gx[k] = gx[k + 1] - weight[k] * sin[k]
        gy[k] = gy[k + 1] + weight[k] * cos[k]
        hx[k] = hx[k + 1] - weight[k] * cos[k]
        hy[k] = hy[k + 1] - weight[k] * sin[k]
    sum_c = sum_s = 0.0
    for j in range(n):
        sum_c += cos[j]
        sum_s += sin[j]
    c_c[0], c_c[1], c_c[2] = w_h[0], w_h[1], th_h
    c_c[3] = w_h[0] + l * math.cos(th_h) + 2.0 * l * sum_c - l * cos[n - 1]  # tail_pose, (2.3)–(2.5)
    c_c[4] = w_h[1] + l * math.sin(th_h) + 2.0 * l * sum_s - l * sin[n - 1]
    c_c[5] = theta[n - 1]
    E = np.empty(n + 1)
    for row in range(m):
        i = rows[row]
        below = 0.0
        for j in range(i):
            below += math.cos(theta[i] - theta[j])
        A_s[row, 0], A_s[row, 1] = sin[i], -cos[i]
        A_s[row, 2] = -l * (1.0 + math.cos(theta[i] - th_h) + 2.0 * below)
        for c in range(3):
            A_c[row, c] = A_s[row, c]
            A_c[row, 3 + c] = 0.0
        tail = 0.0
        for k in range(n - 1, -1, -1):
            if k < i:
                tail += math.cos(theta[i] - theta[k])
            B_c[row, k] = l + 2.0 * l * tail if k <= i else 0.0
        if derivatives[0] or derivatives[1]:
            E[0] = 0.0
            for q in range(n):
                E[q + 1] = E[q] + math.sin(theta[i] - theta[q])
        if derivatives[0]:
            lever = math.sin(theta[i] - th_h)
            for q in range(n):
                below_i = q <= i
                dA_s[q, row, 0] = cos[i] if below_i else 0.0
                dA_s[q, row, 1] = sin[i] if below_i else 0.0
                dA_s[q, row, 2] = l * (lever + 2.0 * E[q]) if below_i else 0.0
        if derivatives[1]:
            for q in range(n):
                for k in range(n):
                    dB_c[q, row, k] = -2.0 * l * (E[q] - E[k]) if k < q <= i else 0.0
    for c in range(3):  # the rows of (2.13): [J_{n,1}, −I_3] and −J_{n,2}
        for d in range(6):
            A_c[m + c, d] = 0.0
        A_c[m + c, c] = 1.0
        A_c[m + c, 3 + c] = -1.0
    A_c[m, 2] = -l * math.sin(th_h) + gx[0]
    A_c[m + 1, 2] = l * math.cos(th_h) + gy[0]
    for k in range(n):
        B_c[m, k], B_c[m + 1, k], B_c[m + 2, k] = -gx[k], -gy[k], -1.0
    if derivatives[1]:
        for q in range(n):
            for k in range(n):
                start = max(k, q)
                dB_c[q, m, k], dB_c[q, m + 1, k], dB_c[q, m + 2, k] = -hx[start], -hy[start], 0.0


@njit(cache=True)
def gram_det_gradient_into(U, s, Vt, grad):
    """det of the small Gram matrix of X = U S Vᵀ and ∂det/∂X = 2 U diag(s_i Π_{j≠i} s_j²) Vᵀ into ``grad``
    (two_point.gram_det_gradient, products from j = 0 in order)."""
    p = s.shape[0]
    det = 1.0
    for j in range(p):
        det *= s[j] * s[j]
    for a in range(grad.shape[0]):
        for b in range(grad.shape[1]):
            grad[a, b] = 0.0
    for i in range(p):
        others = 1.0
        for j in range(p):
            if j != i:
                others *= s[j] * s[j]
        scale = 2.0 * s[i] * others
        for a in range(grad.shape[0]):
            for b in range(grad.shape[1]):
                grad[a, b] += U[a, i] * scale * Vt[i, b]
    return det


@njit(cache=True)
def _gram_term(gain, svd, d, eta):
    """gain · det of the Gram matrix of X = U S Vᵀ (``svd``), its gradient chained through ``d`` = ∂X/∂φ into η."""
    U, s, Vt = svd
    grad = np.empty((U.shape[0], Vt.shape[1]))
    det = gram_det_gradient_into(U, s, Vt, grad)
    for q in range(eta.shape[0]):
        total = 0.0
        for a in range(grad.shape[0]):
            for b in range(grad.shape[1]):
                total += d[q, a, b] * grad[a, b]
        eta[q] += gain * total
    return gain * det


@njit(cache=True)
def objective_terms(phi, phi_th, k_u, svd_a, dA_s, svd_b, dB_c, eta):
    """V_u (3.12) = k_{u,1} V_{u,1} + k_{u,2} det(A_σᵀA_σ) + k_{u,3} det(B_{c,σ}B_{c,σ}ᵀ) (3.13)–(3.16), and its
    gradient η = ∂V_u/∂φ (3.6) into ``eta``: V_{u,1} = −Σ max(|φ_k| − φ_th, 0)², the Gram terms by the chain rule
    through ``dA_s`` = ∂A_σ/∂φ and ``dB_c`` = ∂B_{c,σ}/∂φ with the SVDs ``svd_a`` of A_σ and ``svd_b`` of B_{c,σ}.
    A term whose gain is 0 is skipped: its SVD and derivative are not read."""
    V1 = 0.0
    for q in range(phi.shape[0]):
        excess = max(abs(phi[q]) - phi_th, 0.0)
        V1 -= excess * excess
        eta[q] = k_u[0] * (-2.0 * excess * np.sign(phi[q]))
    V = k_u[0] * V1
    if k_u[1] != 0.0:
        V += _gram_term(k_u[1], svd_a, dA_s, eta)
    if k_u[2] != 0.0:
        V += _gram_term(k_u[2], svd_b, dB_c, eta)
    return V


@njit(cache=True)
def input_terms(A_c, svd_b, eta, c_c, c_d, c_d_dot, k_p, k_v, u):
    """u_σ = u_c + u_v (3.3) into ``u``; returns ‖u_σ‖. ξ = ċ_{c,d} + K_p(c_{c,d} − c_c) with K_p = k_p I_6;
    u_c = B_{c,σ}^† A_{c,σ} ξ (3.4), B^† = V S⁻¹ Uᵀ over the singular values above max(rows, cols)·ε·s_0 (the old
    law's cutoff, as ``np.linalg.pinv(B, rtol=None)`` and ``lstsq(rcond=None)``); u_v = k_v (I − B^†B) η (3.5),
    I − B^†B = I − V Vᵀ on the same singular vectors."""
    U, s, Vt = svd_b
    r, n = U.shape[0], Vt.shape[1]
    cut = max(r, n) * _EPS * s[0]
    a_xi = np.zeros(r)
    for row in range(r):
        for c in range(6):
            a_xi[row] += A_c[row, c] * (c_d_dot[c] + k_p * (c_d[c] - c_c[c]))
    for k in range(n):
        u[k] = k_v * eta[k]
    for i in range(s.shape[0]):
        if not s[i] > cut:
            continue
        along, proj = 0.0, 0.0  # (Uᵀ A ξ)_i / s_i and (Vᵀ η)_i
        for row in range(r):
            along += U[row, i] * a_xi[row]
        along /= s[i]
        for k in range(n):
            proj += Vt[i, k] * eta[k]
        for k in range(n):
            u[k] += Vt[i, k] * (along - k_v * proj)
    norm = 0.0
    for k in range(n):
        norm += u[k] * u[k]
    return math.sqrt(norm)
