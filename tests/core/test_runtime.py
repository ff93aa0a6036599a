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
