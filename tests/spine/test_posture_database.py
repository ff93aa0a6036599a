"""The posture database (seed 003 §5.9.1), the push trigger's two levels (§5.9.3), and spine.posture-database's
smoke run."""

import numpy as np
import pytest

from shintai.scenarios.registry import ParameterError, get
from shintai.spine.posture_database import PostureDatabase
from shintai.spine.robots import CLA
from shintai.spine.tactile import STRONG, WEAK, PushTrigger, TriggerLevels, moment_arms, nudge_target, push_moment

D = 3e-3


def _db(**kw):
    db = PostureDatabase(D, **kw)
    db.observe(np.zeros(8), t=0.0)
    return db


@pytest.mark.parametrize("scale, made", [(1 - 1e-6, False), (1 + 1e-6, True)])
def test_node_created_only_beyond_the_threshold(scale, made):
    db = _db()
    direction = np.ones(8) / np.sqrt(8)
    node, created = db.observe(scale * D * direction, t=0.02)
    assert created is made and len(db.nodes) == 1 + made
    assert node.id == (1 if made else 0)
    assert db.violations() == 0


def test_far_from_every_node_not_just_the_last():
    db = _db()
    e = np.eye(8)
    db.observe(2 * D * e[0])  # a second node
    node, created = db.observe(2 * D * e[0] + 0.5 * D * e[1])  # near node 1 only
    assert not created and node.id == 1
    node, created = db.observe(1.2 * D * e[0])  # 1.2 D from node 0, 0.8 D from node 1: near node 1
    assert not created and node.id == 1


def test_posture_sensor_splits_a_node_separately():
    db = PostureDatabase(D, d_sensor=np.radians(5))
    db.observe(np.zeros(8), sensor=np.zeros(2))
    _, created = db.observe(np.full(8, 1e-4), sensor=np.radians([4.0, 0.0]))
    assert not created
    _, created = db.observe(np.full(8, 1e-4), sensor=np.radians([6.0, 0.0]))  # same lengths, sensor beyond
    assert created and db.violations() == 0


def test_nearest_node_and_plan():
    db = _db()
    e = np.eye(8)
    for k in (1, 2, 3):
        db.observe(2 * k * D * e[0])
    assert db.nearest(2.9 * D * e[0]).id == 1 and db.nearest(3.1 * D * e[0]).id == 2
    assert db.plan([0.1 * D * e[0], 0.2 * D * e[0], 5.8 * D * e[0], 4.1 * D * e[0]]) == [0, 3, 2]


def test_history_records_changes_and_stays_in_overlap():
    db = _db()
    e = np.eye(8)
    db.observe(1.5 * D * e[0])  # node 1, 1.5 D away
    for x in (0.45, 0.55, 0.45, 0.55):  # in both neighbourhoods: stays at node 1, no flicker
        db.observe(x * 1.5 * D * e[0])
    db.observe(np.zeros(8) + 0.1 * D * e[0])  # only near node 0
    assert db.history == [0, 1, 0] and db.nodes[0].visits == 2


def test_database_rejects_bad_input():
    with pytest.raises(ValueError):
        PostureDatabase(0.0)
    with pytest.raises(ValueError):
        _db().observe(np.full(8, np.nan))


def test_trigger_two_levels():
    lv = TriggerLevels(weak_nm=0.15, strong_nm=0.6, min_push_s=0.04)
    dt = 1e-3

    def push(peak, axis=1, hold_s=0.2):
        trig, out = PushTrigger(lv), []
        profile = np.concatenate([np.linspace(0, peak, 50), np.full(int(hold_s / dt), peak), np.linspace(peak, 0, 50)])
        for k, size in enumerate(profile):
            tau = np.zeros(3)
            tau[axis] = size
            fired = trig.update(tau, k * dt)
            if fired:
                out.append(fired)
        return out

    assert push(0.10) == []  # below weak: nothing
    (weak,) = push(0.3, axis=0)
    assert weak.level == WEAK and weak.axis == 0 and weak.sign == 1.0
    assert weak.nudge_deg == pytest.approx(lv.gain_deg_per_nm * 0.3, rel=0.02)
    (strong,) = push(0.7)  # strong, fired once
    assert strong.level == STRONG
    assert [f.level for f in push(0.59)] == [WEAK]  # just under strong: weak
    assert push(0.3, hold_s=0.0)[0].level == WEAK  # 0.1 s above half peak: long enough
    with pytest.raises(ValueError):
        TriggerLevels(weak_nm=0.5, strong_nm=0.4)


def test_push_moment_sign_and_nudge():
    arms = moment_arms(CLA.model, np.zeros(3))
    # muscles stretched by +pitch carry more tension under a forward push: τ̂ pitch > 0
    tension = np.where(arms[:, 1] > 0, 5.0, 0.0)
    assert push_moment(arms, tension, np.zeros(8))[1] > 0
    lv = TriggerLevels()
    trig = PushTrigger(lv)
    trig.update(np.array([0, 0.3, 0]), 0.0)
    fired = trig.update(np.array([0, 0.01, 0]), 0.1)
    lengths, whole = nudge_target(CLA.model, np.zeros(3), fired)
    assert np.degrees(whole[1]) == pytest.approx(6.0) and lengths.shape == (8,)


def test_posture_database_short_run(smoke):
    run = smoke("spine.posture-database")
    m = run.result["metrics"]
    assert m["triggers_weak_as_meant"] == 1 and m["triggers_strong"] == 0 and m["nudges"] == 1
    assert m["triggers_unprompted"] == 0 and m["node_pairs_within_threshold"] == 0  # metric kept, check dropped
    assert m["nodes_created_move"] >= 1 and m["history_length"] < m["direct_teaching_samples"]
    assert m["replay_posture_error_max_deg"] < 5.0
    assert (run.out / "node_graph.png").exists()


def test_posture_database_rejects_crossed_levels():
    with pytest.raises(ParameterError):
        get("spine.posture-database").resolve({"weak_nm": "1.0", "strong_nm": "0.5"})
