"""Films of a run rendered after it: record the trajectory while the body steps, render it in processes.

Rendering on a CPU-only machine (Mesa's software OpenGL) costs tens to hundreds of milliseconds a frame,
far more than a physics step; rendering inside the run also serialises it with the simulation. A
:class:`FilmRecorder` therefore only records, at every frame instant, the MuJoCo state that decides the
picture (``mj_getState`` with ``qpos``, activations, mocap poses and time; and the geom colours when a
body recolours geoms during the run, as the snake's grounded wheels do). When it closes, the frames are
rendered by worker processes that split them across the cores — each its own ``mujoco.Renderer`` under
EGL, writing its slice with imageio-ffmpeg — and the slices joined in order into the MP4.

Frames per film: one every ``speed / fps`` seconds of sim time (``speed`` > 1 is a time-lapse), and at
most ``max_frames``: a longer run keeps every k-th recorded frame (k the smallest integer that fits), so
the film becomes a ×(speed·k) time-lapse. The factor, the frame count and the sim time are written beside
the video (``video.json`` for ``video.mp4``, with its middle frame as ``video.poster.jpg``), and the report
page prints them under the video.

The renderer's costly options are set for speed where a viewer does not see the difference
(:func:`fast_options`): the offscreen buffer is the frame's size, the shadow map about 1.5× the frame's
longer side (the models ask for 4096², which at 480×360 looks the same as 1024² and costs twice the time),
multisampling at most 2× (4× looks the same at these sizes). Shadows, reflections and the skybox stay on:
turning them off does change the picture.
"""

from __future__ import annotations

import json
import math
import os
import pickle
import subprocess
import sys
import tempfile
from pathlib import Path

import imageio.v2 as imageio
import imageio_ffmpeg
import mujoco
import numpy as np

from shintai.sim.body import MujocoBody
from shintai.sim.render import make_camera, make_renderer

# what decides the picture: positions, activations (muscle colours), mocap bodies, and the time
STATE = (mujoco.mjtState.mjSTATE_TIME | mujoco.mjtState.mjSTATE_QPOS | mujoco.mjtState.mjSTATE_ACT
         | mujoco.mjtState.mjSTATE_MOCAP_POS | mujoco.mjtState.mjSTATE_MOCAP_QUAT)
MIN_FRAMES_PER_WORKER = 40  # below this a worker's start-up (≈1–2 s: import mujoco, make a GL context) does not pay


def fast_options(model: mujoco.MjModel, width: int, height: int) -> None:
    """Set ``model``'s costly visual options for speed where the picture does not change (module docstring).
    Edits ``model`` in place: use it on a copy."""
    vis = model.vis
    vis.global_.offwidth, vis.global_.offheight = int(width), int(height)
    shadow = 1 << math.ceil(math.log2(1.5 * max(width, height)))
    vis.quality.shadowsize = min(int(vis.quality.shadowsize), shadow) if vis.quality.shadowsize else 0
    vis.quality.offsamples = min(int(vis.quality.offsamples), 2)


def camera_fields(camera) -> dict | int:
    """A picklable description of a camera argument of ``Renderer.update_scene``."""
    if isinstance(camera, mujoco.MjvCamera):
        return {"type": int(camera.type), "fixedcamid": int(camera.fixedcamid),
                "trackbodyid": int(camera.trackbodyid), "lookat": list(camera.lookat), "distance": camera.distance,
                "azimuth": camera.azimuth, "elevation": camera.elevation, "orthographic": int(camera.orthographic)}
    return int(camera)


def camera_from(fields: dict | int):
    if isinstance(fields, int):
        return fields
    cam = mujoco.MjvCamera()
    for key, value in fields.items():
        if key == "lookat":
            cam.lookat[:] = value
        else:
            setattr(cam, key, value)
    return cam


def frame_indices(recorded: int, max_frames: int | None) -> tuple[list[int], int]:
    """The recorded frames a film keeps (every k-th, from the first) and k: at most ``max_frames``."""
    if max_frames is None or recorded <= max_frames:
        return list(range(recorded)), 1
    k = math.ceil(recorded / max_frames)
    return list(range(0, recorded, k)), k


class FilmRecorder:
    """Record a body's run and render it as an MP4 when closed (see the module docstring).

    One frame per ``speed / fps`` seconds of sim time from the state at construction, as
    :class:`~shintai.sim.render.VideoRecorder` (``floor(T · fps / speed) + 1`` recorded frames for a run of
    T seconds, the same state repeated if a body step is longer than a frame), then at most ``max_frames``
    of them kept. ``workers``: rendering processes (default: the cores this process may use, fewer for a
    short film; 1 renders here). An exception inside the ``with`` still leaves a playable video of what was
    recorded. Errors in the output path or the camera are raised here, before the run.
    """

    def __init__(self, body: MujocoBody, path: str | os.PathLike, fps: float = 15, width: int = 480,
                 height: int = 360, camera: str | int | None = None, track: str | None = None,
                 speed: float = 1.0, max_frames: int | None = 300, workers: int | None = None, **view):
        if not fps > 0:
            raise ValueError(f"fps must be positive, got {fps}")
        if not speed > 0:
            raise ValueError(f"speed must be positive, got {speed}")
        if max_frames is not None and max_frames < 1:
            raise ValueError(f"max_frames must be at least 1 (or None), got {max_frames}")
        if int(width) < 2 or int(height) < 2:
            raise ValueError(f"a frame must be at least 2×2 pixels, got {width}×{height}")
        self.body, self.path = body, Path(path)
        self.fps, self.speed, self.max_frames = float(fps), float(speed), max_frames
        self.width, self.height = int(width), int(height)
        self.workers = workers
        self.camera = camera_fields(make_camera(body, camera, track, **view))  # unknown names fail here
        ensure_writable(self.path)
        self.states: list[np.ndarray] = []
        self.colours: dict[int, np.ndarray] = {}  # frame -> geom_rgba from that frame on (when recoloured)
        self._rgba0 = self._rgba = body.model.geom_rgba.copy()
        self._t0 = body.t
        self._size = mujoco.mj_stateSize(body.model, STATE)
        self.frames = 0  # frames written by close()
        self.factor = 1  # frames kept: every factor-th recorded
        self._closed = False
        body.after_step.append(self.capture)
        self.capture()

    @property
    def recorded(self) -> int:
        return len(self.states)

    def capture(self) -> None:
        """Record the state for every frame instant reached since the last capture (cheap: no rendering)."""
        due = math.floor((self.body.t - self._t0) * self.fps / self.speed + 1e-6) + 1 - len(self.states)
        if due <= 0:
            return
        state = np.empty(self._size)
        mujoco.mj_getState(self.body.model, self.body.data, state, STATE)
        rgba = self.body.model.geom_rgba
        if not np.array_equal(rgba, self._rgba):
            self._rgba = rgba.copy()
            self.colours[len(self.states)] = self._rgba
        self.states.extend([state] * due)

    def close(self) -> None:
        """Detach from the body, render the kept frames and finish the MP4 and its ``.json`` (safe twice)."""
        if self.capture in self.body.after_step:
            self.body.after_step.remove(self.capture)
        if self._closed:
            return
        self._closed = True
        keep, self.factor = frame_indices(len(self.states), self.max_frames)
        changes = sorted(self.colours)
        frames, current, j = [], None, 0
        for i in keep:  # with the geom colours in effect at each kept frame, where a body recoloured geoms
            while j < len(changes) and changes[j] <= i:
                current, j = self.colours[changes[j]], j + 1
            frames.append((self.states[i], (self._rgba0 if current is None else current) if changes else None))
        model = pickle.loads(pickle.dumps(self.body.model))  # a copy the fast options may edit
        self.frames = render_frames(model, frames, self.path, self.fps, self.width, self.height, self.camera,
                                    self.workers)
        sim_s = (len(self.states) - 1) * self.speed / self.fps if self.states else 0.0
        meta = {"fps": self.fps, "frames": self.frames, "speed": self.speed * self.factor, "sim_s": sim_s,
                "width": self.width, "height": self.height}
        self.path.with_suffix(".json").write_text(json.dumps(meta) + "\n")
        if self.frames:  # a still for the page: the film's middle frame
            with imageio.get_reader(self.path) as reader:
                imageio.imwrite(self.path.with_suffix(".poster.jpg"), reader.get_data(self.frames // 2), quality=85)

    def __enter__(self) -> FilmRecorder:
        return self

    def __exit__(self, kind, exc, tb) -> None:
        if kind is None:
            self.close()
            return
        try:  # the run failed: film what it did, but never hide its error behind a rendering one
            self.close()
        except Exception:  # noqa: BLE001
            pass


def ensure_writable(path: Path) -> None:
    """Make ``path``'s folder, or raise one-line :class:`OSError` saying why it cannot hold the video."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(f"cannot write {path}: {exc.strerror or exc} ({exc.filename or path.parent})") from None
    if path.is_dir():
        raise OSError(f"cannot write {path}: it is a folder")
    if not os.access(path.parent, os.W_OK):
        raise OSError(f"cannot write {path}: {path.parent} is not writable")


# -- rendering (in worker processes or here) ----------------------------------------------------------
#
# Workers are fresh `python -c WORKER JOB` processes rather than multiprocessing's: a spawned
# multiprocessing child re-imports the caller's __main__ (a script without a main guard would start
# workers without end), and a forked one inherits whatever GL context its parent made. Each worker
# renders a contiguous slice of the frames into its own MP4 segment (the encoding is parallel too);
# ffmpeg's concat demuxer then joins the segments, in order, without re-encoding.


def render_here(model: mujoco.MjModel, frames: list, path: Path, fps: float, width: int, height: int,
                camera) -> int:
    """Render ``frames`` ((state, geom_rgba or None) pairs) of ``model`` into the MP4 ``path`` in this
    process; returns the number of frames written. Edits ``model``'s visual options (:func:`fast_options`)."""
    fast_options(model, width, height)
    data, cam = mujoco.MjData(model), camera_from(camera)
    written = 0
    with make_renderer(model, width, height) as renderer, imageio.get_writer(
            path, format="FFMPEG", fps=fps, codec="libx264", macro_block_size=2, ffmpeg_log_level="error") as writer:
        for state, rgba in frames:
            if rgba is not None:
                model.geom_rgba[:] = rgba
            mujoco.mj_setState(model, data, state, STATE)
            mujoco.mj_forward(model, data)
            renderer.update_scene(data, cam)
            writer.append_data(renderer.render())
            written += 1
    return written


def default_workers(frames: int) -> int:
    """Rendering processes for a film of ``frames``: the cores this process may use, fewer for a short film."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(cores, frames // MIN_FRAMES_PER_WORKER))


def render_frames(model: mujoco.MjModel, frames: list, path: Path, fps: float, width: int, height: int, camera,
                  workers: int | None = None) -> int:
    """Render ``frames`` of ``model`` into the MP4 ``path``, in order, split over ``workers`` processes
    (default :func:`default_workers`; 1 renders here). Returns the number of frames written."""
    workers = min(default_workers(len(frames)) if workers is None else max(1, int(workers)), max(1, len(frames)))
    if workers == 1:
        return render_here(model, frames, path, fps, width, height, camera)
    bounds = np.linspace(0, len(frames), workers + 1).round().astype(int)
    blob = pickle.dumps(model)
    src = str(Path(__file__).resolve().parents[2])  # the folder shintai is imported from
    env = {**os.environ, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl"), "OMP_NUM_THREADS": "1",
           "PYTHONPATH": os.pathsep.join([src, *filter(None, [os.environ.get("PYTHONPATH")])])}
    with tempfile.TemporaryDirectory(prefix=".film-", dir=path.parent) as tmp:
        jobs, procs = [], []
        for w in range(workers):
            job = Path(tmp).resolve() / f"part{w}"  # absolute: ffmpeg reads the listing's names from its folder
            job.with_suffix(".job").write_bytes(pickle.dumps(
                (blob, frames[bounds[w]:bounds[w + 1]], str(job.with_suffix(".mp4")), fps, width, height, camera)))
            jobs.append(job)
            procs.append(subprocess.Popen([sys.executable, "-c", WORKER, str(job.with_suffix(".job"))],
                                          env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
        written, failures = 0, []
        for proc in procs:
            out, err = proc.communicate()
            if proc.returncode == 0 and out.split() and out.split()[-1].isdigit():
                written += int(out.split()[-1])
            elif proc.returncode == 0:
                failures.append(f"a worker wrote no frame count (its output: {out.strip()[-200:]!r})")
            else:
                failures.append((err.strip().splitlines() or [f"exit status {proc.returncode}"])[-1])
        if failures:
            raise RuntimeError(f"rendering {path.name} failed: {failures[0]}")
        listing = Path(tmp) / "parts.txt"
        listing.write_text("".join(f"file '{job.with_suffix('.mp4')}'\n" for job in jobs))
        done = subprocess.run([imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-loglevel", "error", "-f", "concat",
                               "-safe", "0", "-i", str(listing), "-c", "copy", str(path)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            raise RuntimeError(f"joining the parts of {path.name} failed: "
                               f"{(done.stderr.strip().splitlines() or ['ffmpeg error'])[-1]}")
    return written


WORKER = "import sys; from shintai.sim.film import render_job; render_job(sys.argv[1])"


def render_job(job_file: str) -> None:
    """A worker's work: render the slice a job file holds into its MP4 segment; print the frames written."""
    blob, frames, out, fps, width, height, camera = pickle.loads(Path(job_file).read_bytes())
    print(render_here(pickle.loads(blob), frames, Path(out), fps, width, height, camera))


if __name__ == "__main__":  # python -m shintai.sim.film JOB works too
    render_job(sys.argv[1])
