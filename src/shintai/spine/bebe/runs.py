"""The §4.8.3–4.8.4 experiments on our BeBe plant (seed 003; :mod:`shintai.spine.bebe.body`): single-muscle
calibration, the superposition and hysteresis tests, tracking a moving target (and the on-before-off
ablation), lateral pushes (Fig. 4.55) and muscles forced on (Fig. 4.56)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.recorder import Recorder
from shintai.spine.bebe import body as bebe
from shintai.spine.bebe.constants import SPANS
from shintai.spine.robots import BEBE_FORCE_AT_S, BEBE_PUSH_PERIOD_S

FORCED_CASES = {  # Fig. 4.56: "muscles tilting the spine left", "muscles tilting it backwards"
    "left": ("lateral-L/waist-abdomen 1", "ext-oblique-L/waist-abdomen 1", "int-oblique-L/waist-abdomen 1"),
    "back": ("erector-L/waist-abdomen 1", "erector-R/waist-abdomen 1",
             "erector-L/abdomen 1-shoulder", "erector-R/abdomen 1-shoulder"),
}


@dataclass
class BeBeResults:
    shifts: np.ndarray
    tracking: bebe.Episode
    on_first: bebe.Episode
    disturbed: bebe.Episode
    push_events: np.ndarray
    forced: dict  # case -> Episode
    superposition: np.ndarray  # co-operating pairs on one span (bebe.cooperating_pairs)
    cross_span: np.ndarray  # the same muscle kind on two spans (different joints)
    hysteresis: np.ndarray
    untracked: np.ndarray  # target image over the tracking run with the spine still
    sim_time_s: float


def target_path(amplitude_m: float, period_s: float):
    """Slowly moving target (chosen: a Lissajous path across the view, peak speed 2πA/T)."""
    return lambda t: np.array([0.0, amplitude_m * np.sin(2 * np.pi * t / period_s),
                               0.7 * amplitude_m * np.sin(2 * np.pi * t / (1.3 * period_s))])


def push_profile(force_n: float, start_s: float = 1.0):
    """Lateral push on the middle of the spine (Fig. 4.55): right, release, left, release, …"""
    def push(t):
        if t < start_s:
            return np.zeros(3)
        return np.array([0.0, (force_n, 0.0, -force_n, 0.0)[int((t - start_s) // BEBE_PUSH_PERIOD_S) % 4], 0.0])
    return push


def run_bebe(seed: int, recorder: Recorder, *, dead_zone_px: float, cos_threshold: float, target_amplitude_m: float,
             target_period_s: float, tracking_s: float, disturbance_s: float, push_n: float, forced_s: float,
             progress=lambda fraction, what: None) -> BeBeResults:
    """Every run of ``spine.bebe-tracking``: calibration, superposition, hysteresis, tracking a target moving by
    ``target_amplitude_m`` over ``target_period_s`` for ``tracking_s``, pushes of ``push_n`` for ``disturbance_s``
    and forced-on muscles for ``forced_s``. The plants share one seed (the same muscle strengths), the rule's
    signals go to ``recorder``."""
    prm = bebe.BeBeParams()

    def make(target=None):
        return bebe.BeBePlant(prm, target, np.random.default_rng(seed))

    names = list(make().model.muscles.names)
    kw = {"dead_zone_px": dead_zone_px, "cos_threshold": cos_threshold, "recorder": recorder}
    shifts = bebe.calibrate(make)
    progress(0.1, "calibrated")
    pairs = bebe.cooperating_pairs(shifts, len(SPANS), cos_threshold)
    superposition = bebe.superposition_error(make, shifts, pairs)
    kinds = len(bebe.MUSCLE_KINDS)  # for comparison: the same kind on the two lower spans (other joints)
    cross_span = bebe.superposition_error(make, shifts, [(k, k + kinds) for k in range(kinds)])
    hysteresis = np.array([bebe.hysteresis_residual(make, i, 0.5) for i in range(len(names))])
    progress(0.25, "superposition and hysteresis")
    moving = target_path(target_amplitude_m, target_period_s)
    tracking = bebe.track(make(moving), shifts, tracking_s, name="tracking", **kw)
    on_first = bebe.track(make(moving), shifts, tracking_s, off_first=False, name="on_first", **kw)
    progress(0.6, "tracking")
    disturbed = bebe.track(make(), shifts, disturbance_s, push=push_profile(push_n), name="disturbed", **kw)
    events = np.arange(1.0, disturbance_s, BEBE_PUSH_PERIOD_S)
    forced = {}
    for case, muscles in FORCED_CASES.items():
        idx = [names.index(n) for n in muscles]
        forced[case] = bebe.track(make(), shifts, forced_s, name=f"forced_{case}",
                                  forced=lambda t, idx=idx: idx if t >= BEBE_FORCE_AT_S else (), **kw)
    progress(1.0, "disturbances and forced-on muscles")
    sim_time = (len(names) * (1.0 + 1.0) + len(pairs) + kinds + 2 * tracking_s + disturbance_s
                + len(FORCED_CASES) * forced_s)
    still = make(moving)
    untracked = np.array([still.image_at(t) for t in tracking.t])
    return BeBeResults(shifts, tracking, on_first, disturbed, events, forced, superposition, cross_span,
                       hysteresis, untracked, sim_time)


def forced_metrics(res: BeBeResults) -> dict:
    """Per forced-on case: the image error's peak after the muscles come on, the time to re-centre,
    the final error, and how many free muscles the rule switched on."""
    out = {}
    for case, ep in res.forced.items():
        err = np.linalg.norm(ep.target_px, axis=1)
        after = ep.t >= BEBE_FORCE_AT_S
        out[f"forced_{case}_peak_px"] = float(err[after].max())
        out[f"forced_{case}_recovery_s"] = float(bebe.recovery_times(ep, [BEBE_FORCE_AT_S])[0])
        out[f"forced_{case}_final_px"] = float(err[-1])
        out[f"forced_{case}_max_free_on"] = int(ep.on_count.max() - len(FORCED_CASES[case]))
    return out
