"""SQ43 design search (seed 003 §3.2.3): the compass search on test functions, eq. (3.1), and the
compliant-spine stand-in for the FEM."""

from dataclasses import replace

import numpy as np
import pytest

from shintai.spine.sq43 import design as sq43
from shintai.spine.robots import STANDARD_GRAVITY


def quadratic(centre):
    centre = np.asarray(centre, dtype=float)
    return lambda a: -float(np.sum((np.asarray(a) - centre) ** 2))


def test_finds_a_known_optimum_on_the_grid_by_single_steps():
    path = sq43.compass_search(quadratic([3.5, -2.0, 7.5]), [0.0, 0.0, 0.0])
    assert np.allclose(path.end, [3.5, -2.0, 7.5])
    assert len(path.points) - 1 == 7 + 4 + 15  # the L1 distance in 0.5° steps
    steps = np.diff(np.array(path.points), axis=0)
    assert np.all(np.count_nonzero(steps, axis=1) == 1)
    assert np.allclose(np.abs(steps).sum(axis=1), sq43.STEP_DEG)
    assert np.all(np.diff(path.values) > 0)


def test_moves_to_the_best_of_the_2m_neighbours():
    f = lambda a: 3 * a[0] + a[1] - 10 * abs(a[2])  # noqa: E731
    path = sq43.compass_search(f, [0.0, 0.0, 0.0], bound=1.0)
    assert np.allclose(path.points[1], [0.5, 0.0, 0.0])  # steepest single coordinate first
    assert np.allclose(path.end, [1.0, 1.0, 0.0])


def test_respects_the_bounds():
    path = sq43.compass_search(quadratic([40.0, 0.0, -45.0]), [0.0, 0.0, 0.0])
    assert np.allclose(path.end, [30.0, 0.0, -30.0])
    assert np.abs(np.array(path.points)).max() <= sq43.BOUND_DEG


def test_respects_a_feasibility_constraint_and_stops_on_it():
    visited = []

    def f(a):
        visited.append(np.array(a))
        return float(a[0] + a[1])

    path = sq43.compass_search(f, [0.0, 0.0, 0.0], is_feasible=lambda a: a[0] + 2 * a[1] <= 10.0)
    assert all(a[0] + 2 * a[1] <= 10.0 for a in visited)
    assert path.end[0] + 2 * path.end[1] <= 10.0
    assert len(visited) == path.evaluations  # every distinct point evaluated once


def test_stops_where_the_current_point_ties_its_best_neighbour():
    path = sq43.compass_search(lambda a: 1.0, [5.0, 5.0, 5.0])  # eq. 3.2: f(t) = f(t + δt)
    assert len(path.points) == 1 and path.evaluations == 7


def test_rejects_an_infeasible_start():
    with pytest.raises(ValueError, match="feasible"):
        sq43.compass_search(lambda a: 0.0, [31.0, 0.0, 0.0])


def test_eq_3_1_fourth_angle_and_feasibility():
    a4 = sq43.fourth_angle([5.0, 5.0, 5.0])
    assert np.sum(np.sin(np.radians([5.0, 5.0, 5.0, a4]))) == pytest.approx(0.0, abs=1e-12)
    assert a4 == pytest.approx(-15.157, abs=1e-3)
    assert all(sq43.feasible(s) for s in sq43.TABLE_3_1)
    assert not sq43.feasible([30.0, 30.0, 30.0])  # a4 would be −90°
    assert not sq43.feasible([20.0, 20.0, -5.0])  # |a4| > 30°
    assert np.isnan(sq43.fourth_angle([90.0, 90.0, 0.0]))


def test_spine_shape_keeps_both_ends_level_and_the_length():
    prm = sq43.SQ43Params()
    shape = sq43.spine_shape([15.0, 5.0, -15.0], prm)
    assert shape.polyline[-1][2] == pytest.approx(shape.polyline[0][2], abs=1e-12)
    span = shape.polyline[0][1] - shape.polyline[-1][1]
    assert span == pytest.approx(prm.spine_length_m)


def test_flat_spine_twists_as_three_foam_blocks_in_series():
    prm = sq43.SQ43Params()
    assert sq43.torsional_stiffness([0.0, 0.0, 0.0], prm) == pytest.approx(prm.k_torsion / 3)
    C = sq43.spine_compliance(sq43.spine_shape([10.0, -5.0, 20.0], prm), prm)
    assert np.allclose(C, C.T) and np.linalg.eigvalsh(C).min() > 0


def test_inclined_blocks_turn_twist_into_stiff_lateral_bending():
    """Block axes at β = (30°, 0°, −30°): twist compliance Σ cos²β / k_t + sin²β / k_lateral."""
    prm = sq43.SQ43Params()
    beta = np.radians([30.0, 0.0, -30.0])
    compliance = np.sum(np.cos(beta) ** 2 / prm.k_torsion + np.sin(beta) ** 2 / prm.k_bend_lateral)
    assert sq43.torsional_stiffness([30.0, 30.0, -30.0], prm) == pytest.approx(1 / compliance)
    assert sq43.torsional_stiffness([30.0, 30.0, -30.0], prm) > sq43.torsional_stiffness([0.0, 0.0, 0.0], prm)


def test_lift_carries_the_weight_and_a_stiffer_foam_lifts_the_foot_higher():
    prm = sq43.SQ43Params()
    res = sq43.lift_left_front([5.0, 5.0, 5.0], prm)
    assert res.reactions_n.sum() == pytest.approx(prm.mass_kg * STANDARD_GRAVITY)
    assert res.reactions_n.min() >= -1e-9  # no foot pulls the ground
    assert 0.0 < res.height_m < prm.lift_m  # the twisting spine lets the front sag
    stiffer = sq43.lift_left_front([5.0, 5.0, 5.0], replace(prm, k_torsion=2 * prm.k_torsion))
    assert stiffer.height_m > res.height_m


def test_search_on_the_spine_model_ends_at_a_feasible_local_maximum():
    path = sq43.compass_search(sq43.lifted_foot_height_mm, sq43.TABLE_3_1[0], is_feasible=sq43.feasible)
    assert sq43.feasible(path.end) and path.best > path.values[0]
    for e in np.eye(3):
        for s in (1, -1):
            a = path.end + s * sq43.STEP_DEG * e
            assert not sq43.feasible(a) or sq43.lifted_foot_height_mm(a) <= path.best
