"""The registry test for the humanoid's Ninebot (seed 000 §7.3.3) experiments:
each runs at its declared smoke sizes (tests/smoke.py)."""

import pytest
from smoke import check_contract

RUNS = ('humanoid.unicycle-free', 'humanoid.unicycle-learning', 'humanoid.unicycle-no-learning',)


@pytest.mark.parametrize("scenario_id", RUNS)
def test_runs_at_its_smoke_size(scenario_id, smoke):
    check_contract(scenario_id, smoke(scenario_id))
