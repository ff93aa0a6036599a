"""Declared experiments: the runner builds each variant's rig, runs its Loop to the stop rule, records
every n steps into the variant's log, names variant metrics with the unit last, and checks parameters once."""

import numpy as np
import pytest

from shintai.core.benchmarks import NullBody
from shintai.core.runtime import Channel, FunctionModule
from shintai.scenarios import registry
from shintai.scenarios.experiment import Rig, per_variant, unit_of, variant_metric
from shintai.scenarios.registry import Check, Param, ParameterError, experiment
from shintai.scenarios.runner import run_scenario


def test_variant_names_go_before_the_unit():
    assert variant_metric("max_roll_deg", "with") == "max_roll_with_deg"
    assert variant_metric("speed_mps", "fixed") == "speed_fixed_mps"  # not read as _s
    assert variant_metric("distinct_modes", "fixed") == "distinct_modes_fixed"
    assert unit_of("final_pos_error_m") == "_m" and unit_of("count") == ""
    assert per_variant({"with": {"a_m": 1}, "without": {"a_m": 2}}) == {"a_with_m": 1, "a_without_m": 2}


def rig(params, variant, seed):
    """A NullBody driven by a set-point stage feeding a controller stage (the gain differs per variant)."""
    body = NullBody(dt=0.01)
    gain = params["gain"] if variant == "with" else 0.0
    target = FunctionModule(lambda s: {"target": 1.0}, name="target")
    control = FunctionModule(lambda s: {"u": gain * float(s["target"])}, name="control")
    return Rig(body, stages=[[target], [control]], channels=[Channel("target", "set")], duration=params["t"],
               until=lambda s: s["t"] >= params["stop_at"], record={2: lambda s: {"seen": s["target"]}},
               state={"body": body})


def metrics(runs, params):
    return per_variant({v: {"last_u": float(r.loop.command["u"]), "steps": r.steps, "samples": len(r.log.times("seen"))}
                        for v, r in runs.items()})


@pytest.fixture
def toy():
    sc = experiment("test.toy", "nowhere", "a toy", rig=rig, metrics=metrics, variants=("with", "without"),
                    params=[Param("gain", 2.0, lo=0.0, hi=10.0), Param("t", 0.1, lo=0.01, hi=1.0),
                            Param("stop_at", 1.0, lo=0.0, hi=2.0)],
                    checks=[Check("last_u_with", ">", "last_u_without", "consistency: the gain acts")],
                    constraints=[(lambda p: p["stop_at"] != 0.5, "stop_at may not be 0.5")])
    yield sc
    registry.SCENARIOS.pop("test.toy")


def test_the_runner_runs_every_variant_to_its_stop_rule(toy, tmp_path):
    result = run_scenario("test.toy", tmp_path, quiet=True)
    assert result["ok"] and "error" not in result
    m = result["metrics"]
    assert m["last_u_with"] == 2.0 and m["last_u_without"] == 0.0
    assert m["steps_with"] == 10 and m["samples_with"] == 5  # every 2nd of 10 steps
    assert result["sim_time_s"] == pytest.approx(0.2)  # both variants
    log = np.load(tmp_path / "log.npz")
    assert {"with.seen", "without.seen", "with.seen_t"} <= set(log.files)
    stopped = run_scenario("test.toy", tmp_path, {"stop_at": "0.045"}, quiet=True)
    assert stopped["metrics"]["steps_with"] == 6  # the 6th step saw t = 0.05, the first ≥ 0.045


def test_parameters_are_checked_once_before_anything_runs(toy, tmp_path):
    with pytest.raises(ParameterError, match="test.toy: stop_at may not be 0.5"):
        run_scenario("test.toy", tmp_path, {"stop_at": "0.5"}, quiet=True)
    with pytest.raises(ParameterError, match="--set gain=-1"):
        run_scenario("test.toy", tmp_path, {"gain": "-1"}, quiet=True)
    with pytest.raises(ParameterError, match="--video: test.toy has nothing to film"):
        run_scenario("test.toy", tmp_path, video=True, quiet=True)
    assert not (tmp_path / "metrics.json").exists()


def test_a_declaration_needs_a_rig_with_metrics_or_a_compute():
    with pytest.raises(ValueError, match="not both"):
        experiment("test.bad", "x", "x", rig=rig, metrics=metrics, compute=lambda ctx: {})
    with pytest.raises(ValueError, match="needs metrics"):
        experiment("test.bad", "x", "x", rig=rig)
    assert "test.bad" not in registry.SCENARIOS


def test_every_scenario_has_its_notes_file():
    registry.load_all()
    missing = [sid for sid, sc in registry.SCENARIOS.items()
               if sid.split(".")[0] in ("core", "sim") and not (sc.notes_path and sc.notes_path.is_file())]
    assert not missing
