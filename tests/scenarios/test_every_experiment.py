"""One registry test: every experiment runs at the smoke sizes declared beside it (``smoke=`` in its file) and
writes what the contract says (tests/smoke.py ``check_contract``). The runs are made by each body's
``test_smoke_runs.py`` (its ``RUNS``), so that xdist spreads them over the workers; a body's tests that assert
behaviour read the same run through the ``smoke`` fixture, so each experiment runs once. Here: that every
registered experiment declares its smoke sizes, valid ones, and is run by exactly one body file."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from shintai.scenarios import registry

registry.load_all()
TESTS = Path(__file__).resolve().parents[1]


def _runs_by_file() -> dict[str, tuple[str, ...]]:
    runs = {}
    for path in sorted(TESTS.rglob("test_smoke_runs.py")):
        spec = importlib.util.spec_from_file_location(f"_smoke_runs_{len(runs)}", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        runs[str(path.relative_to(TESTS))] = tuple(module.RUNS)
    return runs


def test_every_experiment_declares_smoke_sizes():
    missing = sorted(sid for sid, sc in registry.SCENARIOS.items() if sc.smoke is None)
    assert not missing, f"experiments without smoke= sizes: {missing}"


def test_every_experiment_is_run_by_exactly_one_body_file():
    named = [(sid, f) for f, ids in _runs_by_file().items() for sid in ids]
    counts = {sid: [f for s, f in named if s == sid] for sid, _ in named}
    assert not [sid for sid, files in counts.items() if len(files) > 1], {s: f for s, f in counts.items() if len(f) > 1}
    assert not set(counts) - set(registry.SCENARIOS), f"unknown ids: {set(counts) - set(registry.SCENARIOS)}"
    assert not set(registry.SCENARIOS) - set(counts), f"run by no test_smoke_runs.py: {sorted(set(registry.SCENARIOS) - set(counts))}"


def test_smoke_sizes_are_valid_parameters():
    """A smoke override is a declared parameter within its range (resolve raises otherwise)."""
    for sid, sc in registry.SCENARIOS.items():
        if sc.smoke is not None:
            sc.resolve(sc.smoke)


def test_a_smoke_declaration_must_be_a_dict():
    with pytest.raises(ValueError, match="smoke must be a dict"):
        registry.experiment("test.badsmoke", "x", "x", compute=lambda ctx: {}, smoke=[("a", 1)])
    assert "test.badsmoke" not in registry.SCENARIOS
