"""Cla crawling on hands and knees (spine/cla_crawl.py) and ``spine.cla-crawl-ga`` (seed 003 §5.2.9)."""

import math

import mujoco
import numpy as np
import pytest

from shintai.scenarios.registry import ParameterError, get
from shintai.spine.cla import crawl as CC
from shintai.spine.robots import CLA_LIMIT_RAD, CRAWL_PHASE_S


def test_the_lock_keeps_the_rigid_spine_straight():
    """Locked, the spine stays at 0 even with the hand-made roll commanded; free, the same command rolls it."""
    locked = CC.evaluate(CC.HAND_MADE, lock_spine=True, duration=3.0)
    free = CC.evaluate(CC.HAND_MADE, lock_spine=False, duration=3.0)
    assert locked["max_spine_deg"][0] < 0.5
    assert locked["spine_torque_integral_nms"][0] == 0.0  # a rigid trunk has no spine servos
    assert free["max_roll_deg"][0] > 4.0


def test_genes_give_the_spine_roll_amounts_and_timings():
    genes = np.array([0.0, 1.0, 0.75, 0.5, 0.0, 1.0, 0.5, 0.25])
    roll, dur = CC.decode(genes)
    np.testing.assert_allclose(roll, [-CLA_LIMIT_RAD, CLA_LIMIT_RAD, 0.5 * CLA_LIMIT_RAD, 0.0])
    lo, hi = CRAWL_PHASE_S
    np.testing.assert_allclose(dur, [lo, hi, lo + 0.5 * (hi - lo), lo + 0.25 * (hi - lo)])
    np.testing.assert_allclose(CC.encode(np.degrees(roll), dur), genes)
    ends = np.cumsum(dur)
    starts = ends - dur
    # the roll reaches each phase's amount at the phase's end, starting from straight in the first cycle
    s = CC.schedule(genes, np.concatenate([[0.0], ends - 1e-9, ends[-1] + starts + 1e-9]))
    assert s["roll"][0] == 0.0
    np.testing.assert_allclose(s["roll"][1:5], roll, atol=1e-6)
    np.testing.assert_array_equal(s["phase"][5:], [0, 1, 2, 3])  # the second cycle's phases begin on time
    np.testing.assert_allclose(s["roll"][6:], roll[:3], atol=1e-6)  # … from the previous phase's roll
    # the servo table carries the same roll on all five roll joints
    u = CC.controls(genes, duration=ends[-1])
    t = np.arange(len(u)) * CC.CRAWL_TIMESTEP_S
    for i in range(5):
        np.testing.assert_allclose(u[:, CC.ACTUATED.index(f"j{i + 1}_roll")], CC.schedule(genes, t)["roll"])
    assert not np.any(u[:, [CC.ACTUATED.index(f"j{i + 1}_pitch") for i in range(5)]])


def test_limbs_are_time_scaled_to_the_spine():
    """Each phase swings one limb (right arm, left knee, left arm, right knee); a phase twice as long plays
    the same limb motion at half speed."""
    fast, slow = CC.encode([0, 0, 0, 0], [0.4] * 4), CC.encode([0, 0, 0, 0], [0.8] * 4)
    for k, limb in enumerate(CC.LIMBS):
        mid_fast = CC.schedule(fast, np.array([0.4 * k + 0.2]))
        mid_slow = CC.schedule(slow, np.array([0.8 * k + 0.4]))
        assert mid_fast[f"lift_{limb}"][0] == pytest.approx(1.0)
        assert all(mid_fast[f"lift_{other}"][0] == 0 for other in CC.LIMBS if other != limb)
        for other in CC.LIMBS:
            assert mid_fast[f"c_{other}"][0] == pytest.approx(mid_slow[f"c_{other}"][0])
    # over a cycle every limb's stroke returns to where it began (back −1 → front +1 → back −1)
    s = CC.schedule(fast, np.array([0.0, 1.6 - 1e-9]))
    for limb in CC.LIMBS:
        assert s[f"c_{limb}"][0] == pytest.approx(s[f"c_{limb}"][1], abs=1e-6)


def test_kneels_on_hands_and_knees_at_rest():
    """Held at the start posture for 3 s the body rests on its palms and knees: the trunk stays up and put."""
    m = CC.model()
    d = mujoco.MjData(m)
    mujoco.mj_setState(m, d, CC.settled_state(), mujoco.mjtState.mjSTATE_FULLPHYSICS)
    d.ctrl[:] = CC.start_posture()
    mujoco.mj_forward(m, d)
    start = d.site("pelvis").xpos.copy()
    mujoco.mj_step(m, d, int(3.0 / m.opt.timestep))
    assert np.linalg.norm(d.site("pelvis").xpos - start) < 0.005
    assert d.site("pelvis").xpos[2] > 0.15 and d.site("clavicle").xpos[2] > 0.15
    floor = m.geom("floor").id
    touching = {mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, c.geom1 if c.geom2 == floor else c.geom2)
                for c in d.contact[:d.ncon]}
    assert {"palm_r", "palm_l", "knee_r", "knee_l"} <= touching
    assert not touching & {"head", "clavicle"}
    assert abs(math.degrees(CC.BETA)) < 30  # the trunk nearly level, head a little up


def test_crawl_moves_forward_and_batches_agree():
    """The hand-made crawl goes forward; a batch rollout gives each crawl's own result."""
    one = CC.evaluate(CC.HAND_MADE, duration=3.0)
    both = CC.evaluate(np.stack([CC.RIGID, CC.HAND_MADE]), duration=3.0)
    assert one["distance_m"][0] > 0.05
    assert both["distance_m"][1] == pytest.approx(one["distance_m"][0])
    assert CC.CrawlFitness(3.0)(CC.HAND_MADE[None])[0] == pytest.approx(one["fitness"][0])


def test_scenario_short_run(smoke):
    run = smoke("spine.cla-crawl-ga")
    result = run.result
    assert "error" not in result
    m = result["metrics"]
    for v in ("rigid", "hand_made", "evolved"):
        for key in ("distance_m", "torque_integral_nms", "peak_torque_nm", "heading_drift_deg", "fitness"):
            assert math.isfinite(m[f"{v}.{key}"])
    assert m["rigid.max_spine_deg"] < 0.5 and m["rigid.spine_torque_integral_nms"] == 0
    assert m["generations"] == result["params"]["generations"] and m["crawl_improvement"] >= 0  # elitism
    assert m["evolved.fitness"] == pytest.approx(m["crawl_best_fitness"])  # the replay is the GA's evaluation
    for name in ("crawl_curve", "crawl_comparison", "crawl_paths"):
        assert (run.out / f"{name}.png").exists()
    with pytest.raises(ParameterError, match="eval_s"):
        get("spine.cla-crawl-ga").resolve({"eval_s": "0"})
