"""shintai.sim: the MuJoCo body every MuJoCo-based robot in shintai runs on, and its rendering.

MuJoCo picks its OpenGL backend once, when ``mujoco`` is first imported, from the ``MUJOCO_GL``
environment variable. shintai renders headless on CPU machines (no display, no GPU), where only
EGL through Mesa works, so this package sets ``MUJOCO_GL=egl`` (unless the user chose otherwise)
*before* anything in it imports ``mujoco``. If ``mujoco`` was imported earlier by other code, that
choice was already made; :mod:`shintai.sim.render` then reports a failing context as one line.
"""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from shintai.sim.body import MujocoBody  # noqa: E402  (must follow the MUJOCO_GL default)
from shintai.sim.film import FilmRecorder  # noqa: E402
from shintai.sim.render import VideoRecorder, render_png  # noqa: E402

__all__ = ["FilmRecorder", "MujocoBody", "VideoRecorder", "render_png"]
