"""Swing orders (Table 2) and the exhaustive-search teacher of seed §5.1."""

import numpy as np
import pytest

from shintai.quadruped import constants as C
from shintai.quadruped import swing_order as S

TABLE2 = """0 1234  1 1243  2 1324  3 1342  4 1423  5 1432  6 2134  7 2143  8 2314  9 2341 10 2413 11 2431
12 3124 13 3142 14 3214 15 3241 16 3412 17 3421 18 4123 19 4132 20 4213 21 4231 22 4312 23 4321"""


def test_permutation_table_is_table_2():
    printed = TABLE2.split()
    table = {int(n): tuple(int(c) for c in order) for n, order in zip(printed[::2], printed[1::2])}
    assert len(table) == 24
    assert all(S.PERMUTATIONS[n] == order for n, order in table.items())


def test_spec_listed_entries_and_crawl_order():
    assert S.PERMUTATIONS[21] == (4, 2, 3, 1) == C.CRAWL_ORDER and S.CRAWL == 21
    assert S.PERMUTATIONS[11] == (2, 4, 3, 1)
    assert S.PERMUTATIONS[13] == (3, 1, 4, 2)
    assert S.PERMUTATIONS[10] == (2, 4, 1, 3)
    assert S.order_index((3, 1, 4, 2)) == 13 and S.format_order(21) == "4→2→3→1"
    with pytest.raises(ValueError, match="not a swing order"):
        S.order_index((1, 1, 2, 3))


def table3():
    a = C.TABLE3_ACTIONS
    return S.actions_to_si(a[:, 3], a[:, 0], a[:, 1], a[:, 2])


def test_exhaustive_search_reproduces_the_orders_of_table_4_rows_2_4_and_8_10():
    best, br = S.best_orders(*table3())
    paper = np.array(C.TABLE4_ORDERS)
    assert np.array_equal(best[1:4], paper[1:4]) and np.all(best[1:4] == S.CRAWL)  # Zr = 360 mm: 4→2→3→1
    assert np.array_equal(best[7:10], paper[7:10]) and np.all(best[7:10] == 13)  # Zr 300, Δθ 4.7-5.6°: 3→1→4→2
    full = S.body_movement(*table3())
    assert np.all(br <= full[:, S.CRAWL])
    assert np.allclose(br, full.min(axis=1), rtol=0, atol=S.TIE)


def test_infeasible_orders_have_infinite_body_movement():
    zr, command = S.actions_to_si([360.0], [0.0], [350.0], [15.0])  # a huge step at the top height
    br = S.body_movement(zr, command)
    assert np.isinf(br).any()
    best, _ = S.best_orders(zr, command)
    assert best[0] == -1 or np.isfinite(br[0, best[0]])


def test_teacher_set_labels_are_the_exhaustive_optimum():
    teacher = S.teacher_set(per_order=5, draws=200, seed=1)
    assert np.array_equal(S.label(teacher.x), teacher.label)
    counts = np.bincount(teacher.label, minlength=24)
    assert set(np.flatnonzero(counts)) == set(teacher.optimal_orders)
    assert np.all(counts[list(teacher.optimal_orders)] <= 5)
    assert np.all((teacher.x >= S.TEACHER_LOW) & (teacher.x <= S.TEACHER_HIGH))
    assert np.array_equal(teacher.target.argmax(axis=1), teacher.label)
    again = S.teacher_set(per_order=5, draws=200, seed=1)
    assert np.array_equal(again.x, teacher.x)
