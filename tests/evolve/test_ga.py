"""The genetic algorithm: presets, operators, determinism, executors, checkpoints and resume."""

import dataclasses
import importlib.util
import operator
import signal
import subprocess
import sys
import time
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from shintai.evolve import (GAConfig, GeneticAlgorithm, ItemError, ProcessExecutor, SerialExecutor,
                            load_checkpoint)
from shintai.evolve.benchmarks import rastrigin, sphere, sphere_rows

GENES = 6
LO, HI = -5.12 * np.ones(GENES), 5.12 * np.ones(GENES)
TARGET = np.array([1.0, -2.0, 0.5, 3.0, -1.0, 0.0])


def distance_to_target(genome):
    return sphere(genome - TARGET)


def negative_distance(genome):
    return -sphere(genome - TARGET)


def evolve(fitness, config, seed=0, resume=False, **kwargs):
    return GeneticAlgorithm(fitness, LO, HI, config, seed=seed, **kwargs).run(resume=resume)


def assert_same_result(a, b):
    assert np.array_equal(a.best_genome, b.best_genome)
    assert a.best_fitness == b.best_fitness
    assert a.generations_run == b.generations_run
    for name, values in a.history.arrays().items():
        assert np.array_equal(values, getattr(b.history, name), equal_nan=True), name


def test_seed004_preset_minimises_rastrigin():
    result = evolve(rastrigin, GAConfig.seed004(generations=40))
    assert result.generations_run == 40
    assert result.best_fitness <= 0.1 * result.history.best[0]
    assert result.best_fitness <= 6.0
    assert result.best_fitness == rastrigin(result.best_genome)


def test_seed003_preset_minimises_sphere():
    result = evolve(distance_to_target, GAConfig.seed003(generations=60, minimize=True))
    assert result.best_fitness <= 0.15 * result.history.best[0]
    assert result.best_fitness <= 4.0


def test_seed003_preset_maximises():
    result = evolve(negative_distance, GAConfig.seed003(generations=60))
    assert np.all(np.diff(result.history.best_so_far) >= 0)
    assert result.best_fitness >= 0.15 * result.history.best[0]
    assert result.best_fitness >= -4.0
    assert result.best_fitness == result.history.best[-1]


def test_preset_values_follow_the_theses():
    sq43, quadruped = GAConfig.seed003(), GAConfig.seed004()
    assert (sq43.population, sq43.crossover_rate, sq43.mutation_rate, sq43.cull_rate) == (20, 0.2, 0.02, 0.4)
    assert (sq43.selection, sq43.minimize, sq43.carried()) == ("truncation", False, 12)
    assert GAConfig.seed003(population=105).carried() == 105 - 42
    assert (quadruped.population, quadruped.elitism, quadruped.tournament_size) == (100, 10, 3)
    assert (quadruped.crossover, quadruped.crossover_rate, quadruped.minimize) == ("uniform", 0.6, True)


@pytest.mark.parametrize("crossover", ["uniform", "one_point", "blend"])
def test_genes_stay_in_bounds(crossover):
    seen = []

    def beyond_the_box(genome):
        seen.append(genome.copy())
        return sphere(genome - 10.0)

    config = GAConfig(population=20, generations=15, crossover=crossover, crossover_rate=1.0,
                      mutation_rate=0.5, mutation_sigma=1.0)
    result = evolve(beyond_the_box, config)
    seen = np.array(seen)
    assert np.all(seen >= LO) and np.all(seen <= HI)
    assert np.allclose(result.best_genome, HI, atol=0.5)


def test_elitism_keeps_the_best():
    config = GAConfig(population=20, generations=25, elitism=1, mutation_rate=0.3, mutation_sigma=0.3)
    result = evolve(rastrigin, config, seed=3)
    assert np.all(np.diff(result.history.best) <= 0)
    assert np.array_equal(result.history.best, result.history.best_so_far)


def test_truncation_culls_the_stated_fraction(tmp_path):
    config = GAConfig.seed003(generations=6)
    culled = round(0.4 * config.population)
    evaluations, previous, checked = [], [], []

    def counted(genome):
        evaluations.append(1)
        return negative_distance(genome)

    def check_generation(done, total, best):
        state = load_checkpoint(tmp_path / "ck.npz")
        if previous:
            assert len(evaluations) == culled
            top = np.argsort(-previous[-1].fitness, kind="stable")[: config.population - culled]
            assert {tuple(row) for row in previous[-1].population[top]} <= {tuple(row) for row in state.population}
            checked.append(done)
        evaluations.clear()
        previous.append(state)

    GeneticAlgorithm(counted, LO, HI, config, checkpoint=tmp_path / "ck.npz").run(progress=check_generation)
    assert checked == [2, 3, 4, 5, 6]


def test_same_seed_same_result_other_seed_differs():
    config = GAConfig.seed004(population=30, generations=10)
    first, again = evolve(rastrigin, config, seed=5), evolve(rastrigin, config, seed=5)
    assert_same_result(first, again)
    other = evolve(rastrigin, config, seed=6)
    assert not np.array_equal(first.best_genome, other.best_genome)


def test_non_finite_fitness_counts_as_worst():
    def partly_undefined(genome):
        return np.nan if genome[0] > 0 else (np.inf if genome[1] > 0 else sphere(genome))

    result = evolve(partly_undefined, GAConfig(population=20, generations=10))
    assert np.isfinite(result.best_fitness)
    assert result.best_genome[0] <= 0 and result.best_genome[1] <= 0
    assert result.history.worst[0] == np.inf

    maximised = evolve(lambda g: -partly_undefined(g), GAConfig.seed003(generations=5))
    assert np.isfinite(maximised.best_fitness) and maximised.history.worst[0] == -np.inf


def test_batch_fitness_matches_per_genome_fitness():
    config = GAConfig.seed004(population=24, generations=8)
    per_genome = evolve(sphere, config, seed=2)
    batched = evolve(sphere_rows, config, seed=2, batch=True)
    assert_same_result(per_genome, batched)


def test_initial_population_seeds_a_known_solution():
    result = evolve(rastrigin, GAConfig(population=20, generations=3), initial=np.zeros((1, GENES)))
    assert result.history.best[0] == 0.0
    assert result.best_fitness == 0.0 and np.array_equal(result.best_genome, np.zeros(GENES))


def test_progress_reports_every_generation():
    calls = []
    GeneticAlgorithm(sphere, LO, HI, GAConfig(population=10, generations=4)).run(
        progress=lambda done, total, best: calls.append((done, total, best)))
    assert [c[:2] for c in calls] == [(1, 4), (2, 4), (3, 4), (4, 4)]
    assert all(isinstance(c[2], float) for c in calls)


def test_process_executor_gives_the_serial_result():
    config = GAConfig.seed004(population=30, generations=6)
    serial = evolve(rastrigin, config, seed=4, executor=SerialExecutor())
    with ProcessExecutor(workers=2) as pool:
        parallel = evolve(rastrigin, config, seed=4, executor=pool)
        batched = evolve(sphere_rows, config, seed=4, executor=pool, batch=True)
    assert_same_result(serial, parallel)
    assert_same_result(evolve(sphere, config, seed=4), batched)


@pytest.mark.parametrize("field, value", [
    ("population", 1), ("generations", 0), ("elitism", 20), ("selection", "roulette"),
    ("tournament_size", 0), ("cull_rate", 1.0), ("crossover", "two_point"), ("crossover_rate", 1.5),
    ("mutation_rate", -0.1), ("mutation_sigma", float("nan")), ("minimize", "yes"),
])
def test_config_validation_names_the_field(field, value):
    with pytest.raises(ValueError, match=rf"GAConfig\.{field} must be"):
        GAConfig(**{"population": 20, field: value})


def test_truncation_must_leave_a_survivor():
    with pytest.raises(ValueError, match="cull_rate 0.9 leaves no survivor in a population of 2"):
        GAConfig(population=2, selection="truncation", cull_rate=0.9)


def test_bounds_and_initial_are_validated():
    with pytest.raises(ValueError, match="lo < hi"):
        GeneticAlgorithm(sphere, [0, 1], [1, 1])
    with pytest.raises(ValueError, match=r"initial must have shape \(k, 6\)"):
        GeneticAlgorithm(sphere, LO, HI, initial=np.zeros((1, 3)))


def test_resume_extends_a_finished_run(tmp_path):
    config = GAConfig.seed004(population=20, generations=16)
    straight = evolve(rastrigin, config, seed=9)
    evolve(rastrigin, dataclasses.replace(config, generations=7), seed=9, checkpoint=tmp_path / "ck")
    assert load_checkpoint(tmp_path / "ck").generation == 6
    resumed = GeneticAlgorithm(rastrigin, LO, HI, config, seed=9, checkpoint=tmp_path / "ck").run(resume=True)
    assert_same_result(straight, resumed)


def test_resume_refuses_a_different_run(tmp_path):
    path = tmp_path / "ck"
    config = GAConfig(population=10, generations=2)
    evolve(sphere, config, seed=1, checkpoint=path)
    with pytest.raises(ValueError, match=r"different config \(population 10 ≠ 12\)"):
        evolve(sphere, dataclasses.replace(config, population=12), seed=1, checkpoint=path, resume=True)
    with pytest.raises(ValueError, match="different gene bounds"):
        GeneticAlgorithm(sphere, LO, 2 * HI, config, seed=1, checkpoint=path).run(resume=True)
    with pytest.raises(ValueError, match="seed 1, not 2"):
        evolve(sphere, config, seed=2, checkpoint=path, resume=True)


def _load_child():
    spec = importlib.util.spec_from_file_location("ga_child", Path(__file__).with_name("ga_child.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _wait_for_generation(path, generation, process, timeout_s=60.0):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        assert process.poll() is None, "the GA subprocess ended before it was killed"
        if path.exists() and load_checkpoint(path).generation >= generation:
            return
        time.sleep(0.01)
    raise AssertionError(f"no checkpoint of generation {generation} within {timeout_s} s")


def test_killed_run_resumes_to_the_uninterrupted_result(tmp_path):
    child = _load_child()
    path = tmp_path / "ga.ckpt"
    process = subprocess.Popen([sys.executable, str(Path(child.__file__)), str(path)])
    try:
        _wait_for_generation(path, 3, process)
    finally:
        process.send_signal(signal.SIGKILL)
        process.wait()
    killed_at = load_checkpoint(path).generation
    assert 3 <= killed_at < child.CONFIG.generations - 1

    reported = []
    resumed = child.make_ga(rastrigin, path).run(resume=True, progress=lambda done, *_: reported.append(done))
    assert reported[0] == killed_at + 2
    assert_same_result(resumed, child.make_ga(rastrigin, None).run())


@pytest.fixture(scope="module")
def ray_executor():
    pytest.importorskip("ray")
    from shintai.evolve import RayExecutor

    executor = RayExecutor(workers=2)
    yield executor
    executor.close()


def test_serial_process_and_ray_give_identical_results(ray_executor):
    config = GAConfig.seed004(population=30, generations=5)
    serial = evolve(rastrigin, config, seed=8)
    with ProcessExecutor(workers=2) as pool:
        assert_same_result(serial, evolve(rastrigin, config, seed=8, executor=pool))
    assert_same_result(serial, evolve(rastrigin, config, seed=8, executor=ray_executor))
    with pytest.raises(ItemError, match=r"item 2 failed: ZeroDivisionError"):
        ray_executor.map(partial(operator.truediv, 1.0), [1, 2, 0, 4])


def test_a_checkpoint_stores_each_best_genome_once_and_reads_the_first_version(tmp_path):
    """Version 2 keeps the best genome per generation as its distinct rows and an index (a long run's checkpoint
    does not grow by a genome a generation); a version-1 checkpoint still resumes."""
    import json

    import shintai.evolve.ga as G

    config = GAConfig(population=8, generations=12)
    path = tmp_path / "ck.npz"
    full = GeneticAlgorithm(sphere, LO, HI, config, seed=3, checkpoint=path).run()
    state = load_checkpoint(path)
    assert np.array_equal(state.history.best_genome, full.history.best_genome)
    with np.load(path) as data:
        assert len(data["history_best_genome_rows"]) == len(np.unique(full.history.best_genome, axis=0)) < 12
    short = dataclasses.replace(config, generations=6)
    GeneticAlgorithm(sphere, LO, HI, short, seed=3, checkpoint=path).run()  # the state after 6 generations
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    meta = json.loads(str(arrays.pop("meta")))
    arrays["history_best_genome"] = arrays.pop("history_best_genome_rows")[arrays.pop("history_best_genome_index")]
    np.savez(path, meta=np.array(json.dumps({**meta, "version": 1})), **arrays)  # as version 1 wrote it
    resumed = GeneticAlgorithm(sphere, LO, HI, config, seed=3, checkpoint=path).run(resume=True)
    assert np.array_equal(resumed.history.best, full.history.best) and G.CHECKPOINT_VERSION == 2
    assert np.array_equal(resumed.best_genome, full.best_genome)
