"""A TITAN-VIII model in MuJoCo, driven kinematically through an executed walk, rendered to MP4.

The quadruped of seed 004 is kinematic and quasi-static (§6.1): nothing here is simulated. The
MJCF (generated per environment) is a trunk box on a free joint and four legs of capsules with the
link lengths l0..l3 of seed §2.1 at the shoulders of ``constants.SHOULDER_XY``; the obstacles are
their prisms (convex meshes of the printed corners), the goal circle a flat disc.

Each leg is the chain of eq. (1): hip yaw θ0 about the vertical, then l0 horizontal, l1 at θ1 from
horizontal, l2 at the *absolute* angle θ2 (GDA: knee joint = θ2 - θ1), and l3 hanging vertically
(ankle joint = -90° - θ2). Frames are interpolated between the executor's key poses
(:class:`robot.CycleRecord`): per swing the body shifts in four-leg support, then the swing foot
lifts to its apex, moves and lands while the body stands still (seed §3.2, §4.1.1); joint angles come
from the IK of eq. (2) (:func:`robot.leg_angles`), ``qpos`` is set and ``mj_forward`` run per frame by
:class:`WalkReplay`, a Body the runner films like any MuJoCo run (:func:`film_walk`).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from shintai.core.runtime import Body, Loop
from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import world as W
from shintai.scenarios.experiment import film

FPS = 30
SHIFT_FRAMES = 4  # frames per body shift (chosen: about 0.13 s at 30 fps)
SWING_FRAMES = 8  # frames per swing: lift, move, land (chosen: about 0.27 s)
LINK_RADIUS = 0.014
TRUNK_RGBA = "0.3 0.3 0.3 1"
LEG_COLOURS = ("0.12 0.47 0.71 1", "0.84 0.15 0.16 1", "0.09 0.75 0.81 1", "0.89 0.47 0.76 1")


def _leg_xml(i: int) -> str:
    """Leg ``i``: the chain hip (θ0) → thigh (θ1) → shank (knee) → foot (ankle), one capsule per link."""
    x, y = C.SHOULDER_XY[i]
    capsule = f'type="capsule" size="{LINK_RADIUS}" rgba="{LEG_COLOURS[i]}"'
    chain = (("hip", "theta0", "0 0 1", f"{x} {y} {C.SHOULDER_DZ}", C.L0),
             ("thigh", "theta1", "0 -1 0", f"{C.L0} 0 0", C.L1),
             ("shank", "knee", "0 -1 0", f"{C.L1} 0 0", C.L2),
             ("foot", "ankle", "0 -1 0", f"{C.L2} 0 0", C.L3))
    xml = f'<geom type="sphere" size="0.02" pos="{C.L3} 0 0" rgba="0.1 0.1 0.1 1"/>'
    for body, joint, axis, pos, length in reversed(chain):
        xml = (f'<body name="{body}{i}" pos="{pos}"><joint name="{joint}_{i}" axis="{axis}"/>'
               f'<geom {capsule} fromto="0 0 0 {length} 0 0"/>{xml}</body>')
    return xml


def _obstacle_xml(k: int, obstacle: W.Obstacle) -> tuple[str, str]:
    corners = obstacle.polygon
    vertices = " ".join(f"{x:.4f} {y:.4f} {z:.4f}" for z in (0.0, obstacle.height) for x, y in corners)
    rgba = "0.55 0.55 0.58 1" if not obstacle.surmountable else "0.95 0.6 0.2 1"
    return (f'<mesh name="obstacle{k}" vertex="{vertices}"/>',
            f'<geom type="mesh" mesh="obstacle{k}" rgba="{rgba}" contype="0" conaffinity="0"/>')


def titan_mjcf(env: W.Environment) -> str:
    """The MJCF of TITAN-VIII in ``env`` (module docstring); contacts are off, nothing is simulated."""
    meshes, geoms = zip(*(_obstacle_xml(k, o) for k, o in enumerate(env.obstacles)))
    shoulders = "".join(f'<geom type="capsule" size="0.02" fromto="0 0 0 {x} {y} {C.SHOULDER_DZ}" rgba="{TRUNK_RGBA}"/>'
                        for x, y in C.SHOULDER_XY)
    gx, gy = env.destination
    return f"""
<mujoco model="titan-viii">
  <option gravity="0 0 0"/>
  <default><geom contype="0" conaffinity="0"/><joint type="hinge" limited="false"/></default>
  <visual><global offwidth="800" offheight="600"/><quality shadowsize="0"/></visual>
  <asset>
    <texture name="grid" type="2d" builtin="checker" rgb1=".88 .88 .86" rgb2=".8 .8 .78" width="300" height="300"/>
    <material name="grid" texture="grid" texrepeat="10 10"/>
    {"".join(meshes)}
  </asset>
  <worldbody>
    <light pos="0 1 3" dir="0 0 -1" directional="true" castshadow="false"/>
    <geom name="floor" type="plane" size="3 4 0.05" pos="0 1 0" material="grid"/>
    {"".join(geoms)}
    <geom name="goal" type="cylinder" size="{C.GOAL_RADIUS} 0.002" pos="{gx} {gy} 0.002" rgba="0.2 0.8 0.3 0.5"/>
    <body name="trunk" pos="0 0 {C.ZR_NOMINAL}">
      <freejoint/>
      <geom type="box" size="{C.TRUNK_WIDTH / 2} {C.BODY_LENGTH / 2} {C.TRUNK_THICKNESS / 2}" rgba="0.35 0.38 0.42 1"/>
      <geom type="box" size=".03 .03 .01" pos="0 {C.BODY_LENGTH / 2 - 0.04} {C.TRUNK_THICKNESS / 2}" rgba=".9 .9 .2 1"/>
      {shoulders}{"".join(_leg_xml(i) for i in range(4))}
    </body>
  </worldbody>
</mujoco>"""


def key_frames(records: list[R.CycleRecord], envs: W.EnvBatch) -> Iterator[tuple[np.ndarray, float, np.ndarray]]:
    """Body pose (x, y, θ), body height and world feet ``(4, 3)`` per frame of an executed walk."""
    feet = np.concatenate([R.NOMINAL_FEET, np.zeros((4, 1))], axis=1)
    zr = C.ZR_NOMINAL
    for rec in records:
        poses = rec.body_poses
        for s in range(5):
            start_z = zr if s == 0 else rec.zr
            for t in np.linspace(0.0, 1.0, SHIFT_FRAMES + 1)[1:]:
                yield poses[s] + t * (poses[s + 1] - poses[s]), start_z + t * (rec.zr - start_z), feet
            if s < 4:
                leg = rec.order[s] - 1
                for foot in _swing(feet[leg], rec.footholds[leg], envs):
                    feet = feet.copy()
                    feet[leg] = foot
                    yield poses[s + 1], rec.zr, feet
        zr = rec.zr


def _swing(a: np.ndarray, b: np.ndarray, envs: W.EnvBatch) -> np.ndarray:
    """Foot positions ``(SWING_FRAMES, 3)`` of a swing: up to the apex, across, down."""
    apex = float(R.swing_height(a[None], b[None], envs)[0][0])
    t = np.linspace(0.0, 1.0, SWING_FRAMES + 1)[1:]
    lift, move = np.clip(4 * t, 0, 1), np.clip(2 * t - 0.5, 0, 1)
    drop = np.clip(4 * t - 3, 0, 1)
    xy = a[:2] + move[:, None] * (b[:2] - a[:2])
    z = np.where(drop > 0, apex + drop * (b[2] - apex), a[2] + lift * (apex - a[2]))
    return np.column_stack([xy, z])


def joint_qpos(pose: np.ndarray, zr: float, feet: np.ndarray, previous: np.ndarray | None) -> np.ndarray:
    """``qpos`` of the model for a body pose, height and world feet; a leg out of reach keeps its
    previous angles."""
    xy = R.to_body(pose[None], feet[None, :, :2])[0]
    local = np.column_stack([xy, feet[:, 2] - zr])
    shoulder = np.column_stack([R.SHOULDER_XY, np.full(4, C.SHOULDER_DZ)])
    theta, ok = R.leg_angles(local, shoulder, np.arange(4))
    t0, t1, t2 = theta.T
    legs = np.column_stack([t0, t1, t2 - t1, -np.pi / 2 - t2])
    if previous is not None:
        legs = np.where(ok[:, None] & np.all(np.isfinite(legs), axis=1)[:, None], legs, previous[7:].reshape(4, 4))
    quat = [np.cos(pose[2] / 2), 0.0, 0.0, np.sin(pose[2] / 2)]
    return np.concatenate([[pose[0], pose[1], zr], quat, legs.ravel()])


class WalkReplay(Body):
    """An executed walk as a Body the runner can film (its one video idiom, ``scenarios.experiment.film``):
    each step shows the next key frame on TITAN-VIII's MJCF (kinematics only, ``dt`` = 1/FPS); ``mj`` is
    the MujocoBody that is filmed. The first frame is the initial stance."""

    channels: dict = {}

    def __init__(self, records: list[R.CycleRecord], env: W.Environment):
        from shintai.sim.body import MujocoBody  # MuJoCo is loaded only when a walk is filmed

        self.mj = MujocoBody(titan_mjcf(env))
        self.dt = 1.0 / FPS
        self.frames = list(key_frames(records, W.EnvBatch.of([env])))
        start = R.CrawlState.initial(1)
        self.qpos = _show(self.mj, joint_qpos(start.pose[0], C.ZR_NOMINAL, start.feet[0], None), 0.0)
        self.shown = 0

    @property
    def t(self) -> float:
        return self.mj.t

    @property
    def duration(self) -> float:
        return len(self.frames) * self.dt

    def snapshot(self) -> dict:
        return {"t": self.t}

    def apply(self, command: dict) -> None:
        pass

    def step(self) -> None:
        pose, zr, feet = self.frames[self.shown]
        self.shown += 1
        self.qpos = _show(self.mj, joint_qpos(pose, zr, feet, self.qpos), self.shown * self.dt)
        for callback in self.mj.after_step:
            callback()


VIEW = {"fps": FPS, "track": "trunk", "distance": 2.4, "azimuth": 60, "elevation": -30}


def film_walk(ctx, records: list[R.CycleRecord], env: W.Environment, variant: str | None = None
              ) -> WalkReplay | None:
    """Film an executed walk through the runner's idiom: ``video.mp4`` (``video_<variant>.mp4``) with
    ``--video``, the live viewer with ``--view``; the replay runs in a Loop of its own (not at all when
    the run asked for neither)."""
    if not (ctx.video or getattr(ctx, "view", False)):
        return None
    body = WalkReplay(records, env)
    with film(ctx, body, variant, **VIEW):
        Loop(body, []).run(body.duration)
    return body


def _show(body, qpos: np.ndarray, time: float) -> np.ndarray:
    """Put the model at ``qpos`` and time ``time`` (kinematics only: ``mj_forward``); returns ``qpos``."""
    body.data.qpos[:] = qpos
    body.data.time = time
    body.forward()
    return qpos
