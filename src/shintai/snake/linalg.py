"""LAPACK's SVD and least squares for the 50 ms tick of seed 001 ch. 3, through NumPy's own gufuncs.

``np.linalg.svd`` and ``np.linalg.lstsq`` call these same kernels (``gesdd``, ``gelsd``), so the numbers are
identical; what is skipped is their per-call bookkeeping (type promotion, an ``errstate`` block), which costs
more than a 12 × 9 factorisation. The inputs here are float64 arrays already; a kernel's failure
(non-convergence) comes back as NaN and is raised as NumPy's ``LinAlgError``.
"""

from __future__ import annotations

import numpy as np
from numpy.linalg import LinAlgError, _umath_linalg

_EPS = np.finfo(float).eps


def _checked(x: np.ndarray, what: str) -> np.ndarray:
    # a failed kernel fills its whole output with NaN: one element tells for one matrix, a stack needs all
    first = x.flat[0]
    if first != first or (x.ndim > 1 and np.isnan(x).any()):
        raise LinAlgError(f"{what} did not converge")
    return x


def singular_values(a: np.ndarray) -> np.ndarray:
    """``np.linalg.svd(a, compute_uv=False)``: singular values, descending, of a matrix or a stack."""
    return _checked(_umath_linalg.svd(a, signature="d->d"), "SVD")


def thin_svd(a: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``np.linalg.svd(a, full_matrices=False)``: U, s, Vᵀ."""
    u, s, vt = _umath_linalg.svd_s(a, signature="d->ddd")
    _checked(s, "SVD")
    return u, s, vt


def lstsq(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.linalg.lstsq(a, b, rcond=None)[0]`` for a matrix a (m × n) and a vector b (m,)."""
    m, n = a.shape
    x = _umath_linalg.lstsq(a, b[:, None], _EPS * max(m, n), signature="ddd->ddid")[0]
    return _checked(x[:, 0], "least squares")
