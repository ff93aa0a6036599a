"""Kenta's taught postures (seed 003 §4.2.1–4.2.2, Fig. 4.1): "three postures taught to Kenta and replayed in
turn, repeatedly" — "record some intermediate postures of the motion by §4.2.1's method (all muscles at a
constant tension, a human moves the robot, the muscle lengths recorded) and replay them interpolating between
them (§6.3.4's interpolators)".

Teaching: every muscle in T mode at the teaching tension while the teacher's hands (:class:`KentaBody`'s
``shape``) hold the spine in each posture for ``KENTA_TAUGHT_S``; the encoder lengths are read at its end.
Replay: the hands let go; the key postures' encoder lengths go, one every ``period``, on the ``l_goal`` channel
to :class:`~shintai.spine.teaching.Playback` (minimum-jerk over ``move_s``), whose ``l_r`` the muscle
controller follows in L mode — cycled ``cycles`` times.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from shintai.core.runtime import Loop
from shintai.scenarios.experiment import Rig, run_rig
from shintai.spine.control import SETPOINTS, Mode
from shintai.spine.geometry import uniform_posture, whole_spine
from shintai.spine.kenta.body import calibrated_kenta
from shintai.spine.kenta.constants import KENTA_KEY_POSTURES_DEG, KENTA_LOCK_PROBE_DEG, KENTA_TAUGHT_S
from shintai.spine.kenta.statics import lock_reels, muscle_span, unstretched_bend
from shintai.spine.robots import KENTA
from shintai.spine.scripted import Schedule
from shintai.spine.teaching import L_GOAL, Playback


def teach(teach_kgf: float, postures_deg=KENTA_KEY_POSTURES_DEG, hold_s: float = KENTA_TAUGHT_S,
          zeroing_s: float = 1.0, disc_nm_rad: float | None = None):
    """§4.2.1: T mode at ``teach_kgf`` on all 40 muscles, the teacher shaping each posture (a uniform bend,
    eq. 4.29); returns (body, control, encoder lengths (3, m), true postures (3, 3n)). ``disc_nm_rad``: the
    discs' stiffness set after the zeroing (a probe; default KENTA's)."""
    body, control, _ = calibrated_kenta(teach_kgf, zeroing_s)
    if disc_nm_rad is not None:
        body.set_disc(disc_nm_rad)
    control.set_modes(Mode.T)
    encoders, truth = [], []
    for whole in np.radians(postures_deg):
        Loop(body, [control], base={"shape": uniform_posture(whole, KENTA.n)}).run(hold_s)
        snap = body.snapshot()
        encoders.append(snap["encoder"].copy())
        truth.append(snap["theta"].copy())
    return body, control, np.array(encoders), np.array(truth)


@dataclass
class Replay:
    """A replay rig's state: the taught postures (whole-spine, rad), the commands' timing, the postures reached
    just before each next command (``reached``), the start time."""

    taught: np.ndarray
    k: int
    cycles: int
    period_s: float
    ticks: int
    t0: float
    reached: list = field(default_factory=list)
    steps: int = 0


def replay_rig(teach_kgf: float, cycles: int, period_s: float, move_s: float, hold_s: float = KENTA_TAUGHT_S,
               zeroing_s: float = 1.0, view=None) -> Rig:
    """§4.2.2 after its prelude (:func:`teach`: zeroing and three taught postures): the taught lengths replayed in
    L mode, in turn, ``cycles`` times, one every ``period_s`` moved to in ``move_s``; records the whole-spine
    posture every step and, per command, the posture just before the next one (:func:`replay_result`)."""
    body, control, encoders, truth = teach(teach_kgf, hold_s=hold_s, zeroing_s=zeroing_s)
    k = len(encoders)
    ticks = int(round(period_s / body.dt))
    goals = Schedule({ticks * i: {"l_goal": encoders[i % k]} for i in range(k * cycles)})
    control.set_modes(Mode.L)
    control.set_targets(l_r=body.snapshot()["encoder"])
    playback = Playback(body.snapshot()["encoder"], key_move_s=move_s)
    run = Replay(whole_spine(truth), k, cycles, period_s, ticks, body.t)

    def observe(snap):
        run.steps += 1  # the Loop's tick after this step
        whole = whole_spine(snap["theta"])
        if run.steps > 1 and (run.steps - 1) % ticks == 0:
            run.reached.append(whole)
        return {"whole": whole}

    return Rig(body, stages=[[goals], [playback], [control]], channels=(*SETPOINTS, L_GOAL),
               duration=k * cycles * period_s, record={1: observe}, view=view or {}, state=run)


def replay_result(log, run: Replay, body) -> dict:
    """Per taught posture the mean distance of the postures reached to it, the fraction nearest their own taught
    posture, the commanded and measured cycle periods, and the series."""
    k, taught = run.k, run.taught
    reached = np.degrees(np.array([*run.reached, whole_spine(body.theta())][:k * run.cycles]))
    wanted = np.degrees(taught)[np.arange(len(reached)) % k]
    errors = np.linalg.norm(reached - wanted, axis=1)
    distance = np.linalg.norm(reached[:, None, :] - np.degrees(taught)[None, :, :], axis=2)
    out = {f"posture_{i + 1}_error_deg": float(np.mean(errors[i::k])) for i in range(k)}
    out["mean_replay_error_deg"] = float(errors.mean())
    out["nearest_taught_fraction"] = float(np.mean(distance.argmin(axis=1) == np.arange(len(reached)) % k))
    out["cycle_period_s"] = k * run.period_s
    t, whole = log.times("whole") - run.t0, log.values("whole")
    out["measured_cycle_period_s"] = cycle_period(t, whole, k * run.period_s)
    out["series"] = {"t": t, "whole": np.degrees(whole), "taught": np.degrees(taught), "reached": reached}
    return out


def cycle_period(t, x, expected: float) -> float:
    """The motion's repetition period [s]: the lag in [0.5, 1.5] × ``expected`` at which the trajectory x (k, d)
    best matches itself shifted (largest mean autocorrelation over its axes); NaN when the run is shorter
    than 1.5 periods."""
    dt = float(np.mean(np.diff(t)))
    x = np.asarray(x, dtype=float) - np.mean(x, axis=0)
    lags = np.arange(int(0.5 * expected / dt), int(1.5 * expected / dt) + 1)
    lags = lags[lags < len(x) - 1]
    if len(lags) == 0 or t[-1] - t[0] < 1.5 * expected:
        return float("nan")
    score = [np.sum(x[:-lag] * x[lag:]) / (len(x) - lag) for lag in lags]
    return float(lags[int(np.argmax(score))] * dt)


def lock_rig(teach_kgf: float, hold_s: float, lock_s: float, zeroing_s: float = 1.0,
             posture_deg=KENTA_LOCK_PROBE_DEG, disc_nm_rad: float | None = None) -> Rig:
    """The ideal replay of one taught posture: taught as in :func:`teach` (the prelude), then every reel locked
    (:func:`~shintai.spine.kenta.statics.lock_reels`) and the hands let go for ``lock_s`` (:func:`lock_result`).
    ``disc_nm_rad`` as in :func:`teach`."""
    body, _, _, _ = teach(teach_kgf, (posture_deg,), hold_s, zeroing_s, disc_nm_rad)
    taught = body.theta()
    span = muscle_span(KENTA.model, taught)
    rate, _ = unstretched_bend(KENTA.model, taught)
    lock_reels(body)
    return Rig(body, [], duration=lock_s, state={"taught": taught, "span": span, "rate": rate})


def lock_result(body, state: dict) -> dict:
    """The whole-spine pitch taught and at the end [deg], the muscles still taut, and the muscle set's span at the
    taught posture (:mod:`~shintai.spine.kenta.statics`: J_m's rank, the unresisted pure joint torques, whether a
    strictly positive tension set balances, the fastest forward bend lengthening no muscle [rad/s per 1 rad/s])."""
    tension, span = body.wire_tension(), state["span"]
    return {"locked_taught_pitch_deg": float(np.degrees(whole_spine(state["taught"])[1])),
            "locked_end_pitch_deg": float(np.degrees(whole_spine(body.theta())[1])),
            "locked_taut_muscles": int(np.sum(tension > 0.0)),
            "muscle_rank": span["rank"], "unresisted_torque_directions": len(span["unresisted"]),
            "balanced_tension_exists": float(span["balanced"]), "unstretched_bend_rate": state["rate"]}


def locked_hold(teach_kgf: float, hold_s: float, lock_s: float, zeroing_s: float = 1.0,
                posture_deg=KENTA_LOCK_PROBE_DEG, disc_nm_rad: float | None = None) -> dict:
    """:func:`lock_rig` run on its own: :func:`lock_result` and the sim time."""
    run = run_rig(lock_rig(teach_kgf, hold_s, lock_s, zeroing_s, posture_deg, disc_nm_rad))
    return lock_result(run.body, run.state) | {"sim_time_s": zeroing_s + hold_s + lock_s}
