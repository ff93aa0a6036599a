"""The stabilizer's compiled kernels are their own Python source bit for bit (no fast-math: the same IEEE operations in
the same order), on states of a standing HRP2 and over every option the module passes them."""

import itertools
import math

import numpy as np
import pytest

from shintai.core.geometry import wrap_pi
from shintai.humanoid.balance.foot_attitude import CONTACT_FZ
from shintai.humanoid.balance.stabilizer import FootSensors, distribution
from shintai.humanoid.balance.stabilizer_tick import (HAS_READ, OUT_SIZE, READ, READ_SUPPORT, READ_VEL, STATE_SIZE, _wrap_pi,
                                                      foot_wrench_rows, lip_tracking)
from shintai.humanoid.balance.standing import Standing


def _states(ticks=(0.2, 0.6)):
    """(the foot sensors, a CoM, a CoM reference) at a few instants of HRP2 stepping left (support changes)."""
    st = Standing(steps=[("l", 0.05, 0.1)])
    sensors, root = FootSensors(st.body), st.body.id("body", "waist")
    done = 0.0
    for t in ticks:
        st.run(t - done)
        done = t
        yield sensors, st.body.data.subtree_com[root].copy(), np.asarray(st.loop.command["com_ref"], float).copy()


def test_the_compiled_foot_wrenches_are_their_python_source_bit_for_bit():
    for sensors, _, _ in _states():
        compiled, source = np.zeros((2, 7)), np.zeros((2, 7))
        foot_wrench_rows(compiled, *sensors._arrays, sensors._index, sensors._weights)
        foot_wrench_rows.py_func(source, *sensors._arrays, sensors._index, sensors._weights)
        assert np.array_equal(compiled, source)
        assert compiled[:, 0].sum() > 100.0  # the feet carry the robot (N)


def test_the_compiled_lip_tracking_is_its_python_source_bit_for_bit_for_every_option():
    """Every reading, origin, support and LIP switch; from a fresh state (no reference, no reading held: the first
    tick) and from one holding a reading of another support; with both feet loaded and with none."""
    rng = np.random.default_rng(0)
    err = np.eye(3) + rng.normal(0.0, 0.01, (3, 3))  # an attitude error for the "imu" reading
    soles = np.array([[0.0, 0.1, 0.0], [0.0, -0.1, 0.0]])
    zr = np.array([0.01, -0.02])
    held = np.linspace(-0.1, 0.1, STATE_SIZE)
    held[9], held[14], held[15] = 1.0, 1.0, 1.0  # a reference and a reading of the left support held
    for (sensors, com, cr), code, lip, reading, ankle, start, loaded in itertools.product(
            _states(), (0.0, 1.0, -1.0), (True, False), (0, 1, 2), (False, True), (np.zeros(STATE_SIZE), held),
            (True, False)):
        w = sensors.read_rows().copy()
        if not loaded:
            w[:, 0] = 0.0  # no foot above the contact threshold: no measured ZMP, no LIP tracking
        ankles = w[:, 3:5] + 0.004
        results = []
        for kernel in (lip_tracking, lip_tracking.py_func):
            out, state = np.zeros(OUT_SIZE), start.copy()
            for k in range(3):  # three ticks: the filters' state carried
                kernel(out, state, w, com + 0.001 * k, cr, zr, soles, code, -4.0, -0.5, 0.3, 0.004, 0.9, CONTACT_FZ,
                       lip, reading, err, ankle, ankles, 0.01)
            results.append((out.copy(), state.copy()))
        (o1, s1), (o2, s2) = results
        assert np.array_equal(o1, o2, equal_nan=True) and np.array_equal(s1, s2)
        assert np.isfinite(o1[:2]).all() and o1[12] == float(lip and loaded)  # p_d; whether Eq. 26 ran


def test_the_compiled_wrap_is_core_geometrys_bit_for_bit():
    angles = np.concatenate([np.linspace(-20.0, 20.0, 4001), [math.pi, -math.pi, 2 * math.pi, -0.0, 0.0, 1e-300]])
    assert all(_wrap_pi(a) == wrap_pi(a) and math.copysign(1, _wrap_pi(a)) == math.copysign(1, wrap_pi(a))
               for a in angles.tolist())


def test_the_compiled_distributor_is_its_python_source_bit_for_bit():
    rng = np.random.default_rng(1)
    for k in range(300):
        px, py, lx, ly, rx, ry = rng.normal(0.0, 0.2, 6)
        if k % 7 == 0:
            lx, ly = rx, ry  # the feet on one point: α = ½
        args = (px, py, lx, ly, rx, ry, (0.0, 1.0, -1.0)[k % 3], 560.0)
        assert distribution(*args) == distribution.py_func(*args)


def _feet_tick(state, w, code, reading=1):
    out = np.zeros(OUT_SIZE)
    lip_tracking(out, state, w, np.array([0.01, 0.0, 0.8]), np.zeros(3), np.zeros(2), np.zeros((2, 3)), code, -4.0,
                 -0.5, 0.3, 0.004, 0.9, CONTACT_FZ, True, reading, np.eye(3), False, np.zeros((2, 2)), 0.0)
    return out


def test_the_feet_reading_restarts_its_velocity_when_the_support_changes():
    """The "feet" reading's velocity is the filtered difference of the CoM's offset from the stance feet: across a
    change of the stance (another frame origin) it is held, not differenced, and the next tick differences again."""
    w = np.zeros((2, 7))
    w[:, 0], w[0, 4], w[1, 4] = 300.0, 0.1, -0.1  # both feet loaded, a sole point each
    state = np.zeros(STATE_SIZE)
    state[HAS_READ], state[READ_SUPPORT], state[READ], state[READ_VEL] = 1.0, 1.0, 0.5, 0.2  # a left-support reading
    _feet_tick(state, w, 0.0)
    assert state[READ_VEL] == 0.2 and state[READ_SUPPORT] == 0.0  # held over the change to double support
    x0 = state[READ]
    w[:, 3] -= 0.001  # the feet 1 mm back: the CoM's offset 1 mm more ahead
    _feet_tick(state, w, 0.0)
    assert state[READ] - x0 == pytest.approx(0.001)
    assert state[READ_VEL] == pytest.approx(0.9 * 0.2 + 0.1 * 0.001 / 0.004)


def test_a_foot_at_the_contact_threshold_is_not_in_the_measured_zmp():
    w = np.zeros((2, 7))
    w[0, 0], w[1, 0], w[0, 4], w[1, 4] = 300.0, CONTACT_FZ, 0.1, -0.1
    out = _feet_tick(np.zeros(STATE_SIZE), w, 0.0, reading=0)
    assert out[3] == pytest.approx(0.1)  # the measured ZMP on the left sole alone
