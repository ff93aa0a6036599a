"""Kinematic plant (the thesis's model (2.10) as a Body)."""

import numpy as np
import pytest

from shintai.core.runtime import ADD, SET, ChannelError, FunctionModule, Loop
from shintai.snake.constants import CH3_GAINS, TRACKING, PlantSettings
from shintai.snake.model import configuration, lateral_velocities
from shintai.snake.plant import KinematicSnake
from shintai.snake.two_point import candidate_modes

MODES = candidate_modes(9, 4, 4, 2)


def stepped(phi, u, grounded, rk4_steps):
    body = KinematicSnake([0.0, 0.0, np.pi], phi, settings=PlantSettings(rk4_steps))
    body.apply({"phi_dot": u, "grounded": grounded.astype(float)})
    body.step()
    return body


def test_rk4_steps_are_converged_at_the_input_limit():
    """The chosen 2 RK4 steps per δt agree with 200 steps to 1e−5 m at ‖u‖ = u_lim (worst case)."""
    rng = np.random.default_rng(0)
    worst = 0.0
    for _ in range(20):
        phi = rng.uniform(-1, 1, 9)
        u = rng.normal(size=9)
        u *= CH3_GAINS.u_lim / np.linalg.norm(u)
        g = MODES[rng.integers(len(MODES))]
        worst = max(worst, np.abs(stepped(phi, u, g, 2).w_h - stepped(phi, u, g, 200).w_h).max())
    assert worst < 1e-5


def test_zero_input_leaves_the_state_unchanged():
    body = stepped(np.array(TRACKING.phi0), np.zeros(9), MODES[3], 2)
    assert np.array_equal(body.w_h, TRACKING.w_h0) and np.array_equal(body.phi, TRACKING.phi0)
    assert body.t == CH3_GAINS.dt and body.slip == 0.0


def test_consistent_input_has_no_slip_and_head_follows_the_constraints():
    """With three grounded wheels A_σ is square: the head velocity is the exact solution, slip 0."""
    rng = np.random.default_rng(1)
    phi = rng.uniform(-1, 1, 9)
    u = 0.3 * rng.normal(size=9)
    grounded = np.zeros(9, bool)
    grounded[[0, 3, 6]] = True
    body = KinematicSnake([0.0, 0.0, 1.0], phi)
    body.apply({"phi_dot": u, "grounded": grounded})
    w_dot, residual = body.head_velocity(body.w_h, body.phi)
    v = lateral_velocities(configuration(body.w_h, body.phi, body.geometry.l), w_dot, u)
    assert np.abs(residual).max() < 1e-12 and np.abs(v[grounded]).max() < 1e-12
    body.step()
    assert body.slip < 1e-12


def test_inconsistent_input_reports_slip():
    """All 9 wheels grounded and arbitrary joint rates: the constraints cannot all hold → slip > 0."""
    body = KinematicSnake([0.0, 0.0, 1.0], np.random.default_rng(2).uniform(-1, 1, 9))
    body.apply({"phi_dot": np.ones(9), "grounded": np.ones(9)})
    body.step()
    assert body.slip > 1e-3


def test_snapshot_layout():
    body = KinematicSnake(TRACKING.w_h0, TRACKING.phi0)
    snap = body.snapshot()
    assert set(snap) == {"t", "w_h", "phi", "psi", "grounded", "slip"}
    assert snap["psi"].shape == (17,) and np.array_equal(snap["psi"][::2], TRACKING.phi0)
    assert not snap["psi"][1::2].any()  # pitch joints are 0 in the plane (§2.3)
    assert snap["grounded"].all()


@pytest.mark.parametrize("command, msg", [
    ({"phi_dot": np.zeros(8)}, "phi_dot must have n = 9"),
    ({"phi_dot": np.zeros(9), "grounded": np.full(9, 0.5)}, "0/1"),
])
def test_bad_commands_are_one_clear_error(command, msg):
    with pytest.raises(ValueError, match=msg):
        KinematicSnake(TRACKING.w_h0, TRACKING.phi0).apply(command)


def test_a_command_to_an_undeclared_channel_is_a_channel_error():
    body = KinematicSnake(TRACKING.w_h0, TRACKING.phi0)
    assert body.channels["grounded"].kind == SET and body.channels["phi_dot"].kind == ADD
    with pytest.raises(ChannelError, match="undeclared channel 'torque'"):
        Loop(body, [FunctionModule(lambda s: {"torque": np.zeros(9)})]).step()


def test_bad_construction_is_one_clear_error():
    with pytest.raises(ValueError, match="n = 9 yaw angles"):
        KinematicSnake(TRACKING.w_h0, np.zeros(8))
    with pytest.raises(ValueError, match="rk4_steps"):
        PlantSettings(0)
