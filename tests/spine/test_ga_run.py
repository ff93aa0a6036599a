"""The shared seed-003 GA run: checkpoints, resume, record and picture (spine/ga_run.py)."""

from types import SimpleNamespace

import numpy as np

from shintai.evolve import stalled
from shintai.scenarios.runner import RunContext
from shintai.spine import ga_run


def _peak(genome: np.ndarray) -> float:
    return -float(np.sum((genome - 0.3) ** 2))


def _ctx(tmp_path, **params):
    p = {"generations": 6, "population": 10, "executor": "serial", "workers": 0, "address": "", "resume": True}
    p.update(params)
    tmp_path.mkdir(parents=True, exist_ok=True)
    return RunContext(SimpleNamespace(id="test.ga", source="test"), p, 3, tmp_path, quiet=True)


def test_evolve_records_checkpoints_and_draws(tmp_path):
    ctx = _ctx(tmp_path)
    result = _evolve(ctx, "peak", _peak, [-1, -1], [1, 1])
    assert len(result.history) == 6
    assert result.history.best_so_far[-1] >= result.history.best_so_far[0]
    assert (tmp_path / "peak.ga.npz").exists() and (tmp_path / "peak_curve.png").exists()
    assert list(ctx.extra["ga_curves"]["peak"]["best"]) == list(result.history.best)


def test_evolve_resume_extends_to_the_uninterrupted_result(tmp_path):
    whole = _evolve(_ctx(tmp_path / "a"), "peak", _peak, [-1, -1], [1, 1])
    _evolve(_ctx(tmp_path / "b", generations=3), "peak", _peak, [-1, -1], [1, 1])
    resumed = _evolve(_ctx(tmp_path / "b"), "peak", _peak, [-1, -1], [1, 1])
    np.testing.assert_array_equal(whole.history.best, resumed.history.best)
    np.testing.assert_array_equal(whole.best_genome, resumed.best_genome)


def test_generations_to_converge():
    assert ga_run.generations_to_converge(np.array([1.0, 5.0, 9.6, 10.0])) == 2
    assert ga_run.generations_to_converge(np.array([1.0, 1.0])) == 0


def _evolve(ctx, *args, **kw):
    """ga_run.evolve with the GA's parameters of ``ctx`` as named arguments (as the experiments pass them)."""
    return ga_run.evolve(ctx, *args, ga=ga_run.GARun(**{k: ctx.params[k] for k in ga_run.GA_KEYS}), **kw)


def test_a_declared_stopping_rule_ends_the_run_before_its_cap(tmp_path):
    """ga_params(stop=True): the run stops once the best improved < stop_tolerance over stop_window generations."""
    ctx = _ctx(tmp_path, generations=200, stop_window=3, stop_tolerance=0.5)
    ga = ga_run.ga_of(ctx.params)
    result = ga_run.evolve(ctx, "peak", _peak, [-1, -1], [1, 1], ga=ga)
    best = result.history.best_so_far
    assert 3 < len(best) < 200 and ga_run.budget_metrics(result, ga) == {"generations": len(best), "stopped_by_rule": 1}
    assert not stalled(best[:-1], 3, 0.5, minimize=False)  # it stopped at the first generation the rule held
    capped = ga_run.GARun(generations=5, population=10, executor="serial")
    assert ga_run.budget_metrics(ga_run.evolve(_ctx(tmp_path / "c"), "peak", _peak, [-1, -1], [1, 1], ga=capped),
                                 capped) == {"generations": 5, "stopped_by_rule": 0}


def test_ga_params_declare_the_rule_only_when_asked():
    names = {p.name for p in ga_run.ga_params(10, 20, stop=True)} - {p.name for p in ga_run.ga_params(10, 20)}
    assert names == set(ga_run.STOP_KEYS)
