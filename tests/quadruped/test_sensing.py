"""The ultrasonic sensing model (seed §3, eqs. 3-6 corrected) and the sensor-in-the-loop rollout."""

import math

import numpy as np
import pytest

from shintai.quadruped import constants as C
from shintai.quadruped import episode as E
from shintai.quadruped import fitness as F
from shintai.quadruped import robot as R
from shintai.quadruped import sensing as U
from shintai.quadruped import training as T
from shintai.quadruped import world as W

RAD = math.radians


def test_equations_3_to_6_by_hand_for_the_right_front_leg():
    t0, t1, t2, L = RAD(-10), RAD(10), RAD(-100), 0.3
    reach = C.L0 + C.L1 * math.cos(t1) + C.L2 * math.cos(t2)  # corrected: the paper prints l2 sin θ2
    xs, ys = C.SHOULDER_XY[1]
    forward = U.obstacle_point(np.array([t0, t1, t2]), L, 1, U.FORWARD)
    side = U.obstacle_point(np.array([t0, t1, t2]), L, 1, U.SIDE)
    assert forward == pytest.approx([xs + reach * math.cos(t0) - L * math.sin(t0),
                                     ys + reach * math.sin(t0) + L * math.cos(t0)])  # eqs. (3), (4)
    assert side == pytest.approx([xs + reach * math.cos(t0) + L * math.cos(t0),
                                  ys + reach * math.sin(t0) + L * math.sin(t0)])  # eqs. (5), (6)
    assert forward == pytest.approx([0.1 + 0.16044 + 0.05209, 0.275 - 0.02829 + 0.29544], abs=1e-4)


def test_left_front_leg_forward_beam_is_mirrored_and_points_forward():
    t0, t1, t2, L = RAD(190), RAD(10), RAD(-100), 0.3
    reach = C.L0 + C.L1 * math.cos(t1) + C.L2 * math.cos(t2)
    xs, ys = C.SHOULDER_XY[0]
    forward = U.obstacle_point(np.array([t0, t1, t2]), L, 0, U.FORWARD)
    assert forward == pytest.approx([xs + reach * math.cos(t0) + L * math.sin(t0),
                                     ys + reach * math.sin(t0) - L * math.cos(t0)])
    right = U.obstacle_point(np.array([RAD(-10), t1, t2]), L, 1, U.FORWARD)
    assert forward == pytest.approx([-right[0], right[1]])  # mirror image of leg 2 at 180° - θ0
    side = U.obstacle_point(np.array([t0, t1, t2]), L, 0, U.SIDE)
    assert side[0] < forward[0] - 0.2  # the side beam points outwards (left)
    with pytest.raises(ValueError, match="front legs"):
        U.beam_direction(0.0, 2, U.FORWARD)


def test_a_zero_reading_is_the_foot_tip_of_equation_1():
    rng = np.random.default_rng(0)
    theta = np.column_stack([rng.uniform(-1, 1, 20), rng.uniform(-1, 1, 20), rng.uniform(-2.5, 0, 20)])
    for leg in (0, 1):
        foot = R.fk(theta, np.r_[C.SHOULDER_XY[leg], 0.0])
        assert np.allclose(U.obstacle_point(theta, 0.0, leg, U.SIDE), foot[:, :2], atol=1e-12)


def box(x0, x1, y0, y1):
    return W.ccw(np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float))


def cast(poly, height=0.3, origin=(0.0, 0.0), direction=(0.0, 1.0), beam_z=C.BEAM_HEIGHT, **kw):
    return U.cast(np.array(origin, dtype=float), np.array(direction, dtype=float), np.array(beam_z),
                  np.asarray(poly)[None], np.array([height]), **kw)


def test_a_beam_meeting_a_wall_at_right_angles_returns_its_distance():
    echo = cast(box(-0.5, 0.5, 0.3, 0.5))
    assert echo.distance == pytest.approx(0.3) and echo.obstacle == 0 and echo.incidence == pytest.approx(0.0)
    side = cast(box(0.2, 0.4, -0.5, 0.5), direction=(1.0, 0.0))
    assert side.distance == pytest.approx(0.2)


def test_nothing_beyond_the_configured_range():
    assert cast(box(-0.5, 0.5, 0.49, 0.7)).distance == pytest.approx(0.49)
    far = cast(box(-0.5, 0.5, C.SENSOR_RANGE + 0.01, 0.7))
    assert np.isnan(far.distance) and far.obstacle == -1
    assert np.isnan(cast(box(-0.5, 0.5, -0.5, -0.3)).distance)  # behind the sensor


def test_an_oblique_surface_beyond_the_incidence_limit_gives_no_echo_and_hides_what_is_behind():
    def slanted(angle_deg):  # a slab whose near edge is turned by angle_deg, its middle 0.3 m ahead
        c, s = math.cos(RAD(angle_deg)), math.sin(RAD(angle_deg))
        near = np.array([[0.3 * c, 0.3 + 0.3 * s], [-0.3 * c, 0.3 - 0.3 * s]])
        return W.ccw(np.vstack([near, near[::-1] + 0.1 * np.array([-s, c])]))
    assert cast(slanted(10)).distance == pytest.approx(0.3)
    assert cast(slanted(10)).incidence == pytest.approx(RAD(10))
    assert np.isnan(cast(slanted(20)).distance) and cast(slanted(20)).incidence == pytest.approx(RAD(20))
    assert cast(slanted(20), incidence_limit=RAD(25)).distance == pytest.approx(0.3)
    polys = np.stack([slanted(20), box(-0.5, 0.5, 0.45, 0.6)])
    behind = U.cast(np.zeros(2), np.array([0.0, 1.0]), np.array(C.BEAM_HEIGHT), polys, np.array([0.3, 0.3]))
    assert np.isnan(behind.distance)  # the slanted slab deflects the beam: the wall behind is not seen


def test_low_obstacles_and_the_one_the_foot_stands_on_do_not_stop_the_beam():
    low = box(-0.5, 0.5, 0.2, 0.3)
    assert np.isnan(cast(low, height=C.BEAM_HEIGHT).distance)
    assert cast(low, height=C.BEAM_HEIGHT + 0.001).distance == pytest.approx(0.2)
    assert np.isnan(cast(box(-0.5, 0.5, -0.1, 0.3)).distance)  # the sensor is inside it


def test_height_by_raising_the_leg_until_the_echo_stops():
    est = U.height_estimate(np.array([0.06, 0.065, 0.07, 0.12, 0.3]), 0.0)
    assert est[:4] == pytest.approx([0.06, 0.07, 0.07, 0.12]) and est[4] == C.WALL_HEIGHT
    assert U.height_estimate(0.12, 0.06) == pytest.approx(0.12)  # from a foot on a 0.06 m top
    tops = np.linspace(C.BEAM_HEIGHT + 0.001, C.BEAM_HEIGHT + C.RAISE_MAX, 200)
    over = U.height_estimate(tops, 0.0) - tops
    assert np.all((over >= -1e-9) & (over < C.HEIGHT_STEP))
    for leg in (0, 1):  # RAISE_MAX: the highest lift of a front foot at its stance that the joint limits allow
        shoulder = np.r_[C.SHOULDER_XY[leg], C.SHOULDER_DZ]
        lifted = [R.leg_angles(np.r_[C.INITIAL_FEET[leg], z - C.ZR_NOMINAL], shoulder, leg)[1]
                  for z in (C.RAISE_MAX, C.RAISE_MAX + C.HEIGHT_STEP)]
        assert lifted == [True, False]


def test_features_of_points_covering_the_corners_are_the_known_features():
    envs = W.EnvBatch.of([W.scenario_421(), W.scenario_422()])
    pose = np.array([[0.0, 0.0, 0.0], [0.05, 0.1, 0.2]])
    features = U.box_features(pose, envs.polygons, envs.heights[..., None].repeat(4, -1))
    assert np.allclose(features, E.obstacle_features(pose, envs))


def test_sentinels_before_detection_and_after_passing():
    pose = np.zeros((2, 3))
    assert np.array_equal(U.box_features(pose, np.zeros((2, 2, 0, 2)), np.zeros((2, 2, 0))),
                          np.broadcast_to(E.SENTINELS, (2, 2, 6)))
    nothing = U.box_features(pose, np.full((2, 2, 5, 2), np.nan), np.full((2, 2, 5), np.nan))
    assert np.array_equal(nothing, np.broadcast_to(E.SENTINELS, (2, 2, 6)))
    envs = W.EnvBatch.of([W.scenario_421()])
    corners = envs.polygons
    tops = envs.heights[..., None].repeat(4, -1)
    passed = U.box_features(np.array([[0.0, 0.9, 0.0]]), corners, tops)
    assert np.array_equal(passed, E.obstacle_features(np.array([[0.0, 0.9, 0.0]]), envs))
    assert np.array_equal(passed[0], E.SENTINELS)
    half = U.box_features(np.array([[0.0, 0.855, 0.0]]), corners, tops)  # right (y <= 0.85) passed, left not
    assert np.array_equal(half[0, 0], E.SENTINELS[0]) and half[0, 1, 2] > 0


def policy(n):
    return E.GenomePolicy(F.ACTION_NET, T.load_action()[None], n)


def test_rollout_without_perception_is_unchanged():
    envs = T.training_envs(6)
    default, explicit = E.rollout(envs, policy(6)), E.rollout(envs, policy(6), perception=None)

    class Known:  # a perception that hands over the known features goes through the hook unchanged
        def reset(self, envs):
            pass

        def __call__(self, k, rows, state, envs):
            return E.obstacle_features(state.pose, envs)

    hooked = E.rollout(envs, policy(6), perception=Known())
    for field in ("cycles", "reached", "collided", "limit", "unstable", "final_error", "poses", "commands", "zr",
                  "orders", "br"):
        a = getattr(default, field)
        assert np.array_equal(a, getattr(explicit, field), equal_nan=a.dtype.kind == "f")
        assert np.array_equal(a, getattr(hooked, field), equal_nan=a.dtype.kind == "f")


def test_sensed_walk_detects_each_obstacle_on_its_boundary_and_inside_the_true_box():
    env = W.scenario_421()
    envs = W.EnvBatch.of([env])
    p = U.SensedObstacles()
    ep = E.rollout(envs, policy(1), perception=p)
    echo = p.obstacle[0] >= 0
    assert np.all(echo.any(axis=-1)) and np.array_equal(p.obstacle[0][echo], np.where(echo, [[0], [1]], -1)[echo])
    for side in (0, 1):  # every point lies on the boundary of the obstacle that echoed
        pts = p.points[0, side][echo[side]]
        assert np.allclose(W.signed_distance(pts, env.obstacles[side].polygon[None]), 0.0, atol=1e-9)
    first = p.cycle[0][echo].min()
    assert first == 0  # seen from the initial stance
    known, sensed = p.known[0], p.sensed[0]
    assert known.shape == (ep.cycles[0], 2, 6)
    assert np.allclose(known[0], E.obstacle_features(np.zeros((1, 3)), envs)[0])
    ahead = ~np.all(sensed == E.SENTINELS, axis=-1)
    d = (sensed - known)[ahead]
    assert np.all(d[:, [0, 2]] <= 1e-9) and np.all(d[:, [1, 3]] >= -1e-9) and np.allclose(d[:, 4], 0.0, atol=1e-12)
    assert np.all(sensed[0, :, 2] < known[0, :, 2] - 0.15)  # at first the front edge only: the depth is short


def test_range_noise_is_seeded():
    envs = T.training_envs(4)
    runs = []
    for seed in (1, 1, 2):
        p = U.SensedObstacles(noise_std=0.02, seed=seed)
        E.rollout(envs, policy(4), perception=p, max_cycles=3)
        runs.append(p.sensed)
    assert np.array_equal(runs[0], runs[1], equal_nan=True) and not np.array_equal(runs[0], runs[2], equal_nan=True)
    with pytest.raises(ValueError, match="noise_std"):
        U.SensedObstacles(noise_std=-0.1)


def test_sensing_ablation_scenario_runs_on_a_subset(smoke):
    run = smoke("quadruped.sensing-ablation")  # 6 of the 96 environments
    result = run.result
    assert "error" not in result, result.get("error")
    m = result["metrics"]
    assert {c["name"]: c["ok"] for c in result["checks"]} == {
        "known_success_rate": True, "sensed_box_inside_true": True, "feature_error_z_max_m": True,
        "detected_fraction": True}
    assert 0.0 <= m["sensed_success_rate"] <= 1.0 and m["first_detection_cycle"] == 1.0
    assert m["sensed_collision_rate"] + m["sensed_limit_rate"] + m["sensed_timeout_rate"] == pytest.approx(
        1 - m["sensed_success_rate"])
    assert m["s421_sensed_reached"] in (0, 1) and m["s422_sensed_final_error_m"] > 0
    assert len(result["extra"]["environments"]) == 6 and len(result["extra"]["success_vs_noise"]) == 6
    for name in ("sensed_walks.png", "success.png", "sensed_features.png"):
        assert (run.out / name).exists()
