"""A black-box search of PI gains for the V-BOARD's speed governor (``shintai/VBoardRide-v0``), in about 1–2 minutes.

    .venv/bin/python examples/vboard_black_box.py [evaluations] [episode seconds]

The policy is Eq. 6.2's PI on each axis, the agent's own integrator: u_* = K_P e_* + K_I ∫ e_* dt for * = v, ω,
clipped to the action bound; its four gains are searched by a (1+1) evolution strategy with the 1/5 success
rule (a CMA-ES on one sample per generation, no covariance), each candidate scored by the return of one episode
riding toward v_d = 0, ω_d = 0.15 rad/s (a slow turn on the spot) from the same seed. It starts from zero gains
(behaviour level 2: balance only) and shows the API (make, reset with options, step, info), not the thesis's
result: MLC learns these gains online (§6.3, ``humanoid.speed-governing``).
"""

import sys
import time

import gymnasium as gym
import numpy as np

import shintai.gym  # noqa: F401  (registers the environments)
from shintai.gym.vboard import AGENT_PERIOD, U_MAX

TARGETS = (0.0, 0.15)  # (v_d [m/s], ω_d [rad/s])
# gain units: a 0.1 m/s (or 0.1 rad/s) error, or that error held 1 s, gives the full action
SCALE = np.array([U_MAX / 0.1, U_MAX / 0.1, U_MAX / 0.1, U_MAX / 0.1])  # (K_P^v, K_I^v, K_P^ω, K_I^ω)


def episode_return(env, z, seconds):
    """The return of one ride with gains ``z * SCALE``; also whether it fell and the final true ω."""
    kp_v, ki_v, kp_w, ki_w = z * SCALE
    obs, _ = env.reset(seed=0, options={"targets": TARGETS})
    integral, total, info = np.zeros(2), 0.0, {"fallen": False, "true_omega": 0.0}
    for _ in range(round(seconds / AGENT_PERIOD)):
        e = obs[4:6]  # (e_v, e_ω) = target − measured
        integral += e * AGENT_PERIOD
        u = np.array([kp_v * e[0] + ki_v * integral[0], kp_w * e[1] + ki_w * integral[1]])
        obs, reward, terminated, truncated, info = env.step(np.clip(u, -U_MAX, U_MAX))
        total += reward
        if terminated or truncated:
            break
    return total, info


def main(evaluations: int = 40, seconds: float = 3.0) -> dict:
    env = gym.make("shintai/VBoardRide-v0")
    rng = np.random.default_rng(0)
    z, sigma = np.zeros(4), 1.0
    best, info = episode_return(env, z, seconds)
    print(f"zero gains (level 2): return {best:8.3f}, fell {info['fallen']}, ω {info['true_omega']:+.3f} rad/s")
    t0 = time.perf_counter()
    for k in range(1, evaluations):
        candidate = z + sigma * rng.standard_normal(4)
        score, cinfo = episode_return(env, candidate, seconds)
        if score > best:
            z, best, info = candidate, score, cinfo
            sigma *= 1.5  # 1/5 success rule: widen on a success, narrow on a failure (steady at 1 success in 5)
            gains = ", ".join(f"{g:.2e}" for g in z * SCALE)
            print(f"eval {k:3d}: return {best:8.3f}, fell {info['fallen']}, ω {info['true_omega']:+.3f} rad/s, "
                  f"gains (K_P^v, K_I^v, K_P^ω, K_I^ω) = ({gains}), σ {sigma:.2f}")
        else:
            sigma *= 1.5 ** -0.25
    print(f"{evaluations} episodes of {seconds:g} s in {time.perf_counter() - t0:.0f} s; best return {best:.3f} "
          f"(target ω_d = {TARGETS[1]} rad/s, reached {info['true_omega']:+.3f})")
    env.close()
    return {"best": best, "gains": z * SCALE}


if __name__ == "__main__":
    args = sys.argv[1:]
    main(int(args[0]) if args else 40, float(args[1]) if len(args) > 1 else 3.0)
