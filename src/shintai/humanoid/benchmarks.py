"""Benchmark: what the tricycle controllers cost on top of bare ``mj_step`` (seed 000 ch. 3).

Two configurations of the riding body, each run for the same simulated time:

* ``pedaling`` — the legs' role switcher (E2/E4: Fig. 3.16, Eqs. 3.7, 3.13–3.14, 3.19) with the
  experiment's per-tick recording (:func:`~shintai.humanoid.tricycle.rig.pedal_rig`);
* ``driving`` — arms and legs together on the E3 slalom script (:class:`~shintai.humanoid.tricycle.ride.Ride`),
  Δt scaled so that steering, pedalling and role swaps all happen.

Each is compared with bare ``mujoco.mj_step`` on the same model for the same number of physics
steps (from the same seated keyframe, the servos holding it). The ratio is the controller + IK +
logging overhead; ``sim_per_wall`` is simulated seconds per wall second of the full run.

Measured on the 2-core machine (loaded by other jobs, so ±25 % run to run, bare mj_step itself
0.22–0.33 s), the code before and after the last round back to back, four pairs in two sessions:
pedalling 2.8–4.1× → 1.9–2.65× (typically 3.2–3.4× → 2.55–2.65×), driving 4.0–6.8× → 3.2–5.8×
(typically 5.2–5.3× → 4.1×); the controller runs' wall time 0.76–1.0 s → 0.60–0.64 s (pedalling,
6.4 s simulated) and 1.12–1.5 s → 0.89–1.27 s (driving, 6 s). Earlier rounds: 3.5–4× → 2.9–3.8×
and 10.5–11.5× → 6.1–6.6×. Issue 6 aims at ≤ 1.5×, not met. Per 4 ms control tick of the
pedalling run (timed around the pieces, without the profiler): physics ≈0.15–0.18 ms (four 1 ms
mj_steps), the two feet's IK ≈0.11–0.13 ms (≈55–65 µs a solve: usually one damped-least-squares step and the
check after it, each a few dozen NumPy / MuJoCo binding calls of ~0.5 µs), everything else
≈0.12–0.14 ms (impedance laws and min-jerk players ≈40 µs, method-(a) angle estimate + switching guard
≈30 µs, the scenario's logging ≈20 µs, Loop / snapshot / apply ≈30 µs) — even a free IK would leave
≈1.8×: ≤ 1.5× needs the per-tick control loop out of Python, not a faster IK. Driving runs four IK
solves a tick (the hands' with the handle-angle estimate in their target).
What was done, with the trajectories unchanged (tricycle-pedaling and tricycle-slalom: metrics and
every ``log.npz`` array bit-identical before/after; passive f_z 152.98994838400301 N, swaps at
110.52°/290.52°, one revolution at 57.308 s): last round — the IK forms a target's quaternion once
per solve (not per iteration), takes damping² I from a per-size cache, keeps views of the scratch data's site rows, has a one-step fast path
when no joint is at a limit and no posture is pursued (``np.minimum/np.maximum`` for ``np.clip``),
``np.concatenate`` for ``np.vstack``; ``cross`` on Python floats (same IEEE products); method (a)
takes the unit axis and the projected zero directions from a cache; ``Segment.state`` calls
``np.dot`` on the shapes ``np.tensordot`` forms, with the exponent arrays cached; ``VehicleFrame``
keeps views of the waist rows; the hands' target reuses the constant steering axis; ``LimbPair``
and the scenario logs form their signal names once and read ids / data rows once; ``‖x‖`` as
``√(x·x)`` (what ``np.linalg.norm`` computes). Earlier: the IK's Jacobian only when a step follows,
site ids cached, no limit bookkeeping when no joint is at a limit, F/T and FK read by id, the
vehicle frame once per waist pose, the handle model's zero directions once per model; caching the
IK's scratch ``MjData`` and one F/T and FK reading per limb per tick (≈17× → ≈7× then).
Both the controller runs and bare mj_step are the faster of two runs.

Issue 13 item 2: the feet on the closed-form leg IK (:meth:`~shintai.humanoid.tricycle.hrp2_limbs.Hrp2Limb.solve`;
trajectories change slightly, see the scenario notes). Twelve interleaved pairs in one process (feet on the
DLS IK vs the closed form, each run against its own bare mj_step, three sessions, load average 1–4 on the
2 cores, bare mj_step 0.39–0.69 s so the ratios spread widely): pedalling 2.8–6.2× (median 3.4×) →
1.9–3.5× (median 2.4×), closed form cheaper in 11 of 12 pairs, fastest runs 1.73 → 1.05 s; driving
5.0–9.8× (median 7.5×) → 4.0–6.0× (median 5.3×), 10 of 12 pairs, fastest runs 2.81 → 2.40 s. A foot's solve
inside these runs: ≈212 µs DLS → ≈47 µs closed form at that load (≈4.5×; the DLS fallback never ran, no
unreachable tick). Still short of ≤ 1.5×: the rest of the tick (laws, interpolators, estimates, the hands'
DLS IK when driving, logging, the Loop) is Python, as above.

``humanoid.leg-ik`` (issue 13 item 2): the analytic leg IK (:mod:`shintai.humanoid.robots.leg_ik`) against
the DLS IK per call on the same 500 sole targets of a pedalling-like foot path, as a ratio in one
run. Measured on the loaded 2-core machine (load average ≈7): analytic ≈22–27 µs, DLS ≈390–510 µs
a call (warm-started, one step and the check each), ratio ≈15×; the two agree to ≈7e-5 rad (the
DLS IK stops at its 0.1 mm / 1 mrad tolerance). Re-measured in this round: 9.6 / 141 µs (14.7×) at a quiet
moment, 18.9 / 143 µs and 38 / 584 µs (7.6×, 15.3×) under load; agreement 6.7e-5 rad.

``humanoid.standing-overhead`` (issue 13): the standing stack's 4 ms Loop tick (preview, footsteps,
stabilizer, foot damping, leg IK; :class:`~shintai.humanoid.balance.standing.Standing`) against bare mj_step for
the same physics steps. Measured on the loaded 2-core machine: ≈3.9× (tick ≈0.95 ms against ≈0.24 ms of
bare physics; per call preview ≈83 µs, footsteps ≈8, stabilizer ≈140, foot damping ≈65, leg IK ≈130,
physics + Loop/snapshot ≈520 µs). The stabilizer's F/T reading and law went from NumPy to Python floats
(≈3× cheaper, same trajectories to 1e-15). The aim of ≤ 1.5× is not met: it leaves ≈0.12 ms a tick for
five Python modules and the Loop; as for the tricycle, it needs the per-tick control out of Python.
"""

from __future__ import annotations

import math
import time

import mujoco
import numpy as np

from shintai.humanoid.tricycle import riding
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    D_THETA_C,
    D_THETA_H,
    DEG,
    DELTA_T,
)
from shintai.humanoid.tricycle.hrp2_limbs import riding_limbs
from shintai.humanoid.robots.leg_ik import JOINT_NAMES, leg_ik
from shintai.humanoid.tricycle.operation import OperationSchedule
from shintai.humanoid.tricycle.ride import Ride, slalom_goals
from shintai.humanoid.robots.hrp2 import build_hrp2
from shintai.humanoid.tricycle.rig import crank_schedule, legs_switcher, pedal_rig
from shintai.scenarios.experiment import run_rig
from shintai.scenarios.registry import benchmark
from shintai.sim import ik


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
    legs, diag = legs_switcher(feet, schedule)
    rig = pedal_rig(body, legs, feet, schedule, lambda s: legs.active == f"legs:{s}-active", diag)
    t0 = time.perf_counter()
    run_rig(rig)
    return body, time.perf_counter() - t0


def driving_run(seconds: float):
    """Arms and legs on the slalom script (Δt = 0.2 s) for about ``seconds``; (body, wall time)."""
    schedule = OperationSchedule(0.0, 0.0, slalom_goals(30 * DEG, 10 * DEG, 60 * DEG), DELTA_T * 0.25, D_THETA_H, D_THETA_C)
    schedule.samples = schedule.samples[:max(1, int(seconds / (2 * schedule.phase)) - 1)]
    ride = Ride(schedule)
    rig = ride.rig()
    t0 = time.perf_counter()
    run_rig(rig)
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


def sole_circle(model: mujoco.MjModel, side: str, ticks: int, radius: float = 0.03):
    """Waist pose and ``ticks`` sole targets (pos, rot) of leg ``side``: from the standing keyframe,
    the sole goes round a vertical circle of ``radius`` in 2 s at the 4 ms control period, pitching
    by up to 0.1 rad — a pedalling-like foot path, each target close to the previous one."""
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("stand").id)
    mujoco.mj_kinematics(model, data)
    w, s = model.body("waist").id, model.site(f"{side}_sole").id
    start, rot0 = data.site_xpos[s].copy(), data.site_xmat[s].reshape(3, 3).copy()
    targets = []
    for k in range(ticks):
        a = 2 * math.pi * k * CONTROL_PERIOD / 2.0
        pitch = 0.1 * math.sin(a)
        c, sn = math.cos(pitch), math.sin(pitch)
        rot = np.array([[c, 0.0, sn], [0.0, 1.0, 0.0], [-sn, 0.0, c]]) @ rot0
        targets.append((start + radius * np.array([math.sin(a), 0.0, 1.0 - math.cos(a)]), rot))
    return data.qpos.copy(), data.xpos[w].copy(), data.xmat[w].reshape(3, 3).copy(), targets


@benchmark("humanoid.leg-ik", "analytic HRP2 leg IK (humanoid.leg_ik) vs the DLS IK (sim.ik) per call, same sole targets")
def leg_ik_cost(ticks: int = 500) -> dict:
    """Both solvers on the same ``ticks`` sole targets of the left leg (:func:`sole_circle`): the DLS
    IK warm-started from its previous solution as the tricycle's feet use it (usually one step and
    the check), the analytic one from nothing. The faster of two passes each (a shared machine)."""
    model = build_hrp2().model
    q0, waist_pos, waist_rot, targets = sole_circle(model, "l", ticks)
    joints = [f"l_{n}" for n in JOINT_NAMES]
    qadr = [model.joint(j).qposadr[0] for j in joints]

    def dls_pass():
        q, out = q0.copy(), []
        t0 = time.perf_counter()
        for target in targets:
            q = ik.solve(model, {"l_sole": target}, q, joints).q
            out.append(q[qadr])
        return time.perf_counter() - t0, out

    def analytic_pass():
        t0 = time.perf_counter()
        out = [leg_ik("l", waist_pos, waist_rot, pos, rot).q for pos, rot in targets]
        return time.perf_counter() - t0, out

    dls, q_dls = min((dls_pass() for _ in range(2)), key=lambda r: r[0])
    analytic, q_analytic = min((analytic_pass() for _ in range(2)), key=lambda r: r[0])
    return {"calls": ticks, "analytic_us_per_call": 1e6 * analytic / ticks, "dls_us_per_call": 1e6 * dls / ticks,
            "dls_over_analytic": dls / analytic,
            "max_joint_difference_rad": float(np.abs(np.array(q_dls) - np.array(q_analytic)).max())}


@benchmark("humanoid.standing-overhead",
           "HRP2 standing on the stabilizer stack (LIP tracking, distributor, foot damping, leg IK): the 4 ms Loop tick vs bare mj_step")
def standing_overhead(seconds: float = 4.0) -> dict:
    """The standing stack (:class:`~shintai.humanoid.balance.standing.Standing`, standing still) for ``seconds`` of
    simulated time against bare ``mj_step`` for the same physics steps from the ``stand`` keyframe (the
    faster of two runs each), with each module's mean time per call from the Loop's ``timing``."""
    from shintai.humanoid.balance.standing import Standing

    def run():
        st = Standing(hold=seconds + 1.0)
        t0 = time.perf_counter()
        st.run(seconds)
        return st, time.perf_counter() - t0

    st, wall = min((run() for _ in range(2)), key=lambda r: r[1])
    ticks = st.loop.tick
    steps = ticks * st.body.substeps
    bare = min(bare_steps(st.body.model, "stand", steps) for _ in range(2))
    modules = {f"{name}_us": t.mean_us for name, t in st.loop.timing.items()}
    rest = 1e6 * wall / ticks - sum(modules.values())
    return {"sim_time_s": st.body.t, "ticks": ticks, "physics_steps": steps, "wall_s": wall, "bare_mj_step_s": bare,
            "overhead_ratio": wall / bare, "tick_us": 1e6 * wall / ticks, "bare_tick_us": 1e6 * bare / ticks,
            **modules, "physics_and_loop_us": rest}
