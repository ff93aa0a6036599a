"""The registry test for the humanoid's tricycle (seed 000 ch. 3–4, §7.3.2, §7.4.1; Kenshiro's pedalling) experiments:
each runs at its declared smoke sizes (tests/smoke.py)."""

import pytest
from smoke import check_contract

RUNS = ('humanoid.kenshiro-pedaling', 'humanoid.obstacle-navigation', 'humanoid.odometry', 'humanoid.outdoor-run', 'humanoid.posture-steps', 'humanoid.sitting-recovery', 'humanoid.small-obstacle', 'humanoid.tricycle-pedaling', 'humanoid.tricycle-slalom', 'humanoid.tricycle-steering',)


@pytest.mark.parametrize("scenario_id", RUNS)
def test_runs_at_its_smoke_size(scenario_id, smoke):
    check_contract(scenario_id, smoke(scenario_id))
