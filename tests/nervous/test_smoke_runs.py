"""The registry test for nervous's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

import pytest
from smoke import check_contract

RUNS = ('nervous.cla-teach', 'nervous.clients', 'nervous.fig-c1',)


@pytest.mark.parametrize("scenario_id", RUNS)
def test_runs_at_its_smoke_size(scenario_id, smoke):
    check_contract(scenario_id, smoke(scenario_id))
