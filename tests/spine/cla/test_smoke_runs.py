"""The registry test for Cla's experiments (spine/cla): each runs at its declared smoke sizes (tests/smoke.py)."""

import pytest
from smoke import check_contract

RUNS = (
    "spine.cla-cop-balance",
    "spine.cla-crawl-ga",
    "spine.cla-levelling",
    "spine.cla-pick-place",
    "spine.cla-pull",
    "spine.cla-roll-over",
    "spine.cla-throw",
    "spine.control-modes",
    "spine.posture-database",
    "spine.software-spring",
    "spine.teach-playback",
)


@pytest.mark.parametrize("scenario_id", RUNS)
def test_runs_at_its_smoke_size(scenario_id, smoke):
    check_contract(scenario_id, smoke(scenario_id))
