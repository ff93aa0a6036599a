"""Damped-least-squares IK on MuJoCo site Jacobians, with joint limits and the reachability gate."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from shintai.sim import ik
from shintai.humanoid.robots import hrp2

ARM = [f"r_{j}" for j in ("shoulder_pitch", "shoulder_roll", "shoulder_yaw", "elbow_pitch", "wrist_yaw",
                          "wrist_roll", "wrist_pitch")]


@pytest.fixture(scope="module")
def robot():
    return hrp2.build_hrp2()


def _set(robot, q, values):
    q = q.copy()
    for name, value in zip(ARM, values):
        q[robot.model.joint(name).qposadr[0]] = value
    return q


def _fk(robot, q, site="r_grasp"):
    """Site position and orientation at qpos ``q`` (on a copy of the data)."""
    data = mujoco.MjData(robot.model)
    data.qpos[:] = q
    mujoco.mj_kinematics(robot.model, data)
    return data.site(site).xpos.copy(), data.site(site).xmat.reshape(3, 3).copy()


def _ranges(robot, joints):
    return np.array([robot.model.joint(j).range for j in joints])


def _values(robot, q, joints):
    return np.array([q[robot.model.joint(j).qposadr[0]] for j in joints])


def test_reaches_a_position_to_0_1_mm_without_touching_the_simulation(robot):
    before = robot.data.qpos.copy()
    target = robot.site_pos("r_grasp") + [0.25, 0.05, 0.2]
    q, ok, (pos_err, _) = ik.solve(robot, {"r_grasp": target}, joints=ARM)
    assert ok and pos_err <= 1e-4
    assert np.linalg.norm(_fk(robot, q)[0] - target) <= 1e-4
    assert np.array_equal(robot.data.qpos, before)
    others = np.ones(robot.model.nq, bool)
    others[[robot.model.joint(j).qposadr[0] for j in ARM]] = False
    assert np.array_equal(q[others], before[others])  # only the named joints moved


def test_reaches_position_and_orientation_of_a_reachable_pose(robot):
    goal = _set(robot, robot.data.qpos, [-0.9, -0.3, 0.4, -1.0, 0.5, 0.3, -0.2])
    pos, rot = _fk(robot, goal)
    q, ok, (pos_err, rot_err) = ik.solve(robot, {"r_grasp": (pos, rot)}, joints=ARM)
    assert ok and pos_err <= 1e-4 and rot_err <= 1e-3
    reached_pos, reached_rot = _fk(robot, q)
    assert np.linalg.norm(reached_pos - pos) <= 1e-4
    assert np.linalg.norm(ik.rotation_error(rot, reached_rot)) <= 1e-3


def test_aligns_one_axis_and_leaves_the_rotation_about_it_free(robot):
    target = robot.site_pos("r_grasp") + [0.3, 0.1, 0.3]
    bar = np.array([0.0, 1.0, 0.0])
    q, ok, _ = ik.solve(robot, {"r_grasp": ik.Target(pos=target, axis=([1, 0, 0], bar))}, joints=ARM)
    pos, rot = _fk(robot, q)
    assert ok and np.linalg.norm(pos - target) <= 1e-4
    assert rot[:, 0] @ bar == pytest.approx(1.0, abs=1e-6)


def test_solves_several_end_effectors_at_once(robot):
    left = ["l" + j[1:] for j in ARM]
    targets = {"r_grasp": robot.site_pos("r_grasp") + [0.2, 0.0, 0.25],
               "l_grasp": robot.site_pos("l_grasp") + [0.2, 0.0, 0.25],
               "l_sole": robot.site_pos("l_sole") + [0.05, 0.0, 0.1]}
    legs = [f"l_{j}" for j in ("hip_yaw", "hip_roll", "hip_pitch", "knee_pitch", "ankle_pitch", "ankle_roll")]
    q, ok, (pos_err, _) = ik.solve(robot, targets, joints=ARM + left + legs)
    assert ok and pos_err <= 1e-4
    for site, target in targets.items():
        assert np.linalg.norm(_fk(robot, q, site)[0] - target) <= 1e-4


def test_reports_an_unreachable_target(robot):
    far = robot.site_pos("r_grasp") + [1.0, 0.0, 0.0]  # beyond the 0.6 m arm
    q, ok, (pos_err, _) = ik.solve(robot, {"r_grasp": far}, joints=ARM)
    assert not ok and pos_err > 0.3
    assert not ik.reachable(robot, {"r_grasp": far}, joints=ARM)
    assert ik.reachable(robot, {"r_grasp": robot.site_pos("r_grasp") + [0.1, 0.0, 0.1]}, joints=ARM)


def test_respects_joint_limits(robot):
    # the elbow cannot bend backwards (Table A.2: back 2°): a point behind the straight arm's
    # elbow is out of reach, and the answer stays inside every limit
    behind = robot.site_pos("r_grasp") + [-0.3, 0.0, 0.35]
    q, ok, _ = ik.solve(robot, {"r_grasp": behind}, joints=["r_elbow_pitch", "r_shoulder_roll"])
    lo, hi = _ranges(robot, ["r_elbow_pitch", "r_shoulder_roll"]).T
    values = _values(robot, q, ["r_elbow_pitch", "r_shoulder_roll"])
    assert not ok
    assert np.all(values >= lo) and np.all(values <= hi)
    assert values[0] == hi[0]  # the elbow stopped at its limit instead of bending backwards


def test_reaches_a_pose_with_joints_at_their_limits(robot):
    at_limit = _set(robot, robot.data.qpos, [-0.5, robot.model.joint("r_shoulder_roll").range[1], 0.0,
                                             robot.model.joint("r_elbow_pitch").range[0], 0.0, 0.0, 0.0])
    q, ok, _ = ik.solve(robot, {"r_grasp": _fk(robot, at_limit)[0]}, joints=ARM)
    lo, hi = _ranges(robot, ARM).T
    values = _values(robot, q, ARM)
    assert ok and np.all(values >= lo) and np.all(values <= hi)


def test_posture_is_pursued_without_leaving_the_target(robot):
    target = robot.site_pos("r_grasp") + [0.2, 0.0, 0.2]
    plain, _, _ = ik.solve(robot, {"r_grasp": target}, joints=ARM)
    q, ok, _ = ik.solve(robot, {"r_grasp": target}, joints=ARM, posture={"r_wrist_roll": 0.6})
    assert ok and np.linalg.norm(_fk(robot, q)[0] - target) <= 1e-4
    wrist = robot.model.joint("r_wrist_roll").qposadr[0]
    assert abs(q[wrist] - 0.6) < abs(plain[wrist] - 0.6)


def test_bad_names_fail_with_one_clear_line(robot):
    with pytest.raises(KeyError, match="unknown site 'nose'"):
        ik.solve(robot, {"nose": np.zeros(3)})
    with pytest.raises(ValueError, match="hinge and slide joints only"):
        ik.solve(robot, {"r_grasp": np.zeros(3)}, joints=["root"])


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.floats(-1.0, 1.0), min_size=7, max_size=7))
def test_random_reachable_poses_are_reached(robot, fractions):
    """FK of a random posture inside the limits, IK from a posture 0.3 rad away: reached to 0.1 mm."""
    lo, hi = _ranges(robot, ARM).T
    mid, half = (lo + hi) / 2, np.minimum((hi - lo) / 2, 1.2)
    goal = _set(robot, robot.data.qpos, np.clip(mid + 0.8 * half * np.array(fractions), lo, hi))
    start = _set(robot, goal, np.clip(_values(robot, goal, ARM) + 0.3, lo, hi))
    q, ok, (pos_err, _) = ik.solve(robot, {"r_grasp": _fk(robot, goal)[0]}, start, ARM)
    assert ok and pos_err <= 1e-4


def test_cached_problem_is_per_model_and_gives_the_same_answer():
    """ik.solve reuses its scratch data per (model, joints); a second model gets its own."""
    from shintai.sim import ik as ik_module
    from shintai.humanoid.robots.hrp2 import build_hrp2

    a, b = build_hrp2(), build_hrp2()
    joints = ["r_hip_pitch", "r_knee_pitch", "r_ankle_pitch"]
    target = a.site_pos("r_sole") + [0.03, 0.0, 0.03]
    first = ik_module.solve(a, {"r_sole": target}, joints=joints)
    again = ik_module.solve(a, {"r_sole": target}, joints=joints)
    other = ik_module.solve(b, {"r_sole": target}, joints=joints)
    assert first.ok and np.array_equal(first.q, again.q) and np.array_equal(first.q, other.q)
    assert ik_module.cached_problem(a.model, joints) is not ik_module.cached_problem(b.model, joints)


def test_reused_buffers_do_not_carry_over_between_solves(robot):
    """The error and Jacobian buffers are kept per problem and set of target kinds: solving other targets on the
    same problem in between (another site, another kind, a posture) leaves the answer to the first unchanged."""
    pos = robot.site_pos("r_grasp") + [0.15, -0.05, 0.2]
    axis_target = ik.Target(pos=pos, axis=([1, 0, 0], [0.0, 0.6, 0.8]))
    first = ik.solve(robot, {"r_grasp": axis_target}, joints=ARM)
    ik.solve(robot, {"r_grasp": (pos, np.eye(3))}, joints=ARM)
    ik.solve(robot, {"r_grasp": pos + [0.05, 0.0, 0.0]}, joints=ARM, posture={"r_wrist_roll": 0.4})
    ik.solve(robot, {"r_grasp": ik.Target(pos=pos + [0.0, 0.1, 0.0], axis=([1, 0, 0], [0.0, 1.0, 0.0]))}, joints=ARM)
    again = ik.solve(robot, {"r_grasp": axis_target}, joints=ARM)
    assert first.ok and np.array_equal(first.q, again.q) and first.residual == again.residual


def test_a_site_axis_changed_in_place_is_honoured(robot):
    """The site's unit axis is kept from solve to solve while its bits stay the same: an axis array changed in
    place between solves is aimed with its new value, as a fresh array would be."""
    pos = robot.site_pos("r_grasp") + [0.15, -0.05, 0.2]
    world = np.array([0.0, 0.6, 0.8])
    local = np.array([1.0, 0.0, 0.0])
    ik.solve(robot, {"r_grasp": ik.Target(pos=pos, axis=(local, world))}, joints=ARM)
    local[:] = [0.0, 0.0, 2.0]  # the z axis, not unit length
    q, ok, _ = ik.solve(robot, {"r_grasp": ik.Target(pos=pos, axis=(local, world))}, joints=ARM)
    fresh = ik.solve(robot, {"r_grasp": ik.Target(pos=pos, axis=(np.array([0.0, 0.0, 1.0]), world))}, joints=ARM)
    assert ok and np.array_equal(q, fresh.q)
    assert _fk(robot, q)[1][:, 2] @ world == pytest.approx(1.0, abs=1e-6)
