"""LAPACK's SVD and least squares for the 50 ms tick of seed 001 ch. 3, through NumPy's own gufuncs.

``np.linalg.svd`` and ``np.linalg.lstsq`` call these same kernels (``gesdd``, ``gelsd``), so the numbers are
identical; what is skipped is their per-call bookkeeping (type promotion, an ``errstate`` block), which costs
more than a 12 × 9 factorisation. The inputs here are float64 arrays already; a kernel's failure
(non-convergence) comes back as NaN and is raised as NumPy's ``LinAlgError``.

:func:`solve_rows` is the same least squares for compiled loops (the kinematic plant's RK4, plant.py): it calls
the dgelsd of NumPy's own LAPACK the way NumPy's gufunc calls it.
"""

from __future__ import annotations

import ctypes

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic
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


# -- the same dgelsd called from compiled loops (the kinematic plant's RK4 stages, plant.py) --------------------

def _numpys_lapack(routine: str) -> int | None:
    """Address of LAPACK ``routine`` in the library NumPy's linalg gufuncs are linked against (NumPy 2.4's wheel:
    scipy-openblas, ILP64, symbols ``scipy_<routine>_64_``). dlsym on the gufunc module searches its dependencies,
    so this is the very function ``np.linalg.lstsq`` calls. An address, not a constant of compiled code: it
    changes per process, so it is passed as an argument (compiled code is cached on disk). None where NumPy is
    linked otherwise (Accelerate on macOS, a distribution's LAPACK): the plant then steps in NumPy (plant.py)."""
    try:
        module = ctypes.CDLL(_umath_linalg.__file__)
        return ctypes.cast(getattr(module, f"scipy_{routine}_64_"), ctypes.c_void_p).value
    except (AttributeError, OSError):
        return None


DGELSD = _numpys_lapack("dgelsd")
HEADER = 8  # int64 scalars before IWORK in a ``solve_rows`` integer workspace: M, N, NRHS, LDA, LDB, RANK, LWORK, INFO


@intrinsic
def _dgelsd(typingctx, address, ints, a, b, s, rcond, work):
    """dgelsd(M, N, NRHS, A, LDA, B, LDB, S, RCOND, RANK, WORK, LWORK, IWORK, INFO) at ``address``, every argument
    by reference: the integers are ``ints[:HEADER]`` in that order, IWORK is ``ints[HEADER:]``."""
    sig = types.void(types.int64, ints, a, b, s, rcond, work)

    def codegen(context, builder, signature, args):
        byte_ptr = ir.IntType(8).as_pointer()
        data = [builder.bitcast(context.make_array(ty)(context, builder, value).data, byte_ptr)
                for ty, value in zip(signature.args[1:], args[1:])]
        ints_ptr = context.make_array(signature.args[1])(context, builder, args[1]).data

        def scalar(k):
            return builder.bitcast(builder.gep(ints_ptr, [ir.Constant(ir.IntType(64), k)]), byte_ptr)

        _, a_ptr, b_ptr, s_ptr, rcond_ptr, work_ptr = data
        routine = builder.inttoptr(args[0], ir.FunctionType(ir.VoidType(), [byte_ptr] * 14).as_pointer())
        builder.call(routine, [scalar(0), scalar(1), scalar(2), a_ptr, scalar(3), b_ptr, scalar(4), s_ptr, rcond_ptr,
                               scalar(5), work_ptr, scalar(6), scalar(HEADER), scalar(7)])
        return context.get_dummy_value()

    return sig, codegen


def least_squares_workspace(m_max: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(ints, reals) for :func:`solve_rows` on systems of up to ``m_max`` rows and ``n`` columns: sized by dgelsd's
    own workspace queries for every row count (so no call allocates)."""
    ints, reals = np.zeros(HEADER + 1, dtype=np.int64), np.zeros(m_max * n + 2 * max(m_max, n) + 2)
    lwork = liwork = 1
    for m in range(1, m_max + 1):
        _query(DGELSD, m, n, ints, reals)
        lwork, liwork = max(lwork, int(reals[-1])), max(liwork, int(ints[HEADER]))
    return np.zeros(HEADER + liwork, dtype=np.int64), np.zeros(m_max * n + 2 * max(m_max, n) + 1 + lwork)


@njit(cache=True)
def _query(lapack, m, n, ints, reals):
    """dgelsd's workspace query for an m × n system, one right-hand side (LWORK = −1): LWORK into ``reals[-1]``,
    LIWORK into ``ints[HEADER]`` (the arguments of :func:`solve_rows`, with WORK at the end of ``reals``)."""
    ldb = max(m, n)
    ints[0], ints[1], ints[2], ints[3], ints[4], ints[6] = m, n, 1, max(1, m), ldb, -1
    _dgelsd(lapack, ints, reals, reals, reals, reals, reals[reals.shape[0] - 1:])


@njit(cache=True)
def solve_rows(lapack, rows, m, x, ints, reals) -> bool:
    """x = ``lstsq(rows[:m, :n], rows[:m, n])`` (n = len(x)) with ``lapack`` = :data:`DGELSD`: what
    ``np.linalg.lstsq(a, b, rcond=None)`` does in its gufunc — the Fortran-order copy of a, b in a buffer of
    max(m, n) rows, dgelsd's workspace query, then dgelsd with that LWORK and rcond = ε·max(m, n) — so the same
    bits, without its per-call cost (allocation, type resolution) in the plant's RK4 stages. m = 0 (every wheel
    lifted) gives the minimum-norm solution 0. False if dgelsd failed or returned NaN (np.linalg's NaN output)."""
    n = x.shape[0]
    if m == 0:
        x[:] = 0.0
        return True
    ldb = max(m, n)
    a, b = reals[:m * n], reals[m * n:m * n + ldb]
    s, rcond = reals[m * n + ldb:m * n + ldb + min(m, n)], reals[m * n + 2 * ldb:m * n + 2 * ldb + 1]
    work = reals[m * n + 2 * ldb + 1:]
    for j in range(n):
        for i in range(m):
            a[j * m + i] = rows[i, j]
    for i in range(m):
        b[i] = rows[i, n]
    ints[0], ints[1], ints[2], ints[3], ints[4], ints[6] = m, n, 1, max(1, m), ldb, -1
    _dgelsd(lapack, ints, a, b, s, rcond, work)  # the workspace query, as NumPy makes it before every solve
    lwork = int(work[0])
    if lwork > work.shape[0] or ints[HEADER] > ints.shape[0] - HEADER:
        raise ValueError("solve_rows: workspace smaller than dgelsd asks (see least_squares_workspace)")
    ints[6] = lwork
    rcond[0] = _EPS * ldb
    _dgelsd(lapack, ints, a, b, s, rcond, work)
    for j in range(n):
        x[j] = b[j]
    return ints[7] == 0 and x[0] == x[0]
