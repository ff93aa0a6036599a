"""A real-valued genetic algorithm with pluggable fitness executors, checkpoints and resume.

Two theses use a GA to generate motion in simulation:

* seed 003 §5.5–5.7 — a parallel GA whose server does reproduction, culling, crossover and
  mutation while many clients run the dynamics solver, one individual each (§5.5.2). SQ43's trot
  (§5.6.2): 6 genes with ranges, population 20, crossover rate 0.2, mutation rate 0.02, culling
  rate 0.4, fitness maximised. HanzouS's brachiation (§5.7.3): 70 genes, population 105, same rates.
* seed 004 §4.1.2 — the RBF network weights of a quadruped: population 100, elite selection of 10
  together with tournament selection of size 3, uniform crossover with probability 0.6, fitness
  (distance and step count penalties) minimised.

One generation: rank the population; copy the carried individuals unchanged (the ``elitism`` best
with tournament selection, every survivor with truncation selection); fill the rest with
offspring — two parents selected, crossed over with probability ``crossover_rate`` (otherwise the
first parent is copied), each gene mutated with probability ``mutation_rate`` by Gaussian noise of
``mutation_sigma`` times the gene's range, clipped to the bounds; evaluate only the offspring.

All randomness is drawn in the driver from one ``np.random.default_rng(seed)``; fitness runs do not
touch it, so serial, process and Ray executors give bit-identical runs for one seed. A non-finite
fitness counts as the worst possible value (``+inf`` when minimising, ``-inf`` when maximising).
After every generation the state is checkpointed atomically, and ``run(resume=True)`` continues a
run from its checkpoint to exactly the result the uninterrupted run would have had.
"""

from __future__ import annotations

import dataclasses
import json
import operator
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import numpy as np

from shintai.evolve.executors import Executor, SerialExecutor

BLEND_ALPHA = 0.5  # BLX-α: a blended gene is drawn from the parents' interval widened by α each side
SELECTIONS = ("tournament", "truncation")
CROSSOVERS = ("uniform", "one_point", "blend")
CHECKPOINT_VERSION = 2  # 2: the best genome per generation stored once per change (1 is still read)

Progress = Callable[[int, int, float], None] | None


@dataclass(frozen=True)
class GAConfig:
    """GA settings; invalid values raise ``ValueError`` naming the field and its allowed range.

    ``elitism`` applies to tournament selection: that many best individuals pass unchanged.
    Truncation selection culls the worst ``cull_rate`` of the population and replaces them by
    offspring of the survivors, which all pass unchanged (so it needs no separate elitism).
    ``mutation_sigma`` is the Gaussian mutation's standard deviation as a fraction of each gene's
    range ``hi - lo``.
    """

    population: int = 20
    generations: int = 30  # generations evaluated, the initial population included
    elitism: int = 1  # tournament selection only
    selection: str = "tournament"  # or "truncation"
    tournament_size: int = 3
    cull_rate: float = 0.4  # truncation selection only
    crossover: str = "uniform"  # or "one_point", "blend" (BLX-0.5)
    crossover_rate: float = 0.6  # probability that a child is a crossover, not a copy of a parent
    mutation_rate: float = 0.02  # per-gene probability
    mutation_sigma: float = 0.1  # fraction of the gene's range
    minimize: bool = True

    def __post_init__(self):
        _check_int("population", self.population, 2, None)
        _check_int("generations", self.generations, 1, None)
        _check_int("elitism", self.elitism, 0, self.population - 1)
        _check_choice("selection", self.selection, SELECTIONS)
        _check_int("tournament_size", self.tournament_size, 1, None)  # entrants drawn with replacement
        _check_real("cull_rate", self.cull_rate, 0.0, 1.0, "[0, 1)", high_open=True)
        if self.selection == "truncation" and self.survivors() < 1:
            raise ValueError(f"GAConfig.cull_rate {self.cull_rate} leaves no survivor in a population of "
                             f"{self.population}")
        _check_choice("crossover", self.crossover, CROSSOVERS)
        _check_real("crossover_rate", self.crossover_rate, 0.0, 1.0, "[0, 1]")
        _check_real("mutation_rate", self.mutation_rate, 0.0, 1.0, "[0, 1]")
        _check_real("mutation_sigma", self.mutation_sigma, 0.0, np.inf, "[0, inf)", high_open=True)
        if not isinstance(self.minimize, bool):
            raise ValueError(f"GAConfig.minimize must be true or false, got {self.minimize!r}")

    @classmethod
    def seed003(cls, **changes) -> GAConfig:
        """Seed 003 §5.6.2 (SQ43 trot) and §5.7.3 (HanzouS brachiation, ``population=105``).

        Population 20, crossover rate 0.2, mutation rate 0.02, culling (selection) rate 0.4: each
        generation the worst 40 % are culled and replaced by offspring of the survivors; fitness
        maximised. The thesis does not name its crossover or mutation operators; chosen here for
        its real-valued genes: blend (BLX-0.5) crossover, per-gene Gaussian mutation of 0.1 × the
        gene's range. ``changes`` override fields.
        """
        base = cls(population=20, generations=30, elitism=0, selection="truncation", cull_rate=0.4,
                   crossover="blend", crossover_rate=0.2, mutation_rate=0.02, mutation_sigma=0.1,
                   minimize=False)
        return dataclasses.replace(base, **changes)

    @classmethod
    def seed004(cls, **changes) -> GAConfig:
        """Seed 004 §4.1.2 (quadruped RBF network weights).

        Population 100, elitism 10, tournament selection of size 3, uniform crossover with
        probability 0.6, fitness minimised. The paper gives no mutation; chosen here: each gene
        mutated with probability 0.02 (the rate of seed 003) by Gaussian noise of 0.1 × its range.
        ``changes`` override fields.
        """
        base = cls(population=100, generations=100, elitism=10, selection="tournament", tournament_size=3,
                   crossover="uniform", crossover_rate=0.6, mutation_rate=0.02, mutation_sigma=0.1,
                   minimize=True)
        return dataclasses.replace(base, **changes)

    def survivors(self) -> int:
        """Individuals left after truncation culls ``round(cull_rate * population)``."""
        return self.population - round(self.cull_rate * self.population)

    def carried(self) -> int:
        """Individuals copied unchanged into the next generation."""
        return self.survivors() if self.selection == "truncation" else self.elitism


def _check_int(name: str, value, low: int, high: int | None) -> None:
    ok = isinstance(value, (int, np.integer)) and not isinstance(value, bool)
    if not ok or value < low or (high is not None and value > high):
        allowed = f"an integer ≥ {low}" if high is None else f"an integer in [{low}, {high}]"
        raise ValueError(f"GAConfig.{name} must be {allowed}, got {value!r}")


def _check_real(name: str, value, low: float, high: float, allowed: str, high_open: bool = False) -> None:
    ok = isinstance(value, (int, float, np.floating)) and not isinstance(value, bool) and np.isfinite(value)
    if not ok or value < low or value > high or (high_open and value == high):
        raise ValueError(f"GAConfig.{name} must be a number in {allowed}, got {value!r}")


def _check_choice(name: str, value, choices: tuple[str, ...]) -> None:
    if value not in choices:
        raise ValueError(f"GAConfig.{name} must be one of {'|'.join(choices)}, got {value!r}")


@dataclass
class History:
    """Per generation (index 0 is the initial population): fitness statistics and the best so far.

    ``mean`` and ``std`` are over the finite fitness values of the generation (NaN if none is).
    """

    best: np.ndarray  # (G,) best fitness of the generation
    mean: np.ndarray  # (G,)
    worst: np.ndarray  # (G,)
    std: np.ndarray  # (G,)
    best_so_far: np.ndarray  # (G,) fitness of best_genome
    best_genome: np.ndarray  # (G, n) best genome found up to and including the generation

    @classmethod
    def empty(cls, n_genes: int) -> History:
        return cls(*(np.empty(0) for _ in range(5)), np.empty((0, n_genes)))

    def __len__(self) -> int:
        return len(self.best)

    def appended(self, fitness: np.ndarray, order: np.ndarray, best_so_far: float,
                 best_genome: np.ndarray) -> History:
        finite = fitness[np.isfinite(fitness)]
        row = (fitness[order[0]], finite.mean() if finite.size else np.nan, fitness[order[-1]],
               finite.std() if finite.size else np.nan, best_so_far)
        columns = (self.best, self.mean, self.worst, self.std, self.best_so_far)
        return History(*(np.append(col, value) for col, value in zip(columns, row)),
                       np.vstack([self.best_genome, best_genome[None, :]]))

    def arrays(self) -> dict[str, np.ndarray]:
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


@dataclass
class GAResult:
    best_genome: np.ndarray
    best_fitness: float
    history: History
    generations_run: int


@dataclass
class Checkpoint:
    """The state after a generation: enough to continue the run bit-identically."""

    generation: int  # index of the last evaluated generation (0 = initial population)
    population: np.ndarray  # (P, n)
    fitness: np.ndarray  # (P,) non-finite values already replaced by the worst value
    rng_state: dict
    history: History
    config: GAConfig
    lo: np.ndarray
    hi: np.ndarray
    seed: int


def save_checkpoint(path: str | os.PathLike, ck: Checkpoint) -> None:
    """Write ``ck`` to ``path`` atomically: a temporary file next to it, then ``os.replace``."""
    path = Path(path)
    meta = {"version": CHECKPOINT_VERSION, "generation": ck.generation, "rng_state": ck.rng_state,
            "config": dataclasses.asdict(ck.config), "seed": ck.seed}
    arrays = {f"history_{k}": v for k, v in ck.history.arrays().items() if k != "best_genome"}
    # the best genome so far changes in few generations: its distinct rows and, per generation, which one
    genomes = ck.history.best_genome
    changed = np.ones(len(genomes), dtype=bool)
    changed[1:] = np.any(genomes[1:] != genomes[:-1], axis=1)
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "wb") as f:
        np.savez(f, meta=np.array(json.dumps(meta)), population=ck.population, fitness=ck.fitness,
                 lo=ck.lo, hi=ck.hi, history_best_genome_rows=genomes[changed],
                 history_best_genome_index=np.cumsum(changed) - 1, **arrays)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def load_checkpoint(path: str | os.PathLike) -> Checkpoint:
    """Read a checkpoint written by :func:`save_checkpoint`."""
    with np.load(path, allow_pickle=False) as data:
        meta = json.loads(str(data["meta"]))
        if meta.get("version") not in (1, CHECKPOINT_VERSION):
            raise ValueError(f"checkpoint {path}: unsupported version {meta.get('version')!r}")
        columns = {f.name: data[f"history_{f.name}"] for f in dataclasses.fields(History) if f.name != "best_genome"}
        columns["best_genome"] = (data["history_best_genome"] if meta["version"] == 1
                                  else data["history_best_genome_rows"][data["history_best_genome_index"]])
        history = History(**columns)
        return Checkpoint(meta["generation"], data["population"], data["fitness"], meta["rng_state"], history,
                          GAConfig(**meta["config"]), data["lo"], data["hi"], meta["seed"])


def _batch_fitness(fitness: Callable[[np.ndarray], np.ndarray], genomes: np.ndarray) -> list[float]:
    """Evaluate a chunk of genomes with a vectorised fitness (module level, so it pickles)."""
    return list(np.asarray(fitness(genomes), dtype=float).reshape(-1))


class GeneticAlgorithm:
    """Evolve genomes in the box ``[lo, hi]`` (seed 003 §5.5–5.7, seed 004 §4.1.2).

    ``fitness(genome) -> float``, or with ``batch=True`` ``fitness(genomes (k, n)) -> (k,)`` so a
    body can vectorise across individuals (the executor then receives chunks of genomes; runs stay
    bit-identical across executors if each row's value does not depend on the other rows). With a
    process or Ray executor the fitness must be picklable. ``initial`` (k ≤ population rows, clipped
    to the bounds) seeds the first population, e.g. with a known solution; the other rows are
    uniform in the bounds. ``checkpoint`` is a file path written after every generation.
    """

    def __init__(self, fitness: Callable, lo: Sequence[float], hi: Sequence[float],
                 config: GAConfig | None = None, seed: int = 0, executor: Executor | None = None,
                 checkpoint: str | os.PathLike | None = None, batch: bool = False,
                 initial: np.ndarray | None = None):
        self.lo, self.hi = _bounds(lo, hi)
        self.config = config or GAConfig()
        self.seed = operator.index(seed)
        self.rng: np.random.Generator | None = None  # the run's one generator, made by run()
        self.executor = executor or SerialExecutor()
        self.checkpoint = None if checkpoint is None else Path(checkpoint)
        self.fitness = fitness
        self.batch = batch
        self.initial = None if initial is None else self._initial_rows(initial)

    @property
    def n_genes(self) -> int:
        return self.lo.size

    def run(self, progress: Progress = None, resume: bool = False,
            stop: Callable[[History], bool] | None = None) -> GAResult:
        """Evolve for ``config.generations`` generations, or until ``stop(history)`` holds after a
        generation (a stopping rule, e.g. convergence); ``progress(done, generations, best)``.

        ``done`` counts the generations evaluated so far, the initial population being the first.
        With ``resume=True`` and an existing checkpoint the run continues from it (its config may
        differ from this one in ``generations`` only, so a finished run can be extended); otherwise
        the run starts afresh and overwrites any checkpoint at the path.
        """
        if resume and self.checkpoint is not None and self.checkpoint.exists():
            state = self._resumed()
        else:
            state = self._first_generation()
            self._report(state, progress)
        while state.generation + 1 < self.config.generations and not (stop is not None and stop(state.history)):
            state = self._next_generation(state)
            self._report(state, progress)
        best = state.history.best_genome[-1]
        return GAResult(best.copy(), float(state.history.best_so_far[-1]), state.history, len(state.history))

    def _report(self, state: Checkpoint, progress: Progress) -> None:
        if self.checkpoint is not None:
            save_checkpoint(self.checkpoint, state)
        if progress is not None:
            progress(state.generation + 1, self.config.generations, float(state.history.best[-1]))

    def _first_generation(self) -> Checkpoint:
        rng = self.rng = np.random.default_rng(self.seed)
        population = rng.uniform(self.lo, self.hi, size=(self.config.population, self.n_genes))
        if self.initial is not None:
            population[: len(self.initial)] = self.initial
        fitness = self._evaluate(population)
        history = self._record(History.empty(self.n_genes), population, fitness)
        return Checkpoint(0, population, fitness, rng.bit_generator.state, history, self.config,
                          self.lo, self.hi, self.seed)

    def _next_generation(self, state: Checkpoint) -> Checkpoint:
        rng = self.rng
        ranked = np.argsort(self._cost(state.fitness), kind="stable")
        population = state.population[ranked]
        carried = self.config.carried()
        offspring = self._offspring(population, rng, self.config.population - carried)
        fitness = np.concatenate([state.fitness[ranked][:carried], self._evaluate(offspring)])
        population = np.vstack([population[:carried], offspring])
        history = self._record(state.history, population, fitness)
        return dataclasses.replace(state, generation=state.generation + 1, population=population,
                                   fitness=fitness, rng_state=rng.bit_generator.state, history=history)

    def _offspring(self, ranked: np.ndarray, rng: np.random.Generator, count: int) -> np.ndarray:
        """``count`` children of parents drawn from the ranked population (best first)."""
        first, second = ranked[self._parents(rng, 2 * count).reshape(2, count)]
        crossed = _crossover(self.config.crossover, first, second, rng)
        children = np.where((rng.random(count) < self.config.crossover_rate)[:, None], crossed, first)
        return self._mutate(children, rng)

    def _parents(self, rng: np.random.Generator, count: int) -> np.ndarray:
        """Ranks of ``count`` selected parents (rank 0 is the best)."""
        cfg = self.config
        if cfg.selection == "truncation":
            return rng.integers(0, cfg.survivors(), size=count)
        entrants = rng.integers(0, cfg.population, size=(count, cfg.tournament_size))
        return entrants.min(axis=1)

    def _mutate(self, children: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        mutate = rng.random(children.shape) < self.config.mutation_rate
        noise = rng.normal(size=children.shape) * (self.config.mutation_sigma * (self.hi - self.lo))
        return np.clip(children + mutate * noise, self.lo, self.hi)

    def _evaluate(self, genomes: np.ndarray) -> np.ndarray:
        if self.batch:
            values = self.executor.map_batches(partial(_batch_fitness, self.fitness), genomes)
        else:
            values = self.executor.map(self.fitness, list(genomes))
        values = np.asarray(values, dtype=float)
        worst = np.inf if self.config.minimize else -np.inf
        return np.where(np.isfinite(values), values, worst)

    def _cost(self, fitness: np.ndarray) -> np.ndarray:
        """Lower is better."""
        return fitness if self.config.minimize else -fitness

    def _record(self, history: History, population: np.ndarray, fitness: np.ndarray) -> History:
        order = np.argsort(self._cost(fitness), kind="stable")
        best_fitness, best_genome = fitness[order[0]], population[order[0]]
        if len(history) and not self._better(best_fitness, history.best_so_far[-1]):
            best_fitness, best_genome = history.best_so_far[-1], history.best_genome[-1]
        return history.appended(fitness, order, best_fitness, best_genome)

    def _better(self, a: float, b: float) -> bool:
        return a < b if self.config.minimize else a > b

    def _resumed(self) -> Checkpoint:
        state = load_checkpoint(self.checkpoint)
        self._check_compatible(state)
        self.rng = np.random.default_rng(self.seed)
        self.rng.bit_generator.state = state.rng_state
        return dataclasses.replace(state, config=self.config)

    def _check_compatible(self, state: Checkpoint) -> None:
        where = f"cannot resume from {self.checkpoint}"
        ours, theirs = dataclasses.asdict(self.config), dataclasses.asdict(state.config)
        differ = [f"{k} {theirs[k]!r} ≠ {ours[k]!r}" for k in ours
                  if k != "generations" and ours[k] != theirs[k]]
        if differ:
            raise ValueError(f"{where}: it was made with a different config ({', '.join(differ)})")
        if not (np.array_equal(state.lo, self.lo) and np.array_equal(state.hi, self.hi)):
            raise ValueError(f"{where}: it was made with different gene bounds")
        if state.seed != self.seed:
            raise ValueError(f"{where}: it was made with seed {state.seed}, not {self.seed}")

    def _initial_rows(self, initial) -> np.ndarray:
        rows = np.atleast_2d(np.asarray(initial, dtype=float))
        if rows.ndim != 2 or rows.shape[1] != self.n_genes or not 1 <= len(rows) <= self.config.population:
            raise ValueError(f"initial must have shape (k, {self.n_genes}) with 1 ≤ k ≤ "
                             f"{self.config.population}, got {rows.shape}")
        if not np.all(np.isfinite(rows)):
            raise ValueError("initial genomes must be finite")
        return np.clip(rows, self.lo, self.hi)


def _crossover(kind: str, first: np.ndarray, second: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Children of parent pairs (rows): uniform, one-point or blend (BLX-α) crossover."""
    count, n = first.shape
    if kind == "uniform":
        return np.where(rng.random((count, n)) < 0.5, first, second)
    if kind == "one_point":
        cut = rng.integers(1, max(n, 2), size=count)
        return np.where(np.arange(n)[None, :] < cut[:, None], first, second)
    u = rng.uniform(-BLEND_ALPHA, 1 + BLEND_ALPHA, size=(count, n))
    return first + u * (second - first)


def _bounds(lo, hi) -> tuple[np.ndarray, np.ndarray]:
    lo, hi = np.asarray(lo, dtype=float).ravel(), np.asarray(hi, dtype=float).ravel()
    if lo.shape != hi.shape or lo.size == 0:
        raise ValueError(f"lo and hi must be non-empty and of one length, got {lo.size} and {hi.size}")
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) and np.all(lo < hi)):
        raise ValueError("gene bounds must be finite with lo < hi for every gene")
    return lo, hi
