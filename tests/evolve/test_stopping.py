"""The shared GA stopping rule (evolve/stopping.py): stop once the best stalled over a window."""

import numpy as np

from shintai.evolve import stalled


def test_maximised_stops_below_the_tolerance_over_the_window_and_not_before_it():
    flat = np.full(21, 0.5)
    assert stalled(flat, 20, 0.01, minimize=False) and not stalled(flat[:20], 20, 0.01, minimize=False)
    assert not stalled(np.linspace(0.2, 0.5, 41), 20, 0.01, minimize=False)  # 0.5 against 0.35: still rising
    step = np.concatenate([np.full(5, 1.0), np.full(20, 1.009)])  # 0.9 % over the 20 generations
    assert stalled(step, 20, 0.01, minimize=False)
    assert not stalled(np.concatenate([np.full(5, 1.0), np.full(20, 1.011)]), 20, 0.01, minimize=False)


def test_minimised_and_negative_values_improve_in_their_direction():
    falling = np.concatenate([np.full(5, 0.40), np.full(200, 0.397)])  # 0.75 % lower: stalled
    assert stalled(falling, 200, 0.01, minimize=True)
    assert not stalled(np.concatenate([np.full(5, 0.40), np.full(200, 0.39)]), 200, 0.01, minimize=True)
    assert not stalled(np.array([-2.0, -1.0]), 1, 0.01, minimize=False)  # −2 → −1 is a 50 % gain
    assert stalled(np.array([-2.0, -1.999]), 1, 0.01, minimize=False)


def test_a_window_of_zero_never_stops():
    assert not stalled(np.full(100, 1.0), 0, 0.01, minimize=False)


def test_a_best_that_does_not_move_has_stalled_even_at_zero():
    """A best stuck at exactly 0 (no relative tolerance to compare with) stops; a move away from 0 does not."""
    assert stalled(np.zeros(21), 20, 0.01, minimize=False) and stalled(np.zeros(21), 20, 0.01, minimize=True)
    assert not stalled(np.concatenate([np.zeros(1), np.full(20, 1e-9)]), 20, 0.01, minimize=False)
