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
