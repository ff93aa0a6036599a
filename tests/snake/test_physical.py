"""Applications of §3.4 on the MuJoCo snake (scenarios_physical.py): targets, caging, door, handcart set-up."""

import math
from dataclasses import replace

import numpy as np
import pytest

from shintai.core import Loop, Recorder
from shintai.scenarios.registry import ParameterError, get
from shintai.snake.constants import CAGING, CH3_GAINS, DOOR, HANDCART, MUJOCO_SNAKE
from shintai.snake.model3d import chain_from_pose, euler_zyx
from shintai.snake.mujoco_plant import MujocoSnake
from shintai.snake.scenarios_physical import (
    DoorOperator,
    ShiftControl,
    Waypoints,
    base_candidates,
    caging_targets,
    door_geometry,
    door_scene,
    double_arm_model,
    handcart_geometry,
    handcart_initial,
    knob_point,
    simulate_caging,
)
from shintai.snake.two_point import TwoPointLaw


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
        Waypoints.through((0.0, 0.0), (c0, c0))


def test_short_caging_run_keeps_the_box_in_the_u():
    recorder = Recorder()
    run, track = simulate_caging(3.0, recorder=recorder)
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


def test_door_phase_1_hooks_the_knob_and_starts_to_open_the_door():
    """A short run of the §3.4.3 operator: the head reaches the knob, the hook engages, the door opens."""
    knob = knob_point(0.0)
    geometry = door_geometry()
    law = TwoPointLaw(geometry, replace(CH3_GAINS, n_c=DOOR.n_c))
    body = MujocoSnake([knob[0] - DOOR.approach_gap, knob[1], math.pi], DOOR.phi0, geometry, scene=door_scene(),
                       head_pose="model")
    operator = DoorOperator(body, law)
    Loop(body, [operator], Recorder()).run(DOOR.t_approach + 6.0)
    phases = [phase for _, phase in operator.events]
    assert phases == ["pull"] and operator.events[0][0] <= DOOR.t_approach + 0.5
    assert body.mj.data.eq_active[body.mj.id("equality", "hook")]
    assert 0.02 < body.mj.joint_qpos("hinge") < 0.3  # opening, following the slow arc
    assert operator.hook_distance() < 0.01


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
