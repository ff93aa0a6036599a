"""Benchmark: one GA generation of the action network, 100 individuals x 96 environments (eq. 9).

Three ways to evaluate the same population, whose fitness values must agree bit for bit:

* ``serial``: the naive path, one individual at a time (a 96-episode rollout each);
* ``vectorised``: the whole population in one lock-step rollout of 9600 episodes
  (``fitness.action_fitness_batch``), one process;
* ``process``: the vectorised fitness over chunks of the population on a process pool of all cores
  (what ``quadruped.train`` runs by default).

The population is the shipped fixed-order network and 99 mutants of it (the GA's mutation at its
default rate), i.e. a generation late in training, whose walks last as long as trained walks do.
"""

from __future__ import annotations

import os
import time

import numpy as np

from shintai.evolve import ProcessExecutor
from shintai.quadruped import constants as C
from shintai.quadruped import fitness as F
from shintai.quadruped import training as T
from shintai.scenarios.registry import benchmark

POPULATION = C.GA_POPULATION


def late_population(size: int = POPULATION, seed: int = 0) -> np.ndarray:
    """The shipped network and ``size - 1`` mutants of it (per-gene Gaussian mutation, clipped)."""
    rng = np.random.default_rng(seed)
    lo, hi = F.ACTION_NET.bounds()
    best = T.load_action()
    mutate = rng.random((size - 1, best.size)) < C.GA_MUTATION_RATE
    noise = rng.normal(size=mutate.shape) * C.GA_MUTATION_SIGMA * (hi - lo)
    return np.vstack([best, np.clip(best + mutate * noise, lo, hi)])


def _timed(fn) -> tuple[float, np.ndarray]:
    t0 = time.perf_counter()
    values = np.asarray(fn(), dtype=float).ravel()
    return time.perf_counter() - t0, values


@benchmark("quadruped.ga-generation",
           "one GA generation (100 individuals x 96 environments): naive serial vs vectorised vs process pool")
def ga_generation() -> dict:
    population = late_population()
    F.training_batch()  # built once, outside the timings
    workers = os.cpu_count() or 1
    serial_s, serial = _timed(lambda: [F.action_fitness(g) for g in population])
    vectorised_s, vectorised = _timed(lambda: F.action_fitness_batch(population))
    with ProcessExecutor(workers) as executor, T.single_threaded_blas():
        executor.map_batches(F.action_fitness_batch, population[:2 * workers])  # warm-up: start the pool
        process_s, parallel = _timed(lambda: executor.map_batches(F.action_fitness_batch, population))
    return {"serial_s": serial_s, "vectorised_s": vectorised_s, "process_s": process_s,
            "vectorised_speedup": serial_s / vectorised_s, "process_speedup": serial_s / process_s,
            "identical": bool(np.array_equal(serial, vectorised) and np.array_equal(serial, parallel)),
            "individuals": len(population), "environments": 96, "workers": workers,
            "mean_cycles": float(np.mean(T.evaluate(population[0], F.training_batch()).cycles))}
