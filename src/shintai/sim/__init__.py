"""shintai.sim: the MuJoCo body every MuJoCo-based robot in shintai runs on, and its rendering.

MuJoCo picks its OpenGL backend once, when ``mujoco`` is first imported, from the ``MUJOCO_GL``
environment variable. shintai renders headless on CPU machines (no display, no GPU), where only
EGL through Mesa works, so this package sets ``MUJOCO_GL=egl`` (unless the user chose otherwise)
*before* anything in it imports ``mujoco``. If ``mujoco`` was imported earlier by other code, that
choice was already made; :mod:`shintai.sim.render` then reports a failing context as one line.

Modules:

benchmarks — Benchmarks of the MuJoCo body: what MujocoBody and the Loop add on top of bare ``mj_step``; films …
corner — A hand on three position-servoed slide axes in a wall corner: the smallest physical rig of the online …
experiments/ — one declared scenario per file (accounts in notes/)
export — Every body's MuJoCo model, exported as MJCF that opens in MuJoCo's own ``simulate`` viewer and any …
film — Films of a run rendered after it: record the trajectory while the body steps, render it in processes
ik — Inverse kinematics: damped least squares on MuJoCo site Jacobians (``mj_jacSite``), for any MuJoCo body
ik_chain — The DLS IK of :mod:`shintai.sim.ik` for one serial chain of hinge joints and one site, compiled (issue 30)
models — The MuJoCo models of ``shintai.sim`` for export (:mod:`shintai.sim.export`)
plots — The figures of the sim experiments (``sim.wall-force``), drawn with ``ctx.figure``
spec — MjSpec building blocks shared by the bodies: the scene (floor, light, integrator), a limited hinge, a …
viewer — A live view of a running MujocoBody in MuJoCo's own viewer (``shintai run ID --view``)
"""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from shintai.sim.body import MujocoBody  # noqa: E402  (must follow the MUJOCO_GL default)
from shintai.sim.film import FilmRecorder  # noqa: E402
from shintai.sim.render import VideoRecorder, render_png  # noqa: E402

__all__ = ["FilmRecorder", "MujocoBody", "VideoRecorder", "render_png"]
