"""seqplugin (§6.3.4, App. C.2.2): propocmd's arguments and options, the queue, :clear, methods, the
minjerksequence velocity at queued postures, @ID → done, and bad commands that change nothing."""

import numpy as np
import pytest
from nervous_support import run, ticks

from shintai.nervous.commands import Client
from shintai.nervous.nerve import Nerve
from shintai.nervous.plugins.sequence import balanced_velocity

FIG_C1 = [(250, 60.0), (350, 120.0), (600, 60.0), (850, 0.0)]  # App. C.2.2: (time [ms], position)


def queue_fig_c1(nerve, method, via="balanced"):
    run(nerve, [f"sequence switch {method}", f"sequence via {via}"])
    last = 0
    for t, x in FIG_C1:
        assert run(nerve, [f"sequence propocmd #f({x} 0 0) {t - last}"]) == ["ok"]
        last = t


def trace(nerve, packets):
    """The target sent at 0, 1, 2, … ms (a packet's ``reference`` is what was sent at the packet before)."""
    out = []
    for _ in range(packets):
        nerve.tick()
        out.append(nerve.state()["reference"][0])
    return np.array(out)


def test_the_default_time_is_one_millisecond(nerve):
    """C.2.1: `sequence propocmd #f(0 1 2) 1` moves the 3 DOF to 0, 1, 2 in 1 ms; 1 is also the default."""
    assert run(nerve, ["sequence propocmd #f(0 1 2)"]) == ["ok"]
    ticks(nerve, 2)  # sent at 0 ms: the start; at 1 ms: the target
    assert np.allclose(nerve.state()["reference"], [0, 1, 2])


@pytest.mark.parametrize("method", ["minjerk", "minjerksequence", "linear"])
def test_fig_c1_targets_are_reached_on_time(nerve, method):
    queue_fig_c1(nerve, method)
    x = trace(nerve, 851)
    assert np.allclose(x[[t for t, _ in FIG_C1]], [p for _, p in FIG_C1], atol=1e-9)


def test_minjerk_stops_at_every_posture_and_minjerksequence_does_not(nerve):
    """C.2.2: with minjerk (and linear) the velocity is 0 at each posture boundary; with minjerksequence a
    posture second or later in the queue gets a non-zero velocity "balanced with the previous entry"."""
    queue_fig_c1(nerve, "minjerk")
    v = np.gradient(trace(nerve, 851), 1e-3)
    assert np.all(np.abs(v[[250, 350, 600]]) < 1.0)  # deg/s: 0 up to the 1 ms central difference
    seq = Nerve("arm3", "dummy")
    run(seq, ["load-plugin sequence", "create-plugin sequence sequence", "start sequence"])
    queue_fig_c1(seq, "minjerksequence")
    v = np.gradient(trace(seq, 851), 1e-3)
    assert np.all(np.abs(v[[250, 350, 600]]) > 50.0)
    assert abs(v[-1]) < 1.0


def test_the_turning_rule_stops_at_a_peak():
    assert balanced_velocity(60.0, 120.0, 60.0, 0.1, 0.25) == pytest.approx((600 * 0.25 - 240 * 0.1) / 0.35)
    n = Nerve("arm3", "dummy")
    run(n, ["load-plugin sequence", "create-plugin sequence sequence via=turning", "start sequence"])
    queue_fig_c1(n, "minjerksequence", via="turning")
    x = trace(n, 851)
    v = np.gradient(x, 1e-3)
    assert abs(v[350]) < 1.0 and abs(v[250]) > 50.0
    assert x.max() <= 120.0 + 1e-9  # no overshoot at the peak


def test_postures_queue_and_clear_flushes_them(nerve):
    c = Client()
    run(nerve, ["sequence propocmd #f(10 0 0) 10 @a", "sequence propocmd #f(20 0 0) 10 @b"], c)
    ticks(nerve, 5)
    run(nerve, ["sequence propocmd #f(0 5 0) 4 :clear @c"], c)
    assert c.received == ["done a cleared", "done b cleared"]
    ticks(nerve, 5)
    assert np.allclose(nerve.state()["reference"], [0, 5, 0])
    assert c.received[-1] == "done c"


def test_with_velocity_sets_the_velocity_at_the_posture(nerve):
    run(nerve, ["sequence propocmd #f(10 0 0) 100 :with-velocity #f(50 0 0)", "sequence propocmd #f(20 0 0) 100"])
    x = trace(nerve, 201)
    assert np.gradient(x, 1e-3)[100] == pytest.approx(50.0, rel=0.01)


def test_bad_commands_change_nothing(nerve):
    run(nerve, ["sequence propocmd #f(10 20 30) 50"])
    ticks(nerve, 10)
    before = (nerve.state()["reference"].copy(), nerve.instances["sequence"].plugin.describe())
    bad = ["sequence propocmd #f(1 2)", "sequence propocmd #f(1 2 3 4)", "sequence propocmd #f(1 2 400)",
           "sequence propocmd #f(1 2 3) 0", "sequence propocmd #f(1 2 3) -5", "sequence propocmd #f(1 2 3) nan",
           "sequence propocmd #f(1 2 3) 10 :bogus", "sequence propocmd #f(1 2 3) 10 :with-velocity",
           "sequence propocmd #f(1 2 3) 10 :with-velocity #f(1)", "sequence propocmd", "sequence propocmd 1 2 3",
           "sequence switch cubic", "sequence propocmd #f(1 2 3) 10 :clear @bad/id"]
    for line in bad:
        (reply,) = run(nerve, [line])
        assert reply.startswith("error: "), line
        assert np.array_equal(nerve.state()["reference"], before[0])
        assert nerve.instances["sequence"].plugin.describe() == before[1], line
    assert run(nerve, ["sequence propocmd #f(1 2 400)"])[0] == \
        "error: propocmd target: j2 = 400 deg is outside its limits [-150, 150]"


def test_angle_vector_needs_a_running_sequence(nerve):
    run(nerve, ["stop sequence"])
    assert run(nerve, ["sequence propocmd #f(1 2 3) 10", "(send *ns* :angle-vector #f(1 2 3))"]) == [
        "error: sequence is not running (start sequence): App. C.2.2, without a running seqplugin :angle-vector "
        "cannot be executed", "error: sequence is not running (start sequence)"]
    c = Client()
    run(nerve, ["start sequence", "sequence propocmd #f(5 5 5) 100 @m"], c)
    ticks(nerve, 3)
    run(nerve, ["stop sequence"], c)
    assert c.received == ["done m stopped"]
