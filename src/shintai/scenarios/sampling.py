"""Where a benchmark's or a scenario's CPU time goes: a sampling profiler, summarised by layer, for ``shintai bench``
and ``shintai run --profile``.

Every ``interval_s`` of the process's CPU time (``ITIMER_PROF``) the main thread's Python stack is sampled. A
signal is handled between bytecodes, so a sample taken during a C call (``mj_step``, a LAPACK kernel) lands
on the Python frame that made it. Each sample is charged to

* a **layer**, the first class met walking out from the innermost frame: a body's ``step`` → ``physics``,
  its other methods (snapshot, apply) → ``body_io``, a module → ``control``, the
  :class:`~shintai.core.runtime.Loop` → ``runtime``, a recorder (signals, films) → ``recording``; when none is on
  the stack, ``plotting`` if Matplotlib or a scenario's plots are (a run's figures after its simulation), else
  ``other`` (a benchmark's own harness, NumPy called directly);
* a **function**, the innermost frame in shintai's source (``spine/control.py:duty``).

The shares are of samples, so of CPU time in the main thread; at 5 ms they cost well under 1 % of it
(:func:`sampled` does nothing where ``SIGPROF`` is missing or outside the main thread).
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time
from collections import Counter
from pathlib import Path

import shintai
from shintai.core.recorder import Recorder
from shintai.core.runtime import Body, Loop, Module

ROOT = str(Path(shintai.__file__).parent) + "/"
LAYERS = ("physics", "body_io", "control", "runtime", "recording", "plotting", "other")


_KINDS: dict = {}  # code object → kind, filled as samples meet them


def _kind(code, module_globals) -> str | None:
    """``body``, ``control``, ``runtime`` or ``recording`` for a method (or a function nested in one) of a
    class of that kind, from its qualified name and its module's globals (the frame's locals are not read:
    reading them from a signal handler can disturb the running frame)."""
    kind = _KINDS.get(code, "")
    if kind == "":
        cls = module_globals.get(code.co_qualname.split(".")[0]) if "." in code.co_qualname else None
        kind = None
        if isinstance(cls, type):
            if issubclass(cls, Recorder) or cls.__name__.endswith("Recorder"):
                kind = "recording"
            elif issubclass(cls, Body):
                kind = "body"
            elif issubclass(cls, Module):
                kind = "control"
            elif issubclass(cls, Loop):
                kind = "runtime"
        _KINDS[code] = kind
    return kind


def layer_of(frame) -> str:
    """The layer a sampled stack belongs to (module docstring): the kind of the first method met walking
    out from the innermost frame; a body's method (or a function it called) counts as ``physics`` if its ``step``
    is further out, before any other kind."""
    plotting = False
    while frame is not None:
        kind = _kind(frame.f_code, frame.f_globals)
        if kind == "body":
            while kind in ("body", None):
                if kind == "body" and frame.f_code.co_name == "step":
                    return "physics"
                frame = frame.f_back
                if frame is None:
                    break
                kind = _kind(frame.f_code, frame.f_globals)
            return "body_io"
        if kind is not None:
            return kind
        plotting = plotting or _is_plotting(frame.f_code)
        frame = frame.f_back
    return "plotting" if plotting else "other"


def _is_plotting(code) -> bool:
    """Matplotlib's code, or a function of a shintai ``plots`` module or of the runner's figure context."""
    name = code.co_filename
    return ("/matplotlib/" in name or (name.startswith(ROOT) and Path(name).stem.startswith("plots"))
            or (name.endswith("scenarios/runner.py") and code.co_name == "figure"))


def function_of(frame) -> str | None:
    """``path:function`` of the innermost frame in shintai's source, the path relative to the package."""
    while frame is not None:
        name = frame.f_code.co_filename
        if name.startswith(ROOT):
            return f"{name[len(ROOT):]}:{frame.f_code.co_name}"
        frame = frame.f_back
    return None


class Samples:
    """What :func:`sampled` collected: sample counts per layer and per function."""

    def __init__(self, interval_s: float):
        self.interval_s = interval_s
        self.layers: Counter[str] = Counter()
        self.functions: Counter[str] = Counter()

    def take(self, frame) -> None:
        self.layers[layer_of(frame)] += 1
        name = function_of(frame)
        if name is not None:
            self.functions[name] += 1

    @property
    def count(self) -> int:
        return sum(self.layers.values())

    def summary(self, top: int = 5) -> dict:
        """Shares of the samples per layer (every layer, summing to 1) and the ``top`` functions."""
        n = max(self.count, 1)
        return {"samples": self.count, "interval_ms": 1e3 * self.interval_s,
                "layers": {k: round(self.layers[k] / n, 3) for k in LAYERS},
                "top": [f"{name} {100 * c / n:.0f}%" for name, c in self.functions.most_common(top)]}


def line(summary: dict) -> str:
    """One printed line of a :meth:`Samples.summary`: the layers above 0.5 % and the top functions."""
    layers = ", ".join(f"{k} {100 * v:.0f}%" for k, v in summary["layers"].items() if v >= 0.005)
    return f"{summary['samples']} samples: {layers}; top: {', '.join(summary['top'])}"


@contextlib.contextmanager
def sampled(interval_s: float = 0.005):
    """Sample the main thread's stack every ``interval_s`` of CPU time while the block runs; yields the
    :class:`Samples`. Nested inside another :func:`sampled` (a benchmark profiling each scenario it runs), each
    sample also reaches the outer one, which gets its handler and interval back on exit."""
    samples = Samples(interval_s)
    if not hasattr(signal, "SIGPROF") or threading.current_thread() is not threading.main_thread():
        yield samples
        return
    outer = signal.getsignal(signal.SIGPROF)

    def take(signum, frame):
        samples.take(frame)
        if callable(outer):
            outer(signum, frame)

    previous = signal.signal(signal.SIGPROF, take)
    timer = signal.setitimer(signal.ITIMER_PROF, interval_s, interval_s)
    try:
        yield samples
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0.0, 0.0)
        signal.signal(signal.SIGPROF, previous)
        if timer[1] > 0:
            signal.setitimer(signal.ITIMER_PROF, timer[1], timer[1])


class Clock:
    """The wall time spent in ``method`` of each of ``objects`` during a run (``seconds``) and how often it was
    called (``calls``), the method wrapped on the instances: a benchmark's split of a tick into named parts
    (the sampler above says where the time goes; a clock measures one part exactly, at ≈0.3 µs a call)."""

    def __init__(self, objects, method: str):
        self.seconds, self.calls = 0.0, 0
        for obj in objects:
            self._wrap(obj, method)

    def _wrap(self, obj, method: str) -> None:
        call, clock = getattr(obj, method), time.perf_counter

        def timed(*args, **kwargs):
            t0 = clock()
            try:
                return call(*args, **kwargs)
            finally:
                self.seconds += clock() - t0
                self.calls += 1

        setattr(obj, method, timed)
