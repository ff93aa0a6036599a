"""The registry test for the humanoid's Ninebot (seed 000 §7.3.3) experiments:
each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = ('humanoid.unicycle-free', 'humanoid.unicycle-learning', 'humanoid.unicycle-no-learning',)


test_runs_at_its_smoke_size = registry_test(RUNS)
