"""Static stability (seed §2.2), the crawl executor (§1.6, §4) and the body-raise rule."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shintai.quadruped import constants as C
from shintai.quadruped import replay as P
from shintai.quadruped import robot as R
from shintai.quadruped import swing_order as S
from shintai.quadruped import world as W

ENVIRONMENTS = W.training_set() + W.unseen_environments(24, seed=11)


def test_stability_margin_of_a_triangle_and_the_stance():
    tri = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    assert np.isclose(R.stability_margin(np.array([0.25, 0.25]), tri), 0.25)
    assert np.isclose(R.stability_margin(np.array([0.25, -0.1]), tri), -0.1)
    assert np.isclose(R.stability_margin(np.array([0.25, 0.25]), tri[::-1]), 0.25)  # any orientation
    stance = np.array(C.INITIAL_FEET)
    assert np.isclose(R.stability_margin(np.zeros(2), stance), 0.25)  # hull of four feet, not a diagonal


def test_longitudinal_margin_measures_along_the_heading():
    square = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
    cog = np.array([0.5, 0.2])
    assert np.isclose(R.longitudinal_margin(cog, square, np.array(0.0)), 0.8)
    assert np.isclose(R.longitudinal_margin(cog, square, np.array(np.pi / 2)), 0.5)


def test_bad_commands_and_orders_are_rejected_in_one_line():
    state, envs = R.CrawlState.initial(1), W.EnvBatch.flat(1)
    with pytest.raises(ValueError, match="permutations of the legs"):
        R.crawl_cycle(state, np.zeros((1, 3)), np.array([[1, 2, 2, 4]]), np.array([0.3]), envs)
    with pytest.raises(ValueError, match="finite with shape"):
        R.crawl_cycle(state, np.full((1, 3), np.nan), np.array([[4, 2, 3, 1]]), np.array([0.3]), envs)


def check_cycle(feet_before: np.ndarray, out: R.CycleOutcome, order) -> None:
    """The record of one cycle against an independent recomputation of its support triangles."""
    rec = out.record(0, 1, np.zeros(3), order)
    feet = feet_before[:, :2].copy()
    for s, leg in enumerate(np.asarray(order) - 1):
        support = [j for j in range(4) if j != leg]
        assert np.allclose(rec.support_triangles[s], feet[support])
        assert np.allclose(rec.cog[s], rec.body_poses[s + 1, :2])  # the body stands still while leg swings
        margin = R.stability_margin(rec.cog[s], feet[support])
        assert np.isclose(margin, rec.margins[s])
        if not rec.unstable:
            assert margin >= C.STABILITY_MARGIN - 1e-9 > 0  # strictly inside the support triangle
        feet[leg] = rec.footholds[leg, :2]
    steps = np.diff(rec.body_poses[:, :2], axis=0)
    assert np.isclose(rec.br_mm, 1000 * np.linalg.norm(steps, axis=1).sum())  # Br = the body's path
    assert np.allclose(rec.body_poses[-1], out.state.pose[0])


@settings(max_examples=150, deadline=None, derandomize=True)
@given(env=st.integers(0, len(ENVIRONMENTS) - 1),
       cycles=st.lists(st.tuples(st.floats(-0.1, 0.1), st.floats(0.0, 0.35), st.floats(-0.26, 0.26),
                                 st.one_of(st.sampled_from([S.CRAWL, 13, 11]), st.integers(0, 23)),
                                 st.sampled_from([0.30, 0.33, 0.36, 0.37])),
                       min_size=1, max_size=5))
def test_static_stability_holds_at_every_swing_instant(env, cycles):
    """Random commands, orders and heights in training and held-out environments: at every swing the
    CoG is inside the support triangle by the margin (unless the cycle is flagged unstable)."""
    envs = W.EnvBatch.of([ENVIRONMENTS[env]])
    state = R.CrawlState.initial(1)
    for dx, dy, dth, order, zr in cycles:
        out = R.crawl_cycle(state, np.array([[dx, dy, dth]]), S.ORDERS[[order]], np.array([zr]), envs)
        check_cycle(state.feet[0], out, S.PERMUTATIONS[order])
        if out.failed[0]:
            break
        state = out.state


@pytest.mark.parametrize("table", list(P.TABLES))
def test_paper_tables_are_feasible(table):
    """Every executed cycle of Tables 3, 6, 7 (their actions, Zr and orders) runs without collision,
    joint-limit violation or lost stability in its environment (the basis of SHOULDER_XY)."""
    replay = P.replay_executor(table)
    assert not (replay.collided or replay.limit or replay.unstable)


def test_paper_tables_climb_with_the_legs_the_paper_names():
    stood = {t: {leg for r in P.replay_executor(t).records for leg in np.flatnonzero(r.stands_on >= 0)}
             for t in ("table6", "table7")}
    assert stood["table6"] <= {0, 2} and 0 in stood["table6"]  # left obstacle: leg 1 climbs (§6.2.1)
    assert stood["table7"] == {1, 3}  # right obstacle: legs 2 and 4 climb (§6.2.2)


def test_body_raise_rule_gives_the_printed_zr():
    agree = total = 0
    for table, (actions, orders, env) in P.TABLES.items():
        envs = W.EnvBatch.of([env()])
        zr, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
        state = R.CrawlState.initial(1)
        for z, c, o in zip(zr, command, orders):
            agree += np.isclose(R.body_height(state.pose, state.feet, envs)[0], z)
            total += 1
            state = R.crawl_cycle(state, c[None], S.ORDERS[[o]], np.array([z]), envs).state
    assert (agree, total) == (30, 31)  # all but Table 3 cycle 7


def test_a_step_into_the_wall_collides():
    envs = W.EnvBatch.of([W.scenario_52()])  # left wall from x = -0.5 to -0.2, y 0.55..0.85
    state = R.CrawlState.initial(1)
    out = R.crawl_cycle(state, np.array([[-0.12, 0.25, 0.0]]), S.ORDERS[[S.CRAWL]], np.array([0.3]), envs)
    state = out.state
    out = R.crawl_cycle(state, np.array([[-0.1, 0.25, 0.0]]), S.ORDERS[[S.CRAWL]], np.array([0.3]), envs)
    assert out.collided[0]


def _one(right: W.Obstacle, left: W.Obstacle) -> W.EnvBatch:
    return W.EnvBatch.of([W.Environment("test", right, left, (0.0, 2.0))])


FAR = W.Obstacle(((3.0, 3.0), (3.3, 3.0), (3.3, 3.3), (3.0, 3.3)), 0.06)  # out of the way


def test_the_trunk_collides_on_a_body_shift_only_with_what_is_taller_than_its_underside():
    """The body-shift check (every key pose's move): a block between the legs, ahead, is hit by a
    0.5 m forward shift when it is a wall, passed over when it is lower than the trunk's underside."""
    start, end, zr = np.zeros((1, 3)), np.array([[0.0, 0.5, 0.0]]), np.array([0.3])
    block = ((-0.1, 0.4), (0.1, 0.4), (0.1, 0.6), (-0.1, 0.6))
    assert R.trunk_collides(start, end, zr, _one(W.Obstacle(block, 0.3), FAR))[0]
    assert not R.trunk_collides(start, end, zr, _one(W.Obstacle(block, 0.06), FAR))[0]
    assert not R.trunk_collides(start, start, zr, _one(W.Obstacle(block, 0.3), FAR))[0]  # not reached


def test_a_swing_path_over_a_wall_collides_and_over_a_low_obstacle_lifts_the_foot():
    a, b = np.array([[0.3, 0.0, 0.0]]), np.array([[0.3, 0.5, 0.0]])
    block = ((0.2, 0.2), (0.4, 0.2), (0.4, 0.4), (0.2, 0.4))
    apex, wall = R.swing_height(a, b, _one(W.Obstacle(block, 0.3), FAR))
    assert wall[0]
    apex, wall = R.swing_height(a, b, _one(W.Obstacle(block, 0.08), FAR))
    assert not wall[0] and apex[0] == pytest.approx(0.08 + C.SWING_CLEARANCE)


def test_a_step_beyond_the_legs_reach_violates_the_joint_limits():
    """The joint limits are checked at the swing's key poses: 0.2 m steps are within reach, a 0.6 m
    step is not (l1 + l2 = 0.355 m)."""
    envs = W.EnvBatch.flat(2)
    out = R.crawl_cycle(R.CrawlState.initial(2), np.array([[0.0, 0.2, 0.0], [0.0, 0.6, 0.0]]),
                        S.ORDERS[[S.CRAWL, S.CRAWL]], np.full(2, C.ZR_NOMINAL), envs)
    assert not out.limit[0] and out.limit[1]
    assert not out.collided.any()
