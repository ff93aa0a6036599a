"""Executors: apply one function to many items, serially, on a process pool, or on Ray.

Seed 003 §5.5.2 builds its parallel GA as a server that sends each individual's genes to as many
clients as it can, each of which runs the dynamics solver and returns the fitness: the analyses of
one generation are independent, so a generation parallelises over its individuals. Here an
executor is that set of clients. The same executors run the scenarios of ``shintai reproduce``.

Every executor has the interface

* ``map(fn, items, progress=None) -> list`` — ``[fn(item) for item in items]``, in input order;
* ``map_batches(fn, items, progress=None) -> list`` — ``fn`` receives a *slice* of ``items`` (a
  chunk) and returns one result per item of the chunk; the results are joined in input order;
* ``progress(done, total)`` is called with the number of items finished as results arrive;
* ``close()``, and use as a context manager; the attribute ``name``.

The process and Ray executors send chunks (about :data:`CHUNKS_PER_WORKER` per worker) to the
module-level :func:`run_chunk`, so ``fn`` must be picklable: a module-level function or a
:func:`functools.partial` of one. Lambdas and local functions are refused with a :class:`TypeError`.
An exception raised by ``fn`` comes back to the caller as :class:`ItemError`, whose message names
the failing item index and the original error (the worker's traceback is attached as a note).
"""

from __future__ import annotations

import contextlib
import ctypes
import multiprocessing
import os
import pickle
import signal
import traceback
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from typing import Any

import numpy as np

CHUNKS_PER_WORKER = 3
KINDS = ("serial", "process", "ray")

Progress = Callable[[int, int], None] | None
Outcome = tuple[list | None, tuple[str, str, str] | None]  # (results, None) or (None, failure)


class ItemError(RuntimeError):
    """``fn`` raised on an item; the message is ``"item <i> failed: <Type>: <message>"``."""


def run_chunk(fn: Callable, start: int, chunk: Sequence, batch: bool) -> Outcome:
    """Apply ``fn`` to a chunk (worker side). Returns ``(results, None)`` or ``(None, failure)``.

    ``failure`` is ``(label, error, traceback)``; returning it rather than raising keeps the error
    report the same on every executor.
    """
    if batch:
        try:
            results = list(fn(chunk))
        except Exception as exc:
            return None, _failure(f"items {start}-{start + len(chunk) - 1}", exc)
        if len(results) != len(chunk):
            error = ValueError(f"batch function returned {len(results)} results for {len(chunk)} items")
            return None, _failure(f"items {start}-{start + len(chunk) - 1}", error)
        return results, None
    results = []
    for i, item in enumerate(chunk):
        try:
            results.append(fn(item))
        except Exception as exc:
            return None, _failure(f"item {start + i}", exc)
    return results, None


def _failure(label: str, exc: BaseException) -> tuple[str, str, str]:
    return label, f"{type(exc).__name__}: {exc}", "".join(traceback.format_exception(exc))


def _raise_failure(failure: tuple[str, str, str]) -> None:
    label, error, trace = failure
    err = ItemError(f"{label} failed: {error}")
    err.add_note(trace.rstrip())
    raise err


PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def die_with_parent(parent_pid: int) -> None:
    """Pool-worker initializer: end this worker when the process that started the pool ends.

    Without it a parent killed by SIGTERM or SIGKILL (a cancelled training run) leaves its forked
    workers computing, and then waiting for work, forever. Linux only (``prctl(PR_SET_PDEATHSIG)``);
    elsewhere a no-op. The ``getppid`` check closes the race of a parent that died before the call.
    """
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
    except (OSError, AttributeError):
        return
    if os.getppid() != parent_pid:
        os._exit(1)


def chunk_bounds(n: int, chunks: int) -> list[tuple[int, int]]:
    """Split ``range(n)`` into ``chunks`` contiguous ``(start, stop)`` pieces of near-equal size."""
    chunks = max(1, min(n, chunks))
    edges = [round(k * n / chunks) for k in range(chunks + 1)]
    return list(zip(edges[:-1], edges[1:]))


def require_picklable(fn: Callable, executor: str) -> None:
    """Raise TypeError unless ``fn`` pickles (a module-level function or a partial of one)."""
    try:
        pickle.dumps(fn)
    except (pickle.PicklingError, AttributeError, TypeError) as exc:
        name = getattr(fn, "__qualname__", type(fn).__name__)
        raise TypeError(f"{executor} executor: fn {name!r} is not picklable; pass a module-level function "
                        f"or a functools.partial of one ({exc})") from None


class Executor:
    """Base of the executors: chunking, ordering, progress and error reporting."""

    name = "executor"

    def map(self, fn: Callable[[Any], Any], items: Iterable, progress: Progress = None) -> list:
        """``[fn(item) for item in items]`` in input order."""
        return self._run(fn, items, progress, batch=False)

    def map_batches(self, fn: Callable[[Sequence], Sequence], items: Iterable, progress: Progress = None) -> list:
        """``fn`` applied to chunks (slices) of ``items``; one result per item, in input order."""
        return self._run(fn, items, progress, batch=True)

    def close(self) -> None:
        """Release the workers (the process executor starts a new pool if used again)."""

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def chunk_count(self, n: int, batch: bool) -> int:
        raise NotImplementedError

    def completed(self, fn: Callable, items: Sequence, bounds: list[tuple[int, int]],
                  batch: bool) -> Iterator[tuple[int, Outcome]]:
        """Yield ``(chunk index, outcome)`` as chunks finish; cancel the rest when closed early."""
        raise NotImplementedError

    def _run(self, fn: Callable, items: Iterable, progress: Progress, batch: bool) -> list:
        items = items if isinstance(items, (Sequence, np.ndarray)) else list(items)
        if len(items) == 0:
            return []
        bounds = chunk_bounds(len(items), self.chunk_count(len(items), batch))
        parts: list[list | None] = [None] * len(bounds)
        done = 0
        with contextlib.closing(self.completed(fn, items, bounds, batch)) as outcomes:
            for k, (results, failure) in outcomes:
                if failure is not None:
                    _raise_failure(failure)
                parts[k] = results
                done += len(results)
                if progress is not None:
                    progress(done, len(items))
        return [r for part in parts for r in part]


class SerialExecutor(Executor):
    """Everything in the calling process: one item at a time for ``map``, one chunk for batches."""

    name = "serial"

    def chunk_count(self, n: int, batch: bool) -> int:
        return 1 if batch else n

    def completed(self, fn, items, bounds, batch):
        for k, (a, b) in enumerate(bounds):
            yield k, run_chunk(fn, a, items[a:b], batch)


class ProcessExecutor(Executor):
    """A pool of ``workers`` processes (default ``os.cpu_count()``), started once and kept warm.

    The pool forks (Linux): workers inherit the parent's imported modules, so start-up is cheap and
    any module-level function of the parent can be sent. ``fn`` must be picklable. Workers end with
    the parent, however it ends (:func:`die_with_parent`).
    """

    name = "process"

    def __init__(self, workers: int | None = None):
        self.workers = _worker_count(workers, os.cpu_count() or 1)
        self._pool: ProcessPoolExecutor | None = None

    def chunk_count(self, n: int, batch: bool) -> int:
        return CHUNKS_PER_WORKER * self.workers

    def pool(self) -> ProcessPoolExecutor:
        if self._pool is None:
            self._pool = ProcessPoolExecutor(self.workers, mp_context=multiprocessing.get_context("fork"),
                                             initializer=die_with_parent, initargs=(os.getpid(),))
        return self._pool

    def completed(self, fn, items, bounds, batch):
        require_picklable(fn, self.name)
        pool = self.pool()
        pending = {pool.submit(run_chunk, fn, a, items[a:b], batch): k for k, (a, b) in enumerate(bounds)}
        try:
            while pending:
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in finished:
                    yield pending.pop(future), future.result()
        finally:
            for future in pending:
                future.cancel()

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None


class RayExecutor(Executor):
    """Tasks on Ray: a real cluster when ``address`` (or the env var ``RAY_ADDRESS``) is given.

    Without an address a private local Ray with ``workers`` CPUs (default ``os.cpu_count()``) is
    started (``address="local"``, so a cluster left running by ``ray start`` is not joined by
    accident). If Ray is already initialised in this process it is used as is. :meth:`close` shuts
    Ray down only if this executor started it. ``fn`` must be picklable.
    """

    name = "ray"

    def __init__(self, address: str | None = None, workers: int | None = None):
        import ray

        self.ray = ray
        workers = None if workers is None else _worker_count(workers, 1)
        address = address or os.environ.get("RAY_ADDRESS") or None
        self.owns_ray = not ray.is_initialized()
        if self.owns_ray and address:
            ray.init(address=address)
        elif self.owns_ray:
            ray.init(address="local", num_cpus=workers or os.cpu_count(), include_dashboard=False,
                     log_to_driver=False, ignore_reinit_error=True)
        self.workers = _worker_count(workers, int(ray.cluster_resources().get("CPU", 1)))
        self.task = ray.remote(run_chunk)

    def chunk_count(self, n: int, batch: bool) -> int:
        return CHUNKS_PER_WORKER * self.workers

    def completed(self, fn, items, bounds, batch):
        require_picklable(fn, self.name)
        fn_ref = self.ray.put(fn)
        index = {self.task.remote(fn_ref, a, items[a:b], batch): k for k, (a, b) in enumerate(bounds)}
        pending = list(index)
        try:
            while pending:
                ready, pending = self.ray.wait(pending, num_returns=1)
                yield index[ready[0]], self.ray.get(ready[0])
        finally:
            for ref in pending:
                self.ray.cancel(ref)

    def close(self) -> None:
        if self.owns_ray and self.ray.is_initialized():
            self.ray.shutdown()
        self.owns_ray = False


def _worker_count(workers: int | None, default: int) -> int:
    """``workers`` checked to be a positive integer, or ``default`` when it is None."""
    if workers is None:
        return max(1, default)
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    return workers


def make_executor(kind: str, workers: int | None = None, address: str | None = None) -> Executor:
    """An executor by name: ``"serial"``, ``"process"`` or ``"ray"`` (``address`` is for Ray only)."""
    if kind not in KINDS:
        raise ValueError(f"unknown executor kind {kind!r}; allowed: {', '.join(KINDS)}")
    if address is not None and kind != "ray":
        raise ValueError(f"an address is only meaningful for the ray executor, not {kind!r}")
    if kind == "serial":
        return SerialExecutor()
    if kind == "process":
        return ProcessExecutor(workers)
    return RayExecutor(address, workers)
