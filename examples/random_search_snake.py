"""Random search of a linear policy on the snake's two-point task (``shintai/SnakeTwoPoint-v0``), for a few seconds.

    .venv/bin/python examples/random_search_snake.py [seconds]

The policy maps the tracking error (c_d − c, 6 values) to the nine joint rates through a 9×6 matrix; random
perturbations of the best matrix are kept when they raise the return of a short episode. It shows the API
(make, reset with a seed, step, render), not a good controller: the thesis's own law (snake.tracking) tracks to
a millimetre.
"""

import sys
import time

import gymnasium as gym
import numpy as np

import shintai.gym  # noqa: F401  (registers the environments)


def episode_return(env, W, seed, steps=100):
    obs, _ = env.reset(seed=seed)
    total = 0.0
    for _ in range(steps):
        error = obs[6:12] - obs[0:6]
        obs, reward, terminated, truncated, _ = env.step(np.clip(W @ error, -1.0, 1.0))
        total += reward
        if terminated or truncated:
            break
    return total


def main(seconds: float = 5.0) -> None:
    env = gym.make("shintai/SnakeTwoPoint-v0", render_mode="rgb_array")
    rng = np.random.default_rng(0)
    best_W = np.zeros((9, 6))
    best = episode_return(env, best_W, seed=0)
    print(f"zero policy: return {best:.3f}")
    t0, tries = time.perf_counter(), 0
    while time.perf_counter() - t0 < seconds:
        W = best_W + 0.5 * rng.standard_normal(best_W.shape)
        score = episode_return(env, W, seed=0)
        tries += 1
        if score > best:
            best, best_W = score, W
            print(f"try {tries}: return {best:.3f}")
    frame = env.render()
    print(f"{tries} tries in {seconds:g} s; best return {best:.3f}; last frame {frame.shape}")
    env.close()


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 5.0)
