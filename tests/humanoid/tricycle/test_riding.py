"""HRP2-JSK seated on the tricycle (seed 000 Ch. 3): the riding assembly, its grasps, its stillness."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from shintai.humanoid.constants import HRP2_LINKS, THETA_C_INIT, THETA_H_MAX
from shintai.humanoid.robots.hrp2 import ft_reaction
from shintai.humanoid.tricycle import vehicle as tricycle
from shintai.humanoid.tricycle import riding
from shintai.sim import ik

SIDES = ("l", "r")


def _run(body, seconds: float, command=None) -> None:
    for _ in range(round(seconds / body.dt)):
        if command:
            body.apply(command)
        body.step()


def _gap(body, side: str) -> float:
    return float(np.linalg.norm(body.site_pos(riding.HAND[side]) - body.site_pos(riding.GRIP[side])))


@pytest.fixture(scope="module")
def seated():
    """Built once, then left alone for 5 s with the servos holding the riding posture."""
    body = riding.build_riding()
    start = {"tricycle": body.body_pos("tricycle"), "crank": body.joint_qpos("crank"),
             "handle": body.joint_qpos("handle"), "imu": body.snapshot()["imu_quat"]}
    _run(body, 5.0)  # SimulationDiverged would fail here
    return body, start


def test_names_for_controllers_exist():
    body = riding.build_riding()
    snap = body.snapshot()
    for side in SIDES:
        for stem in (riding.WRIST_FT[side], riding.ANKLE_FT[side]):
            assert snap[f"{stem}_force"].shape == (3,) and snap[f"{stem}_torque"].shape == (3,)
        for site in (riding.HAND[side], riding.SOLE[side], riding.GRIP[side], riding.PEDAL[side]):
            body.site_pos(site)
        for joint in riding.ARM[side] + riding.LEG[side]:
            body.joint_qpos(joint)
        body.id("equality", riding.HOLD[side])
    assert [snap[name].shape for name in riding.IMU] == [(4,), (3,), (3,)]
    assert "q:handle" in snap and "q:crank" in snap
    body.id("equality", riding.HIP_SADDLE)


def test_starts_seated_with_hands_on_grips_and_soles_flat_on_level_pedals():
    body = riding.build_riding(theta_c=THETA_C_INIT)
    for side in SIDES:
        assert _gap(body, side) <= 1e-4
        assert np.linalg.norm(body.site_pos(riding.SOLE[side]) - body.site_pos(riding.PEDAL[side])) <= 1e-4
        assert body.site_xmat(riding.SOLE[side]) == pytest.approx(np.eye(3), abs=1e-3)
        assert body.site_xmat(riding.PEDAL[side]) == pytest.approx(np.eye(3), abs=1e-9)
    assert body.joint_qpos("crank") == pytest.approx(THETA_C_INIT)
    waist_on_saddle = body.body_pos("waist") - body.site_pos("saddle_top")
    assert waist_on_saddle == pytest.approx([0, 0, HRP2_LINKS.hip_cover], abs=1e-9)


def test_sits_still_for_five_seconds(seated):
    body, start = seated
    snap = body.snapshot()
    assert np.linalg.norm(body.body_pos("tricycle") - start["tricycle"]) < 0.005
    assert abs(body.joint_qpos("crank") - start["crank"]) < 0.01
    assert abs(body.joint_qpos("handle") - start["handle"]) < 0.01
    assert np.abs(snap["imu_quat"] - start["imu"]).max() < 0.01
    assert np.abs(snap["imu_gyro"]).max() < 0.01
    for side in SIDES:
        assert _gap(body, side) < 0.002
        foot, _ = ft_reaction(body, snap, riding.ANKLE_FT[side])
        assert foot[2] > 50.0  # the sole presses on its pedal (unilateral contact kept)
        assert body.contact_force(f"{side}_foot")[2] == pytest.approx(foot[2], rel=0.05)


@pytest.mark.parametrize("options", [
    {"theta_h": THETA_H_MAX}, {"theta_h": -THETA_H_MAX, "theta_c": math.pi / 2},
    {"grasp": "connect"}, {"held": ("l",)}, {"handle_error": (0.02, 0.0, 0.01), "crank_error": (0.01, -0.01)},
])
def test_other_starts_and_options_also_sit_still(options):
    body = riding.build_riding(**options)
    start = body.body_pos("tricycle")
    _run(body, 2.0)
    assert np.linalg.norm(body.body_pos("tricycle") - start) < 0.005
    for side in options.get("held", SIDES):
        assert _gap(body, side) < 0.002


def test_options_reach_the_model():
    body = riding.build_riding(held=("r",), grasp="connect", crank_damping=4.0, crank_friction=0.3,
                               handle_error=(0.03, 0.0, 0.0), crank_error=(0.0, 0.02))
    m = body.model
    assert list(body.data.eq_active[[body.id("equality", riding.HOLD[s]) for s in SIDES]]) == [0, 1]
    assert m.eq_type[body.id("equality", riding.HOLD["r"])] == mujoco.mjtEq.mjEQ_CONNECT
    crank = m.joint("crank").dofadr[0]
    assert (m.dof_damping[crank], m.dof_frictionloss[crank]) == (4.0, 0.3)
    vehicle = body.body_pos("tricycle")
    assert body.site_pos("steer_axis") - vehicle == pytest.approx(tricycle.steer_point() + [0.03, 0, 0], abs=1e-9)
    assert body.site_pos("crank_centre") - vehicle == pytest.approx(tricycle.crank_centre() + [0, 0, 0.02], abs=1e-9)
    for side in SIDES:  # the grips stay where the nominal model has them
        assert body.site_pos(riding.GRIP[side]) - vehicle == pytest.approx(tricycle.grip_position(0.0, side), abs=1e-9)


def test_nominal_kinematic_model_matches_the_simulated_tricycle():
    body = tricycle.build_tricycle(theta_h=0.3, theta_c=1.0)
    for side in SIDES:
        assert body.site_pos(f"grip_{side}") == pytest.approx(tricycle.grip_position(0.3, side), abs=1e-9)
        assert body.site_pos(f"pedal_{side}_top") == pytest.approx(tricycle.pedal_position(1.0, side), abs=1e-9)


def test_grasp_holds_at_the_current_pose_and_release_lets_go():
    body = riding.build_riding()
    riding.release(body, "r")
    arm = {j: body.joint_qpos(j) for j in riding.ARM["r"]}
    arm["r_elbow_pitch"] += 0.15
    _run(body, 0.5, arm)
    assert _gap(body, "r") > 0.02  # let go: the hand moved away
    riding.grasp(body, "r")
    held_at = body.site_pos(riding.HAND["r"]) - body.site_pos(riding.GRIP["r"])
    _run(body, 0.5, arm)
    moved = body.site_pos(riding.HAND["r"]) - body.site_pos(riding.GRIP["r"]) - held_at
    assert np.linalg.norm(moved) < 0.002  # held where it was, not pulled back to the grip centre


def test_the_robot_pedals_one_revolution_and_travels_2_45_m():
    """Both legs follow the nominal pedal circle by IK (position only): the crank, the gear and the
    tyres carry the robot 2.45 m per crank revolution (App. A.1.1)."""
    body = riding.build_riding()
    m = body.model
    legs = riding.LEG["l"] + riding.LEG["r"]
    adr = [m.joint(j).qposadr[0] for j in legs]
    start, q_legs = body.body_pos("tricycle"), body.data.qpos[adr].copy()
    for k in range(1, 73):
        frame = body.data.body("tricycle")
        rot = frame.xmat.reshape(3, 3)
        targets = {riding.SOLE[s]: ik.Target(pos=frame.xpos + rot @ tricycle.pedal_position(math.radians(5 * k), s),
                                             axis=([0, 1, 0], rot[:, 1])) for s in SIDES}
        q0 = body.data.qpos.copy()
        q0[adr] = q_legs
        q, ok, _ = ik.solve(body, targets, q0, legs)
        assert ok, f"pedal out of reach at crank {5 * k} deg"
        q_legs = q[adr]
        _run(body, 0.2, dict(zip(legs, q_legs)))
    crank = body.joint_qpos("crank")
    travel = np.linalg.norm((body.body_pos("tricycle") - start)[:2])
    assert crank > math.radians(330)
    assert travel / crank * 2 * math.pi == pytest.approx(2.45, rel=0.01)


def test_grip_grasp_holds_two_points_on_the_bar_and_grip_error_widens_the_handlebar():
    """The "grip" grasp (GRIP_BAR_OFFSET): two point holds on the bar per hand, so the hand can turn
    about the bar only; ``grip_error`` puts the true grips that much farther out (E1's model error)."""
    body = riding.build_riding(grasp="grip", grip_error=0.01)
    m, vehicle = body.model, body.body_pos("tricycle")
    for side, sign in (("l", 1.0), ("r", -1.0)):
        ids = [body.id("equality", riding.HOLD[side]), body.id("equality", riding.HOLD_BAR[side])]
        assert all(m.eq_type[i] == mujoco.mjtEq.mjEQ_CONNECT for i in ids) and body.data.eq_active[ids].all()
        anchors = [m.eq_data[i, 3:6] for i in ids]  # in the hand body's frame
        assert np.linalg.norm(anchors[1] - anchors[0]) == pytest.approx(np.linalg.norm(riding.GRIP_BAR_OFFSET))
        nominal = tricycle.grip_position(0.0, side)
        assert body.site_pos(riding.GRIP[side]) - vehicle == pytest.approx(nominal + [0, sign * 0.01, 0], abs=1e-9)
    _run(body, 1.0)
    for side in SIDES:
        assert _gap(body, side) < 0.002
    riding.release(body, "l")
    left = [body.id("equality", riding.HOLD["l"]), body.id("equality", riding.HOLD_BAR["l"])]
    assert not body.data.eq_active[left].any()
    riding.grasp(body, "l")
    assert body.data.eq_active[body.id("equality", riding.HOLD_BAR["l"])]
