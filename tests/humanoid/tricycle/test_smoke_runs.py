"""The registry test for the humanoid's tricycle (seed 000 ch. 3–4, §7.3.2, §7.4.1; Kenshiro's pedalling) experiments:
each runs at its declared smoke sizes (tests/smoke.py)."""

from smoke import registry_test

RUNS = ('humanoid.kenshiro-pedaling', 'humanoid.obstacle-navigation', 'humanoid.odometry', 'humanoid.outdoor-run', 'humanoid.posture-steps', 'humanoid.sitting-recovery', 'humanoid.small-obstacle', 'humanoid.tricycle-pedaling', 'humanoid.tricycle-slalom', 'humanoid.tricycle-steering',)


test_runs_at_its_smoke_size = registry_test(RUNS)
