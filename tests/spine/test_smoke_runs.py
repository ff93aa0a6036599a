"""The registry test for the spine experiments outside Cla's folder (Kenta, SQ43, Hanzous, BeBe, the rabbit, mocap
and the shared layers): each runs at its declared smoke sizes (tests/smoke.py); Cla's are in cla/ (two files, so
``--dist loadfile`` spreads the spine's runs over two workers)."""

from smoke import registry_test

RUNS = (
    "spine.bebe-tracking",
    "spine.bvh-retarget",
    "spine.hanzous-brachiation",
    "spine.hanzous-ga",
    "spine.inverse-model",
    "spine.kenta-spine-neck-arms",
    "spine.kenta-taught-postures",
    "spine.rabbit-stiffening",
    "spine.rabbit-yaw-turn",
    "spine.sq43-crawl",
    "spine.sq43-design",
    "spine.sq43-levelling",
    "spine.sq43-standup",
    "spine.sq43-trot-ga",
    "spine.sq43-uneven",
    "spine.tension-sensor",
    "spine.tracking-loops",
)


test_runs_at_its_smoke_size = registry_test(RUNS)
