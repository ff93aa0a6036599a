"""Check kinds and the status rules of the coverage registry; results across seeds (mean ± std)."""

import pytest

from shintai.scenarios.coverage import (DIFFERENCE, NOT_BUILT, NOT_REPRODUCED, REPRODUCED, Row, status_of,
                                        summary)
from shintai.scenarios.registry import Check, Scenario
from shintai.scenarios.seeds import combine

ROW = Row("000:fig9.9", "§9.9, Fig. 9.9", "a test experiment", "x = 1 (§9.9)")
OTHER = Row("000:fig9.8", "§9.8", "another", "y = 2")


def result(*checks, error=None):
    r = {"scenario": "s", "checks": [dict(c) for c in checks]}
    if error:
        r["error"] = error
    return r


def check(name, ok, kind="reproduction", row=None):
    c = {"name": name, "ok": ok, "kind": kind}
    if row:
        c["row"] = row
    return c


def test_a_check_kind_is_reproduction_or_consistency():
    assert Check("a", "<", 1, "x", kind="reproduction").evaluate({"a": 0})["kind"] == "reproduction"
    with pytest.raises(ValueError, match="kind must be"):
        Check("a", "<", 1, "x", kind="thesis")


def test_row_status_follows_only_the_reproduction_checks():
    covers = {"s": ("000:fig9.9",)}
    assert status_of(ROW, {}, {}).status == NOT_BUILT
    ok = status_of(ROW, {"s": result(check("a", True), check("b", False, "consistency"))}, covers)
    assert ok.status == REPRODUCED  # a failing consistency check does not decide
    bad = status_of(ROW, {"s": result(check("a", False), check("b", True, "consistency"))}, covers)
    assert bad.status == NOT_REPRODUCED and "a" in bad.reason
    only_consistency = status_of(ROW, {"s": result(check("b", True, "consistency"))}, covers)
    assert only_consistency.status == NOT_REPRODUCED and "no check compares" in only_consistency.reason
    failed_run = status_of(ROW, {"s": result(check("a", True), error="SimulationDiverged: boom")}, covers)
    assert failed_run.status == NOT_REPRODUCED and "boom" in failed_run.reason
    stated = Row(**{**ROW.__dict__, "difference": "12 cycles, not 9", "why_not": "too slow"})
    assert status_of(stated, {"s": result(check("a", True))}, covers).status == DIFFERENCE
    assert status_of(stated, {"s": result(check("a", False))}, covers).reason == "too slow"


def test_a_check_naming_its_row_counts_only_for_that_row():
    covers = {"s": ("000:fig9.9", "000:fig9.8")}
    r = {"s": result(check("a", True, row="000:fig9.9"), check("b", False, row="000:fig9.8"))}
    assert status_of(ROW, r, covers).status == REPRODUCED
    assert status_of(OTHER, r, covers).status == NOT_REPRODUCED
    counts = summary([status_of(ROW, r, covers), status_of(OTHER, r, covers)])
    assert counts["000"][REPRODUCED] == 1 and counts["000"][NOT_REPRODUCED] == 1 and counts["001"][REPRODUCED] == 0


def test_seeds_combine_as_mean_and_std_and_checks_say_how_many_seeds_held():
    sc = Scenario("s", "src", "sum", run=None, checks=(Check("err_m", "<", 0.5, "x", kind="reproduction"),))
    runs = [{"scenario": "s", "seed": k, "metrics": {"err_m": v, "label": "a"}, "sim_time_s": 1.0,
             "checks": [{"name": "err_m", "ok": v < 0.5}]} for k, v in enumerate((0.2, 0.4, 0.6))]
    out = combine(sc, runs)
    assert out["seeds"] == [0, 1, 2] and out["metrics"]["err_m"] == pytest.approx(0.4)
    assert out["metrics_std"]["err_m"] == pytest.approx(0.1633, abs=1e-4) and out["metrics"]["label"] == "a"
    assert out["checks"][0]["ok"] is True and out["checks"][0]["held_in"] == 2 and out["sim_time_s"] == 3.0
    runs[2]["error"] = "ValueError: x"
    assert combine(sc, runs)["ok"] is False


def test_reproduce_runs_a_stochastic_scenario_over_seeds(tmp_path):
    import json

    from shintai.cli import reproduce
    from shintai.scenarios import registry
    from shintai.scenarios.registry import experiment

    registry.load_all()
    experiment("test.noisy", "nowhere", "noise", compute=lambda ctx: {"draw_m": float(ctx.rng.normal())},
               checks=[Check("draw_m", "<", 10.0, "x", kind="consistency")], stochastic=True)
    try:
        assert reproduce(["test.noisy", "core.minjerk"], tmp_path, "serial", 0, False, "t", seeds=3) == 0
    finally:
        registry.SCENARIOS.pop("test.noisy")
    noisy = json.loads((tmp_path / "test.noisy" / "metrics.json").read_text())
    draws = [json.loads((tmp_path / "test.noisy" / f"seed-{s}" / "metrics.json").read_text())["metrics"]["draw_m"]
             for s in range(3)]
    assert noisy["seeds"] == [0, 1, 2] and len(set(draws)) == 3
    assert noisy["metrics"]["draw_m"] == pytest.approx(sum(draws) / 3) and noisy["checks"][0]["held_in"] == 3
    assert not (tmp_path / "core.minjerk" / "seed-1").exists()  # a deterministic scenario runs once
    assert noisy["metrics_std"]["draw_m"] > 0


def test_every_scenario_classes_its_checks_and_covers_known_rows():
    """No experiment without a row: a scenario's covers name rows of the registry, every check says its kind,
    and a check naming a row names one its scenario covers."""
    import importlib.util

    from shintai.scenarios import registry
    from shintai.scenarios.coverage import all_rows

    registry.load_all()
    rows = all_rows()
    for sid, sc in registry.SCENARIOS.items():
        body = sid.split(".")[0]
        if body not in ("core", "sim") and importlib.util.find_spec(f"shintai.{body}.coverage") is None:
            continue  # a body whose thesis is not catalogued yet
        assert set(sc.covers) <= set(rows), f"{sid} covers unknown rows {set(sc.covers) - set(rows)}"
        for c in sc.checks:
            assert c.kind in ("reproduction", "consistency"), f"{sid}: check {c.name or c.metric} has no kind"
            assert c.row is None or c.row in sc.covers, f"{sid}: check {c.name or c.metric} names a row it does not cover"


def test_a_not_comparable_row_names_the_missing_data_and_no_reproduction_check_is_about_it():
    """A row whose thesis result rests on data the thesis does not print is 'not comparable' and names that
    data; its scenarios declare no reproduction check about it; every other row stays decided by its checks."""
    from shintai.scenarios.coverage import NOT_COMPARABLE, all_rows
    from shintai.scenarios.registry import SCENARIOS, load_all

    covers = {"s": ("000:fig9.9",)}
    unprinted = Row(**{**ROW.__dict__, "not_comparable": "the learning curve"})
    ran = status_of(unprinted, {"s": result(check("b", True, "consistency"))}, covers)
    assert ran.status == NOT_COMPARABLE and "does not print the learning curve" in ran.reason
    assert status_of(unprinted, {"s": result(check("a", True))}, covers).status == NOT_REPRODUCED  # contradiction
    assert status_of(unprinted, {"s": result(error="boom")}, covers).status == NOT_REPRODUCED
    assert status_of(ROW, {"s": result(check("b", True, "consistency"))}, covers).status != NOT_COMPARABLE
    load_all()
    marked = [row for row in all_rows().values() if row.not_comparable]
    assert any(row.key == "004:training" for row in marked)
    for row in marked:
        assert len(row.not_comparable.split()) >= 3, (row.key, row.not_comparable)  # names the data, not "n/a"
        for sc in SCENARIOS.values():
            about = [c.name or c.metric for c in sc.checks if c.kind == "reproduction"
                     and (c.row == row.key or (c.row is None and row.key in sc.covers))]
            assert not about, (row.key, sc.id, about)
