"""Whole-body Cla (spine/cla/body.py): the muscle spine with limbs, seated and standing; the spine lock; the FSR
centre of pressure (eq. 3.5); the head camera's direction."""

import numpy as np
import pytest

from shintai.core.runtime import Loop
from shintai.spine.cla.body import LIMB_JOINTS, ClaBody, build_spec
from shintai.scenarios.experiment import Rig, run_rig
from shintai.spine.cla.control import spine_control
from shintai.spine.control import SETPOINTS
from shintai.spine.cla.postures import GOAL, WHOLE_REF, PostureTargets
from shintai.spine.robots import CLA
from shintai.spine.scripted import Schedule

BEND = np.radians([0.0, 30.0, 0.0])  # whole-spine pitch forward 30°


def bend(body: ClaBody, seconds: float = 1.0) -> np.ndarray:
    """Calibrate, command BEND through the muscles, return the whole-spine (roll, pitch, yaw) reached."""
    control, zero = spine_control(body, calibration_s=0.3)
    Loop(body, stages=[[Schedule({0: {"goal": BEND}})], [PostureTargets(CLA.model, zero, 0.5)], [control]],
         channels=(*SETPOINTS, GOAL, WHOLE_REF)).run(seconds)
    return body.theta().reshape(CLA.n, 3).sum(axis=0)


def test_the_model_has_every_limb_joint_as_a_servo_and_the_muscle_spine():
    m = build_spec("seated").compile()
    names = {m.actuator(i).name for i in range(m.nu)}
    assert set(LIMB_JOINTS) <= names
    assert sum(n.endswith(":motor") for n in names) == CLA.m == 8
    with pytest.raises(ValueError, match="posture must be"):
        build_spec("kneeling")


def test_the_muscles_bend_the_free_spine_and_the_lock_holds_it():
    free = bend(ClaBody("seated"))
    assert np.degrees(free[1]) > 20.0
    locked_body = ClaBody("seated")
    locked_body.lock_spine(True)
    assert locked_body.spine_locked
    locked = bend(locked_body)  # the muscles pull as hard as they can against the lock
    assert np.degrees(np.abs(locked)).max() < 1.5


def test_standing_soles_carry_the_weight_and_the_cop_lies_between_the_feet():
    body = ClaBody("standing")
    control, _ = spine_control(body, calibration_s=0.3)
    run_rig(Rig(body, [control], duration=0.3))  # the muscles holding their targets
    snap = body.snapshot()
    weight = body.model.body_subtreemass[body.id("body", "link0")] * 9.81
    assert snap["sole_force"].sum() == pytest.approx(weight, rel=0.1)
    feet = np.array([body.body_pos("foot_r")[:2], body.body_pos("foot_l")[:2]])
    assert feet[0, 1] < snap["cop"][1] < feet[1, 1]
    assert abs(snap["cop"][0] - feet[:, 0].mean()) < 0.05
    assert np.allclose(snap["gaze"], [1.0, 0.0, 0.0], atol=0.1)  # looking ahead


def test_gripping_carries_an_object_with_the_hand():
    body = ClaBody("seated")
    hand = body.site_pos("hand_r")
    body.place("desk_object", hand + [0.0, 0.0, -0.03])
    body.grip("r", "desk_object")
    body.lock_spine(True)
    for _ in range(200):
        body.apply({"shoulder_pitch_r": 0.8})
        body.step()
    moved = body.object_pos("desk_object") - (hand + [0.0, 0.0, -0.03])
    assert np.linalg.norm(moved) > 0.03
    assert np.linalg.norm(body.object_pos("desk_object") - body.site_pos("hand_r")) < 0.04
