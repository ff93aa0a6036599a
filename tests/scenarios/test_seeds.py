"""The runner hands every rig its seed (DESIGN.md: ``rig(params, variant, seed)``), and every random source of a
run derives from it (issue 25: ``--seed`` was silently ignored by nine humanoid experiments, whose rigs read a
``params["seed"]`` that was never set)."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import shintai

from shintai.scenarios import registry
from shintai.scenarios.registry import experiment
from shintai.scenarios.experiment import Rig
from shintai.scenarios.runner import run_scenario
from shintai.core.benchmarks import NullBody
from shintai.core.runtime import FunctionModule


SRC = Path(shintai.__path__[0])
FILES = sorted(SRC.rglob("*.py"))

# The declared experiments whose rigs draw random numbers (sensor noise, particles, mocap noise); each is built
# at its defaults (caging with its mocap noise on) and must seed every generator it makes from the run's seed.
TABLE_PLANT = {"plant": "table6.2"}
SEEDED_RIGS = {
    "humanoid.vboard-levels": {}, "humanoid.vboard-plant-id": {}, "humanoid.vboard-posture": {},
    # Table 6.2's plant: the default ("board") first runs the plant identification, a seed-0 run of its own
    "humanoid.speed-governing": TABLE_PLANT, "humanoid.integrator-comparison": {**TABLE_PLANT, "start": "lift"}, "humanoid.solc": TABLE_PLANT,
    "humanoid.unicycle-learning": {}, "humanoid.unicycle-free": {}, "humanoid.unicycle-no-learning": {},
    "humanoid.odometry": {}, "snake.caging": {"mocap_noise_m": "0.001"},
}


@pytest.fixture
def generators(monkeypatch):
    """Record the seed of every ``np.random.default_rng`` a rig creates."""
    seen: list = []
    make = np.random.default_rng

    def recording(seed=None):
        seen.append(seed)
        return make(seed)

    monkeypatch.setattr(np.random, "default_rng", recording)
    return seen


@pytest.mark.parametrize("scenario_id", sorted(SEEDED_RIGS))
def test_every_generator_of_a_rig_derives_from_the_run_seed(scenario_id, generators):
    sc = registry.get(scenario_id)
    params = sc.resolve(SEEDED_RIGS[scenario_id])
    variant = sc.variants(params)[0]
    drawn = {}
    sc.rig(params, variant, 4)  # once before: what a rig caches per process (an identified plant) is not the run's
    for seed in (5, 6):
        generators.clear()
        sc.rig(params, variant, seed)
        drawn[seed] = [int(s) if s is not None else None for s in generators]
    assert drawn[5], f"{scenario_id}: its rig made no random generator (remove it from SEEDED_RIGS?)"
    assert None not in drawn[5], f"{scenario_id}: an unseeded generator"
    assert len(drawn[5]) == len(drawn[6]) and all(a != b for a, b in zip(drawn[5], drawn[6])), \
        f"{scenario_id}: generators did not follow the run's seed: {drawn}"


def test_two_seeds_give_different_logs_and_one_seed_the_same_log_twice(tmp_path):
    """End to end through ``shintai run``: the caging run's mocap noise (a MuJoCo run of 0.05 s)."""
    sets = {"duration_s": "0.05", "mocap_noise_m": "0.002"}
    logs = {}
    for name, seed in (("a", 0), ("b", 0), ("c", 5)):
        run_scenario("snake.caging", tmp_path / name, dict(sets), seed=seed, quiet=True)
        with np.load(tmp_path / name / "log.npz") as z:
            logs[name] = {k: z[k] for k in z.files}
    same = lambda x, y: x.keys() == y.keys() and all(np.array_equal(x[k], y[k]) for k in x)  # noqa: E731
    assert same(logs["a"], logs["b"])
    assert not same(logs["a"], logs["c"])


def test_the_runner_passes_its_seed_to_the_rig(tmp_path):
    seen = []

    def rig(params, variant, seed):
        seen.append(seed)
        return Rig(NullBody(dt=0.01), [FunctionModule(lambda s: None, name="idle")], duration=0.02)

    experiment("test.seeded", "nowhere", "a toy", rig=rig, metrics=lambda runs, params: {})
    try:
        run_scenario("test.seeded", tmp_path, seed=7, quiet=True)
    finally:
        registry.SCENARIOS.pop("test.seeded")
    assert seen == [7]


def test_no_library_reads_a_seed_from_the_parameters():
    """A seed comes from the runner, never from the experiment's parameter dict."""
    offenders = []
    for path in FILES:
        for node in ast.walk(ast.parse(path.read_text())):
            key = None
            if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant):
                key = node.slice.value
            elif isinstance(node, ast.Call) and getattr(node.func, "attr", None) == "get" and node.args \
                    and isinstance(node.args[0], ast.Constant):
                key = node.args[0].value
            if key == "seed" and "params" in ast.unparse(node):
                offenders.append(f"{path.relative_to(SRC)}:{node.lineno}")
    assert not offenders, offenders
