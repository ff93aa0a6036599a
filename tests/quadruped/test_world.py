"""The environments of seed §4.1.1 (Table 1), the named scenarios and the held-out generator."""

import numpy as np
import pytest

from shintai.quadruped import constants as C
from shintai.quadruped import episode as E
from shintai.quadruped import robot as R
from shintai.quadruped import world as W


def test_training_set_has_96_environments_with_exactly_one_wall_each():
    envs = W.training_set()
    assert len(envs) == 96 == 4 * 2 * 4 * 3
    assert len({e.name for e in envs}) == 96
    for env in envs:
        walls = [o for o in env.obstacles if not o.surmountable]
        assert len(walls) == 1 and walls[0].height == C.WALL_HEIGHT
        assert [o.height for o in env.obstacles if o.surmountable][0] in C.TRAINING_HEIGHTS
        assert tuple(env.destination) in C.DESTINATIONS
        assert np.all(env.right.polygon[:, 0] > 0) and np.all(env.left.polygon[:, 0] < 0)


def test_every_training_obstacle_is_a_0_2_m_deep_parallelogram():
    for env in W.training_set():
        for o in env.obstacles:
            c = np.asarray(o.corners)
            assert np.isclose(abs(c[0, 1] - c[1, 1]), 0.2) and np.isclose(abs(c[2, 1] - c[3, 1]), 0.2)
            assert np.isclose(c[0, 0], c[1, 0]) and np.isclose(c[2, 0], c[3, 0])


def test_section_5_2_environment_is_training_member_x2_y2():
    s52 = W.scenario_52()
    member = next(e for e in W.training_set() if e.name == "x2y2-r0.12-l0.3-d3")
    assert np.allclose(member.right.corners, s52.right.corners) and np.allclose(member.left.corners, s52.left.corners)
    assert (member.right.height, member.left.height, member.destination) == (0.12, 0.3, s52.destination)


def test_named_scenarios_match_the_paper():
    s421, s422 = W.scenario_421(), W.scenario_422()
    assert (s421.right.height, s421.left.height, s421.destination) == (0.3, 0.12, (-0.15, 2.2))
    assert (s422.right.height, s422.left.height, s422.destination) == (0.07, 0.3, (0.35, 2.1))
    assert W.scenario_621().right == s421.right and W.scenario_622().left == W.scenario_52().left


def test_bad_obstacles_are_rejected_in_one_line():
    with pytest.raises(ValueError, match="convex"):
        W.Obstacle(((0, 0), (1, 1), (1, 0), (0, 1)), 0.1)
    with pytest.raises(ValueError, match="4 finite"):
        W.Obstacle(((0, 0), (1, 0), (1, 1)), 0.1)
    with pytest.raises(ValueError, match="too thin"):
        W.Obstacle(((0, 0), (1, 0), (1, 0.05), (0, 0.05)), 0.1)


def test_unseen_environments_are_seeded_and_within_the_ranges():
    a, b = W.unseen_environments(40, seed=3), W.unseen_environments(40, seed=3)
    assert a == b and a != W.unseen_environments(40, seed=4)
    for env in a:
        heights = sorted(o.height for o in env.obstacles)
        assert heights[1] == C.WALL_HEIGHT and C.UNSEEN_HEIGHTS[0] <= heights[0] <= C.UNSEEN_HEIGHTS[1]
        assert C.UNSEEN_DEST_X[0] <= env.destination[0] <= C.UNSEEN_DEST_X[1]
        assert C.UNSEEN_DEST_Y[0] <= env.destination[1] <= C.UNSEEN_DEST_Y[1]
    jitter = [np.abs(np.asarray(e.right.corners)[:, 0] - 0.5).min() for e in a]
    assert 0 < max(jitter) <= C.JITTER


def test_sentinels_replace_an_obstacle_behind_the_body():
    envs = W.EnvBatch.of([W.scenario_52()])
    ahead = E.obstacle_features(np.zeros((1, 3)), envs)[0]
    assert np.allclose(ahead[0], [0.5, 0.1, 0.86, 0.65, 0.12, 0.0])
    passed = E.obstacle_features(np.array([[0.0, 1.0, 0.0]]), envs)[0]
    assert np.allclose(passed, [C.SENTINEL_RIGHT, C.SENTINEL_LEFT])


def test_footholds_leave_the_forbidden_bands():
    envs = W.EnvBatch.of([W.scenario_52()])  # right: x 0.1..0.5, y ~0.65..0.86, h 0.12; left wall
    planned = np.array([[[0.3, 0.66], [0.3, 0.75], [0.08, 0.75], [-0.3, 0.70], [0.3, 0.3]]])
    foot, stand, ok = R.snap_footholds(planned, envs)
    assert ok.all()
    assert stand[0, 0] == 0 and foot[0, 0, 2] == 0.12  # 5 mm inside the edge: onto the top, 30 mm in
    assert np.isclose(W.signed_distance(foot[0, 0, :2], envs.polygons[0, 0]), -C.TOP_BAND)
    assert np.linalg.norm(foot[0, 0, :2] - planned[0, 0]) < 0.03
    assert np.allclose(foot[0, 1], [0.3, 0.75, 0.12]) and stand[0, 1] == 0  # admissible already
    assert np.allclose(foot[0, 2], [0.05, 0.75, 0.0]) and stand[0, 2] == -1  # off the edge band
    assert stand[0, 3] == -1 and foot[0, 3, 2] == 0.0  # never on a wall top
    assert np.allclose(foot[0, 4], [0.3, 0.3, 0.0])
    sd = W.signed_distance(foot[0, :, None, :2], envs.polygons[0])
    assert np.all((sd >= C.GROUND_BAND - 1e-9) | ((sd <= -C.TOP_BAND + 1e-9) & envs.surmountable[0]))
