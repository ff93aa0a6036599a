"""The stabilizer's compiled kernels are their own Python source bit for bit (no fast-math: the same IEEE operations in
the same order), on states of a standing HRP2 and over every option the module passes them."""

import itertools
import math

import numpy as np

from shintai.humanoid.balance.foot_attitude import CONTACT_FZ
from shintai.humanoid.balance.stabilizer import FootSensors, distribution
from shintai.humanoid.balance.stabilizer_tick import OUT_SIZE, STATE_SIZE, foot_wrench_rows, lip_tracking
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
    rng = np.random.default_rng(0)
    err = np.eye(3) + rng.normal(0.0, 0.01, (3, 3))  # an attitude error for the "imu" reading
    soles = np.array([[0.0, 0.1, 0.0], [0.0, -0.1, 0.0]])
    zr = np.array([0.01, -0.02])
    for (sensors, com, cr), code, lip, reading, ankle in itertools.product(
            _states(), (0.0, 1.0, -1.0), (True, False), (0, 1, 2), (False, True)):
        w = sensors.read_rows().copy()
        ankles, dx = (w[:, 3:5] + 0.004, 0.01) if ankle else (np.zeros((2, 2)), math.nan)
        results = []
        for kernel in (lip_tracking, lip_tracking.py_func):
            out, state = np.zeros(OUT_SIZE), np.linspace(-0.1, 0.1, STATE_SIZE)
            state[9], state[14], state[15] = 1.0, 1.0, code  # a reference and a reading of the same support held
            for k in range(3):  # three ticks: the filters' state carried
                kernel(out, state, w, com + 0.001 * k, cr, zr, soles, code, -4.0, -0.5, 0.3, 0.004, 0.9, CONTACT_FZ,
                       lip, reading, err, ankles, dx)
            results.append((out.copy(), state.copy()))
        (o1, s1), (o2, s2) = results
        assert np.array_equal(o1, o2, equal_nan=True) and np.array_equal(s1, s2)
        assert np.isfinite(o1[:2]).all()  # p_d


def test_the_compiled_distributor_is_its_python_source_bit_for_bit():
    rng = np.random.default_rng(1)
    for k in range(300):
        px, py, lx, ly, rx, ry = rng.normal(0.0, 0.2, 6)
        if k % 7 == 0:
            lx, ly = rx, ry  # the feet on one point: α = ½
        args = (px, py, lx, ly, rx, ry, (0.0, 1.0, -1.0)[k % 3], 560.0)
        assert distribution(*args) == distribution.py_func(*args)
