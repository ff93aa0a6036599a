"""snake/linalg.py: the same numbers as np.linalg's SVD and least squares, and their failure raised."""

import numpy as np
import pytest

from shintai.snake.linalg import DGELSD, least_squares_workspace, lstsq, singular_values, solve_rows, thin_svd


def test_the_kernels_give_numpys_numbers_bit_for_bit():
    rng = np.random.default_rng(0)
    for _ in range(200):
        m, n = rng.integers(3, 13), rng.integers(3, 10)
        a, b = rng.normal(size=(m, n)), rng.normal(size=m)
        assert np.array_equal(lstsq(a, b), np.linalg.lstsq(a, b, rcond=None)[0])
        assert np.array_equal(singular_values(a), np.linalg.svd(a, compute_uv=False))
        for ours, numpys in zip(thin_svd(a), np.linalg.svd(a, full_matrices=False)):
            assert np.array_equal(ours, numpys)
    stack = rng.normal(size=(5, 12, 9))  # mode selection's batched SVD
    assert np.array_equal(singular_values(stack), np.linalg.svd(stack, compute_uv=False))
    rank_deficient = np.ones((6, 3))
    assert np.array_equal(lstsq(rank_deficient, np.arange(6.0)),
                          np.linalg.lstsq(rank_deficient, np.arange(6.0), rcond=None)[0])


def test_a_failed_kernel_raises_linalg_error():
    bad = np.full((4, 3), np.nan)
    with pytest.raises(np.linalg.LinAlgError), np.errstate(invalid="ignore"):
        singular_values(bad)
    with pytest.raises(np.linalg.LinAlgError), np.errstate(invalid="ignore"):
        thin_svd(bad)
    with pytest.raises(np.linalg.LinAlgError), np.errstate(invalid="ignore"):
        lstsq(bad, np.ones(4))
    with pytest.raises(np.linalg.LinAlgError), np.errstate(invalid="ignore"):
        singular_values(np.stack([np.eye(3), np.full((3, 3), np.nan)]))


def test_the_compiled_least_squares_gives_numpys_numbers_bit_for_bit():
    """solve_rows (the plant's RK4 stages) calls NumPy's own dgelsd as its gufunc does: the same bits, for
    overdetermined, square, underdetermined and rank-deficient systems; no rows gives the minimum-norm 0."""
    rng = np.random.default_rng(1)
    workspace = least_squares_workspace(12, 3)
    x = np.empty(3)
    for trial in range(300):
        m = int(rng.integers(1, 13))
        rows = rng.normal(size=(12, 4))
        if trial % 5 == 0:
            rows[:, 1] = 2.0 * rows[:, 0]  # rank 2
        assert solve_rows(DGELSD, rows, m, x, *workspace)
        assert np.array_equal(x, np.linalg.lstsq(rows[:m, :3], rows[:m, 3], rcond=None)[0])
    assert solve_rows(DGELSD, np.ones((12, 4)), 0, x, *workspace) and not x.any()
    with np.errstate(invalid="ignore"):
        assert not solve_rows(DGELSD, np.full((12, 4), np.nan), 5, x, *workspace)
