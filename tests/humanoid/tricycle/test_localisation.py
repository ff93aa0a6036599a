"""Self-localisation (seed 000 §7.3.2): the MCL converges on a known map from a wrong initial guess, the
odometry motion model moves the particles by the increment, the wheel odometry follows Eq. 4.15, and the
visual odometry's drift is the documented one."""

import math

import numpy as np
import pytest

from shintai.humanoid.tricycle.ch4_riding import Obstacle
from shintai.humanoid.tricycle.localisation import (
    LOCALISATION,
    ParticleFilter,
    VisualOdometry,
    WheelOdometry,
    box_map,
    compose,
    relative,
)

ROOM = [Obstacle("front", (0.05, 2.0, 0.5), (4.0, 0.0, 0.5)), Obstacle("right", (2.5, 0.05, 0.5), (1.5, -2.0, 0.5)),
        Obstacle("left", (1.0, 0.05, 0.5), (2.5, 2.0, 0.5)), Obstacle("pillar", (0.15, 0.15, 0.5), (2.5, -0.8, 0.5))]


def sensed(cmap, pose, fov=math.radians(80), max_range=5.0):
    """Occupied cell centres within the field of view of ``pose``, in its frame (no occlusion)."""
    i, j = np.nonzero(cmap.occupied)
    world = cmap.centre(i, j)
    local = np.array([relative(pose, (x, y, 0.0))[:2] for x, y in world])
    r, a = np.hypot(*local.T), np.arctan2(local[:, 1], local[:, 0])
    keep = (r < max_range) & (np.abs(a) < fov / 2)
    return local[keep]


def test_mcl_converges_from_wrong_guess():
    cmap = box_map(ROOM)
    truth = np.array([1.0, 0.3, -0.3])
    guess = truth + [0.35, -0.3, 0.15]  # 46 cm and 8.6° off
    pf = ParticleFilter(cmap, guess, rng=np.random.default_rng(1), sigma=(0.3, 0.3, 0.2))
    points = sensed(cmap, truth)
    assert len(points) > 100
    for _ in range(20):
        pf.predict((0.0, 0.0, 0.0))
        assert pf.correct(points)
    est = pf.pose
    assert np.hypot(*(est[:2] - truth[:2])) < 0.05
    assert abs(est[2] - truth[2]) < math.radians(2)
    assert pf.resamples > 0


def test_motion_model_moves_by_increment():
    cmap = box_map(ROOM)
    pf = ParticleFilter(cmap, (0.0, 0.0, 0.5), rng=np.random.default_rng(2), sigma=(0.0, 0.0, 0.0))
    d = (0.2, 0.01, 0.05)
    pf.predict(d)
    np.testing.assert_allclose(pf.pose, compose((0.0, 0.0, 0.5), d), atol=0.01)
    assert pf.p[:, 0].std() > 0  # noise grows with the motion (Table 5.6)
    assert not pf.correct(np.zeros((3, 2)))  # too few points: prediction only


def test_wheel_odometry_arc():
    """Eq. 4.15: one crank revolution at φ turns the rear axle by D_c tan φ / L along an arc."""
    odo = WheelOdometry((0.0, 0.0, 0.0), d_c=2.45, wheelbase=1.2, back=0.6)
    odo.step(0.0, math.radians(-25))
    for k in range(1, 101):
        odo.step(2 * math.pi * k / 100, math.radians(-25))
    dtheta = 2.45 * math.tan(math.radians(-25)) / 1.2
    assert odo.axle[2] == pytest.approx(dtheta, rel=1e-9)
    radius = 1.2 / math.tan(math.radians(-25))
    assert odo.axle[0] == pytest.approx(-0.6 + radius * math.sin(dtheta), abs=1e-9)


def test_visual_odometry_drift():
    """Straight 1 m of camera motion: the estimate is longer by the scale error and turned by the drift."""
    vo = VisualOdometry((0.0, 0.0, 0.0), rng=np.random.default_rng(3))
    for k in range(101):
        pose = vo.step((0.01 * k, 0.0, 0.0), (0.0, 0.0, 0.0))
    s = LOCALISATION
    assert np.hypot(*pose[:2]) == pytest.approx(1 + s.vo_scale, abs=0.03)
    assert pose[2] == pytest.approx(s.vo_yaw_drift, abs=0.03)


def test_jitter_does_not_spin_particles():
    """A millimetre backward jitter (the head moving while the handle turns) leaves the headings alone
    (AMCL's odometry model: rot1 = 0 below 1 cm)."""
    pf = ParticleFilter(box_map(ROOM), (0.0, 0.0, 0.0), rng=np.random.default_rng(4), sigma=(0.0, 0.0, 0.0))
    for _ in range(20):
        pf.predict((-0.002, 0.001, 0.0))
    assert np.abs(pf.p[:, 2]).max() < 0.01


def test_odometry_scenario_short(smoke):
    """humanoid.odometry's smoke run, 0.4 m at −25° pedalled by the legs: the tricycle turns right and stops; the
    MCL stays within a few centimetres of the truth and ends nearer than the wheel odometry."""
    out = smoke("humanoid.odometry").result
    m = out["metrics"]
    assert "error" not in out and m["stopped"] == 1 and m["overturned"] == 0
    assert m["true_end_yaw_deg"] < -3 and m["true_end_y_m"] < 0  # a right turn at θ_h = −25°
    assert m["handle_end_deg"] == pytest.approx(-25, abs=3)
    assert m["localisation_max_error_m"] < 0.06
    assert m["localisation_end_error_m"] < m["wheel_end_error_m"]
    assert m["mcl_corrections"] == m["mcl_updates"]  # the room is always in view


def test_navigation_on_estimated_pose_short(smoke):
    """obstacle-navigation's smoke run, 5 s: the scan placed by the MCL pose puts the wall in the costmap, the
    estimate stays within 5 cm while the wall is in view; pose=estimated runs the estimated variant alone."""
    from shintai.scenarios.registry import get

    sc = get("humanoid.obstacle-navigation")
    assert list(sc.variants(sc.resolve({"pose": "estimated"}))) == ["estimated"]
    out = smoke("humanoid.obstacle-navigation").result
    m = out["metrics"]
    assert "error" not in out and m["reached_estimated"] == 0
    assert m["wall_in_costmap_estimated"] == 1 and m["mcl_corrected_share_estimated"] == 1.0
    assert m["min_clearance_estimated_m"] > 0.0 and m["path_length_estimated_m"] > 0.2
    assert m["localisation_max_error_estimated_m"] < 0.05 and m["overturned_estimated"] == 0
