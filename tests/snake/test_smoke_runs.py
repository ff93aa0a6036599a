"""The registry test for snake's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

import pytest
from smoke import check_contract

RUNS = (
    "snake.caging",
    "snake.door",
    "snake.handcart",
    "snake.switching-ablation",
    "snake.tracking",
    "snake.two-plane-pitch",
    "snake.two-plane-roll",
)


@pytest.mark.parametrize("scenario_id", RUNS)
def test_runs_at_its_smoke_size(scenario_id, smoke):
    check_contract(scenario_id, smoke(scenario_id))
