"""Output folders that cannot be made are a usage error (one line, exit 2); the progress of many runs is
weighted by each run's expected wall time; a demo variant is labelled and stays out of the reproduction table."""

import json
import time

import pytest

from shintai.cli import WeightedProgress, expected_walls, main, reproduce
from shintai.scenarios import registry
from shintai.scenarios.registry import Param, experiment
from shintai.scenarios.report import coverage, load_results


@pytest.mark.parametrize("command", [["run", "core.minjerk"], ["reproduce", "--only", "core.minjerk"],
                                     ["demo", "--no-video"]])
@pytest.mark.parametrize("where", ["below", "is"])
def test_an_out_path_that_cannot_be_a_folder_is_one_line_and_exit_2(command, where, tmp_path, capsys):
    (tmp_path / "file").write_text("x")
    out = tmp_path / "file" / "sub" if where == "below" else tmp_path / "file"
    assert main([*command, "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"shintai: error: --out {out}: cannot make the folder"), err
    assert "Traceback" not in err[0]


def test_expected_walls_prefer_the_last_run_then_the_declaration_then_the_median(tmp_path):
    registry.load_all()
    ids = ["core.minjerk", "core.search-index", "snake.tracking"]
    (tmp_path / "core.minjerk").mkdir()
    (tmp_path / "core.minjerk" / "metrics.json").write_text(json.dumps({"wall_time_s": 12.0}))
    sc = registry.SCENARIOS["core.search-index"]
    old, sc.estimate_s = sc.estimate_s, 30.0
    try:
        walls = expected_walls(ids, tmp_path)
    finally:
        sc.estimate_s = old
    assert walls["core.minjerk"] == 12.0 and walls["core.search-index"] == 30.0
    if registry.SCENARIOS["snake.tracking"].estimate_s is None:
        assert walls["snake.tracking"] == 30.0  # the median of the known (upper middle of two)


def test_progress_of_many_runs_counts_their_expected_wall_time(tmp_path):
    seen = []
    jobs = [("long", str(tmp_path / "long")), ("short", str(tmp_path / "short"))]
    progress = WeightedProgress(lambda fraction, message: seen.append(fraction), jobs, {"long": 90.0, "short": 10.0})
    progress.start = time.time() - 1
    (tmp_path / "short").mkdir()
    (tmp_path / "short" / "metrics.json").write_text("{}")
    progress(1, 2)  # the short run finished: 10 % of the work, not half of it
    (tmp_path / "long").mkdir()
    (tmp_path / "long" / "metrics.json").write_text("{}")
    progress(2, 2)
    assert seen == [pytest.approx(0.1), 1.0]


def test_progress_falls_back_to_the_count_where_results_are_not_seen(tmp_path):
    seen = []
    jobs = [("a", str(tmp_path / "a")), ("b", str(tmp_path / "b"))]
    WeightedProgress(lambda f, m: seen.append(f), jobs, {"a": 90.0, "b": 10.0})(1, 2)  # elsewhere (a cluster)
    assert seen == [0.5]


def short_rig(params, variant, seed):
    from shintai.core.benchmarks import NullBody
    from shintai.scenarios.experiment import Rig

    return Rig(NullBody(dt=0.01), duration=params["t"])


@pytest.fixture
def demo_toy():
    sc = experiment("test.demo-toy", "nowhere", "a toy with a shortened demo run", rig=short_rig,
                    metrics=lambda runs, params: {"steps": runs["run"].steps}, params=[Param("t", 0.5, lo=0.01, hi=1.0)],
                    demo=True, demo_params={"t": 0.05}, covers=("001:fig3.6",))
    yield sc
    registry.SCENARIOS.pop("test.demo-toy")


def test_a_demo_variant_runs_shortened_is_labelled_and_stays_out_of_the_table(demo_toy, tmp_path):
    assert reproduce(["test.demo-toy"], tmp_path, "serial", 0, video=False, title="t", quiet=True, demo=True) == 0
    result = json.loads((tmp_path / "test.demo-toy" / "metrics.json").read_text())
    assert result["params"]["t"] == 0.05 and result["metrics"]["steps"] == 5
    assert result["demo_variant"] == {"params": {"t": "0.05"}} and "--set t=0.05" in result["command"]
    row = [s for s in coverage(load_results(tmp_path, ["test.demo-toy"])) if s.row.key == "001:fig3.6"][0]
    assert row.status == "not run here" and "demo" in row.reason
    page = (tmp_path / "index.html").read_text()
    assert "demo variant: t=0.05" in page  # the card says what the demo changed
    # a reproduction of the same scenario runs it at its defaults
    assert reproduce(["test.demo-toy"], tmp_path, "serial", 0, video=False, title="t", quiet=True) == 0
    assert "demo_variant" not in json.loads((tmp_path / "test.demo-toy" / "metrics.json").read_text())


def test_a_demo_variant_tells_checks_it_did_not_measure_from_checks_that_fail(tmp_path):
    from shintai.scenarios.registry import Check

    experiment("test.demo-checks", "nowhere", "a toy whose demo variant skips a metric", rig=short_rig,
               metrics=lambda runs, params: {"steps": runs["run"].steps, **({"long_m": 1.0} if params["t"] > 0.1 else {})},
               params=[Param("t", 0.5, lo=0.01, hi=1.0)], demo=True, demo_params={"t": 0.05},
               checks=[Check("steps", ">", 1, "consistency: it ran"), Check("steps", ">", 10, "consistency: long enough"),
                       Check("long_m", "<", 2.0, "consistency: only a long run measures it")])
    try:
        assert reproduce(["test.demo-checks"], tmp_path, "serial", 0, video=False, title="t", quiet=True, demo=True,
                         checks_only_ran=True) == 0
    finally:
        registry.SCENARIOS.pop("test.demo-checks")
    page = (tmp_path / "index.html").read_text()
    assert "✗ 1 check fails, 1 hold, 1 not measured by this variant" in page
    assert "fails steps 5 (needs &gt; 10)" in page  # the why-line names what it measured and got wrong


def test_demo_params_are_checked_when_declared():
    with pytest.raises(ValueError, match="demo_params= without demo=True"):
        experiment("test.bad-demo", "nowhere", "x", rig=short_rig, metrics=dict, params=[Param("t", 0.5)],
                   demo_params={"t": 0.1})
    with pytest.raises(ValueError, match="demo_params: --set t=5"):
        experiment("test.bad-demo", "nowhere", "x", rig=short_rig, metrics=dict, params=[Param("t", 0.5, hi=1.0)],
                   demo=True, demo_params={"t": 5})
    assert "test.bad-demo" not in registry.SCENARIOS


def test_report_md_also_leads_with_the_bodies(demo_toy, tmp_path):
    assert reproduce(["test.demo-toy"], tmp_path, "serial", 0, video=False, title="t", quiet=True, demo=True) == 0
    text = (tmp_path / "REPORT.md").read_text()
    assert text.index("## Bodies") < text.index("## Summary per thesis") < text.index("## Thesis experiments")
    assert "`test.demo-toy`: a toy with a shortened demo run — 0/0 checks hold — demo variant, not a reproduction" in text
