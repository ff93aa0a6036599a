"""``shintai/TricyclePedal-v0``: the agent's samples go through the thesis's active/passive limbs as a joystick
script's would (seed 000 Fig. 3.16): the crank and the handle follow them, the tricycle rolls D_c per revolution."""

import gymnasium as gym
import numpy as np
import pytest

import shintai.gym  # noqa: F401
from shintai.humanoid.constants import DEG, TRICYCLE


@pytest.fixture(scope="module")
def driven():
    env = gym.make("shintai/TricyclePedal-v0")
    obs0, _ = env.reset(seed=0)
    steps = [env.step(np.array([0.0, 1.0]))[0] for _ in range(3)]  # three full crank steps, handle straight
    steps.append(env.step(np.array([1.0, -1.0]))[0])  # then one handle step, crank held
    env.close()
    return obs0, steps


def test_full_crank_steps_turn_the_crank_and_roll_the_tricycle(driven):
    obs0, steps = driven
    after = steps[2]
    assert after[9] == pytest.approx(30 * DEG)  # commanded θ_c: 3 × Δθ_c
    assert after[7] == pytest.approx(30 * DEG, abs=5 * DEG)  # measured by the robot's FK (method (a))
    travel = np.hypot(after[0] - obs0[0], after[1] - obs0[1])
    assert travel == pytest.approx(TRICYCLE.travel_per_rev * 30 / 360, rel=0.25)


def test_a_handle_step_turns_the_handle_and_holds_the_crank(driven):
    _, steps = driven
    before, after = steps[2], steps[3]
    assert after[8] == pytest.approx(5 * DEG) and after[9] == before[9]
    assert after[6] == pytest.approx(5 * DEG, abs=2 * DEG)
    assert abs(after[7] - before[7]) < 3 * DEG


def test_reset_settles_and_the_zero_action_holds():
    env = gym.make("shintai/TricyclePedal-v0")
    obs0, _ = env.reset(seed=1)
    assert min(obs0[10], obs0[11]) > 100.0  # pedal forces settled toward Table 3.4's 150 N, not the keyframe's 15 N
    obs, reward, terminated, _, info = env.step(np.zeros(2))
    env.close()
    assert obs[8] == 0.0 and obs[9] == 0.0  # nothing commanded
    assert abs(obs[7] - obs0[7]) < 2 * DEG and abs(reward) < 0.02
    assert info == {"outcome": "driving"} and not terminated


def test_seeded_resets_and_a_random_policy():
    """The generic check of tests/gym/test_envs.py (check_env runs there too), for this env."""
    from gym_checks import seeded_resets_and_a_random_policy

    seeded_resets_and_a_random_policy("shintai/TricyclePedal-v0")
