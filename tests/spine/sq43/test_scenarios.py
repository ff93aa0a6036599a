"""Short runs of the SQ43 whole-body scenarios (levelling, crawl, GA trot)."""

from shintai.scenarios.runner import run_scenario


def test_levelling_short(tmp_path):
    result = run_scenario("spine.sq43-levelling", out=tmp_path, quiet=True, overrides={"rise_mm": "15"})
    m = result["metrics"]
    assert m["settled_roll_up_without_deg"] > 2.0 and m["abs_settled_roll_up_with_deg"] < 1.0
    assert (tmp_path / "levelling_roll.png").exists()


def test_crawl_short(tmp_path):
    result = run_scenario("spine.sq43-crawl", out=tmp_path, quiet=True, overrides={"cycles": "1"})
    m = result["metrics"]
    assert m["lift_clearance_shifted_mm"] > m["lift_clearance_standing_mm"]
    assert m["lift_clearance_standing_rigid_mm"] > m["lift_clearance_standing_mm"]
    assert m["crawl_forward_mm"] > 0


def test_trot_ga_short(tmp_path):
    result = run_scenario("spine.sq43-trot-ga", out=tmp_path, quiet=True, overrides={
        "generations": "2", "population": "4", "executor": "serial", "duration_s": "1.5"})
    m = result["metrics"]
    assert m["generations"] == 2 and m["seconds_per_individual"] < 1.0
    assert (tmp_path / "trot_curve.png").exists() and (tmp_path / "trot.ga.npz").exists()
    assert m["replay_fitness"] == m["best_fitness"]
