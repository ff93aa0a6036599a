"""Every registered environment passes Gymnasium's checker, resets identically from a seed, and runs a random
policy for a few steps (gym_checks.RANDOM_STEPS)."""

import gymnasium as gym
import numpy as np
import pytest
from gym_checks import seeded_resets_and_a_random_policy
from gymnasium.utils.env_checker import check_env

import shintai.gym
from shintai.gym import ENVIRONMENTS

IDS = sorted(ENVIRONMENTS)
# the tricycle's random steps (each a crank sample of the thesis's rig) run from tests/gym/test_tricycle.py, a
# file of its own, so that `pytest -n 2 --dist loadfile` puts them beside this file rather than after it
SEPARATE = {"shintai/TricyclePedal-v0"}
# the humanoid's vehicles run both checks (and their own) in tests/gym/test_vehicles.py
VEHICLES = {"shintai/VBoardRide-v0", "shintai/NinebotRide-v0"}


@pytest.mark.parametrize("env_id", sorted(set(IDS) - VEHICLES))
def test_checker_passes(env_id):
    env = gym.make(env_id, render_mode="rgb_array")
    try:
        check_env(env.unwrapped, skip_render_check=False)
    finally:
        env.close()


@pytest.mark.parametrize("env_id", sorted(set(IDS) - SEPARATE - VEHICLES))
def test_seeded_resets_and_a_random_policy(env_id):
    seeded_resets_and_a_random_policy(env_id)


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
