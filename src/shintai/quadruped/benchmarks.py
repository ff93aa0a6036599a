"""Benchmark: one GA generation of the action network, 100 individuals x 96 environments (eq. 9).

Three ways to evaluate the same population, whose fitness values must agree bit for bit:

* ``serial``: the naive path, one individual at a time (a 96-episode rollout each);
* ``vectorised``: the whole population in one lock-step rollout of 9600 episodes
  (``fitness.action_fitness_batch``), one process;
* ``dense``: the same rollout with the network evaluated on all 9600 rows every cycle (the forward pass
  before issue 27; late in a generation a few long walks remain and it cost more than the crawl) —
  :class:`DenseGenomePolicy`, the naive form of ``episode.GenomePolicy``;
* ``process``: the vectorised fitness over chunks of the population on a process pool of all cores
  (what ``quadruped.train`` runs by default).

Where the vectorised generation's time goes is measured in the same run: ``crawl_s`` in
``robot.crawl_cycle`` (the walking cycles), ``network_s`` in the action network's forward pass, the rest
(``loop_s``) the Loop, perception and bookkeeping. The crawl was made faster without changing a bit
(issue 27 item 2, notes/train.md "Speed"); its earlier form is not kept, so that ratio was measured by
running this benchmark at both commits.

The population is the shipped fixed-order network and 99 mutants of it (the GA's mutation at its
default rate), i.e. a generation late in training, whose walks last as long as trained walks do.
"""

from __future__ import annotations

import os
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shintai.evolve import ProcessExecutor
from shintai.evolve.ga import Checkpoint, GeneticAlgorithm, History, save_checkpoint
from shintai.quadruped.episode import GenomePolicy, rollout
from shintai.quadruped.networks import ActionNetwork
from shintai.quadruped import constants as C
from shintai.quadruped import fitness as F
from shintai.quadruped import robot as R
from shintai.quadruped import training as T
from shintai.scenarios.registry import benchmark

POPULATION = C.GA_POPULATION


@dataclass(frozen=True)
class DenseGenomePolicy:
    """``episode.GenomePolicy`` evaluated on every row of the ``k x E`` batch, active or not."""

    net: ActionNetwork
    genomes: np.ndarray
    n_envs: int

    def __call__(self, x: np.ndarray, rows: np.ndarray) -> np.ndarray:
        k = len(self.genomes)
        dense = np.zeros((k * self.n_envs, x.shape[1]))
        dense[rows] = x
        return self.net.forward(self.genomes, dense.reshape(k, self.n_envs, -1)).reshape(k * self.n_envs, -1)[rows]


def dense_fitness_batch(genomes: np.ndarray) -> np.ndarray:
    """``fitness.action_fitness_batch`` over the 96 environments with :class:`DenseGenomePolicy`."""
    envs = F.training_batch()
    ep = rollout(envs.tile(len(genomes)), DenseGenomePolicy(F.ACTION_NET, genomes, len(envs)))
    return F.episode_costs(ep).reshape(len(genomes), len(envs)).sum(axis=1)


def driver_seconds(population: np.ndarray, generations: int = 400) -> float:
    """The GA's own work in one generation (ranking, selection, crossover, mutation and the checkpoint of a
    run ``generations`` long), with the fitness values given: what training spends outside the episodes."""
    lo, hi = F.ACTION_NET.bounds()
    ga = GeneticAlgorithm(lambda g: np.zeros(len(g)), lo, hi, T.TrainSettings().config(generations + 1), batch=True)
    ga.rng = np.random.default_rng(0)
    fitness = np.arange(len(population), dtype=float)
    history = History(*(np.zeros(generations) for _ in range(5)), np.repeat(population[:1], generations, 0))
    state = Checkpoint(generations - 1, population, fitness, ga.rng.bit_generator.state, history, ga.config,
                       lo, hi, 0)
    with tempfile.TemporaryDirectory() as folder:
        t0 = time.perf_counter()
        ranked = population[np.argsort(fitness, kind="stable")]
        ga._offspring(ranked, ga.rng, len(population) - ga.config.carried())
        save_checkpoint(Path(folder) / "ga.npz", state)
        return time.perf_counter() - t0


def late_population(size: int = POPULATION, seed: int = 0, best: np.ndarray | None = None) -> np.ndarray:
    """The network ``best`` (default: the shipped one) and ``size - 1`` mutants of it (per-gene Gaussian
    mutation, clipped)."""
    rng = np.random.default_rng(seed)
    lo, hi = F.ACTION_NET.bounds()
    best = T.load_action() if best is None else best
    mutate = rng.random((size - 1, best.size)) < C.GA_MUTATION_RATE
    noise = rng.normal(size=mutate.shape) * C.GA_MUTATION_SIGMA * (hi - lo)
    return np.vstack([best, np.clip(best + mutate * noise, lo, hi)])


def split_seconds(population: np.ndarray) -> tuple[float, float, float]:
    """``fitness.action_fitness_batch(population)``'s wall time split into the crawl cycles, the network's
    forward passes and the rest: the two are timed where the rollout calls them (``robot.crawl_cycle``
    through the episode module, the policy's ``net.forward``)."""
    spent = {"crawl": 0.0, "network": 0.0}

    def timed(key, fn):
        def call(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[key] += time.perf_counter() - t0
        return call

    class TimedNet:
        n_out = F.ACTION_NET.n_out

        def forward(self, genomes, x):
            return timed("network", F.ACTION_NET.forward)(genomes, x)

    envs, crawl = F.training_batch(), R.crawl_cycle
    R.crawl_cycle = timed("crawl", crawl)
    try:
        t0 = time.perf_counter()
        rollout(envs.tile(len(population)), GenomePolicy(TimedNet(), population, len(envs)))
        total = time.perf_counter() - t0
    finally:
        R.crawl_cycle = crawl
    return spent["crawl"], spent["network"], total - spent["crawl"] - spent["network"]


def _timed(fn) -> tuple[float, np.ndarray]:
    t0 = time.perf_counter()
    values = np.asarray(fn(), dtype=float).ravel()
    return time.perf_counter() - t0, values


@benchmark("quadruped.ga-generation",
           "one GA generation (100 individuals x 96 environments): naive serial vs vectorised (network on the active "
           "rows, or dense) vs process pool; the vectorised run split into crawl, network and loop; the GA driver's "
           "own share")
def ga_generation() -> dict:
    population = late_population()
    F.training_batch()  # built once, outside the timings
    workers = os.cpu_count() or 1
    serial_s, serial = _timed(lambda: [F.action_fitness(g) for g in population])
    vectorised_s, vectorised = _timed(lambda: F.action_fitness_batch(population))
    dense_s, dense = _timed(lambda: dense_fitness_batch(population))
    with ProcessExecutor(workers) as executor, T.single_threaded_blas():
        executor.map_batches(F.action_fitness_batch, population[:2 * workers])  # warm-up: start the pool
        process_s, parallel = _timed(lambda: executor.map_batches(F.action_fitness_batch, population))
    crawl_s, network_s, loop_s = split_seconds(population)
    return {"serial_s": serial_s, "vectorised_s": vectorised_s, "process_s": process_s, "dense_s": dense_s,
            "crawl_s": crawl_s, "network_s": network_s, "loop_s": loop_s,
            "crawl_share": crawl_s / (crawl_s + network_s + loop_s),
            "vectorised_speedup": serial_s / vectorised_s, "process_speedup": serial_s / process_s,
            "active_rows_speedup": dense_s / vectorised_s, "driver_s": driver_seconds(population),
            "identical": bool(np.array_equal(serial, vectorised) and np.array_equal(serial, parallel)
                              and np.array_equal(serial, dense)),
            "individuals": len(population), "environments": 96, "workers": workers,
            "mean_cycles": float(np.mean(T.evaluate(population[0], F.training_batch()).cycles))}
