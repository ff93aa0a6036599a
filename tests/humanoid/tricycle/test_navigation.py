"""Large obstacles (seed 000 §4.4.2): the tricycle model Eqs. 4.15–4.28, the depth sensor, the
costmap, the global path and our dynamic-window planner."""

import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.constants import NAVIGATION, SCENE, THETA_H_MAX, TRICYCLE, WHEELBASE
from shintai.humanoid.tricycle.constants import OBSTACLE_GROUP
from shintai.humanoid.tricycle.navigation import (Costmap, DepthSensor, DynamicWindow, crank_rate, crank_reference,
    footprint_points, global_path, handle_reference, integrate_pose, osi_references, trajectory_footprints,
    tricycle_rates)
from shintai.sim.spec import scene_spec

D_C = TRICYCLE.travel_per_rev


def test_bicycle_model_round_trip():
    """Eqs. 4.18–4.21 invert Eqs. 4.15–4.16: the (ω_c, φ) they give reproduce (ẋ, θ̇) at θ = 0 (Eq. 4.17)."""
    for xdot, yaw_rate in [(0.3, 0.05), (0.2, -0.04), (0.4, 0.0)]:
        omega_c = crank_rate(xdot)
        phi = handle_reference(xdot, yaw_rate, limit=math.pi / 2 - 1e-6)
        rates = tricycle_rates(0.0, phi, omega_c, 0.0)
        assert rates[0] == pytest.approx(xdot)
        assert rates[1] == pytest.approx(0.0)
        assert rates[2] == pytest.approx(yaw_rate)
    # Eq. 4.16: one crank revolution per D_c metres; heading θ turns the velocity
    assert tricycle_rates(math.pi / 2, 0.0, 2 * math.pi, 0.0)[:2] == pytest.approx([0.0, D_C])


def test_handle_reference_limits_and_singular_origin():
    assert handle_reference(0.3, 10.0) == pytest.approx(THETA_H_MAX)  # Θ_H = 25° (Table 3.4)
    assert handle_reference(0.0, 0.3) == 0.0  # ẋ^ref = 0: straight (goal reached)
    assert handle_reference(0.3, 0.05) == pytest.approx(math.atan(WHEELBASE * 0.05 / 0.3))


def test_crank_reference_from_measured_angle():
    """Eq. 4.22: θ_c^ref = θ_c(t) + 2πΔt ẋ^ref / D_c."""
    assert crank_reference(1.0, 0.3, 0.8) == pytest.approx(1.0 + 2 * math.pi * 0.8 * 0.3 / D_C)


def test_osi_form_is_the_linearisation():
    """Eq. 4.28 with sgn = −E equals Eq. 4.25, and matches Eq. 4.21 for small yaw rates at ẋ = δẋ*."""
    dx = 0.1
    rho = osi_references(2.0, 0.01, dx, 0.8, dx)
    assert rho[0] == pytest.approx(WHEELBASE / dx * 0.01)
    assert rho[1] == pytest.approx(crank_reference(2.0, dx, 0.8))
    assert rho[0] == pytest.approx(handle_reference(dx, 0.01), rel=0.01)


def test_integrate_pose_arc():
    """A quarter circle of radius v/ω."""
    end = integrate_pose([0.0, 0.0, 0.0], 1.0, 1.0, math.pi / 2)
    assert end == pytest.approx([1.0, 1.0, math.pi / 2])


def test_rollout_and_footprints_are_the_per_pose_steps_bit_for_bit():
    """The planner's float rollout is integrate_pose step by step, and trajectory_footprints is footprint_points
    of each pose stacked: equal to the last bit (the planner's choices depend on them)."""
    rng = np.random.default_rng(0)
    dwa = DynamicWindow()
    for v, w in [(0.3, 0.0), (0.25, 1e-10), *rng.uniform([0.0, -0.5], [0.4, 0.5], (20, 2))]:
        pose = rng.uniform([-2.0, -2.0, -math.pi], [2.0, 2.0, math.pi])
        traj = dwa.rollout(pose, v, w)
        chain = [pose]
        for _ in range(10):
            chain.append(integrate_pose(chain[-1], v, w, NAVIGATION.horizon / 10))
        assert np.array_equal(traj, np.array(chain))
        assert np.array_equal(trajectory_footprints(traj), np.concatenate([footprint_points(p) for p in traj]))


def wall_scene(x=2.0):
    spec = scene_spec("wall", *SCENE)
    spec.worldbody.add_geom(name="wall", type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.05, 1.0, 0.6], pos=[x, 0, 0.6],
                            group=OBSTACLE_GROUP)
    spec.worldbody.add_site(name="head_camera", pos=[0, 0, 1.0])
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


def test_depth_sensor_range_on_a_known_scene():
    model, data = wall_scene(2.0)
    sensor = DepthSensor()
    origin, dirs, dist = sensor.ranges(model, data)
    centre = np.argmin(np.linalg.norm(dirs - [1, 0, 0], axis=1))
    assert dist[centre] == pytest.approx(2.0 - 0.05, abs=0.01)  # the wall's face, nearly straight ahead
    hit = dist >= 0
    assert np.allclose((origin + dirs[hit] * dist[hit, None])[:, 0], 1.95, atol=1e-6)
    # nothing beyond the sensor range, the floor ignored (not an obstacle geom)
    far_model, far_data = wall_scene(NAVIGATION.max_range + 1.0)
    assert (sensor.ranges(far_model, far_data)[2] < 0).all()


def test_costmap_from_a_known_wall():
    model, data = wall_scene(2.0)
    costmap = Costmap()
    assert costmap.mark(DepthSensor().scan(model, data)) > 0
    i, j = np.nonzero(costmap.occupied)
    xy = costmap.centre(i, j)
    assert np.all(np.abs(xy[:, 0] - 1.95) <= costmap.res)  # only the face's cells
    assert xy[:, 1].min() < -0.5 and xy[:, 1].max() > 0.5  # spread across the wall's width
    assert costmap.clearance(np.array([[1.0, 0.0]]))[0] == pytest.approx(0.95, abs=2 * costmap.res)


def blocked_costmap():
    costmap = Costmap()
    ys = np.linspace(-1.0, 0.4, 60)
    costmap.mark(np.stack([np.full_like(ys, 4.0), ys], axis=-1))
    return costmap


def test_global_path_goes_around_the_wall():
    costmap = blocked_costmap()
    path = global_path(costmap, (0.0, 0.0), (8.0, 0.0), NAVIGATION.footprint_r, NAVIGATION.path_margin)
    assert path is not None
    assert costmap.clearance(path).min() > NAVIGATION.footprint_r
    assert path[np.argmin(np.abs(path[:, 0] - 4.0)), 1] > 0.4  # passes the open (+y) end


def test_global_path_costs_what_scipys_dijkstra_finds():
    """The path is 8-connected from the start's cell to the goal's through free cells, and its cost (each step's
    length times the entered cell's weight) is the least scipy's Dijkstra finds on the same graph."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import dijkstra

    costmap, r, margin, penalty = blocked_costmap(), NAVIGATION.footprint_r, NAVIGATION.path_margin, 10.0
    start, goal = (0.0, 0.0), (8.0, 0.0)
    path = global_path(costmap, start, goal, r, margin, penalty)
    i, j = costmap.cell(path)
    steps = np.stack([np.diff(i), np.diff(j)], axis=-1)
    assert np.abs(steps).max() == 1 and np.all(np.abs(steps).sum(axis=1) > 0)
    (si,), (sj,) = costmap.cell(start)
    (gi,), (gj,) = costmap.cell(goal)
    assert (i[0], j[0], i[-1], j[-1]) == (si, sj, gi, gj)
    weight = 1.0 + penalty * np.clip((r + margin - costmap.distance) / margin, 0.0, 1.0)
    free = costmap.distance > r
    free[si, sj] = True
    assert free[i, j].all()
    cost = float(np.sum(np.hypot(*steps.T) * weight[i[1:], j[1:]]))
    n0, n1 = costmap.shape
    a, b = np.meshgrid(np.arange(n0), np.arange(n1), indexing="ij")
    rows, cols, vals = [], [], []
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di or dj:
                ok = (a + di >= 0) & (a + di < n0) & (b + dj >= 0) & (b + dj < n1)
                ok[ok] &= free[(a + di)[ok], (b + dj)[ok]]
                rows.append((a * n1 + b)[ok])
                cols.append(((a + di) * n1 + b + dj)[ok])
                vals.append(math.hypot(di, dj) * weight[(a + di)[ok], (b + dj)[ok]])
    graph = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n0 * n1,) * 2)
    best = dijkstra(graph.tocsr(), indices=si * n1 + sj)[gi * n1 + gj]
    assert cost == pytest.approx(best, rel=1e-12)


def test_dwa_avoids_a_wall():
    """Closed loop on the kinematic model Eq. 4.15: the DWA reaches the goal around the wall
    without the footprint ever touching it, and stops there."""
    costmap = blocked_costmap()
    dwa = DynamicWindow()
    pose, vel = np.zeros(3), (0.0, 0.0)
    goal = (8.0, 0.0)
    min_clear = np.inf
    for k in range(400):
        if k % 10 == 0:
            path = global_path(costmap, pose[:2], goal, NAVIGATION.footprint_r, NAVIGATION.path_margin)
        v, w, _ = dwa.plan(costmap, pose, vel, goal, path)
        vel = (v, w)
        assert abs(w) <= v * math.tan(THETA_H_MAX) / WHEELBASE + 1e-9  # the steering limit
        pose = integrate_pose(pose, v, w, NAVIGATION.period)
        min_clear = min(min_clear, costmap.clearance(footprint_points(pose)).min() - NAVIGATION.footprint_r)
        if (v, w) == (0.0, 0.0):
            break
    assert np.hypot(*(pose[:2] - goal)) <= NAVIGATION.goal_tolerance + 0.05
    assert min_clear > 0.0
