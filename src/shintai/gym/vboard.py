"""``shintai/VBoardRide-v0``: HRP2-JSK rides the V-BOARD (seed 000 ch. 6, App. A.1.2) and the agent is its speed
governor — it commands u_v and u_ω, the inputs of Eq. 6.5's foot-pitch mixing [Δθ_R, Δθ_L] = [[1, 1], [1, −1]]
[u_v, u_ω], in the place of Fig. 6.6's PID (Eq. 6.2) and MLC.

The rig is behaviour level 2 of §6.2.1 (:class:`~shintai.humanoid.vboard.ride.VboardRide` ``level=2``): the
standing stack's balance (LIP tracking, ZMP distributor, foot torque damping Eqs. 5.1–5.3 with D = 40, force
difference control), Table 6.1's sensors (ω from the chest gyro every 4 ms, v from Eq. 6.3's filter every 24 ms,
24 ms late) and the foot-pitch integrator (θ̇ ≈ Δθ/Δt, Eq. 6.7) adding the soles' pitch to the damping's δ — all
but the governor, whose place the agent takes on the additive channel ``foot_pitch`` (the damping's δ adds there
as Eq. 6.5's disturbance d). Episodes start riding (:mod:`shintai.gym.riding`: lift boarding, then 0.5 s).

* **Action** (2,): (u_v, u_ω) [rad per 4 ms control period], each within ±``U_MAX`` = 3e-4 rad (0.075 rad/s of
  foot pitch); held for the agent's period, integrated every control period as the governor's output is.
* **Observation** (6,): the governor's inputs — v [m/s] and ω [rad/s] as the sensors give them, the targets v_d
  [m/s], ω_d [rad/s], and the errors e_v = v_d − v [m/s], e_ω = ω_d − ω [rad/s] (Eq. 6.2's e_*).
* **Reward**: −(|v − v_d| + W_ω |ω − ω_d|) on the scooter's *true* speeds (:mod:`~shintai.gym.riding`), W_ω = the
  wheel track's half W/2 = 0.2575 m (Fig. A.4: a yaw-rate error as the speed error it makes at each wheel).
* **Targets** (v_d, ω_d) drawn at reset within ±(0.1 m/s, 0.2 rad/s); ``options={"targets": (0, 0)}`` rides
  standing still as §6.4.1 does. **Terminated** when the robot falls (``ride.fallen()``: the waist 0.15 m low or
  tilted 0.5 rad); 500 steps of 24 ms (12 s, six of MLC's 2 s mini-batches) at most.

Measured (seed 0, v_d = ω_d = 0; 6 s rides from the first observation): the zero action rides with |v| < 6 cm/s;
u_ω = +3e-4 spins the scooter up to ω ≈ 2 rad/s within 0.6 s and falls after 4 s; u_v = +3e-4 (toes down, forward
by Eq. A.1) moves it *backwards* (−0.14 m/s after 0.6 s, against −0.02 with the zero action) and falls after
≈5 s, −3e-4 after ≈6 s — the damping cancels a foot-pitch step within ≈0.2 s (the level-3 caveat of
``vboard_ride.py``, where fixed PID gains also fall within 6 s), so u_v's authority over v is small and
wrong-signed; the example's search (``examples/vboard_black_box.py``) finds a negative K_I for v.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from shintai.gym.riding import RideEnv

# --- the adapter to the humanoid package (re-point these imports after the humanoid move) ------------------
from shintai.humanoid.constants import VBOARD, V_PERIOD
from shintai.humanoid.learning.speed_governing import foot_pitch_increments
from shintai.humanoid.vboard.constants import EXCITE_AMPLITUDE, VIEW
from shintai.humanoid.vboard.ride import VboardRide


def ride_stack(seed: int):
    """(body, stages, channels, ride): behaviour level 2 (module doc), the governor's place left to the agent."""
    ride = VboardRide(level=2, seed=seed)
    return ride.body, ride.stages, ride.channels, ride


# --- this environment's choices -------------------------------------------------------------------------
AGENT_PERIOD = V_PERIOD  # s, 24 ms = 6 control periods: the governor runs every 4 ms, but v is new every 24 ms
# (Table 6.1); one agent step per v sample
U_MAX = 5 * EXCITE_AMPLITUDE  # rad per control period, chosen: 5× the plant-identification square wave (6e-5,
# which moves v ±0.3 m/s over a 1 s half-period); at this bound a constant u falls within ≈4–6 s (measured)
V_D_MAX, OMEGA_D_MAX = 0.1, 0.2  # m/s, rad/s, chosen: small targets about §6.4.1's standing still (v_d = ω_d = 0)
OMEGA_WEIGHT = VBOARD.track / 2  # m/rad, W/2 (Fig. A.4)
EPISODE_STEPS = 500  # 12 s of riding: six MLC mini-batches (T_L = 2 s, §6.3.2)
V_BOUND, OMEGA_BOUND = 10.0, 20.0  # m/s, rad/s: observation bounds, far beyond a ride (a fall spins ≈11 rad/s)


class VBoardRideEnv(RideEnv):
    """Seed 000 ch. 6: the agent governs the V-BOARD's v and ω through Eq. 6.5 (module doc)."""

    agent_period = AGENT_PERIOD
    action_channel = "foot_pitch"
    episode_steps = EPISODE_STEPS
    target_range = np.array([V_D_MAX, OMEGA_D_MAX])
    omega_weight = OMEGA_WEIGHT
    metadata = {"render_modes": ["rgb_array"], "render_fps": round(1 / AGENT_PERIOD)}

    def __init__(self, render_mode: str | None = None):
        super().__init__(render_mode)
        self.action_space = gym.spaces.Box(-U_MAX, U_MAX, (2,), dtype=np.float64)
        bound = np.array([V_BOUND, OMEGA_BOUND])
        bound = np.concatenate([bound, self.target_range, bound + self.target_range])
        self.observation_space = gym.spaces.Box(-bound, bound, dtype=np.float64)

    def stack(self, seed):
        return ride_stack(seed)

    def to_command(self, action):
        return foot_pitch_increments(float(action[0]), float(action[1]))

    def observe(self, snapshot):
        measured = np.array([self.measured("v"), self.measured("omega")])
        measured = np.clip(measured, -self.observation_space.high[:2], self.observation_space.high[:2])
        return np.concatenate([measured, self.targets, self.targets - measured])

    def camera(self):
        return dict(VIEW)
