"""The registry test for the humanoid's V-BOARD (seed 000 ch. 5–6, §7.4.2) experiments:
each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = ('humanoid.integrator-comparison', 'humanoid.solc', 'humanoid.speed-governing', 'humanoid.vboard-boarding', 'humanoid.vboard-levels', 'humanoid.vboard-plant-id', 'humanoid.vboard-posture',)


test_runs_at_its_smoke_size = registry_test(RUNS)
