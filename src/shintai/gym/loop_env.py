"""A Gymnasium environment over a shintai Body and its modules, run by the shared Loop.

The agent is one more module: :class:`ActionModule` writes the latest action to a channel of the rig every
tick — a set channel, whose one writer it is, or an additive one, where it adds to the other modules'
contributions (a governor's place on the riders' ``foot_pitch``); :meth:`LoopEnv.step` runs the Loop for one agent period and reads the snapshot. A subclass says
what the rig is (:meth:`LoopEnv.build`), what the agent sees (:meth:`observe`) and what it is paid
(:meth:`reward`) — the bodies, laws and modules are the scenarios' own, not copies.
"""

from __future__ import annotations

from collections.abc import Sequence

import gymnasium as gym
import numpy as np

from shintai.core.runtime import Body, Channel, Loop, Module, Snapshot


class ActionModule(Module):
    """Writes the agent's latest command to ``channel`` every tick (the agent is a module of the Loop; the
    channel's kind, set or additive, is the rig's)."""

    def __init__(self, channel: str, size: int):
        super().__init__(f"agent:{channel}")
        self.channel = channel
        self.action = np.zeros(size)

    def update(self, snapshot: Snapshot):
        return {self.channel: self.action}


class LoopEnv(gym.Env):
    """Base of shintai's environments (module doc). Subclasses set ``agent_period`` (s), ``action_channel``,
    ``observation_space``, ``action_space`` and implement :meth:`build`, :meth:`observe`, :meth:`reward`;
    :meth:`to_command` maps an action to the channel's value (default: as is)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20}
    agent_period: float
    action_channel: str

    def __init__(self, render_mode: str | None = None):
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode must be None or 'rgb_array', got {render_mode!r}")
        self.render_mode = render_mode
        self.loop: Loop | None = None
        self.snapshot: Snapshot | None = None
        self._renderer = None

    # -- what a subclass provides ------------------------------------------------------------------

    def build(self, rng: np.random.Generator) -> tuple[Body, Sequence[Sequence[Module]], Sequence[Channel]]:
        """The rig for a new episode: body, stages of modules (the agent is added as a first stage), loop
        channels."""
        raise NotImplementedError

    def observe(self, snapshot: Snapshot) -> np.ndarray:
        raise NotImplementedError

    def reward(self, snapshot: Snapshot, action: np.ndarray) -> float:
        raise NotImplementedError

    def terminated(self, snapshot: Snapshot) -> bool:
        return False

    def to_command(self, action: np.ndarray) -> np.ndarray:
        return np.asarray(action, dtype=float)

    def info(self, snapshot: Snapshot) -> dict:
        """The ``info`` dict :meth:`step` returns (default: empty)."""
        return {}

    # -- Gymnasium ---------------------------------------------------------------------------------

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        body, stages, channels = self.build(self.np_random)
        self.agent = ActionModule(self.action_channel, int(np.prod(self.action_space.shape)))
        self.loop = Loop(body, stages=[[self.agent], *stages], channels=channels)
        self.ticks = int(round(self.agent_period / body.dt))
        self.snapshot = self.loop.view(body.snapshot())
        self.loop.start()
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
        return self.observe(self.snapshot), {}

    def step(self, action):
        if self.loop is None:
            raise RuntimeError("call reset() before step()")
        action = np.asarray(action, dtype=float).reshape(self.action_space.shape)
        if not np.all(np.isfinite(action)):
            raise ValueError(f"action must be finite, got {action}")
        self.agent.action = self.to_command(np.clip(action, self.action_space.low, self.action_space.high))
        self.loop.run(self.ticks * self.loop.body.dt)
        self.snapshot = self.loop.view(self.loop.body.snapshot())
        obs = self.observe(self.snapshot)
        return (obs, float(self.reward(self.snapshot, action)), bool(self.terminated(self.snapshot)), False,
                self.info(self.snapshot))

    def render(self):
        if self.render_mode != "rgb_array" or self.loop is None:
            return None
        from shintai.sim.render import make_camera, make_renderer, mujoco_of

        mj = mujoco_of(self.loop.body)
        if mj is None:
            return self.draw()
        if self._renderer is None:
            self._renderer = make_renderer(mj.model, 320, 240)
            self._camera = make_camera(mj, **self.camera())
        self._renderer.update_scene(mj.data, self._camera)
        return self._renderer.render().copy()

    def camera(self) -> dict:
        """Options of :func:`shintai.sim.render.make_camera` for a MuJoCo body's frames."""
        return {}

    def draw(self) -> np.ndarray:
        """A frame of a body that is not MuJoCo (a kinematic model): subclasses draw it."""
        raise NotImplementedError

    def close(self):
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None


def figure_pixels(fig) -> np.ndarray:
    """A matplotlib figure as an (H, W, 3) uint8 array (then closed)."""
    import matplotlib.pyplot as plt

    fig.canvas.draw()
    image = np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    plt.close(fig)
    return image
