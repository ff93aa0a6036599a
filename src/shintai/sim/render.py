"""Headless rendering of a MujocoBody: PNG stills and MP4 videos of a run.

Rendering uses MuJoCo's offscreen renderer through EGL (Mesa on CPU machines; see
:mod:`shintai.sim` for why ``MUJOCO_GL=egl`` is set). If no OpenGL context can be made, a one-line
:class:`RuntimeError` says how to fix it.

Cameras: ``camera`` names a camera of the model (or its index); ``track`` names a body that a
free camera follows at a fixed distance and angle (good for robots that move away); with neither,
MuJoCo's default free camera looks at the whole model.

A :class:`VideoRecorder` attaches itself to the body: every ``body.step()`` calls its
:meth:`VideoRecorder.capture`, so a ``Loop.run`` is recorded without changes to the loop. It renders during
the run, one frame at a time, with the model's own visual options; the runner's films use
:class:`shintai.sim.film.FilmRecorder` instead (render after the run, on worker processes; benchmark
``sim.film-fps`` compares the two).
"""

from __future__ import annotations

import importlib
import math
import os
import sys
from pathlib import Path

import imageio.v2 as imageio
import mujoco
import numpy as np

from shintai.sim.body import MujocoBody

CameraSpec = str | int | mujoco.MjvCamera


_gl_failure: str | None = None  # set after the first failed context: MuJoCo may abort on a retry


def honour_mujoco_gl() -> None:
    """Make MuJoCo's renderer use the backend ``MUJOCO_GL`` names now.

    MuJoCo reads ``MUJOCO_GL`` once, when its GL-context module is first imported. If ``mujoco``
    was imported before :mod:`shintai.sim` set ``MUJOCO_GL=egl`` (a test file or script that says
    ``import mujoco`` first), it picked GLFW, which needs a display; re-importing that module
    switches to the requested backend for every renderer made afterwards.
    """
    gl = sys.modules.get("mujoco.rendering.classic.gl_context")
    wanted = os.environ.get("MUJOCO_GL", "").lower().strip()
    if gl is not None and getattr(gl, "_MUJOCO_GL", wanted) != wanted:
        importlib.reload(gl)


def mujoco_of(body) -> MujocoBody | None:
    """The MuJoCo body to film for a shintai Body: itself, or the MujocoBody it wraps (``body.mj``)."""
    if isinstance(body, MujocoBody):
        return body
    inner = getattr(body, "mj", None)
    return inner if isinstance(inner, MujocoBody) else None


def make_renderer(model: mujoco.MjModel, width: int, height: int) -> mujoco.Renderer:
    """An offscreen renderer, growing the model's offscreen buffer if the image needs it."""
    global _gl_failure
    if _gl_failure is None:
        honour_mujoco_gl()
        vis = model.vis.global_
        vis.offwidth = max(vis.offwidth, width)
        vis.offheight = max(vis.offheight, height)
        try:
            return mujoco.Renderer(model, height=height, width=width)
        except Exception as exc:  # EGL/GL failures surface as many exception types
            _gl_failure = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    raise RuntimeError(
        f"MuJoCo offscreen rendering unavailable (MUJOCO_GL={os.environ.get('MUJOCO_GL', '')!r}: "
        f"{_gl_failure}); set MUJOCO_GL=egl before mujoco is first imported and install Mesa EGL "
        "(e.g. apt-get install libegl1 libgl1-mesa-dri)")


def make_camera(body: MujocoBody, camera: str | int | None = None, track: str | None = None,
                distance: float | None = None, azimuth: float | None = None,
                elevation: float | None = None) -> CameraSpec:
    """The camera argument for ``Renderer.update_scene`` (see the module docstring)."""
    if camera is not None:
        if track is not None:
            raise ValueError("give either camera= (a model camera) or track= (a body to follow), not both")
        return body.id("camera", camera) if isinstance(camera, str) else int(camera)
    cam = mujoco.MjvCamera()
    mujoco.mjv_defaultFreeCamera(body.model, cam)
    if track is not None:
        cam.type = mujoco.mjtCamera.mjCAMERA_TRACKING
        cam.trackbodyid = body.id("body", track)
        cam.distance = 1.5 * body.model.stat.extent
    for name, value in (("distance", distance), ("azimuth", azimuth), ("elevation", elevation)):
        if value is not None:
            setattr(cam, name, value)
    return cam


def render_png(body: MujocoBody, path: str | os.PathLike, width: int = 640, height: int = 480,
               camera: str | int | None = None, track: str | None = None, **view) -> np.ndarray:
    """Write the body's current state as a PNG; returns the image (height x width x 3, uint8).

    ``view`` may hold ``distance``, ``azimuth``, ``elevation`` for the free/tracking camera.
    """
    cam = make_camera(body, camera, track, **view)
    with make_renderer(body.model, width, height) as renderer:
        renderer.update_scene(body.data, cam)
        image = renderer.render()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    imageio.imwrite(path, image)
    return image


class VideoRecorder:
    """Record a body's run as an MP4: one frame at every 1/fps instant of sim time.

    The first frame is the state at construction; afterwards, each ``body.step()`` calls
    :meth:`capture`, which writes a frame for every 1/fps instant passed since the last one (the
    same image repeated if a body step is longer than a frame, so playback is real time). A run of
    T seconds thus gives ``floor(T * fps) + 1`` frames. Use as a context manager, or call
    :meth:`close` to finish the file; an exception inside the ``with`` still leaves a playable
    video of what was recorded.
    """

    def __init__(self, body: MujocoBody, path: str | os.PathLike, fps: float = 30, width: int = 640,
                 height: int = 480, camera: str | int | None = None, track: str | None = None, **view):
        if fps <= 0:
            raise ValueError(f"fps must be positive, got {fps}")
        self.body = body
        self.path = Path(path)
        self.fps = fps
        self.frames = 0
        self._t0 = body.t
        self._camera = make_camera(body, camera, track, **view)
        self._renderer = make_renderer(body.model, width, height)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._writer = imageio.get_writer(self.path, format="FFMPEG", fps=fps, codec="libx264",
                                          macro_block_size=2)
        body.after_step.append(self.capture)
        self.capture()

    def capture(self) -> None:
        """Write frames for every 1/fps instant reached since the last capture."""
        due = math.floor((self.body.t - self._t0) * self.fps + 1e-6) + 1 - self.frames
        if due <= 0:
            return
        self._renderer.update_scene(self.body.data, self._camera)
        image = self._renderer.render()
        for _ in range(due):
            self._writer.append_data(image)
        self.frames += due

    def close(self) -> None:
        """Detach from the body and finish the MP4 (safe to call twice)."""
        if self.capture in self.body.after_step:
            self.body.after_step.remove(self.capture)
        if self._writer is not None:
            self._writer.close()
            self._renderer.close()
            self._writer = None

    def __enter__(self) -> VideoRecorder:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
