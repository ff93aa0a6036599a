"""Training the two RBF networks with the GA of :mod:`shintai.evolve` (seed §4.1.2, §5.1, §6.1).

:func:`train` runs three stages, each a GA run with its own per-generation checkpoint, so that an
interrupted run resumes where it stopped and a finished stage is not run again:

1. ``action`` — the action network under the fixed crawl order 4→2→3→1 (seed §4.1): fitness
   eq. (9) summed over the training environments (the 96 of seed §4.1.1), every gene (centres,
   widths, weights) evolved (seed §4.1.2);
2. ``order`` — the swing-order network (seed §5.1): its centres and widths evolved on eqs.
   (13)-(15) over the teacher set, the output weights fitted by least squares (networks.py);
3. ``free`` — the action network re-trained with the swing-order network choosing every cycle's
   order (seed §6.1, Fig. 29). The paper re-trains "the RBFNN built under the fixed order" without
   saying how; here the GA starts from stage 1's final population.

GA settings of seed §4.1.2: population 100, elitism 10 with tournament selection of 3, uniform
crossover with probability 0.6 (``GAConfig.seed004``); mutation and generations are not printed
and are chosen in ``constants`` (``GA_*``). Every stage uses the run's seed; the result is
bit-identical for one seed on every executor (serial, process pool, Ray).

Why the GA used to find only crab walks, and what changed (§7.10, §7.17). With the network free to
command any displacement, raw inputs and centres uniform over [-1, 2.5] m, every run converged to a
crab walk — ΔYr ≈ 0, ΔXr ≈ ±130 mm, a steady turn of ~7° per cycle — whose arc passes outside the
obstacles' outer ends: one near-constant command that avoids all 96 layouts without telling the
wall's side (27 cycles in §4.2.1, 0.195 m). The paper's walk through the gap is a far better optimum
of eq. (9) (a simple reactive rule through the gap reaches all 96 environments with eq. (9) = 0.005
against the crab's 1.1), but it lies behind a valley of failing walks (10 (x_dc² + y_dc²) ≈ 25 per
environment, eqs. 10-11): even on two environments, and with normalised inputs and centres on data,
the GA only found walks around the obstacles. The root cause is the action space, not eq. (9): the
paper's robot never makes those steps. Seed §5.1 states the range of its displacement per cycle
(ΔXr ±100 mm, ΔYr 150-350 mm, Δθr ±15°, the domain of the swing-order network that takes the action
network's output, Fig. 29), and every cycle of Tables 3, 6 and 7 lies in it; the command is now
clipped to it (``constants.COMMAND_RANGE``). Forward motion is then forced, the robot has to pass
between the obstacles, and the GA finds the paper's behaviour: shift towards the low obstacle, climb
it with the legs of that side while the others pass the wall on the ground. Two further choices
help it find that walk: the inputs are scaled to [-1, 1] (``constants.ACTION_INPUT_SPANS``), and the
first population has its RBF centres on inputs the robot meets (``init="data"``,
:func:`initial_population`). On two environments (§4.2.1, §5.2), 60 generations: centres on data
passed between the obstacles in 4 of 4 seeds (12-14 cycles), uniform centres reached the goal in
both only in 1 of 2 seeds.

What the GA learns (the shipped set, seed 0, default settings under the stopping rule below; 4630 s for the
fixed-order stage on a shared 2-core machine, before the crawl's speed-up): the fixed-order network reaches all
96 training environments without failure from generation 165 (at 120 it still failed in 5). Until then it
walked every cycle at the range's smallest forward step, 150 mm; after it, with only eq. (12)'s
(x_dc² + y_dc²) T / 50 left to lower, it learns to lengthen its steps once past the obstacles: eq. (9) = 0.475
at 180, 0.338 at 400 (the earlier shipped set's budget), 0.153 at 675 and 0.103 from 773 to 974, where the
rule was met; 11.3 cycles on average (paper 9-11 in its examples), final errors 0.062 m on average (paper
0.023-0.073 m). The swing-order network (16 hidden units, chosen on held-out teacher data,
``constants.ORDER_HIDDEN``) fits 93.8 % of its 160 teacher patterns and 65 % of a held-out set. The
re-training with the free gait (stage ``free``) starts at the converged fixed-order population's 0.103 and
met the rule at its generation 201 without improving: the swing order changes a cycle's body path and
feasibility, not its displacement, so eqs. 9-12 score a walk that stays feasible the same under either
order (notes/free-gait.md). The earlier 400-generation set's re-training had fallen to 0.121 — continued
training of an unconverged baseline, not the free gait's gain.

Stopping rule (issue 27): stages ``action`` and ``free`` stop when the best eq. (9) fitness improved by
less than 1 % over 200 generations (:func:`converged`, constants ``CONVERGENCE_*``); the generation counts
are caps. The shipped set is the first run that met it (both stages at their last generation, tested);
notes/train.md has its course.

Trained weights are ``.npz`` files: ``genome`` (and for the swing-order network its ``centres``,
``sigmas`` and fitted ``weights``), the learning curve (``best``, ``mean`` per generation) and the
settings that made them. A trained set ships in ``trained/``; ``shintai run quadruped.train`` with its
recorded settings (``--set generations=400 --set free_generations=300 --set converge=false``) reproduces it.
"""

from __future__ import annotations

import ctypes
import dataclasses
import glob
import json
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import numpy as np

from shintai.evolve import Executor, GAConfig, GeneticAlgorithm, load_checkpoint, stalled
from shintai.quadruped import constants as C
from shintai.quadruped import fitness as F
from shintai.quadruped import swing_order as S
from shintai.quadruped import world as W
from shintai.quadruped.episode import Episodes, GenomePolicy, OrderPolicy, path_inputs, rollout
from shintai.quadruped.networks import SwingOrderNetwork, SwingOrderPolicy
from shintai.quadruped.swing_order import CRAWL

STAGES = ("action", "order", "free")
INITS = ("data", "uniform")  # initial population of stage ``action`` (constants ``INIT_*``)
FILES = {"action": "action_fixed.npz", "order": "swing_order.npz", "free": "action_free.npz"}
TRAINED_DIR = Path(__file__).parent / "trained"

Progress = Callable[[str, int, int, float], None] | None  # (stage, done, total, best fitness)


@dataclass(frozen=True)
class TrainSettings:
    """What a training run depends on (with the seed, everything)."""

    generations: int = C.GA_GENERATIONS
    order_generations: int = C.GA_ORDER_GENERATIONS
    free_generations: int = C.GA_FREE_GENERATIONS
    mutation_rate: float = C.GA_MUTATION_RATE
    mutation_sigma: float = C.GA_MUTATION_SIGMA
    population: int = C.GA_POPULATION
    environments: int = 96
    seed: int = 0
    init: str = "data"
    order_hidden: int = C.ORDER_HIDDEN
    converge: bool = True  # stop stages action and free at the rule of :func:`converged` (else: the budget)

    def __post_init__(self):
        if not 1 <= self.environments <= 96:
            raise ValueError(f"environments must be in [1, 96], got {self.environments}")
        if self.init not in INITS:
            raise ValueError(f"init must be one of {INITS}, got {self.init!r}")
        if self.order_hidden < 1:
            raise ValueError(f"order_hidden must be >= 1, got {self.order_hidden}")

    @property
    def order_net(self) -> SwingOrderNetwork:
        return SwingOrderNetwork(n_hidden=self.order_hidden)

    def config(self, generations: int) -> GAConfig:
        """``GAConfig.seed004`` with this run's population, generations and mutation."""
        return GAConfig.seed004(population=self.population, generations=generations,
                                elitism=min(C.GA_ELITES, self.population - 1),
                                mutation_rate=self.mutation_rate, mutation_sigma=self.mutation_sigma)

    def generations_of(self, stage: str) -> int:
        return {"action": self.generations, "order": self.order_generations, "free": self.free_generations}[stage]


def converged(best: np.ndarray, window: int = C.CONVERGENCE_WINDOW,
              tolerance: float = C.CONVERGENCE_TOLERANCE) -> bool:
    """The stopping rule of stages ``action`` and ``free`` (constants ``CONVERGENCE_*``): the best
    fitness per generation ``best`` (minimised, index 0 the first population) has improved by less
    than ``tolerance`` of its value ``window`` generations ago (:func:`shintai.evolve.stalled`); never before
    ``window + 1`` generations."""
    return stalled(best, window, tolerance, minimize=True)


def training_envs(n: int) -> W.EnvBatch:
    """``n`` of the 96 training environments, evenly spaced over the set (all 96 for ``n = 96``)."""
    return F.training_batch().take(np.linspace(0, 95, n).round().astype(int))


@dataclass(frozen=True)
class StageResult:
    """One trained stage: the best genome, its fitness, the learning curve and the wall time."""

    stage: str
    genome: np.ndarray
    best_fitness: float
    best: np.ndarray
    mean: np.ndarray
    wall_s: float

    @property
    def generations(self) -> int:
        return len(self.best)


def initial_population(settings: TrainSettings) -> np.ndarray | None:
    """Stage ``action``'s first population: with ``init="data"`` RBF centres on the inputs of
    :func:`episode.path_inputs` in the run's training environments (constants ``INIT_*``), drawn
    from the run's seed; ``None`` (uniform in the gene bounds, drawn by the GA) with ``"uniform"``."""
    if settings.init == "uniform":
        return None
    rng = np.random.default_rng([settings.seed, 1])  # not the GA's generator (seeded with the seed alone)
    return F.ACTION_NET.genomes_on_data(rng, settings.population, path_inputs(training_envs(settings.environments)))


def _fitness(stage: str, settings: TrainSettings, order: SwingOrderPolicy | None):
    """The stage's picklable batch fitness."""
    if stage == "order":
        return partial(F.order_fitness_batch, net=settings.order_net)
    envs = None if settings.environments == 96 else training_envs(settings.environments)
    return partial(F.action_fitness_batch, envs=envs, order_policy=order)


def run_stage(stage: str, settings: TrainSettings, executor: Executor, checkpoint: Path, resume: bool,
              order: SwingOrderPolicy | None = None, initial: np.ndarray | None = None,
              progress: Progress = None) -> StageResult:
    """One GA run of a stage (module docstring); ``order`` is the swing-order policy of stage ``free``."""
    net = settings.order_net if stage == "order" else F.ACTION_NET
    lo, hi = net.bounds()
    if stage == "action" and initial is None:
        initial = initial_population(settings)
    ga = GeneticAlgorithm(_fitness(stage, settings, order), lo, hi, settings.config(settings.generations_of(stage)),
                          seed=settings.seed, executor=executor, checkpoint=checkpoint, batch=True, initial=initial)
    report = None if progress is None else partial(progress, stage)
    stop = (lambda history: converged(history.best)) if settings.converge and stage != "order" else None
    t0 = time.perf_counter()
    result = ga.run(report, resume=resume, stop=stop)
    h = result.history
    return StageResult(stage, result.best_genome, result.best_fitness, h.best, h.mean, time.perf_counter() - t0)


@contextmanager
def single_threaded_blas() -> Iterator[None]:
    """NumPy's OpenBLAS on one thread while training (restored after); forked workers inherit it.

    The GA already spreads individuals over the cores; OpenBLAS's own threads, spinning on 2 shared
    cores, made one generation of the swing-order network (least squares per genome) 50 times
    slower (30 s instead of 0.6 s). Ray workers get one thread from Ray (``OMP_NUM_THREADS=1``).
    Without NumPy's bundled OpenBLAS this does nothing.
    """
    pattern = str(Path(np.__file__).parent.parent / "numpy.libs" / "libscipy_openblas*.so")
    libs = [ctypes.CDLL(path) for path in glob.glob(pattern)]
    calls = [(getattr(lib, f"scipy_openblas_{verb}_num_threads64_", None) for verb in ("get", "set")) for lib in libs]
    calls = [(get, put) for get, put in calls if get is not None and put is not None]
    before = [get() for get, _ in calls]
    for _, put in calls:
        put(1)
    try:
        yield
    finally:
        for (_, put), n in zip(calls, before):
            put(n)


def train(out: Path, settings: TrainSettings, executor: Executor, resume: bool = True,
          stages: tuple[str, ...] = STAGES, progress: Progress = None) -> dict[str, StageResult]:
    """Run ``stages`` in order (``free`` needs the other two), writing ``FILES`` and the GA
    checkpoints ``<stage>.ga.npz`` into ``out``."""
    unknown = [s for s in stages if s not in STAGES]
    if unknown or ("free" in stages and not {"action", "order"} <= set(stages)):
        raise ValueError(f"stages must be drawn from {STAGES} and 'free' needs 'action' and 'order', got {stages}")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    results: dict[str, StageResult] = {}
    for stage in (s for s in STAGES if s in stages):
        order = load_order(out / FILES["order"]) if stage == "free" else None
        initial = load_checkpoint(out / "action.ga.npz").population if stage == "free" else None
        results[stage] = run_stage(stage, settings, executor, out / f"{stage}.ga.npz", resume, order, initial,
                                   progress)
        save(out / FILES[stage], results[stage], settings)
    return results


# --- Trained weights ------------------------------------------------------------------------------

def save(path: Path, result: StageResult, settings: TrainSettings) -> None:
    """Write a stage's network (module docstring) to ``path``."""
    arrays = {"genome": result.genome, "best": result.best, "mean": result.mean,
              "settings": np.array(json.dumps(dataclasses.asdict(settings)))}
    if result.stage == "order":
        policy = order_policy(result.genome)
        arrays.update(centres=policy.centres, sigmas=policy.sigmas, weights=policy.weights)
    np.savez(path, **arrays)


def _load(path: Path | None, stage: str):
    path = TRAINED_DIR / FILES[stage] if path is None else Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"trained weights not found: {path} (make them with `shintai run quadruped.train`)")
    return np.load(path, allow_pickle=False)


def load_action(path: Path | None = None, stage: str = "action") -> np.ndarray:
    """The action-network genome of ``path`` (default: the shipped ``stage`` network, ``action`` for
    the fixed-order one, ``free`` for the one re-trained with the swing-order network)."""
    if stage not in ("action", "free"):
        raise ValueError(f"an action network is stage 'action' or 'free', got {stage!r}")
    with _load(path, stage) as data:
        genome = data["genome"]
    if genome.shape != (F.ACTION_NET.size,):
        raise ValueError(f"{path}: not an action network ({genome.shape[0]} genes, expected {F.ACTION_NET.size})")
    return genome


def order_policy(genome: np.ndarray) -> SwingOrderPolicy:
    """The swing-order network of a genome (its hidden size from the genome's length), its output
    weights fitted to the default teacher set."""
    h, rest = divmod(len(genome), C.ORDER_INPUTS + 1)
    if rest:
        raise ValueError(f"not a swing-order genome: {len(genome)} genes is no multiple of {C.ORDER_INPUTS + 1}")
    return SwingOrderNetwork(n_hidden=h).trained(genome, F.default_teacher())


def load_order(path: Path | None = None) -> SwingOrderPolicy:
    """The swing-order network of ``path`` (default: the shipped one) as a policy."""
    with _load(path, "order") as data:
        if "weights" not in data:
            raise ValueError(f"{path}: not a swing-order network (no fitted weights)")
        return SwingOrderPolicy(data["centres"], data["sigmas"], data["weights"])


def load_curve(path: Path | None = None, stage: str = "action") -> tuple[np.ndarray, np.ndarray, dict]:
    """The learning curve (best and mean fitness per generation) and settings stored with a network."""
    with _load(path, stage) as data:
        return data["best"], data["mean"], json.loads(str(data["settings"]))


# --- Evaluation -----------------------------------------------------------------------------------

def evaluate(genome: np.ndarray, envs: W.EnvBatch, order: OrderPolicy | None = None,
             record: bool = False) -> Episodes:
    """One episode per environment with the action network ``genome`` (and a swing-order policy)."""
    return rollout(envs, GenomePolicy(F.ACTION_NET, np.asarray(genome)[None], len(envs)), order, record=record)


def success(ep: Episodes) -> np.ndarray:
    """Episodes that reached the goal circle (a walk stops at its first failure, so no failure)."""
    return ep.reached & ~(ep.collided | ep.limit | ep.unstable)


def order_accuracy(policy: SwingOrderPolicy, teacher=None) -> float:
    """Fraction of teacher patterns whose optimal order the network picks (argmin |o - 1|)."""
    teacher = F.default_teacher() if teacher is None else teacher
    return float(np.mean(policy(teacher.x[:, 0], teacher.x[:, 1:]) == teacher.label))


def order_generalisation(policy: SwingOrderPolicy, draws: int = C.ORDER_UNIFORM_DRAWS,
                         seed: int = C.ORDER_UNIFORM_SEED) -> dict[str, float]:
    """How the swing-order network does off its teacher patterns: accuracy on a held-out teacher set
    (``teacher_set(seed=ORDER_HELDOUT_SEED)``), and on ``draws`` uniform draws of the teacher ranges
    (from the initial stance, as the teacher) the fractions of feasible draws where its order is
    optimal (ties counted), infeasible, and where the crawl order is optimal, with the mean Br [mm] of
    its, the crawl and the best order over the draws where its and the crawl order are feasible; and
    the share of feasible draws where two or more orders tie for the least Br, and the median of the
    least Br over the commanded displacement."""
    heldout = order_accuracy(policy, S.teacher_set(seed=C.ORDER_HELDOUT_SEED))
    x = np.random.default_rng(seed).uniform(S.TEACHER_LOW, S.TEACHER_HIGH, size=(draws, 4))
    br = S.body_movement(x[:, 0], x[:, 1:])
    best = br.min(axis=1)
    ok = np.isfinite(best)
    mine = br[np.arange(draws), policy(x[:, 0], x[:, 1:])]
    both = ok & np.isfinite(mine) & np.isfinite(br[:, CRAWL])
    return {"heldout_accuracy": heldout,
            "uniform_optimal_fraction": float(np.mean(mine[ok] <= best[ok] + S.TIE)),
            "uniform_infeasible_fraction": float(np.mean(~np.isfinite(mine[ok]))),
            "uniform_crawl_optimal_fraction": float(np.mean(br[ok, CRAWL] <= best[ok] + S.TIE)),
            "uniform_br_network_mm": float(1000 * mine[both].mean()),
            "uniform_br_crawl_mm": float(1000 * br[both, CRAWL].mean()),
            "uniform_br_best_mm": float(1000 * best[both].mean()),
            # context of the teacher (swing-order docstring, "why 8, not 19"): draws whose best Br is
            # shared by two or more orders, and the best Br over the commanded displacement |(ΔXr, ΔYr)|
            "uniform_tied_fraction": float(np.mean(np.sum(br[ok] <= best[ok, None] + S.TIE, axis=1) > 1)),
            "uniform_br_over_displacement_median": float(np.median(best[ok] / np.hypot(x[ok, 1], x[ok, 2])))}
