"""SQ43's accelerometer levelling as a Module (spine/sq43/levelling.py, seed 003 §3.2.4)."""

import numpy as np

from shintai.scenarios.experiment import run_rig
from shintai.spine.sq43 import levelling as L


def levelled_series(levelling):
    run = run_rig(L.levelling_rig(levelling, duration=5.5))
    return {"t": run.log.values("t_s"), "roll_deg": run.log.values("roll_deg"), "acted": run.state.acted}


def test_levelling_reduces_the_roll():
    without = levelled_series(None)
    levelled = levelled_series(L.Levelling())
    late = without["t"] > 5.0
    assert without["roll_deg"][late].mean() > 3.0
    assert abs(levelled["roll_deg"][late].mean()) < 1.0 and len(levelled["acted"]) >= 1


def test_board_height_rises_holds_and_lowers():
    h = L.board_height(np.array([0.0, 1.5, 4.0, 6.5, 8.0]), 20.0)
    np.testing.assert_allclose(h, [0.0, 0.01, 0.02, 0.01, 0.0])
