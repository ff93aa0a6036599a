"""``shintai/SnakeTwoPoint-v0``: the passive-wheel snake's two-point task of seed 001 §3.3 for a learning
agent — move the head and the tail wheel along their targets with joint-rate commands.

The body is the thesis's kinematic snake (:class:`~shintai.snake.plant.KinematicSnake`, n = 9, δt = 0.05 s,
no-slip constraints of the grounded wheels, eq. 2.10) started at §3.3's pose. Each episode's targets are a
ramp (3.21) from the start to an end pose drawn around §3.3's c_{c,e} (seeded). With ``switching=True`` the
wheels' mode is chosen by the thesis's mode selection every t_σ = 2 s (:class:`~shintai.snake.two_point.ModeSelection`,
V_m of eq. 3.19); with ``False`` the mode chosen at t = 0 stays (the constraint never switches).

* **Action** (9,): yaw-joint rates φ̇ [rad/s], each in [−1, 1] (§3.3's input limit u_lim = 4 bounds their norm
  by 4 rad/s; a box of ±1 keeps the norm ≤ 3).
* **Observation** (36,): the controlled variables c = [x_h, y_h, θ_h, x_t, y_t, θ_t] [m, rad] (3.2), their
  targets c_d at this instant, the ramp's end c_{c,e}, the joint angles φ [rad] (9) and the grounded wheels σ
  (9, 1 = on the floor).
* **Reward**: −(‖head position error‖ + ‖tail position error‖) [m] per step (0 is perfect tracking).
* Episodes of ``duration_s`` (default 30 s = 600 steps of 0.05 s); the ramp takes two thirds of it.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from shintai.gym.loop_env import LoopEnv, figure_pixels
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, TRACKING
from shintai.snake.model import body_points, configuration
from shintai.snake.plant import KinematicSnake
from shintai.snake.targets import PiecewiseLinear
from shintai.snake.two_point import ModeSelection, TwoPointLaw

TARGET_SPREAD_M = 0.1  # chosen: end positions drawn within ±10 cm of §3.3's, headings within ±0.3 rad
TARGET_SPREAD_RAD = 0.3
RATE_LIMIT = 1.0  # rad/s per joint (see the module doc)
POSITION_BOUND_M = 20.0  # observation bounds: far beyond where 1 rad/s joints take the snake in an episode
HEADING_BOUND_RAD = 8 * np.pi  # headings are unwrapped (A6), so they may pass ±π


class SnakeTwoPointEnv(LoopEnv):
    """Seed 001 §3.3 two-point tracking with joint-rate actions (module doc)."""

    agent_period = CH3_GAINS.dt
    action_channel = "phi_dot"
    metadata = {"render_modes": ["rgb_array"], "render_fps": int(round(1 / CH3_GAINS.dt))}

    def __init__(self, switching: bool = True, duration_s: float = 30.0, render_mode: str | None = None):
        super().__init__(render_mode)
        self.switching, self.duration_s = switching, duration_s
        self.law = TwoPointLaw(CH3_ROBOT, CH3_GAINS)
        n = CH3_ROBOT.n
        self.action_space = gym.spaces.Box(-RATE_LIMIT, RATE_LIMIT, (n,), np.float64)
        pose = [POSITION_BOUND_M, POSITION_BOUND_M, HEADING_BOUND_RAD] * 2  # c, then c_d, then c_{c,e}
        low = np.array([-b for b in pose * 3] + [-np.pi] * n + [0.0] * n)
        self.observation_space = gym.spaces.Box(low, -low + np.r_[np.zeros(18 + n), np.ones(n)], dtype=np.float64)

    def build(self, rng):
        body = KinematicSnake(TRACKING.w_h0, TRACKING.phi0, CH3_ROBOT, CH3_GAINS.dt)
        c0 = self.law.controlled(configuration(TRACKING.w_h0, TRACKING.phi0, CH3_ROBOT.l))
        spread = np.array([TARGET_SPREAD_M, TARGET_SPREAD_M, TARGET_SPREAD_RAD] * 2)
        c_e = np.asarray(TRACKING.c_e) + rng.uniform(-spread, spread)
        self.target = PiecewiseLinear.ramp(c0, c_e, 2.0 * self.duration_s / 3.0)
        modes = ModeSelection(self.law, CH3_GAINS.t_sigma if self.switching else None)
        return body, [[modes]], ()

    def controlled(self, snapshot) -> np.ndarray:
        return self.law.controlled(configuration(snapshot["w_h"], snapshot["phi"], CH3_ROBOT.l))

    def observe(self, snapshot):
        c_d, _ = self.target(float(snapshot["t"]))
        return np.concatenate([self.controlled(snapshot), c_d, self.target.poses[-1], snapshot["phi"],
                               np.asarray(snapshot["grounded"], dtype=float)])

    def reward(self, snapshot, action):
        e = self.target(float(snapshot["t"]))[0] - self.controlled(snapshot)
        return -(np.hypot(e[0], e[1]) + np.hypot(e[3], e[4]))

    def draw(self):
        """Top view: the body (▲ head), grounded wheels red, lifted hollow, the targets as crosses."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        snap = self.snapshot
        cfg = configuration(snap["w_h"], snap["phi"], CH3_ROBOT.l)
        pts = body_points(cfg)
        c_d, _ = self.target(float(snap["t"]))
        fig, ax = plt.subplots(figsize=(3.2, 2.4), dpi=100)
        ax.plot(pts[:, 0], pts[:, 1], "-", color="0.3", lw=2)
        ax.plot(*pts[0], "^", color="tab:orange")
        ax.plot([c_d[0], c_d[3]], [c_d[1], c_d[4]], "x", color="tab:green")
        ax.set_aspect("equal")
        ax.set_xlim(-1.2, 0.6)
        ax.set_ylim(-0.9, 0.5)
        ax.set_title(f"t = {snap['t']:.1f} s", fontsize=8)
        ax.tick_params(labelsize=6)
        return figure_pixels(fig)
