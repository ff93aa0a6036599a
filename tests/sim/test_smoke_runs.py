"""The registry test for sim's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = ('sim.wall-force',)


test_runs_at_its_smoke_size = registry_test(RUNS)
