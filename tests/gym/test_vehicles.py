"""``shintai/VBoardRide-v0`` and ``shintai/NinebotRide-v0``: the agent is the speed governor of seed 000 ch. 6–7 —
its (u_v, u_ω) reach the foot-pitch integrator through Eq. 6.5, episodes start riding after the lift lets go,
observations are the governor's inputs and a fall ends the episode."""

import gymnasium as gym
import numpy as np
import pytest
from gym_checks import seeded_resets_and_a_random_policy
from gymnasium.utils.env_checker import check_env

import shintai.gym  # noqa: F401
from shintai.gym import ENVIRONMENTS
from shintai.gym.riding import ERROR_CAP, SETTLE_S
from shintai.gym.vboard import AGENT_PERIOD, EPISODE_STEPS, U_MAX

IDS = ["shintai/VBoardRide-v0", "shintai/NinebotRide-v0"]
TICKS = 6  # control periods per agent step: 24 ms / 4 ms


@pytest.mark.parametrize("env_id", IDS)
def test_checker_passes(env_id):
    env = gym.make(env_id, render_mode="rgb_array")
    try:
        check_env(env.unwrapped, skip_render_check=True)  # rendering: once, in the random-policy test
    finally:
        env.close()


@pytest.mark.parametrize("env_id", IDS)
def test_seeded_resets_and_a_random_policy(env_id):
    seeded_resets_and_a_random_policy(env_id)  # a few steps of riding, and one rendered frame


@pytest.mark.parametrize("env_id", IDS)
def test_an_episode_starts_riding_after_the_lift_lets_go(env_id):
    env = gym.make(env_id)
    obs, info = env.reset(seed=3)
    ride = env.unwrapped.ride
    assert ride.lift.released and info["t_ride"] == pytest.approx(SETTLE_S, abs=0.005)
    assert not info["fallen"] and abs(info["true_v"]) < 0.1
    assert ENVIRONMENTS[env_id][1] == EPISODE_STEPS and env.unwrapped.agent_period == AGENT_PERIOD
    env.close()


def test_the_vboard_agents_u_reaches_the_foot_pitch_through_eq_6_5():
    env = gym.make("shintai/VBoardRide-v0")
    env.reset(seed=0, options={"targets": (0.0, 0.0)})
    u_v, u_w = 2e-4, -1e-4
    obs, *_ = env.step(np.array([u_v, u_w]))
    ride = env.unwrapped.ride
    # Δθ_R = u_v + u_ω, Δθ_L = u_v − u_ω every 4 ms control period, integrated (Eq. 6.7)
    assert ride.foot_pitch.theta == pytest.approx([TICKS * (u_v + u_w), TICKS * (u_v - u_w)], rel=1e-12)
    # the observation is the governor's input: the sensors' v and ω, the targets, e = target − measured
    assert obs[0] == ride.sensors.v and obs[1] == env.unwrapped.loop.command["omega"]
    assert np.array_equal(obs[2:4], [0.0, 0.0]) and np.array_equal(obs[4:], -obs[:2])
    env.close()


def test_the_ninebot_agent_is_c_v():
    env = gym.make("shintai/NinebotRide-v0")
    env.reset(seed=0, options={"targets": (0.05,)})
    obs, *_ = env.step(np.array([-2e-4]))
    ride = env.unwrapped.ride
    assert ride.foot_pitch.theta == pytest.approx([TICKS * -2e-4] * 2, rel=1e-12)  # Eq. 6.5 with u_ω = 0
    assert np.allclose(ride.speed.pid.gains, 0.0)  # C_v adds nothing
    assert obs[0] == ride.sensors.v and obs[1] == 0.05 and obs[2] == pytest.approx(0.05 - obs[0])
    env.close()


@pytest.mark.parametrize("env_id", IDS)
def test_a_constant_full_action_falls_and_the_fall_costs_the_rest_of_the_episode(env_id):
    env = gym.make(env_id)
    env.reset(seed=0, options={"targets": np.zeros(len(env.unwrapped.target_range))})
    for step in range(1, 301):  # measured: the V-BOARD falls after ≈130 steps, the Ninebot after ≈210
        obs, reward, terminated, truncated, info = env.step(env.action_space.high)
        if terminated:
            break
        assert -ERROR_CAP <= reward <= 0.0
    assert terminated and info["fallen"] and not truncated
    assert reward == -ERROR_CAP * (EPISODE_STEPS - step + 1)
    env.close()


@pytest.mark.parametrize("env_id", IDS)
def test_bad_actions_and_options_are_refused(env_id):
    env = gym.make(env_id)
    env.reset(seed=0)
    with pytest.raises(ValueError, match="finite"):
        env.unwrapped.step(np.full(env.action_space.shape, np.nan))
    with pytest.raises(ValueError, match="targets"):
        env.reset(seed=0, options={"targets": np.full(len(env.unwrapped.target_range), 10.0)})
    with pytest.raises(ValueError, match="unknown reset options"):
        env.reset(seed=0, options={"speed": 1.0})
    assert env.action_space.high[0] == U_MAX
    env.close()


def test_the_example_black_box_search_runs(capsys):
    import runpy
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "vboard_black_box.py"
    result = runpy.run_path(str(example), run_name="example")["main"](2, 0.1)
    assert np.isfinite(result["best"]) and result["gains"].shape == (4,)
    assert "zero gains (level 2)" in capsys.readouterr().out
