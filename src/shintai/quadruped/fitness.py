"""GA fitness functions (minimised) of the two networks, as plain picklable module-level functions.

* Action network, eqs. (9)-(12) of seed §4.1.2: over the environments,
  Σ (fitness_o + fitness_a + fitness_c) with, at the cycle k where the walk stopped,
  fitness_o = 10 (x_dc² + y_dc²) after a collision, fitness_a = 10 (x_dc² + y_dc²) after a
  joint-limit violation (also when no stable body position exists: the cycle is outside the robot's
  range, chosen), and fitness_c = (x_dc² + y_dc²) T / 50 always (eq. 9 sums all three), where
  (x_dc, y_dc) is the destination error and T the walking cycles used (50 at the cap).
  :func:`action_fitness_batch` rolls out all k x E episodes of a population in lock-step.
* Swing-order network, eqs. (13)-(15) of seed §5.1: over the teacher patterns,
  Σ (fitness_A + fitness_B) with fitness_A = |o_j1 - 1| for the target unit j1 and fitness_B the
  largest |o_j - ts_j| over the units with ts_j = 0 (the paper: "applied for ts_j = 0").

Both are deterministic: episodes and the default teacher set use no randomness at evaluation time.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import world as W
from shintai.quadruped.episode import Episodes, GenomePolicy, OrderPolicy, rollout
from shintai.quadruped.networks import ActionNetwork, SwingOrderNetwork, as_genomes
from shintai.quadruped.swing_order import TeacherSet, teacher_set

ACTION_NET = ActionNetwork()
ORDER_NET = SwingOrderNetwork()


@lru_cache(maxsize=1)
def training_batch() -> W.EnvBatch:
    """The 96 training environments of seed §4.1.1 as one batch (built once per process)."""
    return W.EnvBatch.of(W.training_set())


@lru_cache(maxsize=1)
def default_teacher() -> TeacherSet:
    """The swing-order teacher set with the default (seeded) construction (built once per process)."""
    return teacher_set()


def episode_costs(ep: Episodes) -> np.ndarray:
    """fitness_o + fitness_a + fitness_c of each episode, eqs. (10)-(12)."""
    e2 = np.sum(ep.final_error**2, axis=1)
    fitness_o = np.where(ep.collided, C.FITNESS_PENALTY * e2, 0.0)
    fitness_a = np.where(ep.limit | ep.unstable, C.FITNESS_PENALTY * e2, 0.0)
    fitness_c = e2 * ep.cycles / C.MAX_CYCLES
    return fitness_o + fitness_a + fitness_c


def action_fitness_batch(genomes, envs: W.EnvBatch | None = None,
                         order_policy: OrderPolicy | None = None) -> np.ndarray:
    """Eq. (9) for each of ``k`` action-network genomes ``(k, n)`` over ``envs`` (default: the 96
    training environments) with the crawl order or ``order_policy``; ``(k,)``."""
    genomes = as_genomes(genomes, ACTION_NET.size, "action_fitness_batch")
    envs = training_batch() if envs is None else envs
    k = len(genomes)
    ep = rollout(envs.tile(k), GenomePolicy(ACTION_NET, genomes, len(envs)), order_policy)
    return episode_costs(ep).reshape(k, len(envs)).sum(axis=1)


def action_fitness(genome, envs: W.EnvBatch | None = None, order_policy: OrderPolicy | None = None) -> float:
    """Eq. (9) of one action-network genome."""
    return float(action_fitness_batch(genome, envs, order_policy)[0])


def order_fitness_batch(genomes, teacher: TeacherSet | None = None,
                        net: SwingOrderNetwork = ORDER_NET) -> np.ndarray:
    """Eq. (13) for each of ``k`` swing-order genomes ``(k, n)`` of ``net`` on the teacher set
    (default: the seeded :func:`default_teacher`); ``(k,)``."""
    genomes = as_genomes(genomes, net.size, "order_fitness_batch")
    teacher = default_teacher() if teacher is None else teacher
    o = net.outputs(genomes, teacher, teacher.x)  # (k, N, 24)
    ts = teacher.target
    fitness_a = np.abs(np.sum(o * ts, axis=-1) - 1.0)
    fitness_b = np.max(np.where(ts == 0, np.abs(o - ts), -np.inf), axis=-1)
    return np.sum(fitness_a + fitness_b, axis=-1)


def order_fitness(genome, teacher: TeacherSet | None = None, net: SwingOrderNetwork = ORDER_NET) -> float:
    """Eq. (13) of one swing-order genome."""
    return float(order_fitness_batch(genome, teacher, net)[0])
