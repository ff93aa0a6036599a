"""E9's runs on the MuJoCo Cla, arms down (seed 003 §4.2): a hand teaches a motion under tension control,
the recording is replayed in L mode k× faster, and three key postures are taught and replayed.

Each run is one Loop: the hand (:class:`~shintai.spine.scripted.Hand`) writes the body's ``hand``
channel; the playback writes ``l_r`` (and ``mode``) for the muscle controller in the next stage; a key
posture is commanded on ``l_goal`` by a :class:`~shintai.spine.scripted.Schedule` one stage earlier.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable

import numpy as np

from shintai.core.constants import KGF_N
from shintai.core.runtime import Loop
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.cla.constants import KEY_POSTURES_DEG
from shintai.spine.cla.setup import calibrated
from shintai.spine.control import SETPOINTS, Gains, Mode, MuscleControl
from shintai.spine.geometry import SpineModel, uniform_posture, whole_spine
from shintai.spine.robots import (
    CLA,
    CLA_ARMS_DOWN,
    CLA_TRUNK_LOADS,
    E9_EXTRA_TICKS,
    E9_KEY_MOVE_S,
    E9_KEY_PERIOD_S,
    E9_RETURN_S,
    E9_TAUGHT_S,
    SAMPLE_PERIOD_S,
)
from shintai.spine.scripted import Hand, Schedule
from shintai.spine.teaching import L_GOAL, Playback, Recorder, Recording


def demonstration(duration_s: float) -> np.ndarray:
    """A human moving the spine (chosen; the thesis gives no trajectory): whole-spine roll, pitch
    and yaw as smooth swings starting and ending at rest, ``duration_s`` long, sampled every 1 ms:
    shape (k, 3) [rad]."""
    t = np.arange(0.0, duration_s + 1e-9, 1e-3)
    s = t / duration_s
    envelope = np.sin(np.pi * s) ** 2
    whole = np.stack([np.radians(20) * np.sin(2 * np.pi * s),
                      np.radians(15) * np.sin(4 * np.pi * s),
                      np.radians(10) * np.sin(2 * np.pi * s + 1.0)], axis=-1) * envelope[:, None]
    return whole


def peak_muscle_speed(model: SpineModel, whole, dt: float = 1e-3) -> float:
    """Largest |dλ/dt| of any muscle along a uniform-bend trajectory [m/s]."""
    lengths = model.lengths(uniform_posture(np.asarray(whole), model.n))
    return float(np.abs(np.diff(lengths, axis=0)).max() / dt)


def teaching_body(teach_kgf: float) -> tuple[SpineBody, MuscleControl]:
    """Cla, arms down, encoders zeroed (§4.6.4), its controller's T-mode target the teaching tension."""
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    control = MuscleControl(CLA.m, Gains(T_r=teach_kgf * KGF_N))
    calibrated(body, control)
    return body, control


def teach(teach_kgf: float, demo) -> tuple[Recording, float]:
    """§4.2.2 (b): all muscles in T mode at the teaching tension while the hand moves the spine along
    ``demo`` (whole-spine angles, 1 ms apart); the encoders are logged every 20 ms. Returns the
    recording and the sim time used (the 1 s zeroing included)."""
    body, control = teaching_body(teach_kgf)
    control.set_modes(Mode.T)
    recorder = Recorder()
    hand = Hand([uniform_posture(w, CLA.n) for w in demo])
    Loop(body, [hand, control, recorder]).run(len(demo) * 1e-3 + 0.2)
    return recorder.recording, len(demo) * 1e-3 + 1.2


def replay(teach_kgf: float, recording: Recording, speedup: int,
           film: Callable[[SpineBody], contextlib.AbstractContextManager] | None = None) -> dict[str, float]:
    """§4.2.2: replay every ``speedup``-th sample in L mode (the hand has let go); tracking of the
    encoder targets and of the taught posture, and how often a motor saturated."""
    body, control = teaching_body(teach_kgf)
    samples = recording.decimated(speedup)
    playback = Playback(samples[0])
    playback.play(samples[1:])
    loop = Loop(body, stages=[[playback], [control]], channels=SETPOINTS)
    steps = int(round((len(samples) - 1) * SAMPLE_PERIOD_S / body.dt)) + E9_EXTRA_TICKS
    taught = whole_spine(recording.postures[np.minimum(np.arange(len(samples)) * speedup, len(recording.postures) - 1)])
    err, ref, post, saturated = [], [], [], []

    def observe(snap):  # after each tick: the encoders against the l_r the playback wrote
        target = snap["l_r"]
        err.append(snap["encoder"] - target)
        ref.append(target - samples[0])
        saturated.append(int(np.any(np.abs(loop.command["duty"]) >= 0.99)))
        i = min(int(loop.tick * body.dt / SAMPLE_PERIOD_S), len(taught) - 1)
        post.append(np.degrees(whole_spine(snap["theta"]) - taught[i]))

    with film(body) if film is not None else contextlib.nullcontext():
        loop.run(steps * body.dt, every={1: observe})
    err, ref, post = np.array(err), np.array(ref), np.array(post)
    rms_err, rms_ref = float(np.sqrt(np.mean(err**2))), float(np.sqrt(np.mean(ref**2)))
    return {"rms_length_error_mm": 1e3 * rms_err, "max_length_error_mm": 1e3 * float(np.abs(err).max()),
            "relative_length_error": rms_err / rms_ref, "rms_posture_error_deg": float(np.sqrt(np.mean(post**2))),
            "saturated_fraction": sum(saturated) / steps,
            "required_peak_speed_mm_s": 1e3 * float(np.abs(np.diff(samples, axis=0)).max() / SAMPLE_PERIOD_S),
            "duration_s": (len(samples) - 1) * SAMPLE_PERIOD_S, "sim_time_s": steps * body.dt + 1.0}


def key_postures(teach_kgf: float) -> float:
    """§4.2.1 / §4.2.2 (a): three postures taught by hand under tension control, replayed in L mode
    with minimum-jerk interpolation; mean whole-spine error at the replayed postures [deg]."""
    body, control = teaching_body(teach_kgf)
    control.set_modes(Mode.T)
    taught = np.radians(KEY_POSTURES_DEG)
    held = int(round(E9_TAUGHT_S / body.dt))
    hand = Hand([p for whole in taught for p in [uniform_posture(whole, CLA.n)] * held]
                + [uniform_posture(np.zeros(3), CLA.n)])
    read = {held * (k + 1): k for k in range(len(taught))}  # the first tick after each posture was held
    encoders, truth = [None] * len(taught), [None] * len(taught)
    loop = Loop(body, [hand, control])

    def read_taught(snap):
        k = read.get(loop.tick - 1)
        if k is not None:
            encoders[k], truth[k] = snap["encoder"], whole_spine(snap["theta"])

    loop.run(len(taught) * held * body.dt + E9_RETURN_S, every={1: read_taught})
    period = int(round(E9_KEY_PERIOD_S / body.dt))
    goals = Schedule({period * k: {"l_goal": enc} for k, enc in enumerate(encoders)})
    playback = Playback(body.snapshot()["encoder"], key_move_s=E9_KEY_MOVE_S)
    loop = Loop(body, stages=[[goals], [playback], [control]], channels=(*SETPOINTS, L_GOAL))
    errors = []

    def error_at_goal(snap):  # the state a period after each goal, before the next one is commanded
        if loop.tick > 1 and (loop.tick - 1) % period == 0:
            errors.append(np.degrees(np.abs(whole_spine(snap["theta"]) - truth[len(errors)])).max())

    loop.run(len(taught) * period * body.dt, every={1: error_at_goal})
    errors.append(np.degrees(np.abs(whole_spine(body.theta()) - truth[len(errors)])).max())
    return float(np.mean(errors))
