"""GA fitness of the action network (eqs. 9-12) and of the swing-order network (eqs. 13-15)."""

import pickle
import time

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import episode as E
from shintai.quadruped import fitness as F
from shintai.quadruped import networks as N
from shintai.quadruped import robot as R
from shintai.quadruped import swing_order as S
from shintai.quadruped import world as W
from shintai.quadruped.episode import Episodes, GenomePolicy, rollout


def episodes(final_error, cycles, collided=False, limit=False, unstable=False) -> Episodes:
    n = len(cycles)
    flag = lambda v: np.full(n, v)  # noqa: E731
    return Episodes(np.array(cycles), flag(False), flag(collided), flag(limit), flag(unstable),
                    np.array(final_error, dtype=float), *([None] * 5))


def test_episode_costs_are_equations_10_to_12():
    e = [[0.3, 0.4], [0.0, 2.0]]  # squared errors 0.25 and 4
    assert np.allclose(F.episode_costs(episodes(e, [10, 50])), [0.25 * 10 / 50, 4.0])
    assert np.allclose(F.episode_costs(episodes(e, [3, 1], collided=True)), [0.25 * (10 + 3 / 50), 4 * (10 + 1 / 50)])
    limit, unstable = episodes(e, [3, 1], limit=True), episodes(e, [3, 1], unstable=True)
    assert np.allclose(F.episode_costs(limit), F.episode_costs(unstable))


def straight_walker() -> np.ndarray:
    """An action network commanding a constant (0, 0.2 m, 0) whatever the input (one wide unit)."""
    net = N.ActionNetwork()
    centres, sigmas, weights = np.zeros((100, 24)), np.full(100, 1.0), np.zeros((100, 3))
    sigmas[0], weights[0] = 1e6, (0.0, 0.2, 0.0)
    return net.encode(centres, sigmas, weights)


def test_action_fitness_is_deterministic_and_batch_consistent():
    rng = np.random.default_rng(0)
    genomes = np.vstack([straight_walker(), N.ActionNetwork().random_genomes(rng, 2)])
    envs = W.EnvBatch.of(W.training_set()[::8])
    batch = F.action_fitness_batch(genomes, envs)
    assert np.array_equal(batch, F.action_fitness_batch(genomes, envs))
    assert [F.action_fitness(g, envs) for g in genomes] == batch.tolist()
    assert np.all(batch > 0) and np.all(np.isfinite(batch))
    assert pickle.loads(pickle.dumps(F.action_fitness_batch)) is F.action_fitness_batch


def test_walking_straight_into_the_wall_is_penalised():
    envs = W.EnvBatch.of([W.scenario_52()])
    ep = rollout(envs, GenomePolicy(F.ACTION_NET, straight_walker()[None], 1))
    assert ep.collided[0] or ep.limit[0]
    assert F.action_fitness(straight_walker(), envs) > C.FITNESS_PENALTY * np.sum(ep.final_error**2)


def test_one_individual_over_the_96_training_environments_is_cheap():
    genome = straight_walker()
    F.action_fitness(genome)  # build the training batch once
    t0 = time.perf_counter()
    F.action_fitness(genome)
    assert time.perf_counter() - t0 < 2.0


def test_order_fitness_is_equations_13_to_15():
    teacher = S.teacher_set(per_order=3, draws=150, seed=2)
    net = N.SwingOrderNetwork(n_hidden=len(teacher.x))
    exact = np.concatenate([N.scale_order_inputs(teacher.x).ravel(), np.full(len(teacher.x), 1e-3)])
    assert F.order_fitness(exact, teacher, net) < 1e-6  # an interpolating network meets every target
    rng = np.random.default_rng(3)
    genomes = net.random_genomes(rng, 3)
    values = F.order_fitness_batch(genomes, teacher, net)
    o = net.outputs(genomes, teacher, teacher.x)
    ts = teacher.target
    expected = [sum(abs(o[k, i, teacher.label[i]] - 1) + max(abs(o[k, i, j]) for j in range(24) if ts[i, j] == 0)
                    for i in range(len(ts))) for k in range(3)]
    assert np.allclose(values, expected)
    assert np.array_equal(values, F.order_fitness_batch(genomes, teacher, net))


def test_each_row_of_a_batch_is_independent_of_the_others():
    """The GA's executors stay bit-identical only if a row's value ignores the other rows."""
    teacher = S.teacher_set(per_order=3, draws=150, seed=2)
    genomes = F.ORDER_NET.random_genomes(np.random.default_rng(4), 3)
    batch = F.order_fitness_batch(genomes, teacher)
    assert [F.order_fitness(g, teacher) for g in genomes] == batch.tolist()


def test_free_gait_rollout_uses_the_swing_order_policy():
    teacher = S.teacher_set(per_order=3, draws=150, seed=2)
    net = N.SwingOrderNetwork(n_hidden=len(teacher.x))
    genome = np.concatenate([N.scale_order_inputs(teacher.x).ravel(), np.full(len(teacher.x), 0.3)])
    policy = net.trained(genome, teacher)
    envs = W.EnvBatch.of(W.training_set()[:4])
    ep = rollout(envs, GenomePolicy(F.ACTION_NET, straight_walker()[None], 4), policy)
    zr, command = ep.zr[:, 0], ep.commands[:, 0]
    assert np.array_equal(ep.orders[:, 0], policy(zr, command))
    value = F.action_fitness(straight_walker(), envs, policy)
    assert value == F.action_fitness(straight_walker(), envs, policy) and np.isfinite(value)


def test_commands_are_clipped_to_the_displacement_range_of_seed_5_1():
    low, high = (np.array(r) for r in C.COMMAND_RANGE)
    assert np.allclose(low, [-0.1, 0.15, np.radians(-15)]) and np.allclose(high, [0.1, 0.35, np.radians(15)])
    envs = W.EnvBatch.of([W.scenario_52()])
    crab = lambda x, rows: np.tile([0.13, 0.0, 0.4], (len(rows), 1))  # noqa: E731  sideways, turning
    ep = rollout(envs, crab, max_cycles=3)
    assert np.allclose(ep.commands[0, 0], [0.1, 0.15, np.radians(15)])  # what the robot executed
    free = rollout(envs, crab, max_cycles=3, command_range=None)
    assert np.allclose(free.commands[0, 0], [0.13, 0.0, 0.4])


def test_path_inputs_are_the_inputs_along_straight_lines_to_the_destinations():
    envs = W.EnvBatch.of([W.scenario_421(), W.scenario_52()])
    x = E.path_inputs(envs, offsets=(0.0,), steps=3)
    assert x.shape == (6, 24)
    start = E.action_inputs(R.CrawlState.initial(2), np.full(2, C.ZR_NOMINAL), envs)
    assert np.allclose(x[:2], start)  # t = 0: the start of each environment
    assert np.allclose(x[4:, 21:23], 0.0)  # t = 1: at the destination


def test_the_network_on_the_active_rows_gives_the_dense_pass_bit_for_bit():
    """episode.GenomePolicy evaluates the network only on the walks still active (issue 27's speed-up); the
    benchmark's dense form evaluates every row: the episodes and eq. 9 must not change by one bit."""
    from shintai.quadruped import benchmarks as B

    population = B.late_population(size=6, seed=3)
    envs = F.training_batch().take([0, 17, 50, 95])
    fast = rollout(envs.tile(6), GenomePolicy(F.ACTION_NET, population, 4))
    dense = rollout(envs.tile(6), B.DenseGenomePolicy(F.ACTION_NET, population, 4))
    assert len(set(fast.cycles.tolist())) > 1  # walks stop at different cycles, so rows go inactive
    assert np.array_equal(fast.commands, dense.commands, equal_nan=True)
    assert np.array_equal(F.episode_costs(fast), F.episode_costs(dense))
    policy = GenomePolicy(F.ACTION_NET, population, 4)
    x = np.random.default_rng(0).normal(size=(5, 24))
    rows = np.array([22, 3, 9, 4, 21])  # any order, genomes 5, 0, 2, 1, 5
    assert np.array_equal(policy(x, rows), B.DenseGenomePolicy(F.ACTION_NET, population, 4)(x, rows))
