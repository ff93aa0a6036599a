"""The fast crawl (issue 27 item 2) gives the results of the code before it bit for bit.

The golden values below were recorded with the code at 0629247 (before the speed-up): eq. 9 values as
``float.hex`` and a digest of every per-cycle array of the episodes, for populations late in training
(``benchmarks.late_population``) over several environment sets, the fixed order and the free gait; the
cycle records of three scenario walks; and a short GA run's curve. A changed bit anywhere in a walk changes
the digest. The networks are those shipped at 0629247, stored in ``data/networks_0629247.npz`` so that
re-trained networks do not change these tests.
"""

import hashlib
from pathlib import Path

import numpy as np
import pytest

from shintai.evolve import SerialExecutor
from shintai.quadruped import benchmarks as B
from shintai.quadruped import fitness as F
from shintai.quadruped import robot as R
from shintai.quadruped import training as T
from shintai.quadruped import world as W
from shintai.quadruped.episode import GenomePolicy, rollout
from shintai.quadruped.networks import SwingOrderPolicy

with np.load(Path(__file__).parent / "data" / "networks_0629247.npz") as _data:
    ACTION, ACTION_FREE = _data["action"], _data["action_free"]  # the networks shipped at 0629247
    ORDER = SwingOrderPolicy(_data["order_centres"], _data["order_sigmas"], _data["order_weights"])

CASES = [  # (population seed, environments, free gait, eq. 9 values, digest of the episodes)
    (0, (0, 9, 17, 30, 41, 50, 66, 95), False,
     ("0x1.eeca40aaaceeap-7", "0x1.378e15e53a0dep+7", "0x1.1e93a7cbc6ef3p+4", "0x1.0b9e51c1ac0ffp+5",
      "0x1.1c6d5f852e610p+7", "0x1.fcaafbe53d459p+7"), "b3f0886651cd08c0"),
    (1, (3, 12, 25, 38, 47, 59, 70, 88), False,
     ("0x1.2a8836f4b5404p-5", "0x1.80284497b5344p+6", "0x1.a1638aa2be426p+5", "0x1.5179aa2afbc00p+6",
      "0x1.1411e322edf94p+6", "0x1.80166fc68e374p+7"), "3068ae766b0a8246"),
    (2, (5, 20, 33, 44, 57, 61, 79, 90), False,
     ("0x1.c5ef22ab767b2p-7", "0x1.236fd28bc35acp-5", "0x1.80ed88ff58970p+5", "0x1.3146aa2260322p+7",
      "0x1.02f0fe92913fcp-6", "0x1.3c608df832021p-7"), "30a4cddf7d3f6bd3"),
    (3, (1, 14, 28, 36, 52, 68, 77, 93), True,
     ("0x1.5503909ae8233p-5", "0x1.4f2e30efdc1a6p+7", "0x1.24bda1c83034cp+6", "0x1.92ecfcb981ae9p-6",
      "0x1.270c527a66518p+5", "0x1.268592ce0a743p+4"), "158b19f85c3c1673"),
]


def digest(*arrays) -> str:
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()[:16]


@pytest.mark.parametrize("seed, envs, free, values, episodes", CASES)
def test_eq9_values_and_walks_are_those_of_the_code_before_the_speed_up(seed, envs, free, values, episodes):
    population = B.late_population(size=6, seed=seed, best=ACTION)
    batch = F.training_batch().take(list(envs))
    ep = rollout(batch.tile(6), GenomePolicy(F.ACTION_NET, population, len(batch)), ORDER if free else None)
    assert len(set(ep.cycles.tolist())) > 5 and (ep.collided | ep.limit | ep.unstable).any()  # varied walks
    fitness = F.episode_costs(ep).reshape(6, -1).sum(axis=1)
    assert np.array_equal(fitness, [float.fromhex(v) for v in values])
    assert np.array_equal(fitness, F.action_fitness_batch(population, batch, ORDER if free else None))
    assert digest(ep.poses, ep.commands, ep.zr, ep.orders, ep.br, ep.cycles, ep.collided, ep.limit, ep.unstable,
                  ep.final_error) == episodes


def test_ga_generations_give_the_curve_of_the_code_before_the_speed_up():
    """Five generations from a late population (the GA's selection, crossover and mutation on eq. 9 values)."""
    settings = T.TrainSettings(generations=5, population=10, environments=8, seed=3)
    r = T.run_stage("action", settings, SerialExecutor(), None, resume=False,
                    initial=B.late_population(size=10, seed=3, best=ACTION))
    assert np.array_equal(r.best, [float.fromhex("0x1.a285c58204469p-6")] * 5)
    assert np.array_equal(r.mean, [float.fromhex(v) for v in (
        "0x1.7144e216c7f85p+6", "0x1.2bf7799b58f42p+6", "0x1.383d45edeae85p+6", "0x1.2997f754353e3p+6",
        "0x1.fd1d7d7cd9125p+5")])
    assert digest(r.genome) == "ac2401cc2d8a0eab"


@pytest.mark.parametrize("free, records", [(False, "bcb9e475cd36d73a"), (True, "f4f37880c7e359d0")])
def test_cycle_records_are_those_of_the_code_before_the_speed_up(free, records):
    """Every recorded quantity of the walks in §4.2.1, §4.2.2 and §5.2 (footholds, body poses, support triangles,
    stability margins, Br, Zr), which the replay and walking experiments report."""
    envs = W.EnvBatch.of([W.scenario_421(), W.scenario_422(), W.scenario_52()])
    ep = T.evaluate(ACTION_FREE if free else ACTION, envs, ORDER if free else None, record=True)
    assert [len(r) for r in ep.records] == ([12, 11, 12] if free else [12, 12, 13])
    assert digest(*(a for recs in ep.records for r in recs
                    for a in (r.footholds, r.stands_on, r.body_poses, r.support_triangles, r.cog, r.margins,
                              np.array([r.br_mm, r.zr])))) == records


def random_states(n: int, seed: int):
    """Body poses, heights and feet around the nominal stance, some far out of reach, some on obstacles."""
    rng = np.random.default_rng(seed)
    pose = np.column_stack([rng.normal(0, 0.5, n), rng.normal(1, 0.5, n), rng.uniform(-np.pi, np.pi, n)])
    xy = R.to_world(pose, np.repeat(R.NOMINAL_FEET[None], n, 0)) + rng.normal(0, 0.08, (n, 4, 2))
    feet = np.concatenate([xy, rng.choice([0.0, 0.07, 0.12, 0.2], (n, 4, 1))], axis=-1)
    return pose, rng.uniform(0.28, 0.42, n), feet


def test_the_joint_limit_mask_is_leg_angles_reduced_bit_for_bit():
    pose, zr, feet = random_states(20000, 0)
    legs = np.tile(np.arange(4), (len(pose), 1))
    fast = R.legs_within_limits(pose, zr, feet, R.ALL_LEGS)
    xy = R.to_body(pose, feet[..., :2])
    foot = np.concatenate([xy, (feet[..., 2] - zr[:, None])[..., None]], axis=-1)
    shoulder = np.concatenate([R.SHOULDER_XY[legs], np.full(legs.shape + (1,), R.C.SHOULDER_DZ)], axis=-1)
    ok = R.leg_angles(foot, shoulder, legs)[1]
    assert 0.05 < ok.all(-1).mean() < 0.95  # both outcomes are tested
    assert np.array_equal(fast, ok.all(-1))
    one = np.random.default_rng(1).integers(0, 4, len(pose))  # one leg's key points (the swing test)
    ok = R.leg_angles(foot, np.concatenate([R.SHOULDER_XY[one][:, None].repeat(4, 1),
                                            np.full((len(one), 4, 1), R.C.SHOULDER_DZ)], -1), one[:, None])[1]
    assert np.array_equal(R.legs_within_limits(pose, zr, feet, one[:, None]), ok.all(-1))


def test_theta0_wrap_is_np_mod_on_the_range_it_meets():
    theta = np.concatenate([np.random.default_rng(2).uniform(-np.pi, np.pi, 100000), [np.pi, -np.pi, 0.0, -0.0]])
    for leg, lo in enumerate(R.THETA0_LIMITS[:, 0]):
        a = np.concatenate([theta - lo, [0.0, -0.0, -1e-300, 1e-300]])
        reduced = a + (a < 0) * (2 * np.pi)
        assert np.array_equal(np.mod(a, 2 * np.pi), reduced)
        assert np.array_equal(np.signbit(np.mod(a, 2 * np.pi)), np.signbit(reduced))
        assert np.array_equal(R.wrap_theta0(theta, leg), lo + (theta - lo + ((theta - lo) < 0) * (2 * np.pi)))


def test_distances_segments_and_footholds_are_the_general_forms_bit_for_bit():
    envs = F.training_batch()
    rng = np.random.default_rng(3)
    n = 4000
    batch = envs.take(rng.integers(0, 96, n))
    p = rng.uniform([-0.7, -0.2], [0.7, 2.4], (n, 4, 2))
    p[:200, 0] = batch.polygons[:200, 0, 1]  # on a corner
    sd, near, _ = W.closest_boundary(p[..., None, :], batch.polygons[:, None])
    assert np.array_equal(W.signed_distance(p[..., None, :], batch.polygons[:, None]), sd)
    assert np.array_equal(W.nearest_inside(p[..., None, :], batch.polygons[:, None]),
                          np.where((sd <= 0)[..., None], p[..., None, :], near))
    a, b = p[:, :2], p[:, 2:]
    b[:100] = batch.polygons[:100, 1, :2]  # ending on corners
    hits = W.segment_hits(a[:, :, None], b[:, :, None], batch.polygons[:, None])
    assert 0.05 < hits.mean() < 0.95 and np.array_equal(R.crossings(a, b, batch), hits)
    centre, radius = batch.circles
    everywhere = (centre[:, None], np.full_like(radius[:, None], np.inf))  # no obstacle skipped
    culled = R._stand(p, batch.polygons[:, None], batch.surmountable[:, None], batch.normals[:, None],
                      (centre[:, None], radius[:, None]))
    full = R._stand(p, batch.polygons[:, None], batch.surmountable[:, None], batch.normals[:, None], everywhere)
    assert not full[0].all() and (full[1] >= 0).any()
    assert all(np.array_equal(x, y) for x, y in zip(culled, full))
