"""Every registered environment passes Gymnasium's checker, resets identically from a seed, and runs a random
policy for 200 steps."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import shintai.gym
from shintai.gym import ENVIRONMENTS

IDS = sorted(ENVIRONMENTS)


@pytest.mark.parametrize("env_id", IDS)
def test_checker_passes(env_id):
    env = gym.make(env_id, render_mode="rgb_array")
    try:
        check_env(env.unwrapped, skip_render_check=False)
    finally:
        env.close()


@pytest.mark.parametrize("env_id", IDS)
def test_seeded_resets_and_a_random_policy(env_id):
    env = gym.make(env_id, render_mode="rgb_array")
    try:
        first, _ = env.reset(seed=7)
        again, _ = env.reset(seed=7)
        other, _ = env.reset(seed=8)
        assert np.array_equal(first, again) and not np.array_equal(first, other)
        assert env.observation_space.contains(first)
        env.action_space.seed(0)
        rewards = []
        for _ in range(200):
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


def test_registered_ids_are_gymnasium_makeable():
    assert set(IDS) <= set(gym.registry) and shintai.gym.__name__ == "shintai.gym"


def test_a_bad_action_is_refused():
    env = gym.make("shintai/SnakeTwoPoint-v0")
    env.reset(seed=0)
    with pytest.raises(ValueError, match="finite"):
        env.unwrapped.step(np.full(9, np.nan))
    env.close()


def test_the_example_random_search_runs():
    import runpy
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "random_search_snake.py"
    runpy.run_path(str(example), run_name="example")["main"](0.5)
