"""The `shintai` command contract (DESIGN.md): list, run, reproduce, bench; exit codes; metrics.json."""

import json
import subprocess
import sys

import numpy as np
import pytest

from shintai.cli import main
from shintai.scenarios import registry
from shintai.scenarios.registry import Check, Param, ParameterError
from shintai.scenarios.runner import run_scenario


def test_every_body_package_imports():
    registry.load_all()
    assert registry.LOAD_ERRORS == {}
    assert {"core.search-index", "core.minjerk"} <= set(registry.SCENARIOS)


def test_list_prints_id_source_summary(capsys):
    assert main(["list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert any(line.startswith("core.minjerk") and "seed 003" in line for line in lines)


def test_run_writes_metrics_log_and_plots(tmp_path):
    out = tmp_path / "si"
    assert main(["run", "core.search-index", "--out", str(out), "--quiet"]) == 0
    m = json.loads((out / "metrics.json").read_text())
    assert {"scenario", "source", "seed", "params", "metrics", "checks", "thesis", "sim_time_s",
            "wall_time_s"} <= set(m)
    assert m["params"]["steps"] == 60 and all(c["ok"] and c["basis"] for c in m["checks"])
    assert "scalar_error" in np.load(out / "log.npz")
    assert (out / "search_index.png").stat().st_size > 10_000


def test_failing_check_exits_1(tmp_path):
    # a|g| = 2.4 > 2: the update overshoots more than it corrects and the error grows
    code = main(["run", "core.search-index", "--out", str(tmp_path), "--set", "gain=1.2", "--quiet"])
    m = json.loads((tmp_path / "metrics.json").read_text())
    assert code == 1 and not m["ok"]
    ok = {c["name"]: c["ok"] for c in m["checks"]}
    assert ok["final_error"] is False and ok["monotone_error"] is False and ok["wrong_sign_diverges"] is True


@pytest.mark.parametrize("argv, message", [
    (["run", "no.such"], "unknown scenario"),
    (["run", "core.minjerk", "--set", "nope=1"], "unknown key"),
    (["run", "core.minjerk", "--set", "dt=9"], "dt=9: expected a number in"),
    (["run", "core.minjerk", "--set", "dt=nan"], "expected a number"),
    (["run", "core.minjerk", "--set", "dt"], "KEY=VALUE"),
    (["run", "core.minjerk", "--video"], "no MuJoCo body"),
    (["run", "core.minjerk", "--seed", "-1"], "non-negative"),
    (["reproduce", "--only", "zzz.*"], "matches nothing"),
])
def test_bad_input_is_one_line_and_exit_2(argv, message, capsys, tmp_path):
    assert main(argv + ["--out", str(tmp_path)] if argv[0] == "run" else argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0] and "Traceback" not in err[0]


def test_usage_error_from_the_shell_is_one_line():
    proc = subprocess.run([sys.executable, "-m", "shintai", "run"], capture_output=True, text=True)
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1


def test_a_failing_run_keeps_what_it_computed(tmp_path):
    def run(ctx):
        ctx.recorder.record(0.0, x=1.0)
        ctx.recorder.record(0.1, x=2.0)
        raise FloatingPointError("state became NaN at t=0.1")

    registry.SCENARIOS["test.diverges"] = registry.Scenario("test.diverges", "test", "diverges", run,
                                                            checks=(Check("x", "<", 1, "test"),))
    try:
        result = run_scenario("test.diverges", tmp_path, quiet=True)
    finally:
        del registry.SCENARIOS["test.diverges"]
    assert result["error"] == "FloatingPointError: state became NaN at t=0.1" and not result["ok"]
    assert np.load(tmp_path / "log.npz")["x"].tolist() == [1.0, 2.0]
    assert json.loads((tmp_path / "metrics.json").read_text())["error"].startswith("FloatingPointError")


def test_param_parsing():
    p = Param("n", 3, lo=1, hi=5)
    assert p.parse("4") == 4
    with pytest.raises(ParameterError):
        p.parse("4.5")
    assert Param("on", True).parse("false") is False
    assert Param("plant", "kinematic", choices=("kinematic", "mujoco")).parse("mujoco") == "mujoco"
    with pytest.raises(ParameterError, match="one of kinematic|mujoco"):
        Param("plant", "kinematic", choices=("kinematic", "mujoco")).parse("pybullet")


def test_check_against_another_metric():
    c = Check("a", "<=", "b", "ordering")
    assert c.evaluate({"a": 1.0, "b": 2.0})["ok"] and not c.evaluate({"a": 3.0, "b": 2.0})["ok"]
    assert not Check("a", "<=", 1.0, "x").evaluate({"a": float("nan")})["ok"]
    assert not Check("missing", "<=", 1.0, "x").evaluate({})["ok"]


@pytest.mark.parametrize("executor", ["serial", "process", "ray"])
def test_reproduce_writes_report_and_index(tmp_path, executor):
    assert main(["reproduce", "--only", "core.*", "--out", str(tmp_path), "--executor", executor]) == 0
    report = (tmp_path / "REPORT.md").read_text()
    assert "core.minjerk" in report and "core.search-index" in report and "2 of 2" in report
    assert '<table id="scenarios">' in (tmp_path / "index.html").read_text()
    assert (tmp_path / "core.minjerk" / "metrics.json").exists()


def test_report_lists_unfinished_scenarios(tmp_path):
    from shintai.scenarios.report import write_report

    run_scenario("core.minjerk", tmp_path / "core.minjerk", quiet=True)
    results = write_report(tmp_path, ["core.minjerk", "core.search-index"])
    assert results[0]["ok"] and "not run" in results[1]["error"]
    assert "1 of 2" in (tmp_path / "REPORT.md").read_text()


def test_report_carries_each_scenarios_account(tmp_path):
    """The explanation of what reproduces and what does not (the scenario's notes/<name>.md) travels
    with its metrics.json into REPORT.md and index.html."""
    from shintai.scenarios.registry import get
    from shintai.scenarios.report import write_report

    result = run_scenario("core.minjerk", tmp_path / "core.minjerk", quiet=True)
    notes = get("core.minjerk").notes_path.read_text().strip()
    assert result["notes"] == notes and notes
    write_report(tmp_path, ["core.minjerk"])
    assert "### core.minjerk (pass)" in (tmp_path / "REPORT.md").read_text()
    assert notes.splitlines()[0] in (tmp_path / "REPORT.md").read_text()
    from shintai.scenarios.markdown import to_html

    page = (tmp_path / "index.html").read_text()
    assert 'id="notes-core.minjerk"' in page and to_html(notes) in page  # rendered as HTML


def test_run_profile_writes_where_the_time_went(tmp_path, capsys):
    assert main(["run", "core.minjerk", "--out", str(tmp_path), "--quiet", "--profile"]) == 0
    profile = json.loads((tmp_path / "profile.json").read_text())
    assert profile["samples"] > 0 and sum(profile["layers"].values()) == pytest.approx(1.0, abs=0.01)
    assert profile["layers"]["plotting"] > 0  # its figure, drawn after the run
    assert "profile: " in capsys.readouterr().out
    assert "profile" not in json.loads((tmp_path / "metrics.json").read_text())  # the contract's file unchanged


def test_bench_writes_json(tmp_path):
    assert main(["bench", "--only", "core.loop-overhead", "--out", str(tmp_path)]) == 0
    bench = json.loads((tmp_path / "bench.json").read_text())
    assert bench["core.loop-overhead"]["ratio_loop_vs_direct"] > 0
    profile = bench["core.loop-overhead"]["profile"]  # where its CPU time went, by layer
    assert profile["samples"] > 0 and profile["layers"]["runtime"] > 0


def test_demo_videos_only_where_default_parameters_render():
    registry.load_all()
    for sc in registry.SCENARIOS.values():
        if sc.demo and sc.demo_video and sc.video:
            params = sc.resolve(sc.demo_params)  # the parameters the demo runs it with
            assert params.get("plant", "mujoco") == "mujoco", f"{sc.id}: the demo would ask a non-MuJoCo plant for video"


class Stream:
    def __init__(self, tty):
        self.tty, self.text = tty, ""

    def isatty(self):
        return self.tty

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def test_progress_is_a_bar_on_a_terminal_lines_in_a_log_and_nothing_when_quiet():
    from shintai.scenarios.runner import Progress

    tty, log, quiet = Stream(True), Stream(False), Stream(False)
    for out, q in ((tty, False), (log, False), (quiet, True)):
        p = Progress("train", stream=out, quiet=q)
        for k in range(101):
            p(k / 100, "gen")
    assert "\r" in tty.text and "[############------------]  50%" in tty.text and tty.text.endswith("\n")
    lines = log.text.splitlines()
    assert "\r" not in log.text and len(lines) == 11 and lines[5].startswith("train:  50.0%")
    assert quiet.text == ""


def test_reproduce_quiet_prints_no_progress(tmp_path, capsys):
    assert main(["reproduce", "--only", "core.minjerk", "--out", str(tmp_path), "--executor", "serial", "--quiet"]) == 0
    captured = capsys.readouterr()
    assert "reproduce" not in captured.err and "1/1 pass" in captured.out
