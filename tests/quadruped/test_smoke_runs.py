"""The registry test for quadruped's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

import pytest
from smoke import check_contract

RUNS = (
    "quadruped.avoid-known",
    "quadruped.avoid-s52",
    "quadruped.avoid-unseen",
    "quadruped.free-gait",
    "quadruped.generalization",
    "quadruped.real-robot-standin",
    "quadruped.replay",
    "quadruped.sensing-ablation",
    "quadruped.swing-order",
    "quadruped.train",
)


@pytest.mark.parametrize("scenario_id", RUNS)
def test_runs_at_its_smoke_size(scenario_id, smoke):
    check_contract(scenario_id, smoke(scenario_id))
