"""The smoke runs of the SQ43 whole-body scenarios (levelling, crawl, GA trot)."""


def test_levelling_short(smoke):
    run = smoke("spine.sq43-levelling")
    m = run.result["metrics"]
    assert m["settled_roll_up_without_deg"] > 2.0 and m["abs_settled_roll_up_with_deg"] < 1.0
    assert (run.out / "levelling_roll.png").exists()


def test_crawl_short(smoke):
    m = smoke("spine.sq43-crawl").result["metrics"]
    assert m["lift_clearance_shifted_mm"] > m["lift_clearance_standing_mm"]
    assert m["lift_clearance_standing_rigid_mm"] > m["lift_clearance_standing_mm"]
    assert m["crawl_forward_mm"] > 0


def test_trot_ga_short(smoke):
    run = smoke("spine.sq43-trot-ga")
    m = run.result["metrics"]
    assert m["generations"] == run.result["params"]["generations"] == 2 and m["seconds_per_individual"] < 1.0
    assert (run.out / "trot_curve.png").exists() and (run.out / "trot.ga.npz").exists()
    assert m["replay_fitness"] == m["best_fitness"]
