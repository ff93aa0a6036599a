"""Cla's visual tracking (seed 003 §5.2.10, Fig. 5.12): neck and spine loops of different periods
(:mod:`shintai.spine.tracking_loops`) on the seated whole-body Cla, after its encoder zeroing; the spine loop's
posture from Cla's NN (§4.4.3: 8-40-15 on the 343 uniform bends) or by Jacobian integration.

Cla's whole body (:mod:`shintai.spine.cla.body`) has a head camera but no ball: :class:`TrackedCla` adds the
target as a point the ``target`` channel moves (not drawn), seen through ``head_cam``.
"""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import SET, declare
from shintai.spine.cla.body import ClaBody
from shintai.spine.cla.constants import CLA_NECK_LIMIT_RAD
from shintai.spine.cla.control import spine_control
from shintai.spine.robots import CLA, CLA_FOV_DEG
from shintai.spine.tracking_loops import (
    TRACKING_GAINS,
    TRACKING_PERIODS_S,
    GazeLoop,
    SpineGazeLoop,
    Tracking,
    image_offset,
    posture_estimator,
    tracking_stages,
)


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


def cla_tracking(loops: tuple[str, ...], amplitude_m: float, path_period_s: float, estimator: str = "nn",
                 rng: np.random.Generator | None = None) -> tuple[TrackedCla, list, Tracking]:
    """Cla zeroed (1 s, :func:`~shintai.spine.cla.control.spine_control`), then the stages of its tracking run
    with the visual ``loops`` on, the spine's posture by ``estimator`` (as :func:`posture_estimator`; the NN
    trained from ``rng``): (body, stages, :class:`Tracking`)."""
    estimate = shadow = None
    if "spine" in loops:
        estimate = posture_estimator(estimator, CLA.model, rng if rng is not None else np.random.default_rng(0))
        shadow = posture_estimator("jacobian", CLA.model, None) if estimator == "nn" else None
    body = TrackedCla()
    control, zero = spine_control(body)
    parts = {"neck": lambda: GazeLoop("neck", TRACKING_PERIODS_S["neck"], TRACKING_GAINS["neck"],
                                      ("neck_yaw", "neck_pitch"), -1.0, CLA_NECK_LIMIT_RAD),
             "spine": lambda: SpineGazeLoop(CLA.model, zero, TRACKING_PERIODS_S["spine"], TRACKING_GAINS["spine"],
                                                 estimate, shadow=shadow)}
    modules = [parts[name]() for name in loops]
    eye = body.data.cam_xpos[body.id("camera", "head_cam")].copy()
    return (body, *tracking_stages(body, control, eye, modules, amplitude_m, path_period_s))
