"""Fitness test functions and the executor benchmark of one GA generation.

Seed 003 §5.5.2 parallelises a GA generation over its individuals because each individual's
analysis is independent; the benchmark measures what that buys on this machine: one generation of
40 individuals whose fitness is a ~10 ms CPU-bound rollout, evaluated serially, on the process pool
and on Ray. The test functions are module level so every executor can send them to its workers.
"""

from __future__ import annotations

import contextlib
import importlib.util
import os
import time

import numpy as np

from shintai.evolve.executors import Executor, ProcessExecutor, RayExecutor, SerialExecutor
from shintai.scenarios.registry import benchmark

POPULATION = 40
GENES = 8
ROLLOUT_STEPS = 4000  # about 10 ms of CPU on one core of the development machine
ROLLOUT_SIZE = 12
REPEATS = 5


def sphere(genome: np.ndarray) -> float:
    """Sum of squares; minimum 0 at the origin."""
    return float(np.sum(np.square(genome)))


def rastrigin(genome: np.ndarray) -> float:
    """Rastrigin's multimodal function; minimum 0 at the origin, local minima near integer points."""
    x = np.asarray(genome, dtype=float)
    return float(10 * x.size + np.sum(x * x - 10 * np.cos(2 * np.pi * x)))


def sphere_rows(genomes: np.ndarray) -> np.ndarray:
    """:func:`sphere` of each row, vectorised (a ``batch=True`` fitness)."""
    return np.sum(np.square(genomes), axis=1)


def rollout_fitness(genome: np.ndarray, steps: int = ROLLOUT_STEPS) -> float:
    """Deterministic CPU-bound work standing in for a body simulation (~10 ms at the default steps).

    A small nonlinear system ``x ← tanh(A x + 0.1 g)`` whose matrix ``A`` depends on the genome
    ``g`` is rolled out for ``steps`` steps; the fitness is the mean of ``|x|²``.
    """
    g = np.resize(np.asarray(genome, dtype=float), ROLLOUT_SIZE)
    a = 0.9 * np.eye(ROLLOUT_SIZE) + 0.05 * np.outer(np.sin(np.arange(ROLLOUT_SIZE)), g) / ROLLOUT_SIZE
    x = np.ones(ROLLOUT_SIZE)
    total = 0.0
    for _ in range(steps):
        x = np.tanh(a @ x + 0.1 * g)
        total += float(x @ x)
    return total / steps


def generation_seconds(executors: dict[str, Executor], population: np.ndarray) -> dict[str, float]:
    """Per executor, the best of :data:`REPEATS` timed evaluations of ``population``.

    Each executor first evaluates the population once (warm-up: pool and workers started); the
    timed evaluations then alternate between executors so that a passing load on the machine
    affects them alike.
    """
    genomes = list(population)
    for executor in executors.values():
        executor.map(rollout_fitness, genomes)
    times: dict[str, list[float]] = {name: [] for name in executors}
    for _ in range(REPEATS):
        for name, executor in executors.items():
            t0 = time.perf_counter()
            executor.map(rollout_fitness, genomes)
            times[name].append(time.perf_counter() - t0)
    return {name: min(values) for name, values in times.items()}


@benchmark("evolve.executors", "GA generation: process pool and Ray vs serial on a ~10 ms CPU-bound fitness")
def executors_benchmark() -> dict:
    population = np.random.default_rng(0).uniform(-1, 1, size=(POPULATION, GENES))
    workers = os.cpu_count() or 1
    with contextlib.ExitStack() as stack:
        executors = {"serial": SerialExecutor(), "process": stack.enter_context(ProcessExecutor(workers))}
        if importlib.util.find_spec("ray") is not None:
            executors["ray"] = stack.enter_context(RayExecutor(workers=workers))
        seconds = generation_seconds(executors, population)
    serial_s, process_s, ray_s = seconds["serial"], seconds["process"], seconds.get("ray")
    return {"serial_s": serial_s, "process_s": process_s, "ray_s": ray_s,
            "process_speedup": serial_s / process_s,
            "ray_speedup": None if ray_s is None else serial_s / ray_s,
            "population": POPULATION, "workers": workers, "fitness_ms": 1e3 * serial_s / POPULATION}
