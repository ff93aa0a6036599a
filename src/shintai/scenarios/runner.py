"""Running one scenario: the context a scenario's run function gets, and what is written.

``run_scenario`` writes into the output folder (DESIGN.md contract): ``metrics.json``, ``log.npz``,
the PNG plots the scenario drew, and ``video.mp4`` with ``--video``. If the scenario raises (a
diverging simulation, a NaN state) the error is kept in ``metrics.json`` as one line and whatever
was logged and plotted before the failure is still written.
"""

from __future__ import annotations

import inspect
import json
import math
import os
import sys
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from shintai.core.recorder import Recorder
from shintai.scenarios.registry import Scenario, get


class Progress:
    """Progress of a long run on stderr: a bar with the time left on a terminal; plain lines otherwise (at
    every 10 % and at least every ``every_s`` seconds, for logs); nothing when ``quiet``."""

    width = 24  # characters of the bar

    def __init__(self, label: str, stream=None, quiet: bool = False, every_s: float = 30.0):
        self.label = label
        self.stream = stream or sys.stderr
        self.quiet = quiet
        self.every_s = every_s
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self._last_decile = -1
        self._t0 = time.perf_counter()
        self._last_line = -float("inf")

    def __call__(self, fraction: float, message: str = "") -> None:
        if self.quiet:
            return
        fraction = min(max(fraction, 0.0), 1.0)
        elapsed = time.perf_counter() - self._t0
        left = f" {elapsed * (1 - fraction) / fraction:5.0f}s left" if 0.0 < fraction < 1.0 else ""
        if self.tty:
            full = int(round(self.width * fraction))
            bar = "#" * full + "-" * (self.width - full)
            line = f"{self.label} [{bar}] {100 * fraction:3.0f}% {elapsed:5.0f}s{left} {message}".rstrip()
            self.stream.write("\r" + line[:119].ljust(79) + ("\n" if fraction >= 1.0 else ""))
            self.stream.flush()
            return
        decile = int(fraction * 10)
        if decile > self._last_decile or elapsed - self._last_line >= self.every_s:
            self._last_decile = max(decile, self._last_decile)
            self._last_line = elapsed
            self.stream.write(f"{self.label}: {100 * fraction:5.1f}% {elapsed:6.1f}s{left} {message}".rstrip() + "\n")
            self.stream.flush()


@dataclass
class RunContext:
    """What a scenario's ``run(ctx)`` gets: validated parameters, a seeded RNG, the output folder.

    The run function returns its metrics (a dict of numbers computed from the simulation). It sets
    ``ctx.sim_time_s`` to the simulated time it covered, logs time series into ``ctx.recorder`` and
    draws plots with ``ctx.figure(name)``.
    """

    scenario: Scenario
    params: dict[str, Any]
    seed: int
    out: Path
    video: bool = False
    quiet: bool = False
    view: bool = False
    recorder: Recorder = field(default_factory=Recorder)
    sim_time_s: float = 0.0
    extra: dict[str, Any] = field(default_factory=dict)  # extra JSON-able results (tables) for the report
    runs: dict[str, Any] = field(default_factory=dict)  # a declared experiment's runs by variant

    def __post_init__(self):
        self.rng = np.random.default_rng(self.seed)
        self.progress = Progress(self.scenario.id, quiet=self.quiet)

    @property
    def video_path(self) -> Path:
        return self.out / "video.mp4"

    @contextmanager
    def figure(self, name: str, nrows: int = 1, ncols: int = 1, **kwargs):
        """Yield ``(fig, axes)``; saved as ``<out>/<name>.png`` on exit (also if the block fails)."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        kwargs.setdefault("figsize", (6.4 * ncols ** 0.8, 3.6 * nrows ** 0.8 + 0.6))
        fig, axes = plt.subplots(nrows, ncols, **kwargs)
        try:
            yield fig, axes
        finally:
            fig.suptitle(f"{self.scenario.id} ({self.scenario.source})", fontsize=9)
            fig.tight_layout()
            fig.savefig(self.out / f"{name}.png", dpi=110)
            plt.close(fig)


def jsonable(x: Any) -> Any:
    """Numbers and arrays to plain JSON (NaN/inf become null rather than invalid JSON)."""
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return jsonable(x.tolist())
    if isinstance(x, (np.bool_, bool)):
        return bool(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        x = float(x)
        return x if math.isfinite(x) else None
    return x


_COMMIT: list[str | None] = []


def source_commit() -> str | None:
    """The git commit of the shintai checkout that runs (``+dirty`` with uncommitted changes), or None
    outside a checkout (an installed wheel)."""
    if not _COMMIT:
        import subprocess

        here = Path(__file__).resolve().parent
        try:
            head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True, text=True, timeout=10)
            dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=here,
                                   capture_output=True, text=True, timeout=10)
            _COMMIT.append(head.stdout.strip() + ("+dirty" if dirty.stdout.strip() else "")
                           if head.returncode == 0 else None)
        except (OSError, subprocess.SubprocessError):
            _COMMIT.append(None)
    return _COMMIT[0]


def command_line(scenario_id: str, overrides: dict[str, str] | None, seed: int) -> str:
    """The ``shintai run`` command that reproduces a result."""
    sets = "".join(f" --set {k}={v}" for k, v in (overrides or {}).items())
    return f"shintai run {scenario_id}" + (f" --seed {seed}" if seed else "") + sets


def scenario_notes(sc: Scenario) -> str:
    """The scenario's own account — what it reproduces, what differs and why: ``notes/<name>.md``
    (or, for a scenario not yet given one, its run function's or module's docstring)."""
    if sc.notes_path is not None and sc.notes_path.is_file():
        return sc.notes_path.read_text().strip()
    return inspect.getdoc(sc.run) or inspect.getdoc(inspect.getmodule(sc.run)) or ""


def output_folder(out: str | Path, flag: str = "--out") -> Path:
    """Make the output folder ``out``, or raise a one-line ParameterError saying why it cannot be one (a
    file on the way, no permission, a read-only file system)."""
    from shintai.scenarios.registry import ParameterError

    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        where = f" ({exc.filename})" if exc.filename and str(exc.filename) != str(out) else ""
        raise ParameterError(f"{flag} {out}: cannot make the folder: {exc.strerror or exc}{where}") from None
    if not os.access(out, os.W_OK | os.X_OK):
        raise ParameterError(f"{flag} {out}: the folder is not writable")
    return out


def run_scenario(scenario_id: str, out: str | Path | None = None, overrides: dict[str, str] | None = None,
                 seed: int = 0, video: bool = False, quiet: bool = False, view: bool = False,
                 demo_variant: bool = False) -> dict[str, Any]:
    """Run one scenario, write its outputs, and return the content of ``metrics.json``.

    Raises :class:`~shintai.scenarios.registry.ParameterError` for a bad id, ``--set`` or output folder
    before anything runs. Any error during the run is caught and recorded (``"error"``), never lost.
    ``demo_variant``: the run is the demo's shortened one (``overrides`` are the scenario's
    ``demo_params``); ``metrics.json`` says so under ``"demo_variant"`` and the report keeps it out of the
    reproduction table.
    """
    sc = get(scenario_id)
    params = sc.resolve(overrides)
    if video and not sc.films(params):
        from shintai.scenarios.registry import ParameterError

        what = "with these parameters" if sc.video else "(no MuJoCo body to render)"
        raise ParameterError(f"--video: {sc.id} has nothing to film {what}")
    if view:
        from shintai.scenarios.registry import ParameterError
        from shintai.sim.viewer import display_available

        if not sc.films(params):
            raise ParameterError(f"--view: {sc.id} has no MuJoCo body to show with these parameters")
        if not display_available():
            raise ParameterError("--view: no display to open the viewer on (DISPLAY is not set); "
                                 "use --video to film the run instead")
    out = output_folder(out if out is not None else Path("out") / sc.id)
    ctx = RunContext(sc, params, seed, out, video=video, quiet=quiet, view=view)
    t0 = time.perf_counter()
    error = None
    metrics: dict[str, Any] = {}
    try:
        metrics = dict(sc.run(ctx) or {})
        if sc.plots is not None:
            sc.plots(ctx, ctx.runs, params)
    except Exception as exc:  # a diverging simulation or a bug: keep what was computed
        error = f"{type(exc).__name__}: {exc}".splitlines()[0]
    wall = time.perf_counter() - t0
    result = {
        "scenario": sc.id,
        "source": sc.source,
        "seed": seed,
        "params": params,
        "metrics": metrics,
        "checks": [c.evaluate(metrics) for c in sc.checks] if error is None else [],
        "thesis": {k: {"value": v.value, "where": v.where, **({"metric": v.metric} if v.metric else {})}
                   for k, v in sc.thesis.items()},
        "sim_time_s": ctx.sim_time_s,
        "wall_time_s": wall,
        "notes": scenario_notes(sc),
        "covers": list(sc.covers),
        "command": command_line(sc.id, overrides, seed),
        "commit": source_commit(),
    }
    if demo_variant:
        result["demo_variant"] = {"params": dict(overrides or {})}
    if ctx.extra:
        result["extra"] = ctx.extra
    if error is not None:
        result["error"] = error
    result["ok"] = error is None and all(c["ok"] for c in result["checks"])
    result = jsonable(result)
    ctx.recorder.save(out / "log.npz")
    tmp = out / "metrics.json.tmp"
    tmp.write_text(json.dumps(result, indent=2) + "\n")
    os.replace(tmp, out / "metrics.json")
    return result
