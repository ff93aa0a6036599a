"""MuJoCo plant of the wheeled snake (mujoco_plant.py): no side slip, lifting by pitch joints, interface."""

import math

import numpy as np
import pytest

from shintai.core.runtime import SET, ChannelError, FunctionModule, Loop
from shintai.snake.constants import CH3_ROBOT, MUJOCO_SNAKE, TRACKING
from shintai.snake.model import configuration, wheel_poses
from shintai.snake.mujoco_plant import MujocoSnake, head_path_difference, lift_profile, replay_error
from shintai.snake.plant import KinematicSnake
from shintai.snake.two_point import candidate_modes

N = CH3_ROBOT.n


def hold(body, grounded, seconds, phi_dot=None):
    for _ in range(int(round(seconds / body.dt))):
        body.apply({"phi_dot": np.zeros(N) if phi_dot is None else phi_dot, "grounded": grounded})
        body.step()


def test_passive_wheels_do_not_slip_sideways_when_pushed_along():
    """STACK.md: condim 6, elliptic cones, impratio 10 → side slip ≈ 0.1 % of the rolled distance. A straight
    snake (all wheels down) pushed at 31° off its axis (side force 15 % of its weight) rolls along its axis."""
    body = MujocoSnake([0.0, 0.0, 0.0], np.zeros(N))
    hold(body, np.ones(N), 0.2)
    start = body.true_head()
    body._slid = body._rolled = body._jitter = body._path = 0.0  # count from here, after settling
    weight = 9.81 * body.mj.model.body_mass[1:].sum()
    links = [body.mj.id("body", f"link{j}") for j in range(1, 2 * N + 1)]
    for _ in range(30):
        body.mj.data.xfrc_applied[links, :3] = np.array([0.5, 0.3, 0.0]) * weight / len(links)
        hold(body, np.ones(N), body.dt)
    moved = body.true_head() - start
    summary = body.slip_summary()
    assert moved[0] > 0.2 and abs(moved[1]) < 0.01 * moved[0]
    assert summary["lateral_slip_fraction"] < 0.005 and summary["rolled_m"] > 1.0
    # no mode switch: every period is "steady"; a steady push has no vibration to speak of
    assert summary["lateral_slip_fraction_steady"] == pytest.approx(summary["lateral_slip_fraction"])
    assert summary["lateral_jitter_fraction"] == pytest.approx(summary["lateral_slip_fraction"], rel=0.2)


def test_settle_starts_the_clock_with_the_body_at_rest():
    body = MujocoSnake(TRACKING.w_h0, TRACKING.phi0)
    body.settle(0.3)
    snap = body.snapshot()
    assert body.t == 0.0 and snap["t"] == 0.0 and body.slip_summary()["rolled_m"] == 0.0
    assert np.abs(body.mj.data.qvel).max() < 0.05  # at rest
    assert snap["w_h"][:2] == pytest.approx(TRACKING.w_h0[:2], abs=2e-3)


def test_a_mode_switch_moves_the_pitch_joints_no_faster_than_the_lift_rate():
    body = MujocoSnake(TRACKING.w_h0, TRACKING.phi0)
    grounded = candidate_modes(N, 4, 4, 2)[0]
    body.apply({"phi_dot": np.zeros(N), "grounded": grounded})
    assert np.abs(body._rate[1::2]).max() <= MUJOCO_SNAKE.lift_rate + 1e-12


def test_lifting_by_pitch_joints_removes_the_wheels_ground_contact():
    """§2.3, Fig. 2.5: the pitch joints around a lifted wheel raise it; contacts are never switched off."""
    body = MujocoSnake(TRACKING.w_h0, TRACKING.phi0)
    contype = body.mj.model.geom_contype.copy()
    hold(body, np.ones(N), 0.2)
    assert body.snapshot()["wheel_contact"].all()
    for grounded in candidate_modes(N, 4, 4, 2)[[0, 25, 60]]:
        hold(body, grounded, 0.5)
        snap = body.snapshot()
        assert not snap["wheel_contact"][~grounded].any(), (grounded, snap["wheel_contact"])
        assert snap["wheel_contact"][grounded].sum() >= 3  # a rigid body on > 3 supports may leave one hovering
        z = body.wheel_positions()[:, 2] - MUJOCO_SNAKE.wheel_radius
        assert z[~grounded].min() > 0.001 and z[~grounded].mean() > 0.5 * MUJOCO_SNAKE.lift_height
        assert abs(z[grounded]).max() < 0.003
        assert np.abs(snap["psi"][1::2]).max() < 0.2  # small angles (§2.3): the planar model still holds
    assert np.array_equal(body.mj.model.geom_contype, contype)


def test_lift_profile_is_fig_2_5_on_a_straight_body():
    """One lifted wheel between grounded ones: −α, +2α, −α at the neighbours' and its own pitch joints."""
    grounded = np.ones(N, bool)
    grounded[4] = False
    pitch = lift_profile(np.zeros(N), grounded, CH3_ROBOT.l)
    alpha = math.asin(MUJOCO_SNAKE.lift_height / (2 * CH3_ROBOT.l))
    expected = np.zeros(N - 1)
    expected[[3, 4, 5]] = (-alpha, 2 * alpha, -alpha)
    assert pitch == pytest.approx(expected, abs=2e-4)


def test_interface_matches_the_kinematic_plant():
    kinematic = KinematicSnake(TRACKING.w_h0, TRACKING.phi0)
    body = MujocoSnake(TRACKING.w_h0, TRACKING.phi0)
    snap_k, snap_m = kinematic.snapshot(), body.snapshot()
    assert set(snap_k) <= set(snap_m) and {"wheel_contact", "head_pose"} <= set(snap_m)
    for key in snap_k:
        assert np.shape(snap_k[key]) == np.shape(snap_m[key]), key
    assert snap_m["w_h"] == pytest.approx(TRACKING.w_h0, abs=1e-9)
    assert snap_m["phi"] == pytest.approx(TRACKING.phi0, abs=1e-9)
    assert body.dt == kinematic.dt and set(KinematicSnake.channels) <= set(body.channels)
    assert body.channels["grounded"].kind == SET
    with pytest.raises(ChannelError, match="undeclared channel 'torque'"):
        Loop(body, [FunctionModule(lambda s: {"torque": np.zeros(N)})]).step()
    with pytest.raises(ValueError, match="not both"):
        body.apply({"phi_dot": np.zeros(N), "psi_dot": np.zeros(2 * N - 1)})
    with pytest.raises(ValueError, match="phi_dot must have 9"):
        body.apply({"phi_dot": np.zeros(3)})


def test_joint_rates_move_the_joints_and_the_mocap_heading_unwraps():
    """φ̇ is integrated into the servo targets (3 grounded wheels: any joint motion is admissible); the
    measured heading stays continuous near θ(0) = π."""
    body = MujocoSnake(TRACKING.w_h0, TRACKING.phi0)
    three = np.zeros(N, bool)
    three[[0, 3, 6]] = True
    hold(body, three, 1.0, phi_dot=np.full(N, 0.1))
    assert body.snapshot()["phi"] == pytest.approx(np.array(TRACKING.phi0) + 0.1, abs=0.01)
    assert body.snapshot()["w_h"][2] > 2.5  # near π, not wrapped to −π


def test_mocap_noise_is_seeded():
    def reading(seed):
        body = MujocoSnake(TRACKING.w_h0, TRACKING.phi0, mocap_noise=0.001, rng=np.random.default_rng(seed))
        return body.snapshot()["w_h"]

    assert np.array_equal(reading(3), reading(3)) and not np.array_equal(reading(3), reading(4))
    assert np.abs(reading(3)[:2] - TRACKING.w_h0[:2]).max() < 0.005


def test_replay_error_is_zero_for_the_kinematic_plant():
    """The kinematic model replayed on the kinematic plant's own joint motion reproduces its head path."""
    body = KinematicSnake(TRACKING.w_h0, TRACKING.phi0)
    grounded = candidate_modes(N, 4, 4, 2)[10]
    rng = np.random.default_rng(0)
    w, phi, modes = [body.w_h.copy()], [body.phi.copy()], []
    for _ in range(40):
        body.apply({"phi_dot": 0.2 * rng.normal(size=N), "grounded": grounded})
        body.step()
        w.append(body.w_h.copy())
        phi.append(body.phi.copy())
        modes.append(grounded)
    assert replay_error(np.array(w), np.array(phi), np.array(modes), CH3_ROBOT.l, body.dt, 20) < 5e-4
    assert head_path_difference(np.array(w), np.array(w) + [0.003, 0.004, 0.0]) == pytest.approx(0.005)


def test_wheel_layout_matches_the_planar_model():
    """Axle centres of the MuJoCo body = (2.3)–(2.4) at the initial state (wheel n at the tail tip, A2)."""
    body = MujocoSnake(TRACKING.w_h0, TRACKING.phi0)
    planar = wheel_poses(configuration(TRACKING.w_h0, TRACKING.phi0, CH3_ROBOT.l))[:, :2]
    assert body.wheel_positions()[:, :2] == pytest.approx(planar, abs=1e-9)
