"""A scenario as a declaration: its rig, stop rule, recorded signals, metrics, plots and variants.

An experiment file (``shintai/<body>/experiments/<name>.py``) declares what one run is and lets the
runner do the rest (DESIGN.md, "the runner owns the loop"):

* ``rig(params, variant, seed) -> Rig``: the body, the modules (in stages), the loop's own channels, the
  stop rule (``duration`` and/or ``until``), what to record ``every`` n steps and the camera view;
* ``variants``: the runs that make up the experiment (``("with", "without")``, or a function of the
  parameters); one run by default;
* ``metrics(runs, params) -> dict``: numbers computed from what the runs did;
* ``plots(ctx, runs, params)``: pictures drawn with ``ctx.figure``.

The runner builds each variant's rig, films it with ``--video`` (any MuJoCo body, one idiom:
:func:`film`), runs its Loop, records its signals into the variant's own :class:`Recorder` (merged
into ``log.npz`` under ``<variant>.``), then calls ``metrics`` and ``plots``. An experiment that is not
one loop per run — a GA, a batched rollout, a search — declares ``compute(ctx) -> metrics`` instead
and says why in its notes.

Metric names of a variant keep the unit suffix last: :func:`variant_metric` (``max_roll_deg``, ``with``
→ ``max_roll_with_deg``).
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from shintai.core.recorder import Recorder
from shintai.core.runtime import Body, Channel, Command, Loop, Module, Snapshot

# Unit suffixes of metric names (DESIGN.md), longest first so ``_mps`` is not read as ``_s``.
UNITS = ("_n_per_mm", "_deg_s", "_rad_s", "_mm_s", "_m_s", "_mps", "_nm", "_mm", "_ms", "_us", "_deg", "_rad", "_hz", "_kg",
         "_pct", "_m", "_n", "_s", "_a", "_v", "_w", "_j")


def unit_of(metric: str) -> str:
    """The unit suffix of a metric name ('' if it has none)."""
    for unit in UNITS:
        if metric.endswith(unit) and len(metric) > len(unit):
            return unit
    return ""


def variant_metric(metric: str, variant: str) -> str:
    """``metric`` of one variant, the variant's name before the unit: ``max_roll_deg`` → ``max_roll_with_deg``."""
    unit = unit_of(metric)
    stem = metric[: len(metric) - len(unit)] if unit else metric
    return f"{stem}_{variant}{unit}"


def per_variant(by_variant: Mapping[str, Mapping[str, Any]], keys: Sequence[str] | None = None) -> dict[str, Any]:
    """Flatten ``{variant: {metric: value}}`` into ``{variant_metric(metric, variant): value}``."""
    out = {}
    for variant, metrics in by_variant.items():
        for key, value in metrics.items():
            if keys is None or key in keys:
                out[variant_metric(key, variant)] = value
    return out


@dataclass
class Rig:
    """One run of an experiment: what the runner builds a :class:`~shintai.core.runtime.Loop` from.

    ``modules`` run as one stage, or ``stages`` in order; ``channels`` are the loop's own (set-points,
    references). Stop rule: ``duration`` seconds of body time and/or ``until`` (a body time, or a
    predicate on the snapshot tested after each step). ``record`` maps ``n`` to a function of the
    snapshot returning the signals to record every ``n`` steps. ``view``: camera options for the
    video (:class:`~shintai.sim.film.FilmRecorder`: camera, ``fps``, ``speed``, ``max_frames``). ``state``: whatever ``metrics`` and ``plots``
    read afterwards (controllers, schedules, laws).
    """

    body: Body
    modules: Sequence[Module] = ()
    stages: Sequence[Sequence[Module]] | None = None
    channels: Sequence[Channel] = ()
    duration: float | None = None
    until: float | Callable[[Snapshot], bool] | None = None
    record: Mapping[int, Callable[[Snapshot], Mapping[str, Any]]] = field(default_factory=dict)
    view: Mapping[str, Any] = field(default_factory=dict)
    base: Command | None = None
    state: Any = None


@dataclass
class Run:
    """What one variant did: its rig, its loop (timing, the last command), its signals and step count."""

    variant: str
    rig: Rig
    loop: Loop
    log: Recorder
    steps: int

    @property
    def body(self) -> Body:
        return self.rig.body

    @property
    def state(self) -> Any:
        return self.rig.state


# a film's defaults: 15 fps at 480×360, at most 300 frames (20 s; a longer run becomes a time-lapse)
VIDEO_DEFAULTS = {"fps": 15, "width": 480, "height": 360, "max_frames": 300}


def film(ctx, body: Body, variant: str | None = None, **view):
    """The one video idiom: a recorder filming ``body``'s MuJoCo model into ``video.mp4`` (or
    ``video_<variant>.mp4``) when the run asked for ``--video``, and MuJoCo's own viewer showing it live
    when it asked for ``--view``; a null context otherwise. The film is rendered when the block ends, on
    worker processes, from the recorded trajectory (:class:`~shintai.sim.film.FilmRecorder`); ``view``
    may set ``fps``, ``width``, ``height``, the camera, ``speed`` (a time-lapse factor) and ``max_frames``."""
    if not (ctx.video or getattr(ctx, "view", False)):
        return contextlib.nullcontext()
    from shintai.sim.film import FilmRecorder
    from shintai.sim.render import mujoco_of

    mj = mujoco_of(body)
    if mj is None:
        return contextlib.nullcontext()
    stack = contextlib.ExitStack()
    if ctx.video:
        path = ctx.out / ("video.mp4" if variant is None else f"video_{variant}.mp4")
        stack.enter_context(FilmRecorder(mj, path, **{**VIDEO_DEFAULTS, **view}))
    if getattr(ctx, "view", False):
        from shintai.sim.viewer import LiveViewer

        stack.enter_context(LiveViewer(mj, title=f"{ctx.scenario.id}" + (f" ({variant})" if variant else "")))
    return stack


def run_rig(rig: Rig, recorder: Recorder | None = None, progress: Callable[[float], None] | None = None) -> Run:
    """Build the rig's Loop and run it to its stop rule, recording ``rig.record`` (no filming)."""
    recorder = recorder if recorder is not None else Recorder()
    loop = Loop(rig.body, None if rig.stages is not None else list(rig.modules), recorder, rig.base,
                stages=rig.stages, channels=rig.channels)
    every = {n: (lambda snap, fn=fn: recorder.record(snap["t"], **fn(snap))) for n, fn in rig.record.items()}
    steps = loop.run(rig.duration, until=rig.until, every=every, progress=progress)
    return Run("", rig, loop, recorder, steps)


def run_variants(ctx, build: Callable[[dict, str, int], Rig], variants: Sequence[str], filmed: Sequence[str] | None = None
                 ) -> dict[str, Run]:
    """Run every variant of an experiment: build its rig, film it (the first filmed variant into
    ``video.mp4``), run it with progress, merge its signals into ``ctx.recorder`` under ``<variant>.``
    (unprefixed when there is one variant). Returns the runs by variant; a run that fails keeps what
    it recorded in ``ctx.recorder`` and re-raises."""
    runs: dict[str, Run] = {}
    filmed = list(variants if filmed is None else filmed)
    for i, variant in enumerate(variants):
        rig = build(ctx.params, variant, ctx.seed)
        recorder = Recorder()
        name = None if filmed and variant == filmed[0] else variant
        share = 1.0 / len(variants)
        try:
            with film(ctx, rig.body, name, **rig.view) if variant in filmed else contextlib.nullcontext():
                run = run_rig(rig, recorder, lambda f, i=i: ctx.progress((i + f) * share, variant))
        finally:
            ctx.recorder.merge(recorder, "" if len(variants) == 1 else f"{variant}.")
            ctx.sim_time_s += rig.body.t
        run.variant = variant
        runs[variant] = run
    return runs
