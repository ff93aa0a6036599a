"""The common part of the humanoid's vehicle environments (seed 000 ch. 6–7): the agent takes the speed governor's
place in a lift-boarded ride; it is paid for tracking a target speed with the vehicle's *true* speed.

An episode starts as the scenarios' rides do (§6.4.1 Fig. 6.15, §7.3.3 Fig. 7.7 (1)): the robot is lowered onto
the vehicle by the lift, which lets go once the feet carry the weight (``ride.lift.t_release``, ≈1.0 s after the
lowering starts), then rides ``SETTLE_S`` with the zero action, so the first observation is a riding one. The
subclass gives the ride (its adapter, :meth:`RideEnv.stack`), the spaces and the observation; this file knows no
humanoid module (only the ride's ``lift``, ``sensors`` and ``fallen()``).

**Reward** per step: −min(|v − v_d| + W_ω |ω − ω_d|, ``ERROR_CAP``) [m/s], the true v, ω (``ride.sensors.true_v``,
``true_omega``), W_ω a subclass's weight [m/rad] (0 where ω is not governed). The step that falls pays
``ERROR_CAP`` for every step left to the time limit (``episode_steps``), so that falling never pays better than
riding on with the worst error.
"""

from __future__ import annotations

import numpy as np

from shintai.gym.loop_env import LoopEnv

SETTLE_S = 0.5  # s, chosen: after the release the sensors' v (Eq. 6.3's filter, T_f = 0.5 s) and the scooter's
# hand-over transient settle (measured on the V-BOARD: true v −0.05 → −0.02 m/s within 0.5 s)
BOARDING_TIMEOUT_S = 3.0  # s, chosen: the lift lets go ≈1.0 s after the lowering starts (vboard_ride.py); 3× that
ERROR_CAP = 1.0  # m/s, chosen: a step's cost is at most a 1 m/s error (a falling rider's speeds run higher)


class RideEnv(LoopEnv):
    """Lift boarding, speed-tracking reward and fall termination (module doc). Subclasses set ``agent_period``,
    ``action_channel``, ``episode_steps``, ``target_range`` (half-widths of (v_d[, ω_d]) drawn uniformly at
    reset; ``options={"targets": ...}`` fixes them) and ``omega_weight``, and implement :meth:`stack` and
    :meth:`observe`."""

    episode_steps: int
    target_range: np.ndarray
    omega_weight: float = 0.0

    def stack(self, seed: int):
        """The adapter to the humanoid package: ``(body, stages, channels, ride)`` for a ride whose sensors'
        noise follows ``seed``."""
        raise NotImplementedError

    def build(self, rng):
        body, stages, channels, self.ride = self.stack(int(rng.integers(2**31 - 1)))
        fixed = self._options.get("targets")
        n = len(self.target_range)
        if fixed is None:
            self.targets = rng.uniform(-self.target_range, self.target_range)
        else:
            targets = np.asarray(fixed, dtype=float).reshape(-1)
            if targets.shape != (n,) or not np.all(np.isfinite(targets)):
                raise ValueError(f"options['targets'] must be {n} finite numbers, got {fixed!r}")
            if np.any(np.abs(targets) > self.target_range):
                raise ValueError(f"options['targets'] must lie within ±{self.target_range.tolist()}, got {fixed!r}")
            self.targets = targets
        return body, stages, channels

    def reset(self, *, seed=None, options=None):
        options = dict(options or {})
        unknown = set(options) - {"targets"}
        if unknown:
            raise ValueError(f"unknown reset options {sorted(unknown)}; allowed: 'targets'")
        self._options = options
        super().reset(seed=seed, options=options)
        self.agent.action = self.to_command(np.zeros(self.action_space.shape))
        self.loop.run(BOARDING_TIMEOUT_S, until=lambda _: self.ride.lift.released)
        if not self.ride.lift.released:
            raise RuntimeError(f"the lift did not let go within {BOARDING_TIMEOUT_S} s of lowering")
        self.loop.run(SETTLE_S)
        self.snapshot = self.loop.view(self.loop.body.snapshot())
        self.steps = 0
        return self.observe(self.snapshot), self.info(self.snapshot)

    def step(self, action):
        if self.loop is None:
            return super().step(action)  # the base's error
        self.steps += 1  # before the reward: a fall pays for the steps after this one
        try:
            return super().step(action)
        except ValueError:  # a refused action is no step
            self.steps -= 1
            raise

    def measured(self, name: str) -> float:
        """The latest value of a loop channel the ride's sensors write (``v``, ``omega``; 0 before the first tick)."""
        return float(self.loop.command.get(name, 0.0))

    def truth(self) -> np.ndarray:
        """The vehicle's true (v [m/s], ω [rad/s])."""
        return np.array([self.ride.sensors.true_v, self.ride.sensors.true_omega])

    def tracking_error(self) -> float:
        """|v − v_d| + W_ω |ω − ω_d| [m/s] on the true speeds."""
        v, w = self.truth()
        err = abs(v - self.targets[0])
        if self.omega_weight:
            err += self.omega_weight * abs(w - self.targets[1])
        return float(err)

    def reward(self, snapshot, action):
        if self.ride.fallen():
            return -ERROR_CAP * max(self.episode_steps - self.steps + 1, 1)
        return -min(self.tracking_error(), ERROR_CAP)

    def terminated(self, snapshot):
        return self.ride.fallen()

    def info(self, snapshot):
        v, w = self.truth()
        return {"true_v": float(v), "true_omega": float(w), "targets": self.targets.copy(),
                "fallen": bool(self.ride.fallen()), "t_ride": float(self.loop.body.t - self.ride.lift.t_release)}
