"""The registry test for quadruped's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

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


test_runs_at_its_smoke_size = registry_test(RUNS)
