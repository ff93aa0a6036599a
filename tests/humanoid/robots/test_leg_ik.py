"""The analytic leg IK against MuJoCo's FK of the hrp2 model, against the DLS IK, and at its edges."""

import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.constants import HRP2_LINKS, STANDING_POSTURE
from shintai.humanoid.robots.hrp2 import build_hrp2, side_posture
from shintai.humanoid.robots.leg_ik import JOINT_NAMES, LIMITS, hip_point, inside_limits, leg_fk, leg_ik, legs_ik
from shintai.sim import ik


@pytest.fixture(scope="module")
def model():
    return build_hrp2().model


def _random_pose(rng, data):
    data.qpos[:3] = rng.uniform(-1.0, 1.0, 3)
    quat = rng.normal(size=4)
    data.qpos[3:7] = quat / np.linalg.norm(quat)


def _random_leg(rng, side):
    """Leg angles inside 90 % of Table A.2's ranges, the knee bent at least 3° (the solution is then unique)."""
    lo, hi = LIMITS[side].T
    q = rng.uniform(0.9 * lo, 0.9 * hi)
    q[3] = rng.uniform(0.05, 0.9 * hi[3])
    return q


def _set_leg(model, data, side, q):
    for name, value in zip(JOINT_NAMES, q):
        data.qpos[model.joint(f"{side}_{name}").qposadr[0]] = value


def _poses(model, data, side):
    w, s = model.body("waist").id, model.site(f"{side}_sole").id
    return (data.xpos[w].copy(), data.xmat[w].reshape(3, 3).copy(),
            data.site_xpos[s].copy(), data.site_xmat[s].reshape(3, 3).copy())


def test_random_reachable_poses_match_mujoco_fk_to_1e9_both_legs(model):
    rng = np.random.default_rng(13)
    data = mujoco.MjData(model)
    worst_fk, worst_q = 0.0, 0.0
    for _ in range(300):
        data.qpos[:] = model.qpos0
        _random_pose(rng, data)
        truth = {s: _random_leg(rng, s) for s in "lr"}
        for s in "lr":
            _set_leg(model, data, s, truth[s])
        mujoco.mj_kinematics(model, data)
        for s in "lr":
            wp, wr, sp, sr = _poses(model, data, s)
            result = leg_ik(s, wp, wr, sp, sr)
            assert result.ok, (s, result)
            worst_q = max(worst_q, float(np.abs(result.q - truth[s]).max()))
            # the solution through MuJoCo's FK lands on the target
            check = mujoco.MjData(model)
            check.qpos[:] = data.qpos
            _set_leg(model, check, s, result.q)
            mujoco.mj_kinematics(model, check)
            _, _, p, r = _poses(model, check, s)
            worst_fk = max(worst_fk, float(np.abs(p - sp).max()), float(np.abs(r - sr).max()))
    assert worst_fk < 1e-9
    assert worst_q < 1e-9  # the same branch as the sampled posture (knee flexed, |ankle roll| < π/2)


def test_numpy_fk_is_the_models_chain(model):
    rng = np.random.default_rng(1)
    data = mujoco.MjData(model)
    for _ in range(20):
        _random_pose(rng, data)
        q = {s: rng.uniform(-1.0, 1.0, 6) for s in "lr"}
        for s in "lr":
            _set_leg(model, data, s, q[s])
        mujoco.mj_kinematics(model, data)
        for s in "lr":
            wp, wr, sp, sr = _poses(model, data, s)
            p, r = leg_fk(s, q[s], wp, wr)
            assert np.allclose(p, sp, atol=1e-12) and np.allclose(r, sr, atol=1e-12)


def test_standing_keyframe_soles_give_back_the_standing_posture(model):
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("stand").id)
    mujoco.mj_kinematics(model, data)
    wp, wr, _, _ = _poses(model, data, "l")
    soles = {s: _poses(model, data, s)[2:] for s in "lr"}
    posture = side_posture(STANDING_POSTURE)
    for s, result in legs_ik(wp, wr, soles).items():
        for name, value in result.joints(s).items():
            assert value == pytest.approx(posture.get(name, 0.0), abs=1e-12)


def test_same_solution_as_the_dls_ik_on_the_same_targets(model):
    """The DLS IK started from the standing posture converges to the analytic branch."""
    rng = np.random.default_rng(7)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("stand").id)
    q0 = data.qpos.copy()
    for _ in range(10):
        data.qpos[:] = q0
        for s in "lr":  # targets around the standing posture: each joint moved by up to ±0.3 rad
            stand = np.array([data.qpos[model.joint(f"{s}_{n}").qposadr[0]] for n in JOINT_NAMES])
            lo, hi = LIMITS[s].T
            _set_leg(model, data, s, np.clip(stand + rng.uniform(-0.3, 0.3, 6), lo + 0.05, hi - 0.05))
        mujoco.mj_kinematics(model, data)
        for s in "lr":
            wp, wr, sp, sr = _poses(model, data, s)
            analytic = leg_ik(s, wp, wr, sp, sr)
            joints = [f"{s}_{n}" for n in JOINT_NAMES]
            dls = ik.solve(model, {f"{s}_sole": (sp, sr)}, q0, joints, tol=1e-10, rot_tol=1e-10)
            assert dls.ok and analytic.ok
            q_dls = np.array([dls.q[model.joint(j).qposadr[0]] for j in joints])
            assert np.abs(q_dls - analytic.q).max() < 1e-7


def test_out_of_reach_target_gets_a_straight_knee_pointing_at_it_and_a_flag():
    wp, wr = np.zeros(3), np.eye(3)
    hip = hip_point("r", wp, wr)
    ankle_target = hip + np.array([0.1, -0.05, -0.8])  # 0.81 m from the hip, the leg is 0.60 m
    sole = ankle_target - np.array([0.0, 0.0, HRP2_LINKS.ankle_height])
    result = leg_ik("r", wp, wr, sole, np.eye(3))
    assert not result.reachable and not result.ok
    assert result.reach_error == pytest.approx(np.linalg.norm(ankle_target - hip) - 0.6, abs=1e-12)
    assert result.q[3] == 0.0
    p, r = leg_fk("r", result.q, wp, wr)
    ankle = p + r[:, 2] * HRP2_LINKS.ankle_height
    assert np.allclose(r, np.eye(3), atol=1e-12)  # the foot keeps its orientation
    direction = (ankle_target - hip) / np.linalg.norm(ankle_target - hip)
    assert np.allclose(ankle, hip + 0.6 * direction, atol=1e-12)  # as close as the leg gets


def test_joint_limits_are_reported_per_side_and_mirrored():
    wp, wr = np.zeros(3), np.eye(3)
    q = np.array([0.0, 0.0, -0.3, 0.6, -0.3, 0.0])
    q[0] = -40 * math.pi / 180  # hip yaw: right leg allows −45°, the left (mirrored) only −30°
    for side, inside in (("r", True), ("l", False)):
        result = leg_ik(side, wp, wr, *leg_fk(side, q, wp, wr))
        assert result.reachable and np.allclose(result.q, q, atol=1e-12)
        assert result.within_limits is inside
        assert result.violated == (() if inside else ("l_hip_yaw",))
        assert inside_limits(side, result.q.tolist()) is inside  # the per-tick form of within_limits
    assert not inside_limits("r", [math.nan, 0.0, -0.3, 0.6, -0.3, 0.0])
    assert inside_limits("r", [lo for lo, _ in LIMITS["r"].tolist()])  # the range's ends are inside


@pytest.mark.parametrize("args, word", [
    (("x", np.zeros(3), np.eye(3), np.zeros(3), np.eye(3)), "side"),
    (("l", np.zeros(3), np.eye(3), [0.0, math.nan, -0.7], np.eye(3)), "finite"),
    (("l", np.zeros(3), np.eye(2), np.zeros(3), np.eye(3)), "waist_rot"),
])
def test_bad_arguments_raise_one_clear_value_error(args, word):
    with pytest.raises(ValueError, match=word):
        leg_ik(*args)


def test_the_compiled_closed_form_is_its_python_source_bit_for_bit():
    """closed_form is compiled (numba, no fast-math): on random waist and sole poses, both legs, sole and ankle
    targets, in and out of reach, it gives the bits its own source gives on Python floats (the arithmetic the
    stabilizer's and the tricycle's feet used before it was compiled)."""
    from shintai.core.geometry import rot_xy
    from shintai.humanoid.robots.leg_ik import closed_form

    rng = np.random.default_rng(7)
    links = HRP2_LINKS
    for k in range(400):
        side = 1.0 if k % 2 else -1.0
        waist = (rng.normal(0.0, 0.02, 3) + (0.0, 0.0, 0.6 + 0.3 * (k % 7 == 0))).tolist()
        w = (rot_xy(*rng.normal(0.0, 0.1, 2)) @ np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
             if k % 5 == 0 else rot_xy(*rng.normal(0.0, 0.05, 2))).ravel().tolist()
        sole = (rng.normal(0.0, 0.05, 3) + (0.0, side * 0.1, 0.0)).tolist()
        f = rot_xy(*rng.normal(0.0, 0.2, 2)).ravel().tolist()
        args = (side * links.hip_y, links.hip_z, links.ankle_height, links.thigh, links.shank, k % 3 != 0,
                *waist, *w, *sole, *f)
        assert closed_form(*args) == closed_form.py_func(*args)
