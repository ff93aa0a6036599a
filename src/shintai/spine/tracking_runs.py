"""The tracking runs of ``spine.tracking-loops`` (seed 003 §5.2.10, §5.2.12): Kenta's eye, neck and spine loops
and Cla's neck and spine loops, each one Loop — the experimenter moving the ball, the visual loops at their
periods, then the muscle controller (1 ms) in a later stage.

Cla's whole body (:mod:`shintai.spine.cla_body`) has a head camera but no ball: :class:`TrackedCla` adds the
target as a point the ``target`` channel moves (not drawn), seen through ``head_cam``.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable

import numpy as np

from shintai.core.runtime import SET, Loop, declare
from shintai.spine.cla_body import ClaBody
from shintai.spine.cla_control import spine_control
from shintai.spine.control import SETPOINTS
from shintai.spine.kenta_body import ARM_NAMES, calibrated_kenta, image_offset
from shintai.spine.robots import CLA, CLA_FOV_DEG, KENTA, KENTA_EYE_LIMIT_RAD, KENTA_NECK_LIMIT_RAD
from shintai.spine.tracking_loops import (
    TRACKING_GAINS,
    TRACKING_PERIODS_S,
    ArmSwing,
    GazeLoop,
    SpineGazeLoop,
    TargetPath,
    concurrent_fraction,
    measured_period,
    shares,
)

TARGET_DISTANCE_M = 0.9  # chosen: the ball 0.9 m in front of the eyes
CLA_NECK_LIMIT_RAD = np.radians(60.0)  # chosen: within the neck servos' range
# chosen: "moving at once" (Fig. 5.13) judged per 0.5 s window, a part moving when it turns by more than 1°
CONCURRENT_WINDOW_S, CONCURRENT_THRESHOLD_DEG = 0.5, 1.0
SWUNG = ("shoulder_pitch_L", "shoulder_pitch_R", "elbow_pitch_L", "elbow_pitch_R")  # ArmSwing's joints


class TrackedCla(ClaBody):
    """Cla seated without the desk, plus a target point (``target`` channel) seen through its head camera:
    snapshot ``target_image`` (h, v) [rad], ``target_visible``, ``gaze`` ((spine, neck) × (pan, tilt))."""

    def __init__(self):
        super().__init__("seated", desk=False)
        self.channels = {**self.channels, **declare("target", kind=SET)}
        self._cam = self.id("camera", "head_cam")
        self._neck = [self.model.jnt_qposadr[self.id("joint", n)] for n in ("neck_yaw", "neck_pitch")]
        self.target = np.zeros(3)

    def snapshot(self):
        snap = super().snapshot()
        d = self.data
        offset, visible = image_offset(d.cam_xpos[self._cam], d.cam_xmat[self._cam], self.target, CLA_FOV_DEG)
        snap["target_image"], snap["target_visible"] = offset, float(visible)
        spine = snap["theta"].reshape(-1, 3)
        snap["gaze"] = np.array([[spine[:, 2].sum(), -spine[:, 1].sum()],
                                 [d.qpos[self._neck[0]], -d.qpos[self._neck[1]]]])
        return snap

    def apply(self, command) -> None:
        command = dict(command)
        target = command.pop("target", None)
        if target is not None:
            self.target = np.asarray(target, dtype=float)
        super().apply(command)


def _eye_position(body, camera: str) -> np.ndarray:
    return body.data.cam_xpos[body.id("camera", camera)].copy()


def track(robot: str, duration_s: float, amplitude_m: float, path_period_s: float, loops: tuple[str, ...],
          zeroing_s: float = 1.0, film: Callable | None = None, arm_swing_rad: float = 0.0,
          arm_period_s: float = 2.0) -> dict:
    """One tracking run of ``robot`` ("kenta" or "cla") with the visual ``loops`` on; returns the metrics and the
    recorded series (t, image offset, visibility, the parts' gaze). Kenta with ``arm_swing_rad`` > 0 swings both
    arms meanwhile (:class:`ArmSwing`, §5.2.11) and adds ``arm_swing_deg`` (the left shoulder's peak-to-peak),
    ``arm_following_error_deg`` (RMS of the swung joints from their commands) and ``concurrent_fraction`` (the
    0.5 s windows in which the spine, the neck and both arms all moved)."""
    if robot == "kenta":
        body, control, zero = calibrated_kenta(seconds=zeroing_s)
        camera, model = "eye_L", KENTA.model
        parts = {"eyes": lambda: GazeLoop("eyes", TRACKING_PERIODS_S["eyes"], TRACKING_GAINS["eyes"],
                                          ("eye_pan", "eye_tilt"), +1.0, KENTA_EYE_LIMIT_RAD),
                 "neck": lambda: GazeLoop("neck", TRACKING_PERIODS_S["neck"], TRACKING_GAINS["neck"],
                                          ("neck_pan", "neck_tilt"), -1.0, KENTA_NECK_LIMIT_RAD)}
    else:
        body = TrackedCla()
        control, zero = spine_control(body)  # Cla's own zeroing (1 s, cla_control)
        camera, model = "head_cam", CLA.model
        parts = {"neck": lambda: GazeLoop("neck", TRACKING_PERIODS_S["neck"], TRACKING_GAINS["neck"],
                                          ("neck_yaw", "neck_pitch"), -1.0, CLA_NECK_LIMIT_RAD)}
    parts["spine"] = lambda: SpineGazeLoop(model, zero, TRACKING_PERIODS_S["spine"], TRACKING_GAINS["spine"])
    modules = [parts[name]() for name in loops]
    arms = ArmSwing(arm_swing_rad, arm_period_s) if robot == "kenta" and arm_swing_rad > 0 else None
    if arms is not None:
        arms.t0 = body.t
        modules.append(arms)
    eye = _eye_position(body, camera)
    path = TargetPath(eye + np.array([TARGET_DISTANCE_M, 0.0, 0.0]), amplitude_m, path_period_s)
    path.t0 = body.t
    body.apply({"target": path.at(body.t)})
    loop = Loop(body, stages=[[path, *modules], [control]], channels=SETPOINTS)
    series = {"t": [], "image": [], "visible": [], "gaze": [], "arms": []}
    swung = [ARM_NAMES.index(nm) for nm in SWUNG]

    def record(snap):
        series["t"].append(snap["t"])
        series["image"].append(snap["target_image"])
        series["visible"].append(snap["target_visible"])
        series["gaze"].append(snap["gaze"])
        if arms is not None:
            series["arms"].append(snap["arms"][swung])

    t0 = body.t
    with film(body) if film is not None else contextlib.nullcontext():
        loop.run(duration_s, every={10: record})
    s = {k: np.asarray(v) for k, v in series.items()}
    s["t"] = s["t"] - t0
    err = np.degrees(np.linalg.norm(s["image"], axis=1))
    settled = s["t"] >= min(1.0, 0.5 * duration_s)  # chosen: the first second acquires the target
    out = {"rms_tracking_error_deg": float(np.sqrt(np.mean(err[settled] ** 2))),
           "max_tracking_error_deg": float(err[settled].max()),
           "visible_fraction": float(s["visible"][settled].mean()),
           "target_sweep_deg": float(np.degrees(2 * np.arctan(amplitude_m / TARGET_DISTANCE_M))),
           "sim_time_s": duration_s + (zeroing_s if robot == "kenta" else 1.0)}  # + the encoder zeroing
    names = ("spine", "neck", "eyes")[:s["gaze"].shape[1]]
    share = shares(s["gaze"])
    for name, value in zip(names, share):
        out[f"{name}_share"] = float(value)
    for m in modules:
        if m is not arms:
            out[f"{m.name}_period_s"] = measured_period(m.times)
    if arms is not None:
        q = np.degrees(s["arms"][settled])
        wanted = np.degrees([[arms.at(t)[nm] for nm in SWUNG] for t in s["t"][settled] + t0])
        out["arm_swing_deg"] = float(np.ptp(q[:, 0]))
        out["arm_following_error_deg"] = float(np.sqrt(np.mean((q - wanted) ** 2)))
        gaze = np.degrees(s["gaze"][settled])
        out["concurrent_fraction"] = concurrent_fraction(s["t"][settled], [gaze[:, 0], gaze[:, 1], q[:, [0, 2]],
                                                                            q[:, [1, 3]]],
                                                         CONCURRENT_WINDOW_S, CONCURRENT_THRESHOLD_DEG)
    out["series"] = s
    return out
