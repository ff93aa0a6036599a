"""Running a seed-003 GA inside a scenario: the shared parameters, the checkpointed run, the curve.

Chapter 5's three generated motions (SQ43's trot §5.6, HanzouS's brachiation §5.7, Cla's crawl §5.2.9)
all evolve genes with the §5.5 parallel GA (population 20 or 105, crossover 0.2, mutation 0.02, culling
0.4, fitness maximised: :meth:`shintai.evolve.GAConfig.seed003`). Each scenario declares ``GA_PARAMS``
(with its own generation count and population), calls :func:`evolve` with a picklable fitness and those
parameters as a :class:`GARun`, and gets
the result, the per-generation record (``<name>.best``/``<name>.mean``) and the curve picture. A scenario may
declare a stopping rule (``ga_params(..., stop=True)``: robots ``GA_STOP_*``, :func:`shintai.evolve.stalled`), the
generation count then a cap. The GA
state is checkpointed to ``<out>/<name>.ga.npz`` after every generation; ``resume`` continues a killed
run to the identical result. Serial, process and Ray executors give identical generations for one seed
(:mod:`shintai.evolve.ga`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields

import numpy as np

from shintai.evolve import GAConfig, GAResult, GeneticAlgorithm, make_executor, stalled
from shintai.scenarios.registry import Param
from shintai.spine.robots import GA_STOP_TOLERANCE, GA_STOP_WINDOW

EXECUTORS = ("serial", "process", "ray")


def ga_params(generations: int, population: int, stop: bool = False) -> list[Param]:
    """The GA's scenario parameters; ``generations`` and ``population`` are the scenario's defaults; ``stop``:
    the run stops by the rule of robots ``GA_STOP_*`` (``generations`` a cap)."""
    rule = [Param("stop_window", GA_STOP_WINDOW, "stop when the best improved by less than stop_tolerance over this "
                  "many generations (0: run every generation)", lo=0, hi=100000),
            Param("stop_tolerance", GA_STOP_TOLERANCE, "relative improvement of the best over stop_window",
                  lo=0.0, hi=1.0)] if stop else []
    return [
        Param("generations", generations, "GA generations evaluated, the initial population included"
              + (" (a cap: the run stops earlier by stop_window/stop_tolerance)" if stop else ""), lo=1,
              hi=100000),
        *rule,
        Param("population", population, "GA population (seed 003 §5.6.2: 20, §5.7.3: 105)", lo=4, hi=100000),
        Param("executor", "process", "where fitness runs", choices=EXECUTORS),
        Param("workers", 0, "processes or Ray CPUs (0: all local cores)", lo=0, hi=4096),
        Param("address", "", "Ray cluster address (executor=ray; empty: RAY_ADDRESS or a local Ray)"),
        Param("resume", True, "continue from the GA checkpoint in the output folder"),
    ]


@dataclass(frozen=True)
class GARun:
    """The values of :func:`ga_params` for one run: how many generations of which population, where fitness
    runs, and whether to resume from the checkpoint."""

    generations: int
    population: int
    executor: str = "process"
    workers: int = 0
    address: str = ""
    resume: bool = True
    stop_window: int = 0  # 0: no stopping rule, every generation runs
    stop_tolerance: float = 0.0

    @property
    def config(self) -> GAConfig:
        """Seed 003's GA (§5.6.2) with this generation count and population."""
        return GAConfig.seed003(generations=int(self.generations), population=int(self.population))

    def stop(self, history) -> bool:
        """The stopping rule on the best so far (maximised)."""
        return stalled(history.best_so_far, int(self.stop_window), float(self.stop_tolerance), minimize=False)


STOP_KEYS = ("stop_window", "stop_tolerance")  # the parameters of a stopping rule (ga_params(..., stop=True))
GA_KEYS = tuple(f.name for f in fields(GARun) if f.name not in STOP_KEYS)  # the other parameters of ga_params


def ga_of(params) -> GARun:
    """The :class:`GARun` of a scenario's parameters (with its stopping rule where it declares one)."""
    return GARun(**{k: params[k] for k in GA_KEYS + STOP_KEYS if k in params})


def evaluations(population: int, generations: int) -> int:
    """How many fitness runs a GA of ``generations`` made: the first population whole, then only the offspring
    that replace the culled (the survivors are carried with their fitness)."""
    c = GAConfig.seed003(generations=int(generations), population=int(population))
    return c.population + (generations - 1) * (c.population - c.carried())


def evolve(ctx, name: str, fitness: Callable, lo, hi, *, ga: GARun, batch: bool = False,
           initial: np.ndarray | None = None, title: str = "", seed: int | None = None) -> GAResult:
    """Run the GA ``ga`` on ``fitness`` (maximised) in the box ``[lo, hi]``.

    Reports progress, checkpoints to ``<out>/<name>.ga.npz``, records ``<name>.best``/``<name>.mean`` per
    generation, and draws ``<name>_curve.png``. ``fitness`` must be picklable for the process and Ray
    executors (a module-level function or a frozen dataclass instance). ``seed``: the GA's seed (default the
    run's, ``ctx.seed``; a scenario running several independent GAs gives each its own).
    """
    algorithm = GeneticAlgorithm(fitness, lo, hi, ga.config, seed=ctx.seed if seed is None else seed,
                                 checkpoint=ctx.out / f"{name}.ga.npz", batch=batch, initial=initial)

    cap = " (cap)" if ga.stop_window else ""

    def progress(done: int, total: int, best: float) -> None:
        ctx.progress(done / total, f"{name} generation {done}/{total}{cap}, best {best:.4g}")

    with make_executor(ga.executor, ga.workers or None, ga.address or None) as executor:
        algorithm.executor = executor
        result = algorithm.run(progress, resume=bool(ga.resume), stop=ga.stop if ga.stop_window else None)
    history = result.history
    for g in range(len(history)):
        ctx.recorder.record(g, **{f"{name}.best": history.best[g], f"{name}.mean": history.mean[g]})
    ctx.extra.setdefault("ga_curves", {})[name] = {"best": history.best, "mean": history.mean,
                                                   "best_genome": result.best_genome}
    with ctx.figure(f"{name}_curve") as (fig, ax):
        draw_curve(ax, history.best, history.mean, title or name)
    return result


def draw_curve(ax, best, mean, title: str) -> None:
    """A maximised GA's curve: best and mean fitness per generation."""
    g = np.arange(len(best))
    ax.plot(g, best, "-o", ms=3, label="best")
    ax.plot(g, mean, "-", lw=0.8, label="population mean")
    ax.set_xlabel("generation")
    ax.set_ylabel("fitness (maximised)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)


def generations_to_converge(best: np.ndarray, fraction: float = 0.95) -> int:
    """The first generation whose best fitness reaches ``fraction`` of the way from the initial best to
    the final best (0 if the run did not improve). Our measure of "converged in few generations"."""
    best = np.asarray(best, dtype=float)
    gain = best[-1] - best[0]
    if not np.isfinite(gain) or gain <= 0:
        return 0
    return int(np.argmax(best >= best[0] + fraction * gain))


def budget_metrics(result: GAResult, ga: GARun) -> dict:
    """How the run ended: the generations run and whether the stopping rule (not the cap) ended it."""
    n = len(result.history)
    return {"generations": n, "stopped_by_rule": int(bool(ga.stop_window) and ga.stop(result.history))}
