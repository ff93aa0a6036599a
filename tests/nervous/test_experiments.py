"""The nervous scenarios and the benchmark run (small), with their checks (DESIGN.md: tests run scenarios
small; no test asserts a wall-clock time)."""

import json

from shintai.cli import main
from shintai.nervous.benchmarks import nervous_loop


def run(tmp_path, scenario, *sets):
    code = main(["run", scenario, "--out", str(tmp_path), "--quiet", *sum((["--set", s] for s in sets), [])])
    return code, json.loads((tmp_path / "metrics.json").read_text())


def test_fig_c1(tmp_path):
    code, m = run(tmp_path, "nervous.fig-c1")
    assert code == 0, [c for c in m["checks"] if not c["ok"]]
    assert m["metrics"]["peak_minjerk_deg"] == 120.0 and m["metrics"]["peak_minjerksequence_deg"] > 120.0
    assert (tmp_path / "fig_c1.png").exists() and (tmp_path / "fig_c1_log.txt").exists()
    assert {c["kind"] for c in m["checks"]} == {"reproduction", "consistency"}


def test_cla_teach_small(tmp_path):
    code, m = run(tmp_path, "nervous.cla-teach", "cycles=2", "settle_ms=800", "move_ms=500", "hold_ms=900")
    metrics = m["metrics"]
    assert "error" not in m
    assert metrics["shoulder_roll_last_cycle_without_deg"] > 6.0
    assert metrics["shoulder_roll_last_cycle_with_deg"] < 2.0
    assert metrics["posture_error_without_deg"] < 3.0
    assert (tmp_path / "cla_teach.png").exists()


def test_clients_small(tmp_path):
    code, m = run(tmp_path, "nervous.clients", "seconds=1", "postures=4", "move_ms=100")
    metrics = m["metrics"]
    assert "error" not in m
    assert metrics["replies_per_line"] == 1.0 and metrics["pest_error_fraction"] == 1.0
    assert metrics["both_commanders_served"] == 1
    assert metrics["outbox_max"] <= metrics["max_queue_plus_one"]


def test_the_benchmark_runs_and_reports_ratios():
    out = nervous_loop(ticks=200, trials=3, clients=2, seconds=0.3)
    for n in (0, 5, 20):
        assert out[f"dummy_{n}_plugins_vs_period"] > 0 and out[f"cla_{n}_plugins_vs_bare"] > 0
    assert out["latency_median_packets"] > 0 and out["stream_clients"] == 2
