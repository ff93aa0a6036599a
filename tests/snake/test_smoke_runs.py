"""The registry test for snake's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = (
    "snake.caging",
    "snake.door",
    "snake.handcart",
    "snake.switching-ablation",
    "snake.tracking",
    "snake.two-plane-pitch",
    "snake.two-plane-roll",
)


test_runs_at_its_smoke_size = registry_test(RUNS)
