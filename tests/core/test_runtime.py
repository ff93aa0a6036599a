"""Runtime: multi-rate Loop (contributions add, held between updates), Switcher, recorder."""

import numpy as np
import pytest

from shintai.core import Loop, Module, Recorder, SimulationDiverged, Switcher
from shintai.core.benchmarks import NullBody
from shintai.core.runtime import FunctionModule


class Counter(Module):
    def __init__(self, name, period=None, value=1.0):
        super().__init__(name, period)
        self.calls, self.value, self.resets = 0, value, 0

    def reset(self, snapshot):
        self.resets += 1

    def update(self, snapshot):
        self.calls += 1
        self.log(snapshot["t"], **{self.name: self.calls})
        return {"u": np.array([self.value])}


def test_modules_run_at_their_own_period_and_contributions_add():
    body = NullBody(dt=0.001)
    fast, slow = Counter("fast"), Counter("slow", period=0.005, value=10.0)
    loop = Loop(body, [fast, slow], recorder=Recorder())
    loop.run(0.02)
    assert fast.calls == 20 and slow.calls == 4
    # the slow module's contribution is held between its updates: the sum is always 11
    assert body.command["u"][0] == pytest.approx(11.0)
    assert loop.timing["slow"].calls == 4 and loop.timing["fast"].mean_us > 0
    assert loop.recorder.times("slow").tolist() == pytest.approx([0.0, 0.005, 0.01, 0.015])


def test_period_must_be_a_multiple_of_the_body_step():
    with pytest.raises(ValueError, match="whole multiple"):
        Loop(NullBody(dt=0.004), [Counter("a", period=0.006)])


def test_base_command_and_duplicate_names():
    body = NullBody()
    loop = Loop(body, [Counter("a")], base={"u": [5.0]})
    loop.step()
    assert body.command["u"][0] == 6.0
    with pytest.raises(ValueError, match="unique"):
        Loop(body, [Counter("a"), Counter("a")])


def test_switcher_runs_exactly_one_module_and_logs_transitions():
    body = NullBody(dt=0.01)
    drive, recover = Counter("drive", value=1.0), Counter("recover", value=-1.0)
    sw = Switcher([drive, recover], [("drive", "recover", lambda s: 0.05 - 1e-9 <= s["t"] < 0.08 - 1e-9),
                                     ("recover", "drive", lambda s: s["t"] >= 0.08 - 1e-9)])
    loop = Loop(body, [sw])
    seen = []
    for _ in range(12):
        loop.step()
        seen.append(body.command["u"][0])
    assert seen == [1.0] * 5 + [-1.0] * 3 + [1.0] * 4
    assert drive.calls + recover.calls == 12  # never both in one tick
    assert [(round(t, 3), a, b) for t, a, b in sw.transitions_log] == [(0.05, "drive", "recover"),
                                                                        (0.08, "recover", "drive")]
    assert recover.resets == 1 and drive.resets == 2  # activated = reset (initial + return)


def test_switcher_rejects_unknown_names():
    with pytest.raises(ValueError, match="unknown module"):
        Switcher([Counter("a")], [("a", "b", lambda s: True)])


def test_divergence_propagates_and_recorder_keeps_what_was_logged():
    class Exploding(NullBody):
        def step(self):
            super().step()
            if self.t > 0.0035:
                raise SimulationDiverged(f"state is NaN at t={self.t:.4f}")

    rec = Recorder()
    loop = Loop(Exploding(), [FunctionModule(lambda s: None, name="f"), Counter("c")], recorder=rec)
    with pytest.raises(SimulationDiverged, match="NaN"):
        loop.run(1.0)
    assert len(rec.values("c")) == 4


def test_recorder_roundtrip(tmp_path):
    rec = Recorder()
    for k in range(3):
        rec.record(0.1 * k, x=[k, 2 * k], y=k)
    rec.save(tmp_path / "log.npz")
    data = np.load(tmp_path / "log.npz")
    assert data["x"].shape == (3, 2) and data["y_t"].tolist() == pytest.approx([0, 0.1, 0.2])


# --- composition rules (DESIGN.md): declared channels, set channels, stages, run(until=, every=) ---------------

from shintai.core.runtime import ADD, SET, Channel, ChannelError, declare  # noqa: E402


class Writes(Module):
    """Contributes ``value`` to ``channel`` and remembers what it saw of ``reads``."""

    def __init__(self, name, channel, value, reads=None, period=None):
        super().__init__(name, period)
        self.channel, self.value, self.reads, self.seen = channel, value, reads, []

    def update(self, snapshot):
        if self.reads is not None:
            self.seen.append(None if self.reads not in snapshot else float(np.asarray(snapshot[self.reads])))
        return {self.channel: self.value(snapshot) if callable(self.value) else self.value}


def test_a_command_to_an_undeclared_channel_is_one_error_naming_it():
    loop = Loop(NullBody(), [Writes("typo", "uu", 1.0)])
    with pytest.raises(ChannelError, match="'typo' writes undeclared channel 'uu'.*body channels: u"):
        loop.step()
    with pytest.raises(ChannelError, match="base writes undeclared channel 'v'"):
        Loop(NullBody(), [], base={"v": 1.0})


def test_channel_declarations_are_checked():
    with pytest.raises(ChannelError, match="kind must be"):
        Channel("x", kind="max")
    with pytest.raises(ChannelError, match="delay"):
        Channel("x", delay=-1)
    with pytest.raises(ChannelError, match="declared twice"):
        Loop(NullBody(), [], channels=[Channel("u")])  # already a body channel
    with pytest.raises(ValueError, match="not both"):
        Loop(NullBody(), [Counter("a")], stages=[[Counter("b")]])


def test_a_set_channel_takes_exactly_one_writer():
    body = NullBody()
    body.channels = {**declare("u"), **declare("mode", kind=SET)}
    seen = []
    body.apply = lambda command: seen.append(command["mode"].copy())
    loop = Loop(body, [Writes("a", "mode", 2.0), Writes("b", "u", 1.0)])
    loop.step()
    assert seen[-1] == 2.0  # the writer's value, not a sum
    two = Loop(body, [Writes("a", "mode", 2.0), Writes("b", "mode", 3.0)])
    with pytest.raises(ChannelError, match="'mode' has two writers in one tick: 'a' and 'b'"):
        two.step()
    # a held (slow) writer still counts as the writer between its updates
    held = Loop(body, [Writes("slow", "mode", 1.0, period=0.005), Writes("late", "mode", 1.0, period=0.005)])
    with pytest.raises(ChannelError, match="two writers"):
        held.step()


def test_a_later_stage_sees_an_earlier_stages_set_point_in_the_same_tick():
    body = NullBody(dt=0.001)
    planner = Writes("planner", "ref", lambda s: 10.0 * s["t"])
    controller = Writes("controller", "u", 0.0, reads="ref")
    loop = Loop(body, stages=[[planner], [controller]], channels=[Channel("ref", SET)])
    for _ in range(3):
        loop.step()
    assert controller.seen == pytest.approx([0.0, 0.01, 0.02])  # this tick's set-point, no delay
    assert "ref" not in body.command  # loop channels never reach the body
    # in the same stage the set-point is not yet there: stages carry the order, module order does not
    same = Writes("controller", "u", 0.0, reads="ref")
    Loop(NullBody(), [same, Writes("planner", "ref", 1.0)], channels=[Channel("ref", SET)]).step()
    assert same.seen == [None]


def test_a_declared_delay_shows_the_value_that_many_ticks_later():
    body = NullBody(dt=0.001)
    writer = Writes("writer", "ref", lambda s: round(s["t"] * 1000) + 1.0)
    reader = Writes("reader", "u", 0.0, reads="ref")
    loop = Loop(body, [writer, reader], channels=[Channel("ref", ADD, delay=2, default=0.0)])
    for _ in range(5):
        loop.step()
    assert reader.seen == [0.0, 0.0, 1.0, 2.0, 3.0]


def test_run_until_a_time_or_a_predicate_with_decimated_hooks():
    body = NullBody(dt=0.01)
    loop = Loop(body, [Counter("a")])
    ticks = []
    assert loop.run(until=0.1, every={3: lambda s: ticks.append(round(s["t"], 6))}) == 10
    assert ticks == [0.0, 0.03, 0.06, 0.09]
    assert body.t == pytest.approx(0.1)
    # snapshots at t = 0.10, 0.11, ...: the sixth (0.15) is the first that holds; the run stops after its step
    assert loop.run(1.0, until=lambda s: s["t"] >= 0.145) == 6
    with pytest.raises(ValueError, match="at least one step"):
        loop.run(0.1, every={0: print})
    with pytest.raises(ValueError, match="duration or until"):
        loop.run(until=lambda s: True)


def test_restage_adds_and_removes_modules_between_ticks_without_resetting_the_others():
    """nervous starts and stops plugins while its loop runs (seed 003 §6.3.4)."""
    from shintai.core.benchmarks import NullBody

    resets = []

    class Counter(Module):
        def reset(self, snapshot):
            resets.append(self.name)
            self.n = 0

        def update(self, snapshot):
            self.n += 1
            return {"u": np.full(1, float(self.n))}

    a, b = Counter("a"), Counter("b")
    loop = Loop(NullBody(), [a])
    loop.run(3 * loop.body.dt)
    assert resets == ["a"] and a.n == 3
    loop.restage([[a, b]])
    assert resets == ["a", "b"]  # only the new one is reset
    loop.step()
    assert a.n == 4 and b.n == 1 and loop.command["u"][0] == 5.0
    assert loop.timing["a"].calls == 4 and loop.timing["b"].calls == 1
    loop.restage([[b]])
    loop.step()
    assert a.n == 4 and b.n == 2 and loop.command["u"][0] == 2.0
    with pytest.raises(ValueError, match="unique"):
        loop.restage([[b, b]])


def test_a_group_is_one_switched_system_whose_members_add_and_restart_with_it():
    """Group: members' contributions add; a slow member runs on the group's first tick after each
    reset (switched in) and is held between its updates; inactive, the whole group is held."""
    from shintai.core.runtime import Group

    body = NullBody(dt=0.01)
    fast, slow = Counter("fast", value=1.0), Counter("slow", period=0.03, value=10.0)
    idle = Counter("idle", value=-1.0)
    group = Group("pair", [fast, slow], period=0.01)
    sw = Switcher([group, idle], [("pair", "idle", lambda s: 0.04 - 1e-9 <= s["t"] < 0.06 - 1e-9),
                                  ("idle", "pair", lambda s: s["t"] >= 0.06 - 1e-9)])
    loop = Loop(body, [sw])
    seen = []
    for _ in range(10):
        loop.step()
        seen.append(body.command["u"][0])
    assert seen == [11.0] * 4 + [-1.0] * 2 + [11.0] * 4
    assert slow.calls == 2 + 2  # ticks 0 and 3, then again at its restart (tick 6) and 3 later (tick 9)
    assert fast.calls == 8 and fast.resets == slow.resets == 2
    with pytest.raises(ValueError):
        Group("bad", [Counter("odd", period=0.015)], period=0.01)
