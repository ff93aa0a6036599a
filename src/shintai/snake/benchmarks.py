"""Benchmark: speed of the §3.3 tracking run on the kinematic plant, where its 50 ms tick goes, and the speed of
mode selection (§3.2.4); ``meets_target``: the run is at least issue 30's
:data:`~shintai.snake.constants.REALTIME_TARGET` times real time.

Mode selection is compared with its naive form, one candidate at a time through the model's public
functions (T_σ row deletion (2.11), A_{c,σ}, B_{c,σ} (2.15), one SVD each), on the same states.
"""

from __future__ import annotations

import time

import numpy as np

from shintai.scenarios.experiment import run_rig
from shintai.scenarios.registry import benchmark
from shintai.scenarios.sampling import Clock
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, REALTIME_TARGET, TRACKING
from shintai.snake.model import (
    configuration,
    constraint_matrices,
    mode_matrices,
    second_point_jacobians,
    two_point_matrices,
)
from shintai.snake.tracking import TrackingRun, tracking_rig
from shintai.snake.two_point import TwoPointLaw


def naive_select_mode(law: TwoPointLaw, w_h, phi) -> int:
    """argmax V_m (3.19) evaluated candidate by candidate (the reference form)."""
    cfg = configuration(w_h, phi, law.geometry.l)
    A, B = constraint_matrices(cfg)
    J1, J2 = second_point_jacobians(cfg, cfg.n)
    k_m1, k_m2 = law.gains.k_m
    best, best_V = 0, -np.inf
    for i, grounded in enumerate(law.candidates):
        A_c, B_c = two_point_matrices(*mode_matrices(A, B, grounded), J1, J2)
        V = k_m1 * np.linalg.svd(A_c, compute_uv=False)[-1] + k_m2 * np.linalg.svd(B_c, compute_uv=False)[-1]
        if V > best_V:
            best, best_V = i, V
    return best


def _per_call_us(fn, states, repeat: int) -> float:
    t0 = time.perf_counter()
    for _ in range(repeat):
        for w_h, phi in states:
            fn(w_h, phi)
    return 1e6 * (time.perf_counter() - t0) / (repeat * len(states))


def _tick_breakdown_run(duration: float) -> tuple[TrackingRun, float, dict]:
    """The tracking run with its tick split: the plant's step (RK4 of (2.10), eight dgelsd), the controller's
    input (3.3)–(3.6) (three SVDs) and mode selection (3.19), and the rest (runtime, recording, snapshots)."""
    t0 = time.perf_counter()
    run_rig(tracking_rig(CH3_GAINS.dt))  # one tick first: loads the plant's compiled loop (compiles it if not cached)
    first_tick = time.perf_counter() - t0
    rig = tracking_rig(duration)
    controller, law = rig.state["controller"], rig.state["law"]
    parts = {"plant_step": Clock([rig.body], "step"), "control_input": Clock([law], "input"),
             "mode_selection": Clock([law], "select_mode"), "controller": Clock([controller], "update")}
    t0 = time.perf_counter()
    run = TrackingRun.of(run_rig(rig))
    wall = time.perf_counter() - t0
    ticks = len(run.mode)
    us = {k: 1e6 * clock.seconds / ticks for k, clock in parts.items()}
    breakdown = {"first_tick_s": first_tick, "tick_us": 1e6 * wall / ticks, "plant_step_us": us["plant_step"],
                 "control_input_us": us["control_input"], "mode_selection_us_per_tick": us["mode_selection"],
                 "controller_other_us": us["controller"] - us["control_input"] - us["mode_selection"]}
    breakdown["rest_us"] = breakdown["tick_us"] - us["plant_step"] - us["controller"]
    return run, wall, breakdown


@benchmark("snake.tracking-speed", "snake.tracking (120 s, kinematic plant): sim/wall time and the tick's split; "
           "mode-selection cost per call")
def tracking_speed(duration: float = TRACKING.t_end) -> dict:
    run, wall, breakdown = _tick_breakdown_run(duration)
    law = TwoPointLaw(CH3_ROBOT, CH3_GAINS)
    picks = np.linspace(0, len(run.t) - 1, 20).astype(int)
    states = [(run.c[k, :3], run.phi[k]) for k in picks]
    agree = all(law.select_mode(w, p)[0] == naive_select_mode(law, w, p) for w, p in states)
    fast = _per_call_us(law.select_mode, states, repeat=10)
    naive = _per_call_us(lambda w, p: naive_select_mode(law, w, p), states, repeat=2)
    return {
        "sim_time_s": float(run.t[-1]),
        "wall_time_s": wall,
        "realtime_factor": float(run.t[-1]) / wall,
        "realtime_target": REALTIME_TARGET,
        "meets_target": bool(float(run.t[-1]) / wall >= REALTIME_TARGET),
        "control_periods": len(run.mode),
        **breakdown,
        "candidates": len(law.candidates),
        "mode_selection_us": fast,
        "mode_selection_naive_us": naive,
        "mode_selection_speedup": naive / fast,
        "mode_selection_agrees": agree,
    }
