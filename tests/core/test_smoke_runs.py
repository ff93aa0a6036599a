"""The registry test for core's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = ('core.minjerk', 'core.search-index',)


test_runs_at_its_smoke_size = registry_test(RUNS)
