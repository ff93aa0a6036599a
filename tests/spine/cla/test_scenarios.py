"""The smoke runs of the whole-body Cla behaviours (levelling, throw) and the pull's plan (seed 003 §5.2.2–5.2.4)."""

import numpy as np

from shintai.spine.cla.body import ClaBody
from shintai.spine.cla.pull import TIMELINE, PullPattern, arm_keyframes, hand_at, object_x, reach_at_desk


def test_levelling_short(smoke):
    run = smoke("spine.cla-levelling")  # the first tilt only (0.5–1.5 s), levelled by 2.5 s
    m = run.result["metrics"]
    assert m["adjustments"] >= 1
    assert m["settled_tilt_1_without_deg"] > 8.0 and m["settled_tilt_1_with_deg"] < 5.0
    assert (run.out / "shoulder_tilt.png").exists()


def test_throw_short(smoke):
    run = smoke("spine.cla-throw")
    m = run.result["metrics"]
    assert m["spine_yaw_travel_without_spine_deg"] < 1.0 < m["spine_yaw_travel_with_spine_deg"]
    assert m["hand_speed_with_spine_mps"] > 1.0 and m["hand_speed_without_spine_mps"] > 1.0
    assert m["spine_start_s"] < m["shoulder_start_s"] < m["elbow_start_s"]  # §5.2.3's order
    assert (run.out / "hand_speed.png").exists()


def test_pull_plan_reaches_behind_the_object_only_when_leaning():
    m = ClaBody("seated").model
    lean = np.radians(70.0)
    x = object_x(m, 0.005)
    assert reach_at_desk(m, 0.0) < x - 0.02 < reach_at_desk(m, lean)  # the near face: beyond reach, unless leaning
    keys = arm_keyframes(m, lean, x)
    behind = hand_at(m, lean, keys["down"])
    assert behind[0] > x + 0.02  # the planned hand is behind the object's far face
    upright = hand_at(m, 0.0, keys["down"])  # the same arm targets, spine straight: short of the object
    assert upright[0] < x - 0.02 or upright[2] > 0.62
    pattern = PullPattern(keys, lean, keys["fold"])
    pattern.reset({"t": 0.0})
    goals = [pattern.update({"t": t}).get("goal") for t in np.arange(0.0, TIMELINE[-1][0], 0.01)]
    leans = [g[1] for g in goals if g is not None]
    assert np.allclose(leans, [0.0, 0.0, lean, lean, 0.5 * lean, 0.0])  # fold, lift, over, down, half, pulled


def test_poses_short(smoke):
    """Figs. 3.38 and 5.1, short moves: the side bends bring the hands far lower with the spine than locked, the
    model leaves the locked arm short of every pose's target, and the lock holds."""
    run = smoke("spine.cla-poses")
    m = run.result["metrics"]
    assert m["hand_above_soles_spine_m"] < m["hand_above_soles_locked_m"] - 0.05
    assert abs(m["roll_bend_right_spine_deg"]) > 45.0 and m["max_spine_change_locked_deg"] < 1.5
    assert min(v for k, v in m.items() if k.startswith("model_gap_")) > 0.05
    assert (run.out / "poses.png").exists()


def test_rpy_short(smoke):
    """Fig. 4.42, short moves: the spine follows every axis of the combined commands (errors a fraction of the
    commanded angles), the joints near the model's uniform bend."""
    run = smoke("spine.cla-rpy")
    m = run.result["metrics"]
    assert 0.0 < m["max_axis_error_deg"] < 10.0
    assert all(m[f"joint_rms_{k}_deg"] < 4.0 for k in (1, 2, 3))
    assert (run.out / "rpy.png").exists()
