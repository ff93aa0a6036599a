"""Visual tracking by feedback loops of different periods run in parallel (seed 003 §5.2.10, §5.2.12,
Figs. 5.12, 5.14), as Loop configurations of runtime Modules.

§5.2.10 (Cla): the target's position in the image (colour-region detection) drives "(1) a routine adjusting
the neck's pan (yaw) and tilt (pitch) angles according to it, and (2) a routine that finds the spine's present
posture from the present muscle lengths (§4.4.3) and bends the spine about the pitch and yaw axes by an angle
matching the target's offset", run in parallel, tuned by their gains. §5.2.12 (Kenta): "three control loops of
different periods moving the eyes, the neck and the spine by visual feedback, run in parallel".

* :class:`GazeLoop` — a servoed part (eyes or neck): every period, pan += g·h and pitch ∓= g·v, with (h, v)
  the target's angles from the optical axis (left and up positive), clipped to the part's range.
* :class:`SpineGazeLoop` — every period, the present whole-spine posture from the encoder lengths by a
  :func:`posture_estimator`: §4.4.3's adopted NN ("本研究では、筋長空間から関節変位空間への変換 … ニューラル
  ネットワークによるものとする"; Kenta's spine too, §5.9.3 "脊椎部分は、現在の姿勢の推定は 4.4.3 節に述べたように
  ニューラルネットワークを利用する"), trained per robot, or Jacobian integration (eqs. 4.26–4.28) from the
  previous estimate, the method §4.4.3 rejects; then the whole-spine yaw += g·h, pitch −= g·v as a uniform
  bend (eq. 4.29) turned into encoder targets ``l_r`` for the muscle controller (L mode) of the next stage.
* :class:`TargetPath` — the experimenter moving the coloured ball (``target`` channel), a Lissajous path.
* :class:`ArmSwing` — Kenta's two arms swung through a cycle (while the loops track, and in Fig. 5.13's run,
  §5.2.11: "脊椎の動きと首の動き・両腕の動きを同時に行っている"): the shoulder pitch ±a sin(2π t / T), left and right in
  antiphase, the elbow bent a (1 − cos(2π t / T)) / 2 with it (the motion is not in the text: chosen).

Periods and gains are not in the text ("周期の異なる3つの制御ループ", §5.2.12): chosen in ``TRACKING_*`` below.
Each loop records when it ran (``times``), so the measured periods come from the run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.spine.control import encoder_targets
from shintai.spine.geometry import SpineModel, uniform_posture, whole_spine
from shintai.spine.inverse_model import NeuralInverse, jacobian_integration
from shintai.spine.robots import (
    CONCURRENT_THRESHOLD_DEG,
    CONCURRENT_WINDOW_S,
    ESTIMATE_DIVERGED_DEG,
    GRID_DEG,
    KENTA_CAMERA_FOVY_DEG,
    NN_HIDDEN,
    NN_ITERATIONS,
    TARGET_DISTANCE_M,
    TRACKING_SPINE_RANGE_RAD,
)

# Chosen, because §5.2.12 gives no period: the eyes at the video frame rate of the CCD cameras (NTSC, 30 Hz),
# the neck at BeBe's image-feedback period (66 ms, §4.8.3), the spine slower again (its muscles move it at
# tens of mm/s, Table 3.3), so the three periods differ as the thesis says.
TRACKING_PERIODS_S = {"eyes": 0.033, "neck": 0.066, "spine": 0.198}
# Chosen: the fraction of the image offset each loop corrects per period (the thesis tuned its gains by hand)
TRACKING_GAINS = {"eyes": 0.3, "neck": 0.12, "spine": 0.15}


def image_offset(cam_pos, cam_mat, point, fovy_deg: float = KENTA_CAMERA_FOVY_DEG, aspect: float = 4 / 3):
    """The point's (horizontal, vertical) angles from a MuJoCo camera's optical axis [rad] (positive: to the
    camera's left, up) and whether it is inside the field of view."""
    R = np.asarray(cam_mat, dtype=float).reshape(3, 3)  # columns: camera x (right), y (up), z (backward)
    v = R.T @ (np.asarray(point, dtype=float) - np.asarray(cam_pos, dtype=float))
    depth = -v[2]
    h, vert = math.atan2(-v[0], depth), math.atan2(v[1], depth)
    half_v = math.radians(fovy_deg) / 2
    half_h = math.atan(math.tan(half_v) * aspect)
    visible = depth > 0 and abs(h) <= half_h and abs(vert) <= half_v
    return np.array([h, vert]), visible


class TargetPath(Module):
    """Moves the ball on centre + (0, a sin(2π t / T), 0.5 a sin(2π t / (0.7 T))), written to ``target``."""

    def __init__(self, centre, amplitude_m: float, period_s: float, name: str = "experimenter"):
        super().__init__(name)
        self.centre, self.a, self.T = np.asarray(centre, dtype=float), amplitude_m, period_s
        self.t0 = 0.0

    def reset(self, snapshot: Snapshot) -> None:
        self.t0 = float(snapshot["t"])

    def at(self, t: float) -> np.ndarray:
        """The ball's position at body time t (the path starts at the centre when the Loop starts)."""
        t = t - self.t0
        w = 2 * math.pi / self.T
        return self.centre + np.array([0.0, self.a * math.sin(w * t), 0.5 * self.a * math.sin(w * t / 0.7)])

    def update(self, snapshot: Snapshot):
        return {"target": self.at(snapshot["t"])}


class Swing(Module):
    """A cyclic joint motion of amplitude ``a`` and period ``T`` from the time the Loop starts: every tick it
    writes :meth:`at` (the joints' targets at body time t), which a subclass defines."""

    def __init__(self, amplitude_rad: float, period_s: float, name: str):
        super().__init__(name)
        self.a, self.T = amplitude_rad, period_s
        self.t0 = 0.0

    def reset(self, snapshot: Snapshot) -> None:
        self.t0 = float(snapshot["t"])

    def at(self, t: float) -> dict:
        raise NotImplementedError

    def update(self, snapshot: Snapshot):
        return self.at(float(snapshot["t"]))


class ArmSwing(Swing):
    """Both arms' cyclic motion (module docstring): writes ``shoulder_pitch_L/R`` and ``elbow_pitch_L/R`` every tick."""

    def __init__(self, amplitude_rad: float, period_s: float, name: str = "arms"):
        super().__init__(amplitude_rad, period_s, name)

    def at(self, t: float) -> dict:
        phase = 2 * math.pi * (t - self.t0) / self.T
        swing, bend = self.a * math.sin(phase), 0.5 * self.a * (1 - math.cos(phase))
        return {"shoulder_pitch_L": swing, "shoulder_pitch_R": -swing, "elbow_pitch_L": bend, "elbow_pitch_R": bend}


def concurrent_fraction(t, parts, window_s: float, threshold: float) -> float:
    """The fraction of consecutive windows of ``window_s`` in which every part moved: a part is a (P,) or (P, c)
    array of its angles, and it moved in a window when one of its angles spans more than ``threshold``
    (max − min, same unit) there."""
    t = np.asarray(t, dtype=float)
    parts = [np.asarray(x, dtype=float).reshape(len(t), -1) for x in parts]
    moved = []
    for start in np.arange(t[0], t[-1] - window_s + 1e-9, window_s):
        w = (t >= start) & (t < start + window_s)
        if w.sum() >= 2:
            moved.append(all(np.max(x[w].max(axis=0) - x[w].min(axis=0)) > threshold for x in parts))
    return float(np.mean(moved)) if moved else float("nan")


class GazeLoop(Module):
    """A servoed part's visual-feedback loop (eyes, neck). ``channels`` = (pan channel, pitch channel) and
    ``up`` the sign of the pitch command that looks up (+1 eyes' tilt, −1 a pitch that bends down)."""

    def __init__(self, name: str, period: float, gain: float, channels: tuple[str, str], up: float, limit: float):
        super().__init__(name, period)
        self.gain, self.channels, self.up, self.limit = gain, channels, up, limit
        self.angles = np.zeros(2)
        self.times: list[float] = []

    def reset(self, snapshot: Snapshot) -> None:
        self.angles = np.zeros(2)
        self.times = []

    def update(self, snapshot: Snapshot):
        self.times.append(float(snapshot["t"]))
        h, v = snapshot["target_image"]
        self.angles = np.clip(self.angles + self.gain * np.array([h, self.up * v]), -self.limit, self.limit)
        return {self.channels[0]: self.angles[0], self.channels[1]: self.angles[1]}


ESTIMATORS = ("nn", "jacobian")


def posture_estimator(kind: str, model: SpineModel, rng: np.random.Generator, grid_deg=GRID_DEG):
    """θ̂(lengths, previous θ̂) for a spine loop: ``"nn"`` — an ``m-NN_HIDDEN-3n`` network trained (L-BFGS,
    ``NN_ITERATIONS``) on the 343 uniform bends of ``grid_deg`` by eq. 4.25 (:class:`NeuralInverse`), the lengths
    alone its input; ``"jacobian"`` — eqs. 4.26–4.28 integrated from the previous estimate."""
    if kind == "jacobian":
        return lambda lengths, previous: jacobian_integration(model, lengths, theta0=previous).theta
    if kind != "nn":
        raise ValueError(f"posture_estimator: kind must be one of {ESTIMATORS}, got {kind!r}")
    inverse = NeuralInverse(model, (NN_HIDDEN,), rng, grid_deg=grid_deg)
    inverse.fit("lbfgs", NN_ITERATIONS)
    return lambda lengths, previous: inverse.posture(lengths)


class SpineGazeLoop(Module):
    """The spine's loop: posture from muscle lengths by ``estimate`` (:func:`posture_estimator`), then a uniform
    bend toward the target. Every run it records (t, whole-spine estimate, whole-spine truth) in ``estimates``.
    ``shadow``, a second estimator (the Jacobian integration beside the NN, issue 28 item 2), reads the same
    lengths at the same ticks from its own previous estimate without acting; its record is ``shadow_estimates``."""

    def __init__(self, model: SpineModel, zero_lengths, period: float, gain: float, estimate, name: str = "spine",
                 shadow=None):
        super().__init__(name, period)
        self.model, self.zero, self.gain = model, np.asarray(zero_lengths, dtype=float), gain
        self.estimator, self.shadow = estimate, shadow
        self.estimate = np.zeros(3 * model.n)
        self.shadow_estimate = np.zeros(3 * model.n)
        self.shadow_estimates: list[tuple] = []
        self.whole_cmd = np.zeros(3)
        self.times: list[float] = []
        self.estimates: list[tuple] = []

    def reset(self, snapshot: Snapshot) -> None:
        self.estimate = np.zeros(3 * self.model.n)
        self.shadow_estimate = np.zeros(3 * self.model.n)
        self.times, self.estimates, self.shadow_estimates = [], [], []

    def update(self, snapshot: Snapshot):
        self.times.append(float(snapshot["t"]))
        lengths = self.zero - np.asarray(snapshot["encoder"], dtype=float)  # encoder l = λ(0) − λ (control.py)
        self.estimate = self.estimator(lengths, self.estimate)
        roll, pitch, yaw = whole_spine(self.estimate)
        truth = whole_spine(snapshot["theta"])
        self.estimates.append((self.times[-1], np.array([roll, pitch, yaw]), truth))
        if self.shadow is not None:
            self.shadow_estimate = self.shadow(lengths, self.shadow_estimate)
            self.shadow_estimates.append((self.times[-1], np.array(whole_spine(self.shadow_estimate)), truth))
        h, v = snapshot["target_image"]
        ymax, pmax = TRACKING_SPINE_RANGE_RAD
        self.whole_cmd = np.array([0.0, np.clip(pitch - self.gain * v, -pmax, pmax),
                                   np.clip(yaw + self.gain * h, -ymax, ymax)])
        lengths_cmd = self.model.lengths(uniform_posture(self.whole_cmd, self.model.n))
        return {"l_r": encoder_targets(lengths_cmd, self.zero)}


def measured_period(times) -> float:
    """Mean interval between a loop's runs [s] (NaN with fewer than two)."""
    return float(np.mean(np.diff(times))) if len(times) > 1 else float("nan")


def shares(parts) -> np.ndarray:
    """Each part's share of the gaze's pan: mean |pan_k| / Σ_k mean |pan_k| over the run; ``parts`` (k, P, 2)."""
    pan = np.abs(np.asarray(parts)[:, :, 0]).mean(axis=0)
    return pan / max(pan.sum(), 1e-12)


@dataclass
class Tracking:
    """One tracking run as its rig left it: the visual loops, the arm swing (or None) with the indices of its
    joints in the snapshot's ``arms``, and the body time the tracking started at."""

    loops: list
    arms: ArmSwing | None
    swung: list[int]
    t0: float


def tracking_stages(body, control, eye, loops: list, amplitude_m: float, path_period_s: float,
                    arms: ArmSwing | None = None, swung=()) -> tuple[list, Tracking]:
    """The stages of a tracking run — the experimenter moving the ball ``TARGET_DISTANCE_M`` in front of ``eye``,
    the visual ``loops`` (and ``arms``), then the muscle controller — and its :class:`Tracking`."""
    modules = list(loops)
    if arms is not None:
        arms.t0 = body.t
        modules.append(arms)
    path = TargetPath(eye + np.array([TARGET_DISTANCE_M, 0.0, 0.0]), amplitude_m, path_period_s)
    path.t0 = body.t
    body.apply({"target": path.at(body.t)})
    return [[path, *modules], [control]], Tracking(list(loops), arms, list(swung), body.t)


def tracking_signals(snap: Snapshot, run: Tracking) -> dict:
    """What a tracking run records: the target's image offset and visibility, the parts' gaze, the swung joints."""
    out = {"image": snap["target_image"], "visible": snap["target_visible"], "gaze": snap["gaze"]}
    if run.arms is not None:
        out["arms"] = snap["arms"][run.swung]
    return out


def tracking_series(log, run: Tracking) -> dict:
    """The recorded signals as arrays, ``t`` from the tracking's start."""
    s = {k: log.values(k) for k in ("image", "visible", "gaze", *(("arms",) if run.arms is not None else ()))}
    s["t"] = log.times("image") - run.t0
    return s


def estimate_errors(estimates, t_from: float) -> dict:
    """The spine loop's posture estimate against the true posture from body time ``t_from``: RMS and max of the
    whole-spine (roll, pitch, yaw) error norm [deg], and the first time (from the loop's first run) it exceeds
    ``ESTIMATE_DIVERGED_DEG`` (NaN: never)."""
    t = np.array([e[0] for e in estimates])
    err = np.degrees([np.linalg.norm(e[1] - e[2]) for e in estimates])
    late = err[t >= t_from] if np.any(t >= t_from) else err
    over = t[err > ESTIMATE_DIVERGED_DEG]
    return {"estimate_rms_error_deg": float(np.sqrt(np.mean(late ** 2))), "estimate_max_error_deg": float(late.max()),
            "estimate_diverged_at_s": float(over[0] - estimates[0][0]) if len(over) else float("nan")}


def tracking_metrics(log, run: Tracking, duration_s: float, amplitude_m: float, swung_names=()) -> dict:
    """The tracking error after the first second, the visible fraction, each part's share of the pan and each
    loop's measured period; with the arms swung, their swing, following error and the concurrent fraction."""
    s = tracking_series(log, run)
    err = np.degrees(np.linalg.norm(s["image"], axis=1))
    settled = s["t"] >= min(1.0, 0.5 * duration_s)  # chosen: the first second acquires the target
    out = {"rms_tracking_error_deg": float(np.sqrt(np.mean(err[settled] ** 2))),
           "max_tracking_error_deg": float(err[settled].max()),
           "visible_fraction": float(s["visible"][settled].mean()),
           "target_sweep_deg": float(np.degrees(2 * np.arctan(amplitude_m / TARGET_DISTANCE_M)))}
    names = ("spine", "neck", "eyes")[:s["gaze"].shape[1]]
    for name, value in zip(names, shares(s["gaze"])):
        out[f"{name}_share"] = float(value)
    for m in run.loops:
        out[f"{m.name}_period_s"] = measured_period(m.times)
        if isinstance(m, SpineGazeLoop) and m.estimates:
            out |= estimate_errors(m.estimates, run.t0 + min(1.0, 0.5 * duration_s))
        if isinstance(m, SpineGazeLoop) and m.shadow_estimates:
            shadow = estimate_errors(m.shadow_estimates, run.t0 + min(1.0, 0.5 * duration_s))
            out |= {f"shadow_jacobian_{k}": v for k, v in shadow.items()}
    arms = run.arms
    if arms is not None:
        q = np.degrees(s["arms"][settled])
        wanted = np.degrees([[arms.at(t)[nm] for nm in swung_names] for t in s["t"][settled] + run.t0])
        out["arm_swing_deg"] = float(np.ptp(q[:, 0]))
        out["arm_following_error_deg"] = float(np.sqrt(np.mean((q - wanted) ** 2)))
        gaze = np.degrees(s["gaze"][settled])
        out["concurrent_fraction"] = concurrent_fraction(s["t"][settled], [gaze[:, 0], gaze[:, 1], q[:, [0, 2]],
                                                                            q[:, [1, 3]]],
                                                         CONCURRENT_WINDOW_S, CONCURRENT_THRESHOLD_DEG)
    return out
