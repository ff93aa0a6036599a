"""The kinematically driven TITAN-VIII MJCF of ``quadruped.video``."""

from types import SimpleNamespace

import mujoco
import numpy as np

from shintai.quadruped import training as T
from shintai.quadruped import video as V
from shintai.quadruped import world as W
from shintai.sim.body import MujocoBody


def two_cycles():
    env = W.scenario_421()
    ep = T.evaluate(T.load_action(), W.EnvBatch.of([env]), record=True)
    return env, ep.records[0][:2]


def foot_tips(body: MujocoBody) -> np.ndarray:
    spheres = [g for g in range(body.model.ngeom) if body.model.geom_type[g] == mujoco.mjtGeom.mjGEOM_SPHERE]
    return np.array([body.data.geom_xpos[g] for g in spheres])


def test_the_model_puts_its_feet_where_the_executor_does():
    """Eq. (1) in MJCF: with the IK angles set as qpos, every foot tip is at the commanded foothold."""
    env, records = two_cycles()
    frames = list(V.key_frames(records, W.EnvBatch.of([env])))
    assert len(frames) == 2 * (5 * V.SHIFT_FRAMES + 4 * V.SWING_FRAMES)
    body = MujocoBody(V.titan_mjcf(env))
    qpos = None
    for pose, zr, feet in frames[::7]:
        qpos = V.joint_qpos(pose, zr, feet, qpos)
        body.data.qpos[:] = qpos
        body.forward()
        assert np.allclose(foot_tips(body), feet, atol=1e-9)
        assert np.allclose(body.body_pos("trunk"), [pose[0], pose[1], zr])


def test_a_walk_is_filmed_through_the_runners_idiom(tmp_path):
    """One frame per key frame and the initial stance, into video_<variant>.mp4 as film() names it."""
    env, records = two_cycles()
    ctx = SimpleNamespace(video=True, view=False, out=tmp_path)
    replay = V.film_walk(ctx, records[:1], env, "one")
    assert replay.shown == len(replay.frames) == 5 * V.SHIFT_FRAMES + 4 * V.SWING_FRAMES
    assert (tmp_path / "video_one.mp4").stat().st_size > 0
    assert V.film_walk(SimpleNamespace(video=False, view=False, out=tmp_path), records[:1], env) is None
