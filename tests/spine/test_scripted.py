"""The experimenter as modules: the hand and the command schedule."""

import numpy as np

from shintai.spine.scripted import Hand, Schedule


def test_schedule_writes_only_on_its_ticks():
    goal = np.array([0.0, 0.1, 0.0])
    schedule = Schedule({0: {"mode": np.zeros(2)}, 3: {"goal": goal}})
    schedule.reset({"t": 0.0})
    out = [schedule.update({}) for _ in range(5)]
    assert set(out[0]) == {"mode"} and out[3]["goal"] is goal
    assert out[1] is None and out[2] is None and out[4] is None


def test_hand_holds_tick_by_tick_then_keeps_the_last_entry():
    """postures[k] on tick k; None lets go; after the list the last entry stays (held or free)."""
    a, b = np.zeros(15), np.ones(15)
    hand = Hand([None, a, b])
    hand.reset({"t": 0.0})
    out = [hand.update({}) for _ in range(5)]
    assert out[0] is None and out[1]["hand"] is a and all(o["hand"] is b for o in out[2:])
    free = Hand([a, None])
    free.reset({"t": 0.0})
    assert [free.update({}) is None for _ in range(3)] == [False, True, True]
