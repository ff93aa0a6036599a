"""Interpolation and the seqplugin sequence player (seed 003 §6.3.4, App. C.2.2)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shintai.core.benchmarks import NullBody
from shintai.core.interpolation import (
    Segment,
    SequencePlayer,
    minimum_jerk,
    via_velocity,
)
from shintai.core.runtime import Loop

finite = st.floats(-5, 5, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(finite, finite, finite, finite, finite, finite, st.floats(0.05, 10))
def test_quintic_meets_its_boundary_conditions(x0, v0, a0, xf, vf, af, T):
    seg = Segment.minjerk(x0, v0, a0, xf, vf, af, T)
    got = seg.state(0.0) + seg.state(T)
    for g, w in zip(got, (x0, v0, a0, xf, vf, af)):
        assert float(g) == pytest.approx(w, abs=1e-8 * (1 + abs(w)) * max(1, 1 / T**2))


def test_rest_to_rest_profile_is_the_textbook_one():
    """x = x0 + Δ(10τ³ − 15τ⁴ + 6τ⁵); peak velocity 1.875 Δ/T at τ = 0.5 (spec §2.3.6)."""
    seg = Segment.minjerk(0, 0, 0, 2.0, 0, 0, 4.0)
    x, v, a = seg.state(2.0)
    assert float(x) == pytest.approx(1.0) and float(v) == pytest.approx(1.875 * 2 / 4) and abs(float(a)) < 1e-12


def test_queue_runs_in_order_and_arrives_on_time():
    p = SequencePlayer([0.0])
    p.push([1.0], 0.5)
    p.push([3.0], 0.5)  # given during the first motion: queued, not overwriting
    p.advance(0.5)
    assert p.x[0] == pytest.approx(1.0) and p.busy
    p.advance(0.5)
    assert p.x[0] == pytest.approx(3.0) and not p.busy
    assert p.v[0] == 0.0  # minjerk: zero velocity at every posture


def test_an_idle_player_holds_at_rest_without_allocating_and_restarts_from_rest():
    p = SequencePlayer([0.0, 2.0])
    p.push([1.0, 1.0], 0.5)
    p.advance(0.3)
    assert p.v.any()  # moving
    held = p.advance(0.3)  # arrives, then idles
    assert np.array_equal(held, [1.0, 1.0]) and not p.busy
    rest_v, rest_a = p.v, p.a
    for _ in range(3):
        out = p.advance(0.004)
        out[0] = 99.0  # the position handed out is the caller's copy
        assert p.v is rest_v and p.a is rest_a  # the same held zeros every idle tick
    assert not rest_v.any() and not rest_a.any() and np.array_equal(p.x, [1.0, 1.0])
    with pytest.raises(ValueError):
        rest_v[0] = 1.0  # shared, so read-only
    x, v, a = p.state
    v[0] = 1.0  # state is a copy, writable
    p.push([0.0, 0.0], 1.0)  # re-planned from rest: the textbook rest-to-rest quintic
    x0, v0, a0 = p.segment.state(0.0)
    assert np.array_equal(x0, [1.0, 1.0]) and not v0.any() and not a0.any()
    p.advance(0.5)
    assert np.allclose(p.x, [0.5, 0.5])


def test_clear_replans_from_the_current_state():
    p = SequencePlayer([0.0, 0.0])
    p.push([1.0, 1.0], 1.0)
    p.push([5.0, 5.0], 1.0)
    p.advance(0.4)
    x, v, a = p.state
    p.push([-1.0, 0.0], 0.8, clear=True)
    x2, v2, a2 = p.segment.state(0.0)
    assert np.allclose(x, x2) and np.allclose(v, v2) and np.allclose(a, a2)
    assert len(p.queue) == 0
    p.advance(0.8)
    assert np.allclose(p.x, [-1.0, 0.0])


def test_via_velocity_and_minjerksequence():
    # Fig. C.1 values: (0,0), (250,60), (350,120), (600,60), (850,0) in ms
    assert via_velocity(0, 60, 120, 0.25, 0.1)[()] > 0  # monotone run: non-zero
    assert via_velocity(60, 120, 60, 0.1, 0.25)[()] == 0  # turning point: zero
    p = SequencePlayer([0.0], method="minjerksequence")
    for x, T in ((60, 0.25), (120, 0.1), (60, 0.25), (0, 0.25)):
        p.push([x], T)
    p.advance(0.25)
    assert p.x[0] == pytest.approx(60) and p.v[0] > 0
    p.advance(0.6)
    assert p.x[0] == pytest.approx(0) and not p.busy


def test_explicit_via_velocity_and_method_switching():
    p = SequencePlayer([0.0])
    p.push([1.0], 1.0, velocity=[0.5])
    p.push([2.0], 1.0)
    p.advance(1.0)
    assert p.v[0] == pytest.approx(0.5)
    p.switch("linear")
    p.push([0.0], 1.0, clear=True)
    p.advance(0.5)
    assert p.x[0] == pytest.approx(0.5) and p.v[0] == pytest.approx(-1.0)
    with pytest.raises(ValueError, match="unknown interpolation method"):
        p.switch("spline")


def test_bad_targets_are_refused():
    p = SequencePlayer([0.0, 0.0])
    with pytest.raises(ValueError, match="2 DOF"):
        p.push([1.0], 1.0)
    with pytest.raises(ValueError, match="finite"):
        p.push([np.nan, 0.0], 1.0)
    with pytest.raises(ValueError, match="positive"):
        p.push([1.0, 1.0], 0.0)


def test_player_as_a_module_in_the_loop():
    body = NullBody(dt=0.001)
    p = SequencePlayer([0.0], channel="u", period=0.004)
    p.push([1.0], 0.1)
    Loop(body, [p]).run(0.2)
    assert body.command["u"][0] == pytest.approx(1.0)


def test_a_player_takes_its_minjerksequence_via_rule():
    """nervous's seqplugin passes its own rule at intermediate postures (App. C.2.2)."""
    calls = []

    def rule(x_prev, x_via, x_next, T_in, T_out):
        calls.append((float(x_prev[0]), float(x_via[0]), float(x_next[0])))
        return np.full(1, 7.0)

    p = SequencePlayer([0.0], method="minjerksequence", via=rule)
    p.push([60.0], 0.25)
    p.push([120.0], 0.1)
    assert calls == [(0.0, 60.0, 120.0)]
    p.advance(0.25)
    assert np.allclose(p.state[1], 7.0)


def test_minimum_jerk_profile_is_the_rest_to_rest_quintic():
    seg = Segment.minjerk(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0)
    for s in np.linspace(0.0, 1.0, 11):
        assert minimum_jerk(s) == pytest.approx(float(seg.state(s)[0][()]), abs=1e-12)
    assert minimum_jerk(0.0) == 0.0 and minimum_jerk(1.0) == 1.0 and minimum_jerk(0.5) == 0.5
