"""The registry test for nervous's experiments: each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = ('nervous.cla-teach', 'nervous.clients', 'nervous.fig-c1',)


test_runs_at_its_smoke_size = registry_test(RUNS)
