"""SQ43 stands up from lying on its belly (seed 003 §3.2.4 立ち上がり動作, Fig. 3.9).

§3.2.4: "各脚のアクチュエータのトルクがそれほど大きくないので, Fig. 3.9 の1の状態からいっせいに脚を伸ばしても
立ち上がることはできない … そこで, 前脚と後脚を交互に少しずつ伸ばすような動きを作り, 脚を伸ばす際には脊椎がその力
を補助するような動きをするようにした … 試行錯誤の時のログを記録しておき, 成功した時にそのシーケンスを繰り返す".
A sequence here is an open-loop schedule of foot targets (relative to the leg roots) and servo B's vertical bend,
replayed on the body (as the thesis replays its log); three strategies (:func:`schedule`): ``all_at_once`` (every
leg extended together, spine straight), ``alternating`` (front and hind pairs extended in turns, servo B bending
while a pair extends) and ``alternating_no_spine`` (the same legs, spine straight). The leg servos' torque limit
is the body's ``servo_torque_nm``; :func:`least_torque` scans the limits with which a strategy stands.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import mujoco
import numpy as np
from mujoco import rollout

from shintai.scenarios.experiment import Rig
from shintai.spine.sq43.body import (
    BODY,
    LEG_JOINTS,
    LEGS,
    SQ43Body,
    SQ43BodySpec,
    actuator_ids,
    build_spec,
    leg_ik,
    servo_ctrl,
)
from shintai.spine.sq43.gaits import CtrlSchedule

STRATEGIES = ("all_at_once", "alternating", "alternating_no_spine")


@dataclass(frozen=True)
class StandUp:
    """The lying pose and the sequences (chosen; Fig. 3.9's photographs are not in the text). Lying: belly on the
    floor (the trunk's half height 20 mm + 1 mm), each foot on the floor ``lie_reach_m`` ahead (front) or behind
    (hind) of its root, the knee folded within its range. ``all_s``: the all-at-once extension; alternating:
    ``steps`` turns of front then hind, each ``phase_s``, servo B bending by ``spine_deg`` (total over the three
    blocks) while the front pair extends and back while the hind pair does. Stood: the shoulder and the hip at
    least ``stood_fraction`` of the natural length above the floor over the last ``hold_s``."""

    lie_height_m: float = 0.021
    lie_reach_m: float = 0.08
    settle_s: float = 0.5
    all_s: float = 3.0
    steps: int = 4
    phase_s: float = 0.75
    spine_deg: float = -40.0  # arched (−), the search's pick (notes/sq43-standup.md)
    hold_s: float = 1.5
    stood_fraction: float = 0.9


def _lying_feet(plan: StandUp) -> dict[str, np.ndarray]:
    return {leg: np.array([plan.lie_reach_m if leg[1] == "F" else -plan.lie_reach_m, 0.0, -plan.lie_height_m])
            for leg in LEGS}


def schedule(plan: StandUp, strategy: str, spec: SQ43BodySpec = BODY, dt: float = 0.002):
    """Foot targets {leg: (T, 3)} and servo B's bend (T,) [deg] at every physics step: settle lying, the strategy's
    extension (cosine-smoothed moves), hold standing."""
    lie, stand = _lying_feet(plan), {leg: np.array([0.0, 0.0, -spec.natural_length_m]) for leg in LEGS}
    # (duration, fraction of the way for front legs, for hind legs, spine bend) at the end of each move
    if strategy == "all_at_once":
        moves = [(plan.all_s, 1.0, 1.0, 0.0)]
    else:
        bend = plan.spine_deg if strategy == "alternating" else 0.0
        moves = []
        for k in range(1, plan.steps + 1):
            moves += [(plan.phase_s, k / plan.steps, (k - 1) / plan.steps, bend),
                      (plan.phase_s, k / plan.steps, k / plan.steps, 0.0)]
    rows_f, rows_h, rows_s = [0.0] * round(plan.settle_s / dt), [0.0] * round(plan.settle_s / dt), [0.0] * round(plan.settle_s / dt)
    for duration, f, h, s in moves:
        n = round(duration / dt)
        w = 0.5 - 0.5 * np.cos(np.pi * np.arange(1, n + 1) / n)
        for rows, end in ((rows_f, f), (rows_h, h), (rows_s, s)):
            start = rows[-1]
            rows += list(start + w * (end - start))
    n_hold = round(plan.hold_s / dt)
    for rows in (rows_f, rows_h, rows_s):
        rows += [rows[-1]] * n_hold
    frac = {"F": np.array(rows_f)[:, None], "H": np.array(rows_h)[:, None]}
    feet = {leg: lie[leg] + frac[leg[1]] * (stand[leg] - lie[leg]) for leg in LEGS}
    return feet, np.array(rows_s)


def lying_state(model: mujoco.MjModel, plan: StandUp, spec: SQ43BodySpec = BODY) -> np.ndarray:
    """qpos lying: the trunk level at ``lie_height_m``, the legs at the lying pose, spine straight."""
    q = np.zeros(model.nq)
    q[:3] = [0.0, 0.0, plan.lie_height_m]
    q[3] = 1.0
    for leg, foot in _lying_feet(plan).items():
        angles = leg_ik(leg, foot, spec)
        for j, name in enumerate(LEG_JOINTS):
            q[model.jnt_qposadr[model.joint(f"{leg}_{name}").id]] = angles[j]
    return q


def standup_ctrl(model, plan: StandUp, strategy: str, spec: SQ43BodySpec = BODY) -> np.ndarray:
    feet, bend = schedule(plan, strategy, spec, model.opt.timestep)
    angles = {leg: leg_ik(leg, feet[leg], spec) for leg in LEGS}
    ctrl = servo_ctrl(model, angles)
    ctrl[:, actuator_ids(model)[1][3:]] = np.radians(bend)[:, None] / 3
    return ctrl


def with_torque(torque_nm: float, spec: SQ43BodySpec = BODY) -> SQ43BodySpec:
    return replace(spec, servo_torque_nm=torque_nm)


def standup_rig(plan: StandUp, strategy: str, torque_nm: float, spec: SQ43BodySpec = BODY, view=None) -> Rig:
    """One stand-up replayed on the body with the leg servos limited to ``torque_nm``; records after every physics
    step the shoulder and hip heights [mm], their pitch [deg] and the largest leg-servo torque [N·m]."""
    spec = with_torque(torque_nm, spec)
    body = SQ43Body(spec)
    model, data = body.model, body.data
    data.qpos[:] = lying_state(model, plan, spec)
    data.qvel[:] = 0.0
    mujoco.mj_forward(model, data)
    ctrl = standup_ctrl(model, plan, strategy, spec)
    data.ctrl[:] = ctrl[0]
    legs = body.leg_ids

    def after(snap):
        return {"t_s": data.time, "shoulder_z_mm": 1e3 * data.body("shoulder").xpos[2],
                "hip_z_mm": 1e3 * data.body("hip").xpos[2],
                "shoulder_pitch_deg": math.degrees(math.asin(np.clip(-data.body("shoulder").xmat[6], -1, 1))),
                "max_leg_torque_nm": float(np.abs(data.actuator_force[legs]).max())}

    return Rig(body, [CtrlSchedule(ctrl)], duration=len(ctrl) * body.dt, record={1: after}, view=view or {},
               state=plan)


def stood(shoulder_z_mm, hip_z_mm, plan: StandUp, dt: float, spec: SQ43BodySpec = BODY) -> bool:
    n = round(plan.hold_s / dt)
    low = min(np.min(shoulder_z_mm[-n:]), np.min(hip_z_mm[-n:]))
    return bool(low >= 1e3 * plan.stood_fraction * spec.natural_length_m)


def simulate(plan: StandUp, strategy: str, torque_nm: float, spec: SQ43BodySpec = BODY) -> dict:
    """The stand-up rolled out in C (no Python per step): whether it stood and its lowest end height held [mm]."""
    spec = with_torque(torque_nm, spec)
    model = build_spec(spec).compile()
    data = mujoco.MjData(model)
    data.qpos[:] = lying_state(model, plan, spec)
    mujoco.mj_forward(model, data)
    state = np.zeros(mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS))
    mujoco.mj_getState(model, data, state, mujoco.mjtState.mjSTATE_FULLPHYSICS)
    ctrl = standup_ctrl(model, plan, strategy, spec)
    ids = [model.sensor(n) for n in ("shoulder_pos", "hip_pos")]
    _, sensors = rollout.rollout(model, data, state[None], ctrl[None], initial_warmstart=np.zeros((1, model.nv)))
    z = [1e3 * sensors[0, :, s.adr[0] + 2] for s in ids]
    n = round(plan.hold_s / model.opt.timestep)
    return {"stood": stood(z[0], z[1], plan, model.opt.timestep, spec),
            "held_mm": float(min(z[0][-n:].min(), z[1][-n:].min()))}


def least_torque(plan: StandUp, strategy: str, torques, spec: SQ43BodySpec = BODY) -> tuple[float, float]:
    """Over a grid of leg-servo torque limits (ascending): the smallest with which ``strategy`` stands, and the
    smallest from which it stands at every larger grid torque (NaN if none). A scan, not a bisection: standing is
    not monotone in the torque (a 0.84–0.86 N·m pocket where the alternating sequence falls, 0.02 N·m scan)."""
    ok = np.array([simulate(plan, strategy, float(t), spec)["stood"] for t in torques])
    first = float(torques[np.argmax(ok)]) if ok.any() else math.nan
    bad = np.flatnonzero(~ok)
    robust = math.nan if not ok[-1] else float(torques[bad[-1] + 1]) if bad.size else float(torques[0])
    return first, robust
