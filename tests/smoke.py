"""Each experiment's smoke run, made once per test session and shared by every test that reads it.

The registry test (``test_every_experiment.py``) and a body's behaviour tests read the same run: the
first to ask runs the experiment at the sizes declared beside it (``smoke=``) and the others wait for it
under a file lock, across pytest-xdist's workers, so no experiment runs twice in a suite. Each body's
``test_smoke_runs.py`` names its experiments in ``RUNS`` (so ``--dist loadfile`` spreads the runs over the
workers by body); ``tests/scenarios/test_every_experiment.py`` holds that every experiment is named once."""

from __future__ import annotations

import fcntl
import json
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path

from shintai.scenarios import registry
from shintai.scenarios.runner import run_scenario


@dataclass(frozen=True)
class SmokeRun:
    out: Path  # the run's output folder (metrics.json, log.npz, plots)
    result: dict  # the content of metrics.json


def shared_root(tmp_path_factory) -> Path:
    """A folder shared by this session's workers (their base folders' parent under xdist), new per session."""
    base = tmp_path_factory.getbasetemp()
    root = (base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base) / "smoke-runs"
    root.mkdir(exist_ok=True)
    return root


def smoke_run(root: Path, scenario_id: str) -> SmokeRun:
    """``scenario_id`` run at its declared smoke sizes, from ``root``'s cache when a worker already ran it."""
    sc = registry.get(scenario_id)
    if sc.smoke is None:
        raise ValueError(f"{scenario_id} declares no smoke sizes (smoke= in its experiment file)")
    out = root / scenario_id
    with open(root / f"{scenario_id}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        done = out / "metrics.json"
        if not (out / ".done").exists():
            run_scenario(scenario_id, out, dict(sc.smoke), quiet=True)
            (out / ".done").touch()
        return SmokeRun(out, json.loads(done.read_text()))


def check_contract(scenario_id: str, run: SmokeRun) -> None:
    """What DESIGN.md's ``metrics.json`` contract says a run writes: its metrics, checks with basis and kind,
    thesis values that say where, the parameters it used. The checks' verdicts are not asserted (a short run
    is not the experiment); that every check is evaluated on a metric the run produced is."""
    from shintai.scenarios.registry import CONSISTENCY, REPRODUCTION

    sc = registry.get(scenario_id)
    written = run.result
    assert "error" not in written, written.get("error")
    assert written["scenario"] == scenario_id and written["params"] == sc.resolve(sc.smoke)
    assert written["metrics"], "no metrics"
    for name, value in written["metrics"].items():
        assert re.fullmatch(r"[A-Za-z0-9_.]+", name), f"metric {name!r} is not a snake_case name"
        if isinstance(value, float):
            assert not math.isinf(value), f"metric {name} is infinite"
    for check in written["checks"]:
        assert check["basis"] and check["kind"] in (REPRODUCTION, CONSISTENCY), check
        assert check["metric"] in written["metrics"], f"check {check['name']}: metric {check['metric']} not produced"
    for key, value in written["thesis"].items():
        assert "§" in value["where"] or "seed" in value["where"], f"thesis value {key} does not say where"


def registry_test(runs: tuple[str, ...]):
    """A body's registry test over ``runs`` (its ``test_smoke_runs.py``: ``test_runs_at_its_smoke_size =
    registry_test(RUNS)``): each runs at its declared smoke sizes and writes what the contract says."""
    import pytest

    @pytest.mark.parametrize("scenario_id", runs)
    def test_runs_at_its_smoke_size(scenario_id, smoke):
        check_contract(scenario_id, smoke(scenario_id))

    return test_runs_at_its_smoke_size
