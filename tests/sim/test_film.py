"""Films rendered after the run (shintai.sim.film): frame counts, order, time-lapse, workers, bad paths."""

import json
import math

import imageio.v2 as imageio
import numpy as np
import pytest

from shintai.core import Loop
from shintai.core.runtime import FunctionModule
from shintai.sim import MujocoBody
from shintai.sim.film import FilmRecorder, fast_options, frame_indices

# a red box sliding along x at 2 m/s past a fixed camera, no gravity: its image moves right frame by frame
SLIDER = """
<mujoco>
  <option timestep="0.01" gravity="0 0 0"/>
  <worldbody>
    <light pos="0 0 3" dir="0 0 -1"/>
    <body name="box" pos="-1 0 0">
      <joint name="x" type="slide" axis="1 0 0"/>
      <geom type="box" size="0.15 0.15 0.15" rgba="1 0 0 1"/>
    </body>
    <camera name="front" pos="0 -4 0" xyaxes="1 0 0 0 0 1"/>
  </worldbody>
  <keyframe><key name="moving" qvel="2"/></keyframe>
</mujoco>
"""


def run(body, seconds):
    Loop(body, [FunctionModule(lambda s: None)]).run(seconds)


def red_x(frame):
    """Mean column of the red pixels of a frame."""
    return np.nonzero(dominant(frame, 0))[1].mean()


def dominant(frame, channel):
    """Pixels where ``channel`` (0 red, 2 blue) exceeds the other two by a margin."""
    f = frame.astype(int)
    others = np.delete(f, channel, axis=-1).max(axis=-1)
    return f[..., channel] - others > 40


def frames_of(path):
    reader = imageio.get_reader(path)
    frames = [f for f in reader]
    reader.close()
    return frames


@pytest.mark.parametrize("workers", [1, 2])
def test_a_short_film_has_its_frames_in_order(tmp_path, workers):
    body = MujocoBody(SLIDER, substeps=2, keyframe="moving")  # dt 20 ms, a frame every 100 ms
    path = tmp_path / "film.mp4"
    with FilmRecorder(body, path, fps=10, width=160, height=96, camera="front", workers=workers) as film:
        run(body, 1.0)
    expected = math.floor(1.0 * 10) + 1
    assert film.frames == expected and body.after_step == []
    frames = frames_of(path)
    assert len(frames) == expected and frames[0].shape == (96, 160, 3)
    xs = [red_x(f) for f in frames]
    assert all(b > a for a, b in zip(xs, xs[1:])), xs  # the box moves right in every frame: in order
    meta = json.loads(path.with_suffix(".json").read_text())
    assert meta == {"fps": 10.0, "frames": expected, "speed": 1.0, "sim_s": pytest.approx(1.0), "width": 160,
                    "height": 96}


def test_workers_join_their_parts_below_a_relative_path(tmp_path, monkeypatch):
    """`make demo` writes to the relative out/demo: the parts' listing must name files ffmpeg can find."""
    monkeypatch.chdir(tmp_path)
    body = MujocoBody(SLIDER, substeps=2, keyframe="moving")
    with FilmRecorder(body, "out/demo/film.mp4", fps=10, width=64, height=48, camera="front", workers=2) as film:
        run(body, 1.0)
    assert film.frames == len(frames_of(tmp_path / "out/demo/film.mp4")) == 11


def test_speed_is_a_time_lapse(tmp_path):
    body = MujocoBody(SLIDER, substeps=2, keyframe="moving")
    with FilmRecorder(body, tmp_path / "fast.mp4", fps=10, speed=4, width=64, height=48, camera="front") as film:
        run(body, 2.0)
    assert film.frames == math.floor(2.0 * 10 / 4) + 1 == len(frames_of(tmp_path / "fast.mp4"))
    assert json.loads((tmp_path / "fast.json").read_text())["speed"] == 4.0


def test_max_frames_keeps_every_kth_frame_and_says_so(tmp_path):
    body = MujocoBody(SLIDER, substeps=2, keyframe="moving")
    with FilmRecorder(body, tmp_path / "cap.mp4", fps=20, max_frames=8, width=64, height=48,
                      camera="front") as film:
        run(body, 1.0)  # 21 recorded frames, at most 8 kept: every 3rd (0, 3, …, 18 → 7 frames)
    assert film.recorded == 21 and film.factor == 3 and film.frames == 7
    assert len(frames_of(tmp_path / "cap.mp4")) == 7
    meta = json.loads((tmp_path / "cap.json").read_text())
    assert meta["speed"] == 3.0 and meta["frames"] == 7


def test_frame_indices():
    assert frame_indices(5, None) == ([0, 1, 2, 3, 4], 1)
    assert frame_indices(5, 5) == ([0, 1, 2, 3, 4], 1)
    assert frame_indices(10, 4) == ([0, 3, 6, 9], 3)
    kept, k = frame_indices(1771, 300)
    assert len(kept) <= 300 and k == 6


def test_recoloured_geoms_are_filmed_with_their_colour_of_the_time(tmp_path):
    body = MujocoBody(SLIDER, substeps=2, keyframe="moving")

    def recolour():
        if body.t >= 0.5 - 1e-9:
            body.model.geom_rgba[0] = (0, 0, 1, 1)  # red until 0.5 s, blue afterwards

    body.after_step.insert(0, recolour)
    with FilmRecorder(body, tmp_path / "colour.mp4", fps=10, width=64, height=48, camera="front", workers=1):
        run(body, 1.0)
    frames = frames_of(tmp_path / "colour.mp4")
    blue = [int(dominant(f, 2).sum()) > int(dominant(f, 0).sum()) for f in frames]
    assert blue == [False] * 5 + [True] * 6


def test_the_fast_options_only_shrink(tmp_path):
    body = MujocoBody(SLIDER)
    model = body.model
    model.vis.quality.shadowsize, model.vis.quality.offsamples = 4096, 4
    fast_options(model, 480, 360)
    assert (model.vis.global_.offwidth, model.vis.global_.offheight) == (480, 360)
    assert model.vis.quality.shadowsize == 1024 and model.vis.quality.offsamples == 2
    model.vis.quality.shadowsize, model.vis.quality.offsamples = 256, 0
    fast_options(model, 480, 360)
    assert model.vis.quality.shadowsize == 256 and model.vis.quality.offsamples == 0


def test_a_bad_out_path_fails_before_the_run_in_one_line(tmp_path):
    (tmp_path / "file").write_text("x")
    body = MujocoBody(SLIDER)
    with pytest.raises(OSError, match="cannot write") as err:
        FilmRecorder(body, tmp_path / "file" / "video.mp4")
    assert "\n" not in str(err.value) and body.after_step == []
    with pytest.raises(KeyError, match="unknown camera"):
        FilmRecorder(body, tmp_path / "v.mp4", camera="top")


def test_a_failing_run_still_leaves_its_film_and_its_error(tmp_path):
    body = MujocoBody(SLIDER, substeps=2, keyframe="moving")
    with pytest.raises(ZeroDivisionError):
        with FilmRecorder(body, tmp_path / "part.mp4", fps=10, width=64, height=48, camera="front"):
            run(body, 0.5)
            1 / 0
    assert len(frames_of(tmp_path / "part.mp4")) == 6
