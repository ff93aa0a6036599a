"""``shintai/NinebotRide-v0``: HRP2-JSK rides the Ninebot One S2 (seed 000 §7.3.3, App. A.1.3) and the agent is
its speed controller C_v — it commands u_v, which Eq. 6.5 with u_ω = 0 (the Ninebot has no yaw input) turns into
the foot-pitch increments [Δθ_R, Δθ_L] = [u_v, u_v], as :class:`~shintai.humanoid.unicycle.ride.SpeedPID` does.

The rig is Fig. 7.8's (:class:`~shintai.humanoid.unicycle.ride.NinebotRide` ``control="parallel"``) with both
controllers at fixed zero gains (``learn=False``): the standing stack's balance on the footboards, Table 6.1's
sensors (v of Eq. 6.3's filter), the foot-pitch integrator (Eq. 6.7) and the training wheels of the learning
runs (NinebotRide's default); C_v's u and C_traj's trajectory correction c (Eq. 7.3, channel ``zmp_mod``) stay
0. The agent adds its u_v on the additive channel ``foot_pitch`` beside C_v's zero, so it is C_v. (C_traj's c is a
set channel that C_traj writes; an agent for it would need the ``control="stabilizer"`` rig, which has no
foot-pitch integrator.) Episodes start riding (:mod:`shintai.gym.riding`: lift boarding, then 0.5 s).

* **Action** (1,): u_v [rad per 4 ms control period] within ±``U_MAX`` (the V-BOARD's bound,
  :mod:`shintai.gym.vboard`), held for the agent's period (24 ms, one v sample of Table 6.1).
* **Observation** (3,): C_v's inputs — v [m/s] as the sensors give it, the target v_d [m/s] and the error
  e_v = v_d − v [m/s] (Eq. 7.1).
* **Reward**: −|v − v_d| on the Ninebot's *true* speed (:func:`~shintai.humanoid.vehicles.ninebot.ninebot_velocity`;
  ω is not governed, W_ω = 0). **Target** v_d drawn at reset within ±0.1 m/s; ``options={"targets": (0.0,)}``
  stands still as §7.3.3's runs do. **Terminated** on a fall (``ride.fallen()``); at most 500 steps (12 s).

Measured (seed 0, v_d = 0; 6 s rides from the first observation): the zero action rides with |v| < 1 cm/s;
u_v = ∓3e-4 drifts v to ±3 cm/s within 2.5 s, then runs away (±0.5 m/s) and falls after ≈5 s — toes down drives
the Ninebot backwards, as on the V-BOARD.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from shintai.gym.riding import RideEnv
from shintai.gym.vboard import AGENT_PERIOD, EPISODE_STEPS, U_MAX, V_BOUND, V_D_MAX

# --- the adapter to the humanoid package (re-point these imports after the humanoid move) ------------------
from shintai.humanoid.learning.speed_governing import foot_pitch_increments
from shintai.humanoid.unicycle.constants import VIEW
from shintai.humanoid.unicycle.ride import NinebotRide


def ride_stack(seed: int):
    """(body, stages, channels, ride): Fig. 7.8's rig at fixed zero gains (module doc), C_v's output the agent's."""
    ride = NinebotRide(control="parallel", learn=False, seed=seed)
    return ride.body, ride.stages, ride.channels, ride


class NinebotRideEnv(RideEnv):
    """Seed 000 §7.3.3: the agent is the Ninebot's speed controller C_v (module doc)."""

    agent_period = AGENT_PERIOD
    action_channel = "foot_pitch"
    episode_steps = EPISODE_STEPS
    target_range = np.array([V_D_MAX])
    metadata = {"render_modes": ["rgb_array"], "render_fps": round(1 / AGENT_PERIOD)}

    def __init__(self, render_mode: str | None = None):
        super().__init__(render_mode)
        self.action_space = gym.spaces.Box(-U_MAX, U_MAX, (1,), dtype=np.float64)
        bound = np.array([V_BOUND, V_D_MAX, V_BOUND + V_D_MAX])
        self.observation_space = gym.spaces.Box(-bound, bound, dtype=np.float64)

    def stack(self, seed):
        return ride_stack(seed)

    def to_command(self, action):
        return foot_pitch_increments(float(np.asarray(action).reshape(-1)[0]), 0.0)

    def observe(self, snapshot):
        v = float(np.clip(self.measured("v"), -V_BOUND, V_BOUND))
        return np.array([v, self.targets[0], self.targets[0] - v])

    def camera(self):
        return dict(VIEW)
