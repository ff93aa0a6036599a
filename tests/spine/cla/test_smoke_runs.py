"""The registry test for Cla's experiments (spine/cla): each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = (
    "spine.cla-cop-balance",
    "spine.cla-crawl-ga",
    "spine.cla-levelling",
    "spine.cla-pick-place",
    "spine.cla-poses",
    "spine.cla-pull",
    "spine.cla-roll-over",
    "spine.cla-roll-over-ga",
    "spine.cla-rpy",
    "spine.cla-throw",
    "spine.control-modes",
    "spine.posture-database",
    "spine.software-spring",
    "spine.teach-playback",
)


test_runs_at_its_smoke_size = registry_test(RUNS)
