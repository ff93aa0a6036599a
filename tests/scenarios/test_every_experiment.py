"""One registry test: every experiment runs at the smoke sizes declared beside it (``smoke=`` in its file) and
writes what the contract says (DESIGN.md, ``metrics.json``): its metrics, checks with basis and kind, its thesis
values, the parameters it used. The checks' verdicts at smoke size are not asserted (a short run is not the
experiment); that every check is evaluated on a metric the run produced is."""

from __future__ import annotations

import json
import math
import re

import pytest

from shintai.scenarios import registry
from shintai.scenarios.registry import CONSISTENCY, REPRODUCTION
from shintai.scenarios.runner import run_scenario

registry.load_all()
SMOKED = sorted(sid for sid, sc in registry.SCENARIOS.items() if sc.smoke is not None)


@pytest.mark.parametrize("scenario_id", SMOKED)
def test_every_experiment_runs_at_its_smoke_size(scenario_id, tmp_path):
    sc = registry.get(scenario_id)
    result = run_scenario(scenario_id, tmp_path, dict(sc.smoke), quiet=True)
    assert "error" not in result, result.get("error")
    written = json.loads((tmp_path / "metrics.json").read_text())
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


def test_smoke_sizes_are_valid_parameters():
    """A smoke override is a declared parameter within its range (resolve raises otherwise)."""
    for sid in SMOKED:
        sc = registry.SCENARIOS[sid]
        sc.resolve(sc.smoke)


def test_a_smoke_declaration_must_be_a_dict():
    with pytest.raises(ValueError, match="smoke must be a dict"):
        registry.experiment("test.badsmoke", "x", "x", compute=lambda ctx: {}, smoke=[("a", 1)])
    assert "test.badsmoke" not in registry.SCENARIOS
