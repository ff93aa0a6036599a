"""Kinematic plant (the thesis's model (2.10) as a Body)."""

import numpy as np
import pytest

from shintai.core.integrators import rk4_constant_rate_floats
from shintai.core.runtime import ADD, SET, ChannelError, FunctionModule, Loop, SimulationDiverged
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, TRACKING, PlantSettings
from shintai.snake.model import configuration, constraint_terms, lateral_velocities
from shintai.snake.plant import KinematicSnake
from shintai.snake.two_point import candidate_modes

MODES = candidate_modes(9, 4, 4, 2)
L = CH3_ROBOT.l


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


def reference_step(w_h, phi, u, grounded, dt, steps):
    """One δt of (2.10) written with the shared helpers: the closed-form rows, np.linalg.lstsq, the float RK4."""
    def head_rate(w, q):
        A, b = constraint_terms(w[2], np.array(q), L, u)
        return np.linalg.lstsq(A[grounded], b[grounded], rcond=None)[0].tolist()

    w, q = rk4_constant_rate_floats(head_rate, list(w_h), list(phi), list(u), dt / steps, steps)
    return np.array(w), np.array(q)


@pytest.mark.parametrize("rk4_steps", [1, 2, 3])
def test_the_compiled_step_is_the_rk4_of_the_model_bit_for_bit(rk4_steps):
    """KinematicSnake.step (a compiled loop) gives the bits of the RK4 of A_σ^† B_σ φ̇ written in NumPy."""
    rng = np.random.default_rng(rk4_steps)
    body = KinematicSnake([0.1, -0.2, 2.0], rng.uniform(-1, 1, 9), settings=PlantSettings(rk4_steps))
    for k in range(10):
        u, g = rng.normal(size=9), MODES[rng.integers(len(MODES))] if k % 3 else rng.random(9) < 0.5
        expected = reference_step(body.w_h, body.phi, u, g, body.dt, rk4_steps)
        body.apply({"phi_dot": u, "grounded": g.astype(float)})
        body.step()
        assert np.array_equal(body.w_h, expected[0]) and np.array_equal(body.phi, expected[1])


def test_a_non_finite_state_is_an_error():
    body = KinematicSnake([0.0, 0.0, 1.0], np.zeros(9))
    body.apply({"phi_dot": np.full(9, 1e308)})
    with pytest.raises((SimulationDiverged, np.linalg.LinAlgError)):
        body.step()


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


def test_without_numpys_lapack_the_plant_steps_in_numpy_to_the_same_bits(monkeypatch):
    """Where NumPy's LAPACK is not reachable from compiled code (linalg.DGELSD None: Accelerate, a distribution's
    LAPACK) the plant steps by the Python RK4 and np.linalg's gufunc — the same numbers as the compiled loop."""
    import shintai.snake.plant as plant
    from shintai.snake.linalg import DGELSD

    if DGELSD is None:
        pytest.skip("this NumPy's LAPACK is not reachable from compiled code: the plant steps in NumPy already")
    rng = np.random.default_rng(7)
    phi0 = rng.uniform(-1, 1, 9)
    compiled = KinematicSnake([0.1, -0.2, 2.0], phi0, settings=PlantSettings(2))
    monkeypatch.setattr(plant, "DGELSD", None)
    fallback = KinematicSnake([0.1, -0.2, 2.0], phi0, settings=PlantSettings(2))
    for k in range(10):
        command = {"phi_dot": rng.normal(size=9), "grounded": MODES[k % len(MODES)].astype(float)}
        for body, lapack in ((fallback, None), (compiled, DGELSD)):
            monkeypatch.setattr(plant, "DGELSD", lapack)
            body.apply(command)
            body.step()
        assert np.array_equal(compiled.w_h, fallback.w_h) and np.array_equal(compiled.phi, fallback.phi)
        assert compiled.slip == fallback.slip
