"""Benchmarks of seed 000's controllers, each against the naive or bare form in one run (a ratio):

* ``humanoid.tricycle-overhead`` — the tricycle controllers on top of bare ``mujoco.mj_step`` on the same model
  and physics steps: ``pedaling`` (the legs' role switcher, Fig. 3.16, Eqs. 3.7, 3.13–3.14, 3.19, with the
  experiment's recording; :func:`~shintai.humanoid.tricycle.rig.pedal_rig`) and ``driving`` (arms and legs on the
  E3 slalom script, :class:`~shintai.humanoid.tricycle.ride.Ride`), each in interleaved pairs (a run, then bare
  mj_step for its steps; the ratio is the pairs' median); ``sim_per_wall`` is simulated seconds per wall second;
  the control share is split further into the limbs' IK (``arm_ik_us``: the hands' DLS solves,
  :func:`shintai.sim.ik.solve` with their targets; ``leg_ik_us``: the feet's closed form,
  :mod:`shintai.humanoid.robots.leg_ik`, and any DLS fallback), the switching diagnostics' method-(a) angles
  (``angle_estimates_us``, Fig. 3.14) and ``control_other_us`` (laws, players, switchers); the rest into the
  recorded signals (``signals_us``) and ``rest_other_us`` (snapshot, combining, applying, the loop);
* ``humanoid.leg-ik`` — the analytic leg IK (:mod:`shintai.humanoid.robots.leg_ik`) against the DLS IK per call on
  the same 500 sole targets of a pedalling-like foot path;
* ``humanoid.standing-overhead`` — the standing stack's 4 ms tick (:class:`~shintai.humanoid.balance.standing.Standing`)
  against bare mj_step for the same physics steps.

The tricycle and standing benches also say where the tick went (:func:`tick_shares`): physics (the run's own
mj_step calls, and their ratio to bare mj_step), control (the modules) and the rest (snapshot, combining,
recording, the loop); the standing bench splits that rest too (:func:`standing_anatomy`). Both say whether the
median ratio meets issue 30's aim, :data:`~shintai.humanoid.constants.TICK_OVERHEAD_TARGET` (``meets_target``).

Measured histories are in git (this docstring's earlier versions) and the benchmarks' ``bench.json``.
"""

from __future__ import annotations

import math
import time
from types import SimpleNamespace

import mujoco
import numpy as np

from shintai.humanoid.constants import CONTROL_PERIOD, D_THETA_C, D_THETA_H, DEG, DELTA_T, TICK_OVERHEAD_TARGET
from shintai.humanoid.robots.hrp2 import build_hrp2
from shintai.humanoid.robots.leg_ik import JOINT_NAMES, leg_ik
from shintai.humanoid.tricycle import riding
from shintai.humanoid.tricycle.hrp2_limbs import riding_limbs
from shintai.humanoid.tricycle.operation import OperationSchedule
from shintai.humanoid.tricycle.ride import Ride, slalom_goals
from shintai.humanoid.tricycle.rig import crank_schedule, legs_switcher, pedal_rig
from shintai.scenarios.experiment import run_rig
from shintai.scenarios.registry import benchmark
from shintai.scenarios.sampling import Clock
from shintai.sim import ik


def bare_steps(model: mujoco.MjModel, keyframe: str, steps: int) -> float:
    """Wall time of ``steps`` bare mj_step calls from the keyframe (its ctrl held)."""
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key(keyframe).id)
    t0 = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, data)
    return time.perf_counter() - t0


class PhysicsClock(Clock):
    """The wall time a body spends in its steps during a run (``seconds``): the physics share of a tick."""

    def __init__(self, body):
        super().__init__([body], "step")


def timed_rig(rig, limbs=(), diagnostics=()):
    """Run ``rig`` (:func:`~shintai.scenarios.experiment.run_rig`); (wall time, the run, its physics seconds, the
    seconds in named parts of the tick — ``{"arm_ik": the hands' DLS solves, "leg_ik": the feet's closed form and DLS
    fallbacks, "angle_estimates": method (a)'s angles in the switching ``diagnostics`` (Fig. 3.14), "signals": the
    rig's recorded signals}`` — and the process's CPU time in the run)."""
    physics = PhysicsClock(rig.body)
    hands, feet = [lb for lb in limbs if lb.kind == "hand"], [lb for lb in limbs if lb.kind == "foot"]
    arm_ik, leg_ik, fallback = Clock(hands, "dls_solve"), Clock(feet, "closed_form"), Clock(feet, "dls_solve")
    estimates = Clock(diagnostics, "measure")
    hooks = [SimpleNamespace(record=hook) for hook in rig.record.values()]  # each recording hook, to be clocked
    signals = Clock(hooks, "record")
    rig.record = dict(zip(rig.record, (h.record for h in hooks)))
    t0, c0 = time.perf_counter(), time.process_time()
    run = run_rig(rig)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    parts = {"arm_ik": arm_ik.seconds, "leg_ik": leg_ik.seconds + fallback.seconds, "angle_estimates": estimates.seconds,
             "signals": signals.seconds}
    return wall, run, physics.seconds, parts, cpu


def pedaling_run(seconds: float):
    """The E2 controller for ``seconds`` of simulated time; returns (body, wall time, run, physics seconds,
    the tick's timed parts, CPU seconds: :func:`timed_rig`)."""
    dt = DELTA_T * 0.25
    schedule = crank_schedule(seconds / (2 * dt) * D_THETA_C / (2 * 3.141592653589793), dt)
    body = riding.build_riding(crank_error=(0.01, 0.0))
    feet = riding_limbs(body, "foot")
    legs, diag = legs_switcher(feet, schedule)
    rig = pedal_rig(body, legs, feet, schedule, lambda s: legs.active == f"legs:{s}-active", diag)
    return body, *timed_rig(rig, feet.values(), [diag])


def driving_run(seconds: float):
    """Arms and legs on the slalom script (Δt = 0.2 s) for about ``seconds``; (body, wall time, run,
    physics seconds, the tick's timed parts, CPU seconds)."""
    schedule = OperationSchedule(0.0, 0.0, slalom_goals(30 * DEG, 10 * DEG, 60 * DEG), DELTA_T * 0.25, D_THETA_H, D_THETA_C)
    schedule.samples = schedule.samples[:max(1, int(seconds / (2 * schedule.phase)) - 1)]
    ride = Ride(schedule)
    return ride.body, *timed_rig(ride.rig(), (*ride.feet.values(), *ride.hands.values()), [ride.leg_diag, ride.arm_diag])


def tick_shares(prefix: str, wall: float, physics: float, loop, bare: float) -> dict:
    """Where a run's tick went (us per control tick): ``physics`` (the body's mj_step calls in the run; against
    bare mj_step in ``physics_vs_bare``), ``control`` (the modules' updates, the Loop's timing) and ``rest``
    (snapshot, combining, applying, recording, the loop itself)."""
    ticks = loop.tick
    control = sum(t.total_s for t in loop.timing.values())
    return {f"{prefix}physics_us": 1e6 * physics / ticks, f"{prefix}control_us": 1e6 * control / ticks,
            f"{prefix}rest_us": 1e6 * (wall - physics - control) / ticks, f"{prefix}physics_vs_bare": physics / bare}


def control_split(prefix: str, shares: dict, parts: dict, ticks: int) -> dict:
    """The control and rest shares split (us per control tick, :func:`timed_rig`'s parts): each limb group's IK and
    the switching diagnostics' angle estimates, then ``control_other`` (the rest of the modules' time: impedance
    laws, players, the role switchers, logging in the modules); the recorded signals, then ``rest_other`` (snapshot,
    combining, applying, the recorder, the loop itself)."""
    control = ("arm_ik", "leg_ik", "angle_estimates")
    out = {f"{prefix}{k}_us": 1e6 * parts[k] / ticks for k in (*control, "signals")}
    out[f"{prefix}control_other_us"] = shares[f"{prefix}control_us"] - sum(out[f"{prefix}{k}_us"] for k in control)
    out[f"{prefix}rest_other_us"] = shares[f"{prefix}rest_us"] - out[f"{prefix}signals_us"]
    return out


@benchmark("humanoid.tricycle-overhead",
           "HRP2 on the tricycle: pedalling / steering+pedalling controllers (IK, laws, logging) vs bare mj_step")
def tricycle_overhead(seconds: float = 6.0, pairs: int = 3) -> dict:
    """Each configuration in ``pairs`` interleaved pairs (a run, then bare mj_step for its physics steps from the
    ``ride`` keyframe): ``overhead_ratio`` is the median of the pairs' ratios (a shared machine's load changes
    between pairs far more than within one), its range beside it, ``overhead_ratio_cpu`` the median on the
    process's CPU time (what other processes' load leaves out); the tick's shares are the fastest run's."""
    out = {"overhead_target": TICK_OVERHEAD_TARGET}
    for name, run in (("pedaling", pedaling_run), ("driving", driving_run)):
        done, cpu_ratios = [], []  # (body, wall, run, physics seconds, timed parts, the bare run right after)
        for _ in range(pairs):
            body, wall, result, physics, parts, cpu = run(seconds)
            steps = int(round(body.t / body.model.opt.timestep))
            c0 = time.process_time()
            done.append((body, wall, result, physics, parts, bare_steps(body.model, "ride", steps)))
            cpu_ratios.append(cpu / (time.process_time() - c0))
        ratios = [wall / bare for _, wall, *_, bare in done]
        body, wall, result, physics, parts, bare = min(done, key=lambda r: r[1])
        steps = int(round(body.t / body.model.opt.timestep))
        shares = tick_shares(f"{name}_", wall, physics, result.loop, bare)
        out.update({f"{name}_sim_time_s": body.t, f"{name}_physics_steps": steps, f"{name}_wall_s": wall,
                    f"{name}_bare_mj_step_s": bare, f"{name}_overhead_ratio": float(np.median(ratios)),
                    f"{name}_overhead_ratio_min": min(ratios), f"{name}_overhead_ratio_max": max(ratios),
                    f"{name}_overhead_ratio_cpu": float(np.median(cpu_ratios)),
                    f"{name}_meets_target": bool(np.median(ratios) <= TICK_OVERHEAD_TARGET),
                    f"{name}_sim_per_wall": body.t / wall, f"{name}_bare_sim_per_wall": body.t / bare,
                    **shares, **control_split(f"{name}_", shares, parts, result.loop.tick)})
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


def wrapper_cost(calls: int = 20000) -> float:
    """Seconds one :class:`~shintai.scenarios.sampling.Clock` adds to a call (a wrapped no-op against the bare
    one): what :func:`standing_anatomy` takes off the loop's own share for each timed call."""

    class Noop:
        def f(self):
            return None

    bare, wrapped = Noop(), Noop()
    Clock([wrapped], "f")

    def loop(obj):
        t0 = time.perf_counter()
        for _ in range(calls):
            obj.f()
        return time.perf_counter() - t0

    return max(0.0, min(loop(wrapped) for _ in range(3)) - min(loop(bare) for _ in range(3))) / calls


def standing_anatomy(seconds: float) -> dict:
    """One more standing run with the rest of the tick timed piece by piece (us per tick): the body's
    ``snapshot`` and the Loop's ``view`` of it, the Loop's combining of the contributions (``_combine``, every
    stage), the body's ``apply``; inside the physics share, MuJoCo's steps and the divergence check; the loop's own
    share (its stage walk, the modules' timing, the dicts of the tick, freeing the last tick's objects) is what is
    left, the timers' own cost (:func:`wrapper_cost`) taken off. The timers slow this run: it is not one of the
    ratio's pairs."""
    from shintai.humanoid.balance.standing import Standing

    st = Standing(hold=seconds + 1.0)
    loop, body = st.loop, st.body
    parts = {"snapshot": Clock([body], "snapshot"), "view": Clock([loop], "view"),
             "combine": Clock([loop], "_combine"), "apply": Clock([body], "apply"),
             "check": Clock([body], "_check_divergence")}
    physics = PhysicsClock(body)
    t0 = time.perf_counter()
    st.run(seconds)
    wall = time.perf_counter() - t0
    ticks = loop.tick
    control = sum(t.total_s for t in loop.timing.values())
    timed_calls = sum(c.calls for c in parts.values()) + ticks  # and the physics clock's
    own = wall - physics.seconds - control - sum(c.seconds for k, c in parts.items() if k != "check")
    own -= timed_calls * wrapper_cost()
    out = {f"rest_{k}_us": 1e6 * c.seconds / ticks for k, c in parts.items() if k != "check"}
    out.update(rest_loop_us=1e6 * own / ticks, physics_check_us=1e6 * parts["check"].seconds / ticks,
               physics_mj_step_us=1e6 * (physics.seconds - parts["check"].seconds) / ticks)
    return out


@benchmark("humanoid.standing-overhead",
           "HRP2 standing on the stabilizer stack (LIP tracking, distributor, foot damping, leg IK): the 4 ms Loop tick vs bare mj_step")
def standing_overhead(seconds: float = 4.0, pairs: int = 5) -> dict:
    """The standing stack (:class:`~shintai.humanoid.balance.standing.Standing`, standing still) for ``seconds`` of
    simulated time against bare ``mj_step`` for the same physics steps from the ``stand`` keyframe, in ``pairs``
    interleaved pairs (a stack run, then a bare run): ``overhead_ratio`` is the median of the pairs' ratios (a
    shared machine's load changes between pairs far more than within one), ``overhead_ratio_cpu`` the same on the
    process's CPU time (what other processes' load leaves out); the tick's shares and each module's mean time per
    call (the Loop's ``timing``) are the fastest stack run's; ``rest_*`` and ``physics_*`` split the rest of the tick
    and its physics in one more run (:func:`standing_anatomy`)."""
    from shintai.humanoid.balance.standing import Standing

    def run():
        st = Standing(hold=seconds + 1.0)
        clock = PhysicsClock(st.body)
        t0, c0 = time.perf_counter(), time.process_time()
        st.run(seconds)
        return st, time.perf_counter() - t0, clock.seconds, time.process_time() - c0

    def bare_cpu(model, steps):  # bare_steps' CPU time: what the process spent, whatever else the machine runs
        c0 = time.process_time()
        wall = bare_steps(model, "stand", steps)
        return wall, time.process_time() - c0

    pairs_run, cpu_ratios = [], []  # (stack, its wall time, its physics seconds, the bare run right after)
    for _ in range(pairs):
        st, wall, physics, cpu = run()
        bare, bare_c = bare_cpu(st.body.model, st.loop.tick * st.body.substeps)
        pairs_run.append((st, wall, physics, bare))
        cpu_ratios.append(cpu / bare_c)
    ratios = [wall / bare for _, wall, _, bare in pairs_run]
    st, wall, physics, bare = min(pairs_run, key=lambda r: r[1])
    ticks = st.loop.tick
    steps = ticks * st.body.substeps
    modules = {f"{name}_us": t.mean_us for name, t in st.loop.timing.items()}
    rest = 1e6 * wall / ticks - sum(modules.values())
    return {"sim_time_s": st.body.t, "ticks": ticks, "physics_steps": steps, "wall_s": wall, "bare_mj_step_s": bare,
            "overhead_ratio": float(np.median(ratios)), "overhead_ratio_min": min(ratios),
            "overhead_ratio_max": max(ratios), "overhead_ratio_cpu": float(np.median(cpu_ratios)), "pairs": pairs,
            "overhead_target": TICK_OVERHEAD_TARGET, "meets_target": bool(np.median(ratios) <= TICK_OVERHEAD_TARGET),
            "tick_us": 1e6 * wall / ticks, "bare_tick_us": 1e6 * bare / ticks,
            **modules, "physics_and_loop_us": rest, **tick_shares("", wall, physics, st.loop, bare),
            **standing_anatomy(seconds)}
