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
