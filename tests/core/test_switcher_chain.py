"""Switcher(chain=True): transitions whose guards hold at the same instant all happen in one update."""

import numpy as np
import pytest

from shintai.core import Loop, Module, Switcher
from shintai.core.benchmarks import NullBody


class Phase(Module):
    def __init__(self, name, value):
        super().__init__(name)
        self.value, self.calls, self.resets = value, 0, 0

    def reset(self, snapshot):
        self.resets += 1

    def update(self, snapshot):
        self.calls += 1
        return {"u": np.array([self.value])}


def three_phases(chain):
    a, b, c = Phase("a", 1.0), Phase("b", 2.0), Phase("c", 3.0)
    late = lambda s: s["t"] >= 0.02 - 1e-9  # noqa: E731
    return Switcher([a, b, c], [("a", "b", late), ("b", "c", late)], chain=chain), (a, b, c)


def test_a_chain_of_guards_holding_at_one_instant_is_one_update():
    sw, (a, b, c) = three_phases(chain=True)
    body = NullBody(dt=0.01)
    Loop(body, [sw]).run(0.05)
    assert [(round(t, 3), x, y) for t, x, y in sw.transitions_log] == [(0.02, "a", "b"), (0.02, "b", "c")]
    assert b.resets == 1 and b.calls == 0  # passed through: reset on entry, never run
    assert c.calls == 3 and body.command["u"][0] == 3.0


def test_without_chain_one_transition_per_update():
    sw, (a, b, c) = three_phases(chain=False)
    Loop(NullBody(dt=0.01), [sw]).run(0.05)
    assert [(round(t, 3), x, y) for t, x, y in sw.transitions_log] == [(0.02, "a", "b"), (0.03, "b", "c")]
    assert b.calls == 1


def test_a_cycle_of_guards_that_keep_holding_is_an_error():
    a, b = Phase("a", 1.0), Phase("b", 2.0)
    sw = Switcher([a, b], [("a", "b", lambda s: True), ("b", "a", lambda s: True)], chain=True)
    with pytest.raises(RuntimeError, match="keep switching"):
        Loop(NullBody(dt=0.01), [sw]).step()
