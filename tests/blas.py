"""Whether this process's BLAS sums a 3-vector product left to right: OpenBLAS's Haswell and Zen kernels do, its
SkylakeX ones (chosen on AVX-512 machines unless ``OPENBLAS_CORETYPE`` says otherwise) do not. Only then does a float
rewrite of NumPy's ``x.dot(y)`` and ``r.T.dot(v)`` give their bits exactly; elsewhere the two differ in the last bit
and the tests that compare them bit for bit compare them to rounding instead."""

from __future__ import annotations

import functools

import numpy as np


@functools.cache
def sums_left_to_right(cases: int = 2000) -> bool:
    rng = np.random.default_rng(12345)
    for _ in range(cases):
        a, w, r = rng.standard_normal(3), rng.standard_normal(3), rng.standard_normal((3, 3))
        (a0, a1, a2), (w0, w1, w2), rows = a.tolist(), w.tolist(), r.tolist()
        if float(a.dot(w)) != a0 * w0 + a1 * w1 + a2 * w2:
            return False
        if r.T.dot(w).tolist() != [rows[0][i] * w0 + rows[1][i] * w1 + rows[2][i] * w2 for i in range(3)]:
            return False
    return True
