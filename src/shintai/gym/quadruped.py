"""``shintai/QuadrupedCrawl-v0``: TITAN-VIII's obstacle avoidance of seed 004 §4 for a learning agent — the
agent is the action network: each step it chooses one walking cycle's displacement.

The body is the batched crawl of the scenarios (:class:`~shintai.quadruped.episode.CrawlBody`, one episode):
quasi-static crawl gait, static stability, joint limits, the body-raise rule and foothold snapping of §4.1.
Each episode's environment is one of the 96 training environments of §4.1.1 (``environments="training"``)
or a generated unseen one (``"unseen"``: Table 1 layouts jittered as ``quadruped.generalization``), drawn
from the reset's seed. The swing order is the crawl order 4→2→3→1 (§4.1.1) or the shipped swing-order
network's choice (``order="network"``, §6, Fig. 29), a module after the agent in the same cycle.

* **Action** (3,) in [−1, 1]: the cycle's body displacement (ΔXr, ΔYr, Δθr) mapped affinely onto our chosen
  clip ``constants.COMMAND_RANGE`` (ΔXr ±0.1 m, ΔYr 0.15–0.35 m, Δθr ±15°): −1 is its low end, +1 its high end.
  This is not the robot's range nor a limit the paper imposes on actions: it is the range of the swing-order
  network's teacher patterns (seed §5.1), which we also use as the action network's output clip so that the
  swing-order network sees inputs inside what it was trained on. So ΔYr never goes below 150 mm (no standing
  still or stepping back), although the paper does not impose that minimum (issue 18).
* **Observation** (24,): the action network's inputs of seed §4 — feet (x_f1, y_f1, …, x_f4, y_f4) in the body
  frame [m], body height Zr [m], the right and left obstacles' (x_max, x_min, y_max, y_min, z_max, z_min) in the
  body frame [m] (sentinels once passed, §2.3), the destination error (x_de, y_de) [m] and θ_de [rad].
* **Reward** (chosen, from eqs. 10–12): −(x_dc² + y_dc²)/50 per cycle, and −10 (x_dc² + y_dc²) for a cycle
  that would collide, leave the joint limits or lose stability (the walk ends there, the cycle is not made).
* **Terminated** when the CoG is inside the 0.2 m goal circle or the walk failed; 50 cycles at most
  (§4.1.2; the registration's ``max_episode_steps``).
* **Info**: ``cycle`` (the walking cycle this step made or, if it failed, tried: 1, 2, …); ``end``: ``None``
  while walking, else why the episode ended — ``"goal"``, ``"collision"``, ``"joint limit"`` or ``"unstable"``
  (lost static stability); ``failure``: the same but ``None`` for ``"goal"``.

Random actions fail fast: in the review of 2026-11-27, 40 of 40 seeded random-policy episodes failed within
1–3 cycles (19 at the first) and the zero (mid-range) action failed at cycle 2–3 in 20 of 20, so an agent
learns mostly from the −10 d² failure reward at first.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from shintai.gym.loop_env import LoopEnv, figure_pixels
from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import training as T
from shintai.quadruped import world as W
from shintai.quadruped.episode import DISPLACEMENT, CrawlBody, SwingOrderModule, action_inputs
from shintai.quadruped.plots import draw_obstacles, draw_walk

POSITION_BOUND_M = 10.0  # observation bounds: far beyond any foot, obstacle corner or destination error
FAILURE_WEIGHT = 10.0  # eqs. 10-11
CYCLE_WEIGHT = 1.0 / C.MAX_CYCLES  # eq. 12's T / 50, spread over the cycles


class QuadrupedCrawlEnv(LoopEnv):
    """Seed 004 §4 obstacle avoidance, one walking cycle per step (module doc)."""

    agent_period = CrawlBody.dt
    action_channel = DISPLACEMENT.name
    metadata = {"render_modes": ["rgb_array"], "render_fps": 2}

    def __init__(self, environments: str = "training", order: str = "crawl", render_mode: str | None = None):
        super().__init__(render_mode)
        if environments not in ("training", "unseen"):
            raise ValueError(f"environments must be 'training' or 'unseen', got {environments!r}")
        if order not in ("crawl", "network"):
            raise ValueError(f"order must be 'crawl' or 'network', got {order!r}")
        self.environments, self.order = environments, order
        self.order_policy = T.load_order() if order == "network" else None
        self.low, self.high = (np.asarray(b, dtype=np.float64) for b in C.COMMAND_RANGE)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (3,), dtype=np.float64)
        bound = np.r_[np.full(23, POSITION_BOUND_M), np.pi]
        self.observation_space = gym.spaces.Box(-bound, bound, dtype=np.float64)

    def build(self, rng):
        if self.environments == "training":
            self.env = W.training_set()[int(rng.integers(96))]
        else:
            self.env = W.unseen_environments(1, int(rng.integers(2**31)))[0]
        self.body = CrawlBody(W.EnvBatch.of([self.env]), record=True)
        return self.body, [[SwingOrderModule(self.order_policy)]], [DISPLACEMENT]

    def to_command(self, action):
        """(ΔXr, ΔYr, Δθr) of the one episode, ``(1, 3)``, from an action in [−1, 1]."""
        a = np.asarray(action, dtype=float).reshape(1, 3)
        return self.low + (a + 1.0) * (self.high - self.low) / 2.0

    def observe(self, snapshot):
        body = self.body
        zr = R.body_height(body.state.pose, body.state.feet, body.envs)
        return np.clip(action_inputs(body.state, zr, body.envs)[0], self.observation_space.low,
                       self.observation_space.high)

    def _distance2(self) -> float:
        e = self.body.envs.destination[0] - self.body.state.pose[0, :2]
        return float(e @ e)

    def reward(self, snapshot, action):
        ep = self.body.episodes
        failed = bool(ep.collided[0] or ep.limit[0] or ep.unstable[0]) and self.body.k == ep.cycles[0]
        return -(FAILURE_WEIGHT if failed else CYCLE_WEIGHT) * self._distance2()

    def terminated(self, snapshot):
        return self.body.done

    def info(self, snapshot):
        """``cycle``, ``end`` and ``failure`` (module doc)."""
        ep = self.body.episodes
        end = None
        for flag, reason in ((ep.collided, "collision"), (ep.limit, "joint limit"), (ep.unstable, "unstable")):
            if flag[0]:
                end = reason
                break
        if end is None and ep.reached[0]:
            end = "goal"
        return {"cycle": int(ep.cycles[0]), "end": end,
                "failure": None if end == "goal" else end}

    def draw(self):
        """Top view: obstacles, the goal circle, the CoG path and the footholds so far."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(3.2, 3.6), dpi=100)
        records = self.body.episodes.records[0]
        if records:
            draw_walk(ax, self.env, records, triangles=False)
        else:
            draw_obstacles(ax, self.env)
            ax.plot(*self.body.state.pose[0, :2], "k.")
            ax.set_aspect("equal")
        ax.set_xlim(-1.0, 1.0)
        ax.set_ylim(-0.5, 2.6)
        ax.set_title(f"{self.env.name}, cycle {self.body.k}", fontsize=7)
        ax.tick_params(labelsize=6)
        return figure_pixels(fig)
