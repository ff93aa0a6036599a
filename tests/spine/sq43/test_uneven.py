"""SQ43's crawl over uneven ground with the accelerometer levelling (spine/sq43/uneven.py, seed 003 §3.2.4, Fig. 3.8)."""

from dataclasses import replace

from shintai.scenarios.experiment import run_rig
from shintai.spine.sq43.body import BODY
from shintai.spine.sq43.gaits import CrawlPlan
from shintai.spine.sq43.levelling import Levelling
from shintai.spine.sq43.uneven import Ground, uneven_result, uneven_rig


def crawl(levelling, spec=BODY, cycles=2):
    run = run_rig(uneven_rig(Ground(), CrawlPlan(), cycles, levelling, 5.0, spec))
    return uneven_result(run.log, run.state)


def test_levelling_bends_the_left_front_leg_onto_the_block_with_four_feet_down():
    r = crawl(Levelling())
    assert r["lf_shortest_mm"] < -0.5 * Ground.height_mm  # stepped up in cycle 2: the leg shortened
    assert r["min_feet_in_contact"] == 4 and r["timeouts"] == 0
    assert r["max_shoulder_roll_after_deg"] <= 1.0


def test_a_trunk_rigid_in_torsion_lifts_a_foot_at_the_step_but_the_foam_spine_does_not():
    assert crawl(None, replace(BODY, twist_free=False))["step_up_feet_in_contact"] < 4
    assert crawl(None)["step_up_feet_in_contact"] == 4


def test_no_block_no_geometry():
    assert replace(Ground(), height_mm=0.0).blocks() == ()
    (x0, x1, y0, y1, h), = Ground().blocks()
    assert x1 - x0 > 0.05 and y0 > 0 and abs(h - 0.015) < 1e-12  # under the left feet only
