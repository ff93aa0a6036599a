"""Fixtures shared by the whole suite."""

from __future__ import annotations

import pytest

from smoke import SmokeRun, shared_root, smoke_run


@pytest.fixture(scope="session")
def smoke(tmp_path_factory):
    """``smoke(scenario_id) -> SmokeRun``: the experiment's run at its declared smoke sizes, made once per
    session however many tests (and xdist workers) read it (tests/smoke.py)."""
    root = shared_root(tmp_path_factory)

    def run(scenario_id: str) -> SmokeRun:
        return smoke_run(root, scenario_id)

    return run
