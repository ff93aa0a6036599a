"""The quadruped scenarios run end to end through the scenario runner."""

import json

from shintai.scenarios.runner import run_scenario


def test_replay_scenario_passes_and_writes_its_outputs(tmp_path):
    result = run_scenario("quadruped.replay", out=tmp_path, quiet=True)
    assert result["ok"], result.get("error") or [c for c in result["checks"] if not c["ok"]]
    m = result["metrics"]
    assert m["table6_climbing_legs"] == "1" and m["table7_climbing_legs"] == "24"
    assert m["exhaustive_orders_as_table4"] == 6
    assert json.loads((tmp_path / "metrics.json").read_text())["scenario"] == "quadruped.replay"
    assert (tmp_path / "paths.png").exists() and (tmp_path / "body_movement.png").exists()
    assert (tmp_path / "log.npz").exists()
