"""Benchmarks of the MuJoCo body: what MujocoBody and the Loop add on top of bare ``mj_step``; films
rendered after the run against rendering during it.

The model is a mid-size chain (hinge links with position servos and an IMU/force sensor set), the
kind of body the humanoids and snakes are. All variants take the same physics steps; times are
per physics step except ``snapshot_us`` and ``snapshot_whole_us`` (per call: a snapshot as a Loop takes it, its
entries formed when read, and one with every entry formed, what the snapshot cost before issue 30 made it lazy).
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import mujoco
import numpy as np

from shintai.core.runtime import FunctionModule, Loop
from shintai.scenarios.registry import benchmark
from shintai.sim.body import MujocoBody


def chain_xml(links: int = 15) -> str:
    """A hanging chain of ``links`` hinge links, each with a position servo, and tip/base sensors."""
    body = '<site name="tip" pos="0 0 -0.1"/>'
    for i in reversed(range(links)):
        axis = "0 1 0" if i % 2 == 0 else "1 0 0"
        site = '<site name="base"/>' if i == 0 else ""
        body = (f'<body name="link{i}" pos="0 0 {-0.1 if i else 0}">'
                f'<joint name="j{i}" type="hinge" axis="{axis}" damping="0.05" armature="0.01"/>'
                f'<geom type="capsule" fromto="0 0 0 0 0 -0.1" size="0.02" mass="0.2"/>'
                f'{site}{body}</body>')
    actuators = "".join(f'<position name="a{i}" joint="j{i}" kp="20" kv="0.5"/>' for i in range(links))
    return f"""<mujoco><option timestep="0.002" integrator="implicitfast"/>
      <worldbody><body name="mount" pos="0 0 2">{body}</body></worldbody>
      <actuator>{actuators}</actuator>
      <sensor><framequat name="imu_quat" objtype="site" objname="tip"/><gyro name="imu_gyro" site="tip"/>
        <accelerometer name="imu_acc" site="tip"/><force name="base_force" site="base"/>
        <torque name="base_torque" site="base"/><jointpos name="j0_pos" joint="j0"/></sensor>
    </mujoco>"""


def bare(model: mujoco.MjModel, steps: int) -> float:
    data = mujoco.MjData(model)
    data.ctrl[:] = 0.3
    t0 = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, data)
    return time.perf_counter() - t0


def body_only(model: mujoco.MjModel, steps: int) -> float:
    body = MujocoBody(model)
    body.apply({"ctrl": np.full(model.nu, 0.3)})
    return timed(body.step, steps)


def snapshots(model: mujoco.MjModel, steps: int) -> float:
    return timed(MujocoBody(model).snapshot, steps)


def whole_snapshots(model: mujoco.MjModel, steps: int) -> float:
    body = MujocoBody(model)
    return timed(lambda: body.snapshot().keys(), steps)  # keys() forms every entry


def in_loop(model: mujoco.MjModel, steps: int, substeps: int = 1) -> float:
    """``steps`` physics steps as ``steps / substeps`` Loop steps with one module holding a posture."""
    body = MujocoBody(model, substeps)
    command = {"ctrl": np.full(model.nu, 0.3)}
    loop = Loop(body, [FunctionModule(lambda snapshot: command, name="hold")])
    loop.start()
    return timed(loop.step, steps // substeps)


def timed(fn, calls: int) -> float:
    t0 = time.perf_counter()
    for _ in range(calls):
        fn()
    return time.perf_counter() - t0


@benchmark("sim.body-overhead", "MujocoBody step + snapshot + Loop vs bare mj_step, same physics steps")
def body_overhead(steps: int = 4000, links: int = 15, repeats: int = 5) -> dict:
    """Per physics step (us): bare mj_step, MujocoBody.step, snapshot (lazy, and with every entry read), a Loop at
    1 and 4 substeps.

    Variants are interleaved and the best of ``repeats`` kept, to damp noise from other processes.
    """
    model = mujoco.MjModel.from_xml_string(chain_xml(links))
    variants = {"bare_mj_step": lambda: bare(model, steps), "body_step": lambda: body_only(model, steps),
                "snapshot": lambda: snapshots(model, steps), "snapshot_whole": lambda: whole_snapshots(model, steps),
                "loop_step": lambda: in_loop(model, steps),
                "loop_4_substeps": lambda: in_loop(model, steps, 4)}
    bare(model, 500)  # warm-up
    best = dict.fromkeys(variants, float("inf"))
    for _ in range(repeats):
        for name, run in variants.items():
            best[name] = min(best[name], run())
    out = {f"{name}_us": 1e6 * t / steps for name, t in best.items()}
    for name in ("body_step", "loop_step", "loop_4_substeps"):
        out[f"ratio_{name}_vs_bare"] = best[name] / best["bare_mj_step"]
    out.update(links=links, physics_steps=steps)
    return out


def lit_chain_xml(links: int = 15) -> str:
    """:func:`chain_xml` on a lit checker floor, with MuJoCo's default visual quality (4096² shadow map, 4×
    multisampling): the kind of scene the films show."""
    floor = ('<asset><texture name="grid" type="2d" builtin="checker" width="512" height="512" rgb1=".2 .3 .4" '
             'rgb2=".1 .2 .3"/><material name="grid" texture="grid" texrepeat="4 4"/></asset>')
    scene = ('<light pos="0 0 4" dir="0 0 -1" castshadow="true"/>'
             '<geom name="floor" type="plane" size="3 3 0.1" material="grid"/>')
    return chain_xml(links).replace("<worldbody>", floor + "<worldbody>" + scene)


def filmed_run(recorder, links: int, seconds: float, fps: float, **options) -> tuple[float, int]:
    """Wall time of a Loop run of ``seconds`` filmed by ``recorder`` (rendering included), and its frames."""
    from shintai.scenarios.experiment import VIDEO_DEFAULTS

    body = MujocoBody(mujoco.MjModel.from_xml_string(lit_chain_xml(links)), 5)
    command = {"ctrl": np.sin(np.arange(body.model.nu))}
    loop = Loop(body, [FunctionModule(lambda snapshot: command, name="hold")])
    size = {k: VIDEO_DEFAULTS[k] for k in ("width", "height")}
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        with recorder(body, Path(tmp) / "video.mp4", fps=fps, track="link7", **size, **options) as rec:
            loop.run(seconds)
        wall = time.perf_counter() - t0
    return wall, rec.frames


@benchmark("sim.film-fps", "frames per second of a filmed run: rendered after the run on workers vs during it")
def film_fps(seconds: float = 4.0, fps: float = 30.0, links: int = 15, repeats: int = 2) -> dict:
    """One filmed run three ways, same frames (no cap): today's :class:`~shintai.sim.render.VideoRecorder`
    (renders in the loop, the model's visual options), :class:`~shintai.sim.film.FilmRecorder` on one
    process (the fast options only), and on the default workers (all the cores). Frames per second of wall
    time, simulation included (it is the same in all three), and the ratios to today's. The three are
    interleaved and the best of ``repeats`` kept, to damp the noise of other processes."""
    from shintai.sim.film import FilmRecorder, default_workers
    from shintai.sim.render import VideoRecorder

    frames = int(seconds * fps) + 1
    runs = {"during_run": (VideoRecorder, {}), "after_run_1_worker": (FilmRecorder, {"workers": 1, "max_frames": None}),
            "after_run_workers": (FilmRecorder, {"max_frames": None})}
    best = dict.fromkeys(runs, float("inf"))
    for _ in range(repeats):
        for name, (recorder, options) in runs.items():
            wall, n = filmed_run(recorder, links, seconds, fps, **options)
            if n != frames:
                raise RuntimeError(f"{name}: {n} frames, expected {frames}")
            best[name] = min(best[name], wall)
    out = {f"{name}_fps": frames / wall for name, wall in best.items()}
    for name in ("after_run_1_worker", "after_run_workers"):
        out[f"ratio_{name}_vs_during_run"] = out[f"{name}_fps"] / out["during_run_fps"]
    out.update(frames=frames, workers=default_workers(frames))
    return out
