"""Applications of §3.4 (caging.py, handcart.py, door.py, door_operator.py, spatial.py): targets, caging, door,
handcart."""

import math

import numpy as np
import pytest

from shintai.scenarios.experiment import run_rig
from shintai.scenarios.registry import ParameterError, get
from shintai.snake.caging import KinematicBox, box_track, caging_rig, caging_targets
from shintai.snake.constants import CAGING, CAGING_BOX, DOOR, HANDCART, MUJOCO_SNAKE
from shintai.snake.door import ShiftControl, door_geometry, door_scene, door_start, knob_point
from shintai.snake.door_operator import DoorRun, Shift, door_rig, hook_distance, pull_metrics, pull_rig
from shintai.snake.handcart import handcart_geometry, handcart_initial, handcart_rig, handcart_series
from shintai.snake.model3d import PLANAR, chain_from_pose, euler_zyx
from shintai.snake.mujoco_plant import MujocoSnake
from shintai.snake.plots import plot_door
from shintai.snake.spatial import base_candidates, double_arm_model, head_raised_two_point_model
from shintai.snake.targets import PiecewiseLinear
from shintai.snake.tracking import TrackingRun


def test_two_stage_targets_are_3_22_with_the_a7_reading():
    target = caging_targets()
    c0 = target.poses[0]
    assert target.poses[2][5] == pytest.approx(2 * math.pi)  # tail heading 0 ≡ 2π, unwrapped (A6)
    assert target(15.0)[0] == pytest.approx(0.5 * (c0 + target.poses[1]))
    assert target(CAGING.t_s1)[0] == pytest.approx(target.poses[1])  # no jump at t_s1 (A7)
    assert target(75.0)[0] == pytest.approx(0.5 * (target.poses[1] + target.poses[2]))
    assert target(75.0)[1] == pytest.approx((target.poses[2] - target.poses[1]) / 90.0)
    assert target(200.0)[1] == pytest.approx(np.zeros(6))
    with pytest.raises(ValueError, match="increasing"):
        PiecewiseLinear.through((0.0, 0.0), (c0, c0))


def test_short_caging_run_keeps_the_box_in_the_u():
    done = run_rig(caging_rig(3.0, "mujoco"))
    run, track = TrackingRun.of(done), box_track(done)
    assert track["caged"].all() and len(track["pos"]) == 60
    assert np.hypot(*(track["final"] - track["pos"][0])[:2]) < 0.02  # not yet reached by the U's bottom
    assert run.pos_error.max() < 0.01 and run.physics["lateral_slip_fraction"] < 0.2
    assert run.grounded.sum(axis=1).max() == 4  # the thesis's n_σ = 4 (§3.3)


def test_knob_moves_on_a_circle_about_the_hinge():
    k0 = knob_point(0.0)
    assert k0 == pytest.approx((-DOOR.knob_offset, DOOR.width - DOOR.knob_from_edge))
    for beta in (0.3, 1.0, DOOR.open_angle):
        assert np.linalg.norm(knob_point(beta)) == pytest.approx(np.linalg.norm(k0))
    assert knob_point(math.pi / 2)[1] < 0  # open 90°: the knob is on the robot's side of the hinge


def door_snake():
    """The door scene's snake placed at the operator's start pose (head raised, §3.4.3)."""
    geometry = door_geometry()
    p_h, R_h, psi = door_start()
    body = MujocoSnake([p_h[0], p_h[1], math.pi], DOOR.phi0, geometry,
                       scene=door_scene(knob_height=p_h[2] - DOOR.knob_drop))
    body.place(p_h, R_h, psi)
    return geometry, body


def test_door_phase_1_hooks_the_knob_and_starts_to_open_the_door():
    """A short run of the §3.4.3 operator: the raised head reaches the knob, the hook engages (through the
    body's set channel), the door opens."""
    run = run_rig(door_rig(duration=DOOR.t_approach + 12.0))
    body, events = run.body, DoorRun.of(run).events
    assert [phase for _, phase in events] == ["pull"] and events[0][0] <= DOOR.t_approach + 0.5
    assert run.state["switcher"].transitions_log[0][1:] == ("approach", "pull")
    assert body.mj.data.eq_active[body.mj.id("equality", "hook")] and run.loop.command["hook"] == 1.0
    assert 0.02 < body.mj.joint_qpos("hinge") < 0.3  # opening, following the slow arc
    assert hook_distance(body) < 0.01
    assert np.abs(body.snapshot()["psi"]).max() < 1.0  # the arm does the pulling; no joint winds up
    grounded = run.log.values("door.grounded").astype(bool)  # the wheels' mode, for the plots
    assert grounded.shape == (len(run.log.times("door.phase")), body.geometry.n)
    assert not grounded[:, :DOOR.raise_n_h - 1].any() and grounded[:, DOOR.raise_n_h - 1].all()
    assert run.log.values("raise.V_m").min() > 0.0


def test_door_plots_draw_wheels_paths_and_modes(tmp_path):
    """plot_door on a short recorded run: the top view, the time series and the mode timeline are written."""
    from contextlib import contextmanager

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    class Ctx:
        @contextmanager
        def figure(self, name, nrows=1, ncols=1, **kwargs):
            fig, axes = plt.subplots(nrows, ncols, **kwargs)
            yield fig, axes
            fig.savefig(tmp_path / f"{name}.png")
            plt.close(fig)

    run = run_rig(door_rig(duration=1.0))
    plot_door(Ctx(), run.log, DoorRun.of(run))
    assert {p.name for p in tmp_path.iterdir()} == {"top_view.png", "phases.png", "modes.png"}


def test_head_raised_two_point_model_matches_the_chain():
    """Phase 2 model: its last three rows are the tail wheel's planar pose rate (2.13) of the 3D chain."""
    geometry = door_geometry()
    p_h, R_h, psi = door_start()
    w_h = np.concatenate((p_h, euler_zyx(R_h)))
    n_h = DOOR.raise_n_h
    modes = base_candidates(geometry.n - n_h + 1, 2, 4, 0, fixed=2, tail_lifted=True)
    assert (~modes[:, -1]).all() and modes[:, :2].all()
    model = head_raised_two_point_model(geometry, n_h, modes)
    A, B, c = model.matrices(w_h, psi, modes[0])
    assert A.shape == (modes[0].sum() + 6, 9) and B.shape[1] == len(model.inputs) == 2 * n_h + geometry.n - n_h
    rng = np.random.default_rng(1)
    w_dot, u, h = rng.normal(size=6) * 0.05, rng.normal(size=len(model.inputs)) * 0.1, 1e-6
    moved = psi.copy()
    moved[model.inputs] += h * u
    tail = lambda w, q: chain_from_pose(w, q, geometry.l).wheel_pose(geometry.n)[PLANAR]  # noqa: E731
    tail_dot = (tail(w_h + h * w_dot, moved) - tail(w_h, psi)) / h
    assert c[6:] == pytest.approx(tail(w_h, psi))
    assert A[-3:] @ np.concatenate((w_dot, tail_dot)) == pytest.approx(B[-3:] @ u, abs=1e-5)


def test_shift_control_moves_the_curve_toward_the_head():
    """[8]: after one shift period each joint has its tail-side neighbour's angle (the robot moves tail-first);
    beyond the tail the curve continues as a serpenoid, continuous at the tail."""
    phi = np.linspace(-0.3, 0.4, DOOR.n)
    shift = ShiftControl(phi)
    assert shift.angles(0.0) == pytest.approx(phi)
    assert shift.angles(DOOR.shift_period)[:-1] == pytest.approx(phi[1:])
    assert abs(shift.angles(DOOR.shift_period)[-1] - phi[-1]) < DOOR.shift_amplitude
    rates = [shift.rates(k * 0.05, 0.05) for k in range(40)]
    assert phi + 0.05 * np.sum(rates, axis=0) == pytest.approx(shift.angles(2.0))
    assert shift.angles(shift.duration) == pytest.approx(shift.angles(shift.duration + 10.0))  # used up
    assert not np.allclose(shift.angles(shift.duration - DOOR.shift_period), shift.angles(shift.duration))


def test_door_shift_phase_puts_every_wheel_on_the_floor():
    """§3.4.3 phase 3: shift control is planar, every wheel on the floor: the operator sends the shift's yaw
    rates as a planar command, so the pitch joints lower the raised head part (and any wheel phase 2 lifted)."""
    geometry, body = door_snake()
    p_h, _, psi = door_start()
    shift = Shift("shift", geometry)
    shift.reset(body.snapshot())
    for _ in range(40):
        command = shift.command(body.snapshot())
        assert "psi_dot" not in command and np.asarray(command["grounded"]).all()
        body.apply(command)
        body.step()
    assert np.abs(psi[1::2]).max() >= DOOR.raise_pitch
    assert np.abs(body.snapshot()["psi"][1::2]).max() < 0.05  # the raised head part is down
    assert body.mj.site_pos("head")[2] < 0.5 * p_h[2]  # the hook came down from the knob's height


def test_base_candidates_follow_the_rules():
    modes = base_candidates(10, 1, 4, 0)
    assert modes[:, 0].all() and modes[:, -1].all() and (modes.sum(1) >= 4).all()
    assert not (~modes[:, :-1] & ~modes[:, 1:]).any()  # no two adjacent lifted (n_c = 1)
    assert len(modes) == len({m.tobytes() for m in modes}) > 10


def test_handcart_starts_with_both_tips_raised_level_and_side_by_side():
    p_h, R_h, psi = handcart_initial()
    geometry = handcart_geometry()
    ch = chain_from_pose(np.concatenate((p_h, euler_zyx(R_h))), psi, geometry.l)
    head, tail = ch.P[0], ch.wheel_position(geometry.n)
    assert head[2] == pytest.approx(tail[2]) and head[2] > 0.08 and head[0] == pytest.approx(tail[0], abs=1e-6)
    base = [ch.wheel_position(i)[2] for i in range(HANDCART.n_h, HANDCART.n_t + 1)]
    assert base == pytest.approx([MUJOCO_SNAKE.wheel_radius] * len(base))
    model = double_arm_model(geometry, HANDCART.n_h, HANDCART.n_t, base_candidates(10, 1, 4, 0))
    A, B, c = model.matrices(ch.head_pose(), psi, np.ones(10, bool))
    assert A.shape == (19, 12) and B.shape == (19, 21) and len(model.inputs) == 21
    assert c[:3] == pytest.approx(head) and c[6:9] == pytest.approx(tail)


def test_physical_scenarios_are_registered_with_video():
    for sid in ("snake.caging", "snake.handcart", "snake.door"):
        assert get(sid).video
    with pytest.raises(ParameterError, match="runs"):
        get("snake.door").resolve({"runs": "-1"})
    assert get("snake.tracking").resolve({"plant": "mujoco"})["plant"] == "mujoco"


def test_kinematic_box_is_pushed_clear_of_the_body_and_only_as_far_as_needed():
    box = KinematicBox((0.0, 0.0))
    reach = box.reach
    box.push(np.array([[reach[0] - 0.01, 0.0], [1.0, 1.0]]))  # one point 1 cm inside the +x face
    assert box.xy == pytest.approx((-0.01, 0.0))
    box.push(np.array([[reach[0] + 0.05, 0.0]]))  # clear: nothing moves
    assert box.xy == pytest.approx((-0.01, 0.0))
    assert reach[0] > CAGING_BOX.half[0] + MUJOCO_SNAKE.tread / 2


def test_kinematic_caging_carries_the_box_with_the_u():
    """§3.4.1 on the kinematic plant: stage 1 closes the U's bottom onto the box, which then moves along."""
    done = run_rig(caging_rig(40.0, "kinematic"))
    run, track = TrackingRun.of(done), box_track(done)
    assert run.pos_error.max() < 0.01 and track["caged"].all()
    assert track["final"][0] - track["pos"][0][0] > 0.01  # pushed forward once the U closed on it


def test_handcart_double_arm_law_tracks_on_the_kinematic_plant():
    """§3.4.2 with §3.3's mode constants (n_c = 2): no stall; head and tail keep their offset; the cart moves."""
    run = handcart_series(run_rig(handcart_rig(12.0, "kinematic")))
    e = run["error"]
    assert max(np.linalg.norm(e[:, :3], axis=1).max(), np.linalg.norm(e[:, 6:9], axis=1).max()) < 1e-3
    assert not run["stopped"].any() and len(np.unique(run["mode"])) > 1
    offset = run["c"][:, :3] - run["c"][:, 6:9]
    assert np.linalg.norm(offset - offset[0], axis=1).max() < 1e-3
    assert run["c"][-1, 0] - run["c"][0, 0] == pytest.approx(0.5 * 12.0 / 120.0, abs=1e-3)


def test_door_pull_is_feasible_with_the_head_raised_as_in_the_thesis():
    """§3.4.3 phase 1 with head-raising control [12] (head-raised model (2.16)–(2.26)) on the kinematic plant:
    the hooked head follows the knob's whole 90° arc (here in 30 s) within the joint limits, never stopped."""
    result = pull_metrics(run_rig(pull_rig(30.0)))
    assert result["max_joint_rad"] < math.pi / 2 and result["stopped_fraction"] == 0.0
    assert result["max_pos_error_m"] < 1e-3


def test_a_modes_matrices_are_the_all_grounded_ones_without_the_lifted_rows():
    """T_σ (2.11), (2.35): spatial.SpatialTwoPoint.select builds B once and deletes rows; that equals building B_σ."""
    geometry = handcart_geometry()
    p_h, R_h, psi = handcart_initial()
    w_h = np.concatenate((p_h, euler_zyx(R_h)))
    modes = base_candidates(HANDCART.n_t - HANDCART.n_h + 1, 2, 4, 0, fixed=2)
    model = double_arm_model(geometry, HANDCART.n_h, HANDCART.n_t, modes)
    B = model.matrices(w_h, psi, np.ones(modes.shape[1], bool))[1]
    rest = np.ones(B.shape[0] - modes.shape[1], bool)
    for g in modes[::7]:
        assert np.array_equal(B[np.r_[g, rest]], model.matrices(w_h, psi, g)[1])
