"""shintai/QuadrupedCrawl-v0: one action is one walking cycle of the scenarios' crawl, the observation the
action network's 24 inputs (seed 004 §4)."""

import gymnasium as gym
import numpy as np

import shintai.gym  # noqa: F401  (registers the environments)
from shintai.quadruped import constants as C
from shintai.quadruped import fitness as F
from shintai.quadruped import training as T
from shintai.quadruped import world as W
from shintai.quadruped.episode import GenomePolicy, rollout


def test_the_shipped_network_as_the_agent_walks_as_in_the_scenarios():
    env = gym.make("shintai/QuadrupedCrawl-v0")
    obs, _ = env.reset(seed=3)
    inner = env.unwrapped
    net = GenomePolicy(F.ACTION_NET, T.load_action()[None], 1)
    low, high = np.asarray(C.COMMAND_RANGE[0]), np.asarray(C.COMMAND_RANGE[1])
    steps, terminated = 0, False
    while not terminated:
        command = np.clip(net(obs[None], np.array([0]))[0], low, high)
        obs, reward, terminated, truncated, _ = env.step(2 * (command - low) / (high - low) - 1)
        steps += 1
        assert reward <= 0 and not truncated
    ep = rollout(W.EnvBatch.of([inner.env]), net)
    assert steps == ep.cycles[0] and ep.reached[0] == T.success(inner.body.finish())[0]
    assert np.allclose(inner.body.state.pose[:, :2], W.EnvBatch.of([inner.env]).destination - ep.final_error, atol=1e-12)
    env.close()


def test_the_observation_is_the_action_networks_24_inputs_at_the_start():
    env = gym.make("shintai/QuadrupedCrawl-v0", environments="unseen", order="network")
    obs, _ = env.reset(seed=0)
    assert obs.shape == (24,)
    assert np.allclose(obs[:8].reshape(4, 2)[:, 0], [-0.25, 0.25, -0.25, 0.25])  # §4.1.1's initial feet, body frame
    assert np.isclose(obs[-2], env.unwrapped.env.destination[1])  # y_de at the start
    env.close()


def test_info_says_why_the_episode_ended():
    env = gym.make("shintai/QuadrupedCrawl-v0")
    ends = set()
    for seed in range(6):
        env.reset(seed=seed)
        rng = np.random.default_rng(seed)
        terminated, k = False, 0
        while not terminated:
            _, reward, terminated, truncated, info = env.step(rng.uniform(-1, 1, 3))
            k += 1
            assert info["cycle"] == k
            if not terminated:
                assert info["end"] is None and info["failure"] is None
        inner = env.unwrapped
        ep = inner.body.episodes
        assert info["end"] in ("goal", "collision", "joint limit", "unstable")
        assert info["failure"] == (None if info["end"] == "goal" else info["end"])
        assert (info["end"] == "goal") == bool(ep.reached[0])
        assert (info["failure"] is not None) == bool(ep.collided[0] or ep.limit[0] or ep.unstable[0])
        ends.add(info["end"])
    assert ends - {"goal"}  # random actions fail (module doc)
    env.close()


def test_the_shipped_network_ends_at_the_goal_in_info():
    env = gym.make("shintai/QuadrupedCrawl-v0")
    obs, _ = env.reset(seed=3)
    net = GenomePolicy(F.ACTION_NET, T.load_action()[None], 1)
    low, high = np.asarray(C.COMMAND_RANGE[0]), np.asarray(C.COMMAND_RANGE[1])
    terminated = False
    while not terminated:
        command = np.clip(net(obs[None], np.array([0]))[0], low, high)
        obs, _, terminated, _, info = env.step(2 * (command - low) / (high - low) - 1)
    assert info["end"] == ("goal" if env.unwrapped.body.episodes.reached[0] else info["failure"])
    env.close()
