"""Kenta moving its spine, neck and both arms at once (seed 003 §5.2.11, Fig. 5.13: "腱太が, 脊椎の動きと首の動き・
両腕の動きを同時に行っている様子を Fig. 5.13 に示す", a photograph; no target, loop or estimator is named).

The spine is commanded through a sequence of whole-spine postures by the forward model: each a uniform bend (eq.
4.29), its muscle lengths by eq. 4.25 (:meth:`~shintai.spine.geometry.SpineModel.lengths`), encoder targets for
L mode (:func:`~shintai.spine.control.encoder_targets`), played one after another by linear interpolation
(:class:`~shintai.spine.teaching.Playback`, §6.3.4's player) so the spine never rests. Meanwhile the whole neck's
pan and tilt swing (:class:`NeckSwing`) and both arms swing (:class:`~shintai.spine.tracking_loops.ArmSwing`);
the motions are not in the text (chosen).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.scenarios.experiment import Rig
from shintai.spine.control import SETPOINTS, encoder_targets
from shintai.spine.geometry import uniform_posture, whole_spine
from shintai.spine.kenta.body import ARM_NAMES, calibrated_kenta
from shintai.spine.kenta.tracking import SWUNG
from shintai.spine.robots import CONCURRENT_THRESHOLD_DEG, CONCURRENT_WINDOW_S, KENTA
from shintai.spine.teaching import Playback
from shintai.spine.tracking_loops import ArmSwing, Swing, concurrent_fraction


class NeckSwing(Swing):
    """The whole neck's pan a sin(2π t / T) and tilt (a / 2) sin(2π t / (0.7 T)) (``neck_pan``, ``neck_tilt``)."""

    def __init__(self, amplitude_rad: float, period_s: float, name: str = "neck"):
        super().__init__(amplitude_rad, period_s, name)

    def at(self, t: float) -> dict:
        w = 2 * math.pi * (t - self.t0) / self.T
        return {"neck_pan": self.a * math.sin(w), "neck_tilt": 0.5 * self.a * math.sin(w / 0.7)}


@dataclass
class AllAtOnce:
    """The run's commands: the whole-spine key postures [rad] in order, each reached ``key_s`` after the previous
    (linearly), the neck and arm swings, and the body time the motion started."""

    keys: np.ndarray
    key_s: float
    neck: NeckSwing
    arms: ArmSwing
    t0: float

    def spine_at(self, t) -> np.ndarray:
        """The commanded whole-spine posture at body times t [rad] (the linear interpolation from straight)."""
        knots = np.vstack((np.zeros(3), self.keys))
        s = (np.asarray(t, dtype=float) - self.t0) / self.key_s
        return np.stack([np.interp(s, np.arange(len(knots)), knots[:, a]) for a in range(3)], axis=-1)


def all_at_once_rig(keys_deg, cycles: int, key_s: float, neck_rad: float, neck_period_s: float, arm_rad: float,
                    arm_period_s: float, zeroing_s: float = 1.0, view=None) -> Rig:
    """Kenta zeroed (§4.6.4), then the key postures ``keys_deg`` (whole-spine roll, pitch, yaw) ``cycles`` times
    through the forward model in L mode while the neck and arms swing; records every 10 steps the whole spine, the
    neck's (pan, tilt) wire angles and the swung arm joints."""
    body, control, zero = calibrated_kenta(seconds=zeroing_s)
    keys = np.radians(np.tile(np.asarray(keys_deg, dtype=float), (cycles, 1)))
    targets = [encoder_targets(KENTA.model.lengths(uniform_posture(w, KENTA.n)), zero) for w in keys]
    playback = Playback(body.snapshot()["encoder"])
    playback.play(targets, key_s)  # linear: each key reached key_s after the previous
    neck, arms = NeckSwing(neck_rad, neck_period_s), ArmSwing(arm_rad, arm_period_s)
    neck.t0 = arms.t0 = body.t
    run = AllAtOnce(keys, key_s, neck, arms, body.t)
    swung = [ARM_NAMES.index(nm) for nm in SWUNG]

    def signals(snap):
        neck = snap["gaze"][1] * np.array([1.0, -1.0])  # (Σ yaw, Σ pitch): the neck wires' pan and tilt
        return {"spine": whole_spine(snap["theta"]), "neck": neck, "arms": snap["arms"][swung]}

    return Rig(body, stages=[[playback, neck, arms], [control]], channels=SETPOINTS, duration=len(keys) * key_s,
               record={10: signals}, view=view or {}, state=run)


def all_at_once_series(log, run: AllAtOnce) -> dict:
    """The recorded signals [deg] with ``t`` from the motion's start, and the commanded ones at the same times."""
    t = log.times("spine")
    neck_cmd = [run.neck.at(x) for x in t]
    return {"t": t - run.t0, "spine": np.degrees(log.values("spine")), "neck": np.degrees(log.values("neck")),
            "arms": np.degrees(log.values("arms")), "spine_cmd": np.degrees(run.spine_at(t)),
            "neck_cmd": np.degrees([[c["neck_pan"], c["neck_tilt"]] for c in neck_cmd]),
            "arms_cmd": np.degrees([[run.arms.at(x)[nm] for nm in SWUNG] for x in t])}


def all_at_once_metrics(log, run: AllAtOnce) -> dict:
    """Per 0.5 s window (``CONCURRENT_*``): the fraction in which the spine, the neck and each arm all turn by more
    than the threshold, and each part's own fraction; each part's sweep; how far each follows its command."""
    s = all_at_once_series(log, run)
    parts = {"spine": s["spine"], "neck": s["neck"], "left_arm": s["arms"][:, [0, 2]],
             "right_arm": s["arms"][:, [1, 3]]}
    out = {"concurrent_fraction": concurrent_fraction(s["t"], list(parts.values()), CONCURRENT_WINDOW_S,
                                                      CONCURRENT_THRESHOLD_DEG)}
    for name, x in parts.items():
        out[f"{name}_moving_fraction"] = concurrent_fraction(s["t"], [x], CONCURRENT_WINDOW_S, CONCURRENT_THRESHOLD_DEG)
        out[f"{name}_sweep_deg"] = float(np.ptp(x, axis=0).max())
    keys_at = np.searchsorted(s["t"], run.key_s * np.arange(1, len(run.keys) + 1) - 1e-9)
    reached = s["spine"][np.minimum(keys_at, len(s["t"]) - 1)]
    out["spine_key_error_deg"] = float(np.linalg.norm(reached - np.degrees(run.keys), axis=1).mean())
    wanted = np.linalg.norm(np.degrees(run.keys), axis=1).sum()
    out["spine_key_reach_fraction"] = float(np.linalg.norm(reached, axis=1).sum() / wanted) if wanted else float("nan")
    out["neck_following_error_deg"] = float(np.sqrt(np.mean((s["neck"] - s["neck_cmd"]) ** 2)))
    out["arm_following_error_deg"] = float(np.sqrt(np.mean((s["arms"] - s["arms_cmd"]) ** 2)))
    return out
