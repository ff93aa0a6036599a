"""The scenario and benchmark registries that body packages add to.

A body package ``shintai.<body>`` declares one scenario per file in ``shintai/<body>/experiments/``
(:func:`experiment`, see :mod:`shintai.scenarios.experiment`), its account in
``shintai/<body>/notes/<name>.md``, and its benchmarks in ``shintai/<body>/benchmarks.py``
(:func:`benchmark`); :func:`load_all` imports every such module, so a new body needs no change here.

A scenario is: an id, the thesis section it reproduces, parameters with defaults and allowed
ranges, what it runs (a rig per variant, or a compute function) and the metrics computed from the
simulation, checks with their basis and kind, and thesis reference values (which go into
``metrics.json`` under ``thesis``, never ``metrics``).
"""

from __future__ import annotations

import importlib
import importlib.util
import operator
import pkgutil
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import shintai


class ParameterError(ValueError):
    """A bad scenario id, ``--set`` key or value: reported as one line, exit status 2."""


@dataclass(frozen=True)
class Param:
    """A scenario parameter with its default and allowed range (``lo``/``hi``) or ``choices``."""

    name: str
    default: Any
    help: str = ""
    lo: float | None = None
    hi: float | None = None
    choices: tuple | None = None

    def allowed(self) -> str:
        if self.choices is not None:
            return "one of " + "|".join(str(c) for c in self.choices)
        if isinstance(self.default, bool):
            return "true|false"
        lo = "-inf" if self.lo is None else f"{self.lo:g}"
        hi = "inf" if self.hi is None else f"{self.hi:g}"
        kind = "an integer" if isinstance(self.default, int) else "a number"
        return f"{kind} in [{lo}, {hi}]"

    def parse(self, text: str) -> Any:
        """Convert ``text`` to the parameter's type and check its range; ParameterError if not."""
        bad = ParameterError(f"--set {self.name}={text}: expected {self.allowed()}")
        d = self.default
        if self.choices is not None:
            for c in self.choices:
                if str(c) == text:
                    return c
            raise bad
        if isinstance(d, bool):
            low = text.strip().lower()
            if low in ("1", "true", "yes", "on"):
                return True
            if low in ("0", "false", "no", "off"):
                return False
            raise bad
        try:
            value: Any = int(text) if isinstance(d, int) else float(text) if isinstance(d, float) else text
        except ValueError:
            raise bad from None
        if isinstance(value, float) and value != value:  # NaN
            raise bad
        if isinstance(value, (int, float)):
            if (self.lo is not None and value < self.lo) or (self.hi is not None and value > self.hi):
                raise bad
        return value


OPS: dict[str, Callable[[Any, Any], bool]] = {
    "<=": operator.le, "<": operator.lt, ">=": operator.ge, ">": operator.gt, "==": operator.eq,
}


REPRODUCTION, CONSISTENCY = "reproduction", "consistency"


@dataclass(frozen=True)
class Check:
    """``metrics[metric] op threshold``; ``threshold`` may name another metric.

    ``basis`` says why this threshold: a thesis value, a thesis claim, or derived. ``kind``:
    ``"reproduction"`` (it compares with a thesis result and its basis quotes where) or
    ``"consistency"`` (a property of our own model or method, a value that follows from our own inputs).
    Only reproduction checks decide whether an experiment reproduces (:mod:`shintai.scenarios.coverage`);
    ``row`` names the coverage row a reproduction check is about when its scenario covers several.
    """

    metric: str
    op: str
    threshold: float | str
    basis: str
    name: str | None = None
    kind: str | None = None
    row: str | None = None

    def __post_init__(self):
        if self.kind not in (None, REPRODUCTION, CONSISTENCY):
            raise ValueError(f"check {self.name or self.metric!r}: kind must be {REPRODUCTION!r} or "
                             f"{CONSISTENCY!r}, got {self.kind!r}")

    def evaluate(self, metrics: dict[str, Any]) -> dict[str, Any]:
        value = metrics.get(self.metric)
        thr = metrics.get(self.threshold) if isinstance(self.threshold, str) else self.threshold
        ok = (value is not None and thr is not None and _finite(value) and _finite(thr)
              and bool(OPS[self.op](value, thr)))
        return {"name": self.name or self.metric, "metric": self.metric, "op": self.op,
                "threshold": thr, "threshold_ref": self.threshold if isinstance(self.threshold, str) else None,
                "value": value, "ok": ok, "basis": self.basis, "kind": self.kind,
                **({"row": self.row} if self.row else {})}


def _finite(x: Any) -> bool:
    try:
        return x == x and abs(float(x)) != float("inf")
    except (TypeError, ValueError):
        return False


@dataclass(frozen=True)
class ThesisValue:
    """A number the thesis reports, for the ``thesis`` field and the report table."""

    value: Any
    where: str
    metric: str | None = None  # the metric of ours it is to be compared with, if any


@dataclass
class Scenario:
    id: str
    source: str
    summary: str
    run: Callable  # run(ctx: RunContext) -> dict of metrics
    params: tuple[Param, ...] = ()
    checks: tuple[Check, ...] = ()
    thesis: dict[str, ThesisValue] = field(default_factory=dict)
    demo: bool = False  # headline scenario of its body, part of `make demo`
    video: bool | Callable[[dict], bool] = False  # can render an MP4 with --video (MuJoCo bodies), per parameters
    demo_video: bool = True  # the demo films it (False where only non-default parameters render)
    constraints: tuple[tuple[Callable[[dict], bool], str], ...] = ()  # (holds(params), message) across parameters
    plots: Callable | None = None  # plots(ctx, runs, params) after the metrics (declared experiments)
    notes_path: Path | None = None  # the scenario's account, <body>/notes/<name>.md
    covers: tuple[str, ...] = ()  # the coverage rows (thesis experiments) it reproduces
    stochastic: bool = False  # its result depends on the seed: `reproduce --seeds N` gives mean ± std
    rig: Callable | None = None  # rig(params, variant, seed) of a declared experiment (None for a compute)
    variants: Callable[[dict], Sequence[str]] | None = None  # its variants' names from the parameters
    smoke: dict[str, Any] | None = None  # `--set` overrides of the registry test's short run (tests/scenarios)
    # `make demo`'s shortened run, if any: --set overrides (KEY -> text) the demo applies. Its results are
    # labelled a demo variant on the page and never enter the reproduction table.
    demo_params: dict[str, str] = field(default_factory=dict)
    estimate_s: float | None = None  # wall time of a default run on 2 cores (for progress; measured, declared)

    def films(self, params: dict) -> bool:
        """Whether ``--video`` can film this scenario with these parameters."""
        return bool(self.video(params) if callable(self.video) else self.video)

    def param(self, name: str) -> Param:
        for p in self.params:
            if p.name == name:
                return p
        keys = ", ".join(p.name for p in self.params) or "none"
        raise ParameterError(f"--set {name}: unknown key for {self.id} (keys: {keys})")

    def resolve(self, overrides: dict[str, str] | None = None) -> dict[str, Any]:
        """Defaults with ``--set`` overrides parsed and range-checked."""
        values = {p.name: p.default for p in self.params}
        for key, text in (overrides or {}).items():
            values[key] = self.param(key).parse(text)
        for holds, message in self.constraints:
            if not holds(values):
                raise ParameterError(f"{self.id}: {message}")
        return values


@dataclass
class Benchmark:
    id: str
    summary: str
    run: Callable[[], dict]  # returns a dict of results (ratios, times)


SCENARIOS: dict[str, Scenario] = {}
BENCHMARKS: dict[str, Benchmark] = {}


def notes_file(scenario_id: str, module_file: str | None) -> Path | None:
    """``<body>/notes/<name>.md`` beside the ``experiments/`` folder of the declaring file."""
    if not module_file:
        return None
    return Path(module_file).resolve().parent.parent / "notes" / f"{scenario_id.split('.', 1)[-1]}.md"


def checked_demo(sc: Scenario) -> Scenario:
    """A scenario whose demo overrides are valid (a declaration error, raised at import, if not)."""
    if sc.demo_params:
        if not sc.demo:
            raise ValueError(f"scenario {sc.id!r}: demo_params= without demo=True")
        try:
            sc.resolve(sc.demo_params)
        except ParameterError as exc:
            raise ValueError(f"scenario {sc.id!r}: demo_params: {exc}") from None
    if sc.estimate_s is not None and not sc.estimate_s > 0:
        raise ValueError(f"scenario {sc.id!r}: estimate_s must be positive, got {sc.estimate_s!r}")
    return sc


def _register(sc: Scenario) -> Scenario:
    old = SCENARIOS.get(sc.id)
    if old is not None and old.notes_path != sc.notes_path:
        raise ValueError(f"scenario {sc.id!r} registered twice")
    SCENARIOS[sc.id] = sc
    return sc


def experiment(id: str, source: str, summary: str, *, params=(), checks=(), thesis=None,
               rig: Callable | None = None, variants: Sequence[str] | Callable[[dict], Sequence[str]] = ("run",),
               metrics: Callable | None = None, plots: Callable | None = None, compute: Callable | None = None,
               filmed: Sequence[str] | Callable[[dict], Sequence[str]] | None = None, constraints=(),
               demo: bool = False, video: bool | Callable[[dict], bool] = False, demo_video: bool = True,
               covers: Sequence[str] = (), stochastic: bool = False, smoke: dict[str, Any] | None = None,
               demo_params: dict | None = None, estimate_s: float | None = None) -> Scenario:
    """Declare and register one scenario (see :mod:`shintai.scenarios.experiment`).

    Either ``rig(params, variant, seed) -> Rig`` (``seed`` the run's, from which every random source derives) with ``metrics(runs, params) -> dict`` (and optionally
    ``plots(ctx, runs, params)``, ``variants``, ``filmed``), or ``compute(ctx) -> dict`` for an
    experiment that is not one loop per run. ``constraints``: ``(holds(params), message)`` pairs
    checked with the parameters (a violation is a parameter error, exit 2). ``smoke``: the parameter overrides
    (as ``--set`` would give them) of the short run the registry test makes of every experiment. ``demo_params``:
    the ``--set`` overrides of the demo's shortened run (a demo variant: labelled as such, never in the reproduction
    table); ``estimate_s``: a default run's wall time, for the progress line of runs of many scenarios.
    """
    if (rig is None) == (compute is None):
        raise ValueError(f"scenario {id!r}: declare rig= (with metrics=) or compute=, not both")
    if rig is not None and metrics is None:
        raise ValueError(f"scenario {id!r}: a rig needs metrics=")
    run = compute
    if rig is not None:
        from shintai.scenarios.experiment import run_variants

        def names_of(params):
            return list(variants(params) if callable(variants) else variants)

        def run(ctx):
            names = names_of(ctx.params)
            shot = filmed(ctx.params) if callable(filmed) else filmed
            ctx.runs = run_variants(ctx, rig, names, shot)
            return metrics(ctx.runs, ctx.params)

    module_file = sys._getframe(1).f_globals.get("__file__")
    return _register(checked_demo(Scenario(
        id, source, summary, run, tuple(params), tuple(checks), dict(thesis or {}), demo, video, demo_video,
        tuple(constraints), plots, notes_file(id, module_file), tuple(covers), stochastic,
        rig=rig, variants=names_of if rig is not None else None, smoke=_smoke(id, smoke),
        demo_params={str(k): str(v) for k, v in (demo_params or {}).items()}, estimate_s=estimate_s)))


def _smoke(scenario_id: str, smoke: dict[str, Any] | None) -> dict[str, str] | None:
    """``smoke`` as ``--set`` texts (``True`` → ``"true"``)."""
    if smoke is None:
        return None
    if not isinstance(smoke, dict):
        raise ValueError(f"scenario {scenario_id!r}: smoke must be a dict of parameter overrides")
    return {k: (str(v).lower() if isinstance(v, bool) else str(v)) for k, v in smoke.items()}


def scenario(id: str, source: str, summary: str, params=(), checks=(), thesis=None,
             demo: bool = False, video: bool | Callable[[dict], bool] = False, demo_video: bool = True, constraints=(),
             covers: Sequence[str] = (), stochastic: bool = False, smoke: dict[str, Any] | None = None,
             demo_params: dict | None = None, estimate_s: float | None = None):
    """Decorator registering ``compute(ctx) -> metrics`` as a scenario (:func:`experiment` with ``compute=``)."""

    def register(fn):
        module_file = sys.modules[fn.__module__].__dict__.get("__file__") if fn.__module__ in sys.modules else None
        _register(checked_demo(Scenario(
            id, source, summary, fn, tuple(params), tuple(checks), dict(thesis or {}), demo, video, demo_video,
            tuple(constraints), None, notes_file(id, module_file), tuple(covers), stochastic, smoke=_smoke(id, smoke),
            demo_params={str(k): str(v) for k, v in (demo_params or {}).items()}, estimate_s=estimate_s)))
        return fn

    return register


def benchmark(id: str, summary: str):
    """Decorator registering ``run() -> dict`` as a benchmark."""

    def register(fn):
        BENCHMARKS[id] = Benchmark(id, summary, fn)
        return fn

    return register


_LOADED = False
LOAD_ERRORS: dict[str, str] = {}  # module -> one-line error, for packages whose scenarios failed to import


def experiment_modules() -> list[str]:
    """Every module of every ``shintai.<body>.experiments`` package, and each body's ``benchmarks``."""
    names = []
    for package in shintai.body_modules("experiments"):
        folder = Path(shintai.__path__[0]) / package.split(".")[1] / "experiments"
        names += [f"{package}.{m.name}" for m in pkgutil.iter_modules([str(folder)]) if not m.ispkg]
    return names + shintai.body_modules("benchmarks")


def load_all() -> None:
    """Import every experiment file and benchmark module of every ``shintai`` subpackage (once).

    A module that fails to import is recorded in :data:`LOAD_ERRORS` (the command line reports it)
    instead of hiding every other body's scenarios.
    """
    global _LOADED
    if _LOADED:
        return
    for name in experiment_modules():
        try:
            importlib.import_module(name)
        except Exception as exc:  # noqa: BLE001 - reported, not swallowed
            LOAD_ERRORS[name] = f"{type(exc).__name__}: {exc}".splitlines()[0]
    _LOADED = True


def demo_ids() -> list[str]:
    """The scenarios ``shintai demo`` runs: one headline scenario per body (``demo=True``), sorted."""
    load_all()
    return [sid for sid in sorted(SCENARIOS) if SCENARIOS[sid].demo]


def get(scenario_id: str) -> Scenario:
    load_all()
    if scenario_id not in SCENARIOS:
        raise ParameterError(f"unknown scenario {scenario_id!r} (see `shintai list`)")
    return SCENARIOS[scenario_id]
