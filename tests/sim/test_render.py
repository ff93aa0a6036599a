"""Headless rendering: PNG stills, MP4 videos with the expected frame count, clear GL errors."""

import math
import os
import subprocess
import sys

import imageio.v2 as imageio
import mujoco
import pytest

from shintai.core import Loop
from shintai.core.runtime import FunctionModule
from shintai.sim import MujocoBody, VideoRecorder, render, render_png

SCENE = """
<mujoco>
  <option timestep="0.005"/>
  <worldbody>
    <light pos="0 0 3" dir="0 0 -1"/>
    <geom name="floor" type="plane" size="2 2 0.1" rgba="0.3 0.5 0.3 1"/>
    <body name="ball" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.1" rgba="0.9 0.2 0.2 1"/>
    </body>
    <camera name="side" pos="0 -3 1" xyaxes="1 0 0 0 0 1"/>
  </worldbody>
</mujoco>
"""


@pytest.mark.parametrize("view", [{}, {"track": "ball"}, {"camera": "side"}])
def test_png_is_written_and_not_blank(tmp_path, view):
    body = MujocoBody(SCENE)
    path = tmp_path / "still.png"
    image = render_png(body, path, width=160, height=120, **view)
    assert image.shape == (120, 160, 3)
    read = imageio.imread(path)
    assert read.shape == (120, 160, 3) and read.astype(float).var() > 0


def test_png_larger_than_default_offscreen_buffer(tmp_path):
    image = render_png(MujocoBody(SCENE), tmp_path / "big.png", width=800, height=600)
    assert image.shape == (600, 800, 3)


def test_mp4_of_a_loop_run_has_one_frame_per_instant(tmp_path):
    body = MujocoBody(SCENE, substeps=2)  # dt = 10 ms, 1/fps = 40 ms
    path = tmp_path / "run.mp4"
    duration, fps = 0.5, 25
    with VideoRecorder(body, path, fps=fps, width=160, height=120, track="ball") as recorder:
        Loop(body, [FunctionModule(lambda s: None)]).run(duration)
    expected = math.floor(duration * fps) + 1
    assert recorder.frames == expected
    assert body.after_step == []  # detached on close
    reader = imageio.get_reader(path)
    assert reader.count_frames() == expected
    frame = reader.get_data(0)
    reader.close()
    assert frame.shape == (120, 160, 3)


def test_body_step_longer_than_a_frame_repeats_frames(tmp_path):
    body = MujocoBody(SCENE, substeps=20)  # dt = 100 ms
    with VideoRecorder(body, tmp_path / "slow.mp4", fps=30, width=64, height=48) as recorder:
        for _ in range(3):
            body.step()
    assert recorder.frames == math.floor(0.3 * 30) + 1


def test_unknown_camera_or_body_raises_key_error(tmp_path):
    body = MujocoBody(SCENE)
    with pytest.raises(KeyError, match="unknown camera 'top'"):
        render_png(body, tmp_path / "x.png", camera="top")
    with pytest.raises(KeyError, match="unknown body 'robot'"):
        VideoRecorder(body, tmp_path / "x.mp4", track="robot")


def test_unavailable_gl_gives_one_line_fix(tmp_path, monkeypatch):
    def no_gl(*args, **kwargs):
        raise ImportError("Cannot initialize a EGL device display.\nsecond line")

    monkeypatch.setattr(mujoco, "Renderer", no_gl)
    monkeypatch.setattr(render, "_gl_failure", None)  # restored afterwards: later tests render
    with pytest.raises(RuntimeError, match="MUJOCO_GL=egl") as err:
        render_png(MujocoBody(SCENE), tmp_path / "x.png")
    assert "\n" not in str(err.value) and "Cannot initialize a EGL device display" in str(err.value)


def test_mujoco_imported_before_shintai_sim_still_renders_headless(tmp_path):
    script = (f"import mujoco\nfrom shintai.sim import MujocoBody, render_png\n"
              f"render_png(MujocoBody({SCENE!r}), {str(tmp_path / 'late.png')!r}, width=64, height=48)\n")
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM", "DISPLAY")}
    result = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "late.png").is_file()
