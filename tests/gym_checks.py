"""Checks every Gymnasium environment of shintai passes (used by tests/gym)."""

import gymnasium as gym
import numpy as np

import shintai.gym  # noqa: F401

# a few random steps (issue 29: a suite that keeps pace): finite observations and rewards, the rewards not all
# equal, a rendered frame; long random runs belong to benchmarks (200 tricycle steps were ≈ 5 min of riding)
RANDOM_STEPS = 5


def seeded_resets_and_a_random_policy(env_id: str) -> None:
    """Seeded resets give identical first observations; a random policy runs ``RANDOM_STEPS`` steps (issue 19)."""
    env = gym.make(env_id, render_mode="rgb_array")
    try:
        first, _ = env.reset(seed=7)
        again, _ = env.reset(seed=7)
        other, _ = env.reset(seed=8)
        assert np.array_equal(first, again) and not np.array_equal(first, other)
        assert env.observation_space.contains(first)
        env.action_space.seed(0)
        rewards = []
        for _ in range(RANDOM_STEPS):
            obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
            assert np.all(np.isfinite(obs)) and np.isfinite(reward)
            rewards.append(reward)
            if terminated or truncated:
                env.reset()
        frame = env.render()
        assert frame.ndim == 3 and frame.shape[2] == 3 and frame.std() > 0
        assert len(set(np.round(rewards, 9))) > 1
    finally:
        env.close()
