"""``shintai/ClaPosture-v0``: Cla's muscle spine (seed 003 §3.6, §4.7) holding a posture under gravity, for a
learning agent that commands its muscles.

The body is Cla's MuJoCo spine (:class:`~shintai.spine.bodies_mujoco.SpineBody`: five vertebra joints, eight
wire muscles on DC motors with encoders and tension sensors, 1 ms control). Its encoders are zeroed at the
basic posture as in §4.6.4, then every muscle runs the thesis's L mode (:class:`~shintai.spine.control.MuscleControl`,
eq. 4.33) toward the target lengths the agent sends — the agent is the "upper layer" of §4.6.5 that chooses
lengths, the firmware's length loop turns them into motor duties. Each episode asks for a uniform bend (roll
and pitch drawn within ±``max_deg``, seeded).

* **Action** (8,): target encoder lengths l_r of the eight muscles [m], each within ±15 mm of the basic
  posture's (a ±30° bend changes them by at most ≈12 mm).
* **Observation** (22,): the whole-spine posture (roll, pitch, yaw) [rad] (sum of the joint angles), the
  target posture (3) [rad], the encoder lengths (8) [m] and the tension-sensor readings (8) [N].
* **Reward**: −‖posture − target‖ [rad] per step.
* Agent period 50 ms (50 control ticks); episodes of ``duration_s`` (default 3 s = 60 steps).
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from shintai.gym.loop_env import LoopEnv
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.cla.setup import CLA_VIEW, calibrated, cla_gains
from shintai.spine.control import SETPOINTS, Mode, MuscleControl
from shintai.spine.geometry import whole_spine
from shintai.spine.robots import CLA

LENGTH_RANGE_M = 0.015  # see the module doc
AGENT_PERIOD_S = 0.05  # chosen: an upper layer at 20 Hz over the 1 ms firmware loop
T_L_KGF, T_R_KGF = 2.0, 0.5  # LL limit and T target of the controller (unused in L mode; E11's defaults)


class ClaPostureEnv(LoopEnv):
    """Cla holding a commanded bend through its muscles' L mode (module doc)."""

    agent_period = AGENT_PERIOD_S
    action_channel = "l_r"

    def __init__(self, max_deg: float = 20.0, duration_s: float = 3.0, render_mode: str | None = None):
        super().__init__(render_mode)
        self.max_rad, self.duration_s = np.radians(max_deg), duration_s
        self.action_space = gym.spaces.Box(-LENGTH_RANGE_M, LENGTH_RANGE_M, (CLA.m,), np.float64)
        bound = np.r_[np.full(6, np.pi), np.full(CLA.m, 0.1), np.full(CLA.m, 500.0)]
        self.observation_space = gym.spaces.Box(-bound, bound, dtype=np.float64)

    def build(self, rng):
        body = SpineBody(CLA)
        control = MuscleControl(CLA.m, cla_gains(T_L_KGF, T_R_KGF))
        calibrated(body, control)
        control.set_modes(Mode.L)
        self.target = np.array([*rng.uniform(-self.max_rad, self.max_rad, 2), 0.0])
        return body, [[control]], [c for c in SETPOINTS if c.name == "l_r"]

    def observe(self, snapshot):
        return np.concatenate([whole_spine(snapshot["theta"]), self.target, snapshot["encoder"], snapshot["tension"]])

    def reward(self, snapshot, action):
        return -float(np.linalg.norm(whole_spine(snapshot["theta"]) - self.target))

    def camera(self):
        return {k: v for k, v in CLA_VIEW.items() if k in ("track", "distance", "azimuth", "elevation")}
