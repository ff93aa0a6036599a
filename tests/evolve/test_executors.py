"""Executors: input order, progress, error reports, picklability and the kind names."""

import operator
import os
import signal
import subprocess
import sys
import time
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from shintai.evolve import ItemError, ProcessExecutor, SerialExecutor, make_executor
from shintai.evolve.executors import chunk_bounds


def later_for_small(x):
    """Return ``x`` after a delay that shrinks as ``x`` grows, so late items finish first."""
    time.sleep(0.002 * (10 - x))
    return x


def worker_pid(_):
    return os.getpid()


def row_sums(rows):
    return np.asarray(rows).sum(axis=1)


@pytest.fixture(params=["serial", "process"])
def executor(request):
    with make_executor(request.param, workers=2) as ex:
        yield ex


def test_results_keep_input_order(executor):
    items = list(range(10))
    assert executor.map(later_for_small, items) == items
    assert executor.map(partial(operator.mul, 3), range(25)) == [3 * i for i in range(25)]


def test_progress_counts_up_to_the_total(executor):
    calls = []
    executor.map(partial(operator.add, 1), range(13), progress=lambda done, total: calls.append((done, total)))
    assert [total for _, total in calls] == [13] * len(calls)
    assert [done for done, _ in calls] == sorted(done for done, _ in calls) and calls[-1][0] == 13


def test_batches_receive_slices_and_keep_order(executor):
    rows = np.arange(40.0).reshape(20, 2)
    assert executor.map_batches(row_sums, rows) == list(rows.sum(axis=1))


def test_error_names_the_item_and_the_original_error(executor):
    with pytest.raises(ItemError) as caught:
        executor.map(partial(operator.truediv, 1.0), [1, 2, 0, 4])
    assert str(caught.value) == "item 2 failed: ZeroDivisionError: float division by zero"
    assert "Traceback" in caught.value.__notes__[0]


def test_empty_input_gives_empty_output(executor):
    assert executor.map(abs, []) == []


def test_pool_stays_alive_across_maps():
    # Which worker takes which chunk depends on the machine's load; what must hold is that both maps
    # ran in the same two worker processes of one pool, started once.
    with ProcessExecutor(workers=2) as pool:
        first = set(pool.map(worker_pid, range(12)))
        workers = set(pool.pool()._processes)
        second = set(pool.map(worker_pid, range(12)))
        assert os.getpid() not in first | second
        assert first | second <= workers and len(workers) == 2
        assert set(pool.pool()._processes) == workers


def test_lambdas_and_local_functions_are_refused():
    def local(x):
        return x

    with ProcessExecutor(workers=2) as pool:
        with pytest.raises(TypeError, match="not picklable; pass a module-level function"):
            pool.map(lambda x: x, [1, 2])
        with pytest.raises(TypeError, match="'test_lambdas_and_local_functions_are_refused.<locals>.local'"):
            pool.map(local, [1, 2])
    assert SerialExecutor().map(lambda x: 2 * x, [1, 2]) == [2, 4]


def test_unknown_kind_names_the_allowed_kinds():
    with pytest.raises(ValueError, match="unknown executor kind 'dask'; allowed: serial, process, ray"):
        make_executor("dask")
    with pytest.raises(ValueError, match="workers must be a positive integer"):
        make_executor("process", workers=0)


def test_chunks_cover_the_items_evenly():
    bounds = chunk_bounds(40, 6)
    assert bounds[0][0] == 0 and bounds[-1][1] == 40
    assert all(a == b for (_, a), (b, _) in zip(bounds, bounds[1:]))
    assert {stop - start for start, stop in bounds} <= {6, 7}
    assert chunk_bounds(3, 6) == [(0, 1), (1, 2), (2, 3)]


def alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f"/proc/{pid}/stat") as f:  # a zombie is dead for our purpose
        return f.read().split(")")[-1].split()[0] != "Z"


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_pool_workers_end_with_their_parent(sig):
    child = subprocess.Popen([sys.executable, str(Path(__file__).with_name("pool_child.py"))],
                             stdout=subprocess.PIPE, text=True)
    workers = [int(p) for p in child.stdout.readline().split()]
    assert len(workers) == 2 and all(alive(p) for p in workers)
    child.send_signal(sig)
    child.wait(timeout=10)
    deadline = time.monotonic() + 10
    while any(alive(p) for p in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(alive(p) for p in workers)
