"""Fig. 5.13's run (seed 003 §5.2.11): Kenta's spine through its key postures by the forward model while the neck and
both arms swing — the smoke run moves all at once; with the spine not commanded the check's fraction falls to 0."""

import numpy as np
import pytest

from shintai.scenarios.experiment import run_rig
from shintai.spine.kenta.spine_neck_arms import NeckSwing, all_at_once_metrics, all_at_once_rig


def test_neck_swing_pan_and_tilt():
    neck = NeckSwing(0.4, 2.0)
    q = neck.at(0.5)
    assert q["neck_pan"] == pytest.approx(0.4) and q["neck_tilt"] == pytest.approx(0.2 * np.sin(np.pi / 1.4))


def test_smoke_run_moves_spine_neck_and_arms_at_once(smoke):
    run = smoke("spine.kenta-spine-neck-arms")
    m = run.result["metrics"]
    assert m["concurrent_fraction"] == 1.0
    assert m["spine_sweep_deg"] > 10.0 and m["neck_sweep_deg"] > 5.0 and m["left_arm_sweep_deg"] > 5.0
    assert m["spine_key_error_deg"] < 10.0  # the forward model's lengths bring the spine near each key
    assert (run.out / "spine_neck_arms.png").exists()


def test_a_still_spine_fails_the_concurrency():
    """Keys all straight: the neck and arms still swing, but the spine does not move, so no window counts."""
    rig = all_at_once_rig(((0.0, 0.0, 0.0),), 2, 0.5, 0.35, 1.0, 0.5, 1.0, zeroing_s=0.2)
    m = all_at_once_metrics(run_rig(rig).log, rig.state)
    assert m["neck_moving_fraction"] == 1.0 and m["left_arm_moving_fraction"] == 1.0
    assert m["spine_moving_fraction"] == 0.0 and m["concurrent_fraction"] == 0.0
