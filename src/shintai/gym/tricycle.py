"""``shintai/TricyclePedal-v0``: HRP2-JSK drives the tricycle of seed 000 ch. 3 for a learning agent — the agent is
the operator's joystick of Fig. 3.16: each step it chooses one command sample (how far to turn the handle and the
crank), and the robot's arms and legs carry it out with the thesis's active/passive limbs.

The body and modules are those of ``humanoid.tricycle-slalom`` (:class:`~shintai.humanoid.tricycle.ride.Ride`): HRP2 seated
on the App. A.1.1 tricycle, the arms on the handle and the legs on the crank as two role
:class:`~shintai.core.runtime.Switcher` s of :class:`~shintai.humanoid.tricycle.operation.LimbPair` (Table 3.4's
impedances, roles swapped by the FK angle estimate at Eq. 3.19's switching angles). The only difference is where
the command samples come from: here an :class:`OperatorModule` appends one per agent step to the schedule the limbs
follow (Fig. 3.16 steps 1 and 4), instead of a joystick script. Each episode asks the robot to drive to a goal
drawn ahead of it (seeded).

* **Action** (2,) in [−1, 1]: the sample's handle step Δθ_h = a₀ · 5° and crank step Δθ_c = max(a₁, 0) · 10°
  (Δθ_h = 5°, Δθ_c = 10°: §3.5.2; the crank only forward, as the thesis pedals: a₁ ≤ 0 holds it, so the zero
  action holds both). The handle target stays within
  ±25° (Θ_H, Table 3.4, §3.5.2).
* **Observation** (14,): the tricycle's pose in the world (x, y [m], yaw [rad]) and the speed of its frame's
  origin (on the crank axis) [m/s], the goal in the
  vehicle frame (x, y [m]), the handle and crank angles the robot measures by its FK (method (a), §3.4.4)
  [rad], the commanded ones [rad], each foot's vertical pedal force [N], and which leg and arm are active
  (1 = left).
* **Reward**: the distance to the goal gained in the step [m]; −1 and the episode ends if the vehicle tips over
  (tilt above ``FALL_TILT``, 30°, as in the tricycle scenarios). ``info["outcome"]``: ``"goal"``, ``"fell"`` or
  ``"driving"``.
* **Reset** lets the seated robot settle for one command sample with no step (the pedal forces rise from the
  keyframe's ≈15 N to Table 3.4's 150 N), so the first observation is a settled one.
* **Terminated** at the goal (within ``GOAL_RADIUS_M``). One step is one command sample, 2Δt = 1.6 s (Δt = 800 ms,
  §3.5.2); episodes of at most 60 samples (96 s, about 1.7 crank revolutions at full pedalling).
"""

from __future__ import annotations

import gymnasium as gym
import mujoco
import numpy as np

from shintai.core.runtime import SET, Channel, Module
from shintai.gym.loop_env import LoopEnv
from shintai.humanoid.constants import D_THETA_C, D_THETA_H, DELTA_T, FALL_TILT, THETA_H_MAX
from shintai.humanoid.tricycle.operation import DEVICES, OperationSchedule, Sample
from shintai.humanoid.tricycle.ride import RIDE_VIEW, Ride

OPERATION = Channel("operation", SET, default=None, doc="the agent's (Δθ_h, Δθ_c) for the next command sample [rad]")
GOAL_DISTANCE_M = (1.5, 3.0)  # chosen: a goal 1.5–3 m ahead (0.6–1.2 crank revolutions, D_c = 2.45 m)
GOAL_BEARING_RAD = np.deg2rad(20.0)  # … within ±20° of straight ahead
GOAL_RADIUS_M = 0.3  # chosen: about the tricycle's half track
POSITION_BOUND_M = 50.0  # observation bounds: far beyond 60 samples of pedalling
FORCE_BOUND_N = 2000.0


class OperatorModule(Module):
    """Fig. 3.16 steps 1 and 4 from an agent: every command sample (2Δt) it appends the next sample, the
    previous targets stepped by the agent's (Δθ_h, Δθ_c) from :data:`OPERATION`, to the schedule the limbs
    follow (a sample with no step holds)."""

    def __init__(self, schedule: OperationSchedule):
        super().__init__("operator", 2 * schedule.phase)
        self.schedule = schedule

    def update(self, snapshot):
        samples = self.schedule.samples
        last = samples[-1] if samples else Sample(0.0, self.schedule.theta_h0, self.schedule.theta_c0, frozenset())
        d_h, d_c = snapshot.get(OPERATION.name, (0.0, 0.0))
        theta_h = float(np.clip(last.theta_h + d_h, -THETA_H_MAX, THETA_H_MAX))
        theta_c = last.theta_c + max(float(d_c), 0.0)
        moves = frozenset(d for d, m in zip(DEVICES, (theta_h != last.theta_h, theta_c != last.theta_c)) if m)
        samples.append(Sample(len(samples) * 2 * self.schedule.phase, theta_h, theta_c, moves))
        return {}


class TricyclePedalEnv(LoopEnv):
    """Seed 000 ch. 3 tricycle driving, one Fig. 3.16 command sample per step (module doc)."""

    agent_period = 2 * DELTA_T
    action_channel = OPERATION.name
    metadata = {"render_modes": ["rgb_array"], "render_fps": 1 / (2 * DELTA_T)}  # one frame per step: real time

    def __init__(self, render_mode: str | None = None):
        super().__init__(render_mode)
        self.action_space = gym.spaces.Box(-1.0, 1.0, (2,), dtype=np.float64)
        bound = np.array([POSITION_BOUND_M, POSITION_BOUND_M, np.pi, 5.0, POSITION_BOUND_M, POSITION_BOUND_M,
                          np.pi, 200 * np.pi, np.pi, 200 * np.pi, FORCE_BOUND_N, FORCE_BOUND_N, 1.0, 1.0])
        low = -bound
        low[-2:] = 0.0
        self.observation_space = gym.spaces.Box(low, bound, dtype=np.float64)

    def build(self, rng):
        schedule = OperationSchedule(0.0, 0.0, [], DELTA_T, D_THETA_H, D_THETA_C)
        self.ride = Ride(schedule)
        distance = rng.uniform(*GOAL_DISTANCE_M)
        bearing = rng.uniform(-GOAL_BEARING_RAD, GOAL_BEARING_RAD)
        start = self.ride.body.body_pos("tricycle")[:2]
        self.goal = start + distance * np.array([np.cos(bearing), np.sin(bearing)])
        self.distance = distance
        return self.ride.body, [[OperatorModule(schedule)], [self.ride.arms, self.ride.legs]], [OPERATION]

    def to_command(self, action):
        a = np.asarray(action, dtype=float)
        return np.array([a[0] * D_THETA_H, max(a[1], 0.0) * D_THETA_C])

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed, options=options)
        self.agent.action = np.zeros(2)  # one sample with no step: the robot settles on its seat and pedals
        self.loop.run(self.agent_period)
        self.snapshot = self.loop.view(self.loop.body.snapshot())
        self.distance = float(np.linalg.norm(self.goal - self._vehicle()[0][:2]))
        return self.observe(self.snapshot), {}

    def _vehicle(self):
        body = self.ride.body
        vehicle = body.id("body", "tricycle")
        rot = body.data.xmat[vehicle].reshape(3, 3)
        return body.data.xpos[vehicle].copy(), rot

    def observe(self, snapshot):
        pos, rot = self._vehicle()
        yaw = float(np.arctan2(rot[1, 0], rot[0, 0]))
        body = self.ride.body
        velocity = np.zeros(6)  # (angular, linear) of the vehicle frame's origin, world axes
        mujoco.mj_objectVelocity(body.model, body.data, mujoco.mjtObj.mjOBJ_BODY, body.id("body", "tricycle"),
                                 velocity, 0)
        velocity = velocity[3:]
        goal = rot[:2, :2].T @ (self.goal - pos[:2])
        samples = self.ride.schedule.samples
        cmd = (samples[-1].theta_h, samples[-1].theta_c) if samples else (0.0, 0.0)
        est = [d.angle if d.angle is not None else 0.0 for d in (self.ride.arm_diag, self.ride.leg_diag)]
        fz = [self.ride.feet[side].force(snapshot)[2] for side in ("left", "right")]
        obs = np.array([pos[0], pos[1], yaw, float(np.hypot(*velocity[:2])), goal[0], goal[1], est[0], est[1],
                        cmd[0], cmd[1], fz[0], fz[1], float(self.ride.legs.active == "legs:left-active"),
                        float(self.ride.arms.active == "arms:left-active")])
        return np.clip(obs, self.observation_space.low, self.observation_space.high)

    def _tipped(self) -> bool:
        _, rot = self._vehicle()
        return bool(np.arccos(np.clip(rot[2, 2], -1.0, 1.0)) > FALL_TILT)

    def reward(self, snapshot, action):
        if self._tipped():
            return -1.0
        distance = float(np.linalg.norm(self.goal - self._vehicle()[0][:2]))
        gained, self.distance = self.distance - distance, distance
        return gained

    def terminated(self, snapshot):
        return self._tipped() or self.distance < GOAL_RADIUS_M

    def info(self, snapshot):
        return {"outcome": "fell" if self._tipped() else "goal" if self.distance < GOAL_RADIUS_M else "driving"}

    def camera(self):
        return dict(RIDE_VIEW)

