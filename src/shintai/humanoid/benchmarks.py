"""Benchmark: what the tricycle controllers cost on top of bare ``mj_step`` (seed 000 ch. 3).

Two configurations of the riding body, each run for the same simulated time:

* ``pedaling`` — the legs' role switcher (E2/E4: Fig. 3.16, Eqs. 3.7, 3.13–3.14, 3.19) with the
  scenario's per-tick logging (:func:`~shintai.humanoid.tricycle_scenarios.pedal_run`);
* ``driving`` — arms and legs together on the E3 slalom script (:class:`~shintai.humanoid.
  driving_scenarios.Ride`), Δt scaled so that steering, pedalling and role swaps all happen.

Each is compared with bare ``mujoco.mj_step`` on the same model for the same number of physics
steps (from the same seated keyframe, the servos holding it). The ratio is the controller + IK +
logging overhead; ``sim_per_wall`` is simulated seconds per wall second of the full run.

Measured on the 2-core machine (loaded by other jobs, so ±25 % run to run): 2.9–3.8× for
pedalling, 6.1–6.6× for driving (before the changes below: 3.5–4×, 10.5–11.5× in the same session);
issue 6 aims at ≤ 1.5×, not met. Per 4 ms control tick of the pedalling run (timed without the
profiler): physics ≈0.31 ms (four 1 ms mj_steps), the two feet's IK ≈0.34 ms (≈0.1–0.17 ms a
solve: usually one damped-least-squares step and the check after it), everything else ≈0.33 ms
(impedance laws, min-jerk players, method-(a) angle estimate, switching guard, logging) — so even a
free IK would leave ≈2×: ≤ 1.5× needs the per-tick control loop out of Python, not a faster IK.
What was done, with the trajectories unchanged (tricycle-pedaling: passive f_z 152.99 N, swaps at
110.52°/290.52°, one revolution at 57.31 s, as before): the IK's Jacobian is formed (``mj_comPos``
+ ``mj_jacSite`` into reused buffers) only when a step follows, not on the final convergence check;
site ids cached; norms and the axis rows without ``np.linalg.norm``/``np.eye``; no limit
bookkeeping when no joint is at a limit; the limbs read F/T force and FK by id, the vehicle frame
is computed once per waist pose, and the handle model's zero directions once per model. Earlier:
caching the IK's scratch ``MjData`` and one F/T and FK reading per limb per tick (≈17× → ≈7× then).
Both the controller runs and bare mj_step are the faster of two runs.
"""

from __future__ import annotations

import time

import mujoco

from shintai.core.recorder import Recorder
from shintai.humanoid import riding
from shintai.humanoid.constants import CONTROL_PERIOD, D_THETA_C, D_THETA_H, DEG, DELTA_C, DELTA_T
from shintai.humanoid.driving_scenarios import Ride, slalom_goals
from shintai.humanoid.hrp2_limbs import riding_limbs
from shintai.humanoid.operation import SIDES, OperationSchedule, role_switcher
from shintai.humanoid.switching import active_leg
from shintai.humanoid.tricycle_scenarios import LEG_GAINS, crank_diagnostic, crank_schedule, foot_plan, pedal_run
from shintai.scenarios.registry import benchmark


def bare_steps(model: mujoco.MjModel, keyframe: str, steps: int) -> float:
    """Wall time of ``steps`` bare mj_step calls from the keyframe (its ctrl held)."""
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key(keyframe).id)
    t0 = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, data)
    return time.perf_counter() - t0


def pedaling_run(seconds: float):
    """The E2 controller for ``seconds`` of simulated time; returns (body, wall time)."""
    dt = DELTA_T * 0.25
    schedule = crank_schedule(seconds / (2 * dt) * D_THETA_C / (2 * 3.141592653589793), dt)
    body = riding.build_riding(crank_error=(0.01, 0.0))
    feet = riding_limbs(body, "foot")
    diag = crank_diagnostic(feet)
    legs = role_switcher("legs", "crank", feet, {leg: foot_plan(leg) for leg in SIDES}, diag,
                         active_leg(0.0, DELTA_C), schedule, LEG_GAINS, CONTROL_PERIOD,
                         {leg: limb.reachable for leg, limb in feet.items()})
    t0 = time.perf_counter()
    pedal_run(Recorder(), "", body, legs, feet, schedule, lambda s: legs.active == f"legs:{s}-active", diag)
    return body, time.perf_counter() - t0


def driving_run(seconds: float):
    """Arms and legs on the slalom script (Δt = 0.2 s) for about ``seconds``; (body, wall time)."""
    schedule = OperationSchedule(0.0, 0.0, slalom_goals(30 * DEG, 10 * DEG, 60 * DEG), DELTA_T * 0.25, D_THETA_H, D_THETA_C)
    schedule.samples = schedule.samples[:max(1, int(seconds / (2 * schedule.phase)) - 1)]
    ride = Ride(schedule)
    t0 = time.perf_counter()
    ride.run(Recorder())
    return ride.body, time.perf_counter() - t0


@benchmark("humanoid.tricycle-overhead",
           "HRP2 on the tricycle: pedalling / steering+pedalling controllers (IK, laws, logging) vs bare mj_step")
def tricycle_overhead(seconds: float = 6.0) -> dict:
    out = {}
    for name, run in (("pedaling", pedaling_run), ("driving", driving_run)):
        # the faster of two runs, as for bare mj_step (the machine is shared; the runs are identical)
        body, wall = min((run(seconds) for _ in range(2)), key=lambda r: r[1])
        steps = int(round(body.t / body.model.opt.timestep))
        bare = min(bare_steps(body.model, "ride", steps) for _ in range(2))
        out.update({f"{name}_sim_time_s": body.t, f"{name}_physics_steps": steps, f"{name}_wall_s": wall,
                    f"{name}_bare_mj_step_s": bare, f"{name}_overhead_ratio": wall / bare,
                    f"{name}_sim_per_wall": body.t / wall, f"{name}_bare_sim_per_wall": body.t / bare})
    return out
