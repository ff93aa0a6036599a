"""SQ43 standing up from its belly (spine/sq43/standup.py, seed 003 §3.2.4, Fig. 3.9)."""

import math

import numpy as np

from shintai.spine.sq43 import standup as S
from shintai.spine.sq43.body import BODY


def test_the_alternating_schedule_moves_one_pair_at_a_time_and_bends_only_with_the_front():
    plan = S.StandUp(steps=3, spine_deg=-30.0)
    feet, bend = S.schedule(plan, "alternating")
    dz_front, dz_hind = np.diff(feet["LF"][:, 2]), np.diff(feet["LH"][:, 2])
    assert not np.any((np.abs(dz_front) > 1e-9) & (np.abs(dz_hind) > 1e-9))  # never both pairs at once
    assert np.all(np.abs(bend[1:][np.abs(dz_hind) > 1e-9]) < np.abs(bend).max())  # the bend returns while the hind extend
    assert bend.min() == -30.0 and bend[-1] == 0.0
    for leg in ("LF", "LH"):
        np.testing.assert_allclose(feet[leg][-1], [0.0, 0.0, -BODY.natural_length_m])
    _, straight = S.schedule(plan, "alternating_no_spine")
    assert np.all(straight == 0.0)


def test_all_at_once_stands_with_enough_torque_and_not_with_too_little():
    plan = S.StandUp()
    assert S.simulate(plan, "all_at_once", 1.0)["stood"]
    low = S.simulate(plan, "all_at_once", 0.4)
    assert not low["stood"] and low["held_mm"] < 0.5e3 * BODY.natural_length_m


def test_the_least_torque_scan_tells_the_first_from_the_reliable(monkeypatch):
    pattern = {0.2: False, 0.4: True, 0.6: False, 0.8: True, 1.0: True}
    monkeypatch.setattr(S, "simulate", lambda plan, strategy, t, spec=BODY: {"stood": pattern[round(t, 1)]})
    assert S.least_torque(S.StandUp(), "x", np.array(list(pattern))) == (0.4, 0.8)
    pattern[1.0] = False
    first, robust = S.least_torque(S.StandUp(), "x", np.array(list(pattern)))
    assert first == 0.4 and math.isnan(robust)
