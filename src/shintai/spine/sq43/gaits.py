"""SQ43's gaits on the MuJoCo body (:mod:`shintai.spine.sq43.body`): the statically planned crawl and its lift
tests (§3.2.4, §3.2.5, Fig. 3.7), and the GA trot's foot-path generator and fitness (§5.6.2, Figs. 5.20–5.21).

**Trot genes (§5.6.2).** "cycle (2.0 ~ 4.0[sec])，fore (40.0 ~ 80.0[mm])，natural-length (208.0 ~ 228.0[mm])，
height (5.0 ~ 25.0[mm])，leg-center (前脚，後脚．それぞれ -30.0 ~ 30.0[mm]) を GA の遺伝子に対応させ … duty は
0.5 に，start-time は 0.0, 1.5[sec] に固定した". Each foot runs the trapezoid DCBA of Fig. 5.20 relative to
its leg root: stance (a fraction ``duty`` of the cycle) on the ground at ``natural-length`` below the root,
sliding back by ``fore`` about ``leg-center``; swing (the rest) lifting by ``height`` in the first quarter,
carried forward at that height, lowered in the last quarter, moving forward by ``fore`` linearly throughout
(the trapezoid's slanted sides; Fig. 5.20's corner timing is not in the text). start-time is "1 サイクルの内
何秒後に前方に脚を運ぶ動作を行うか" (seconds into the cycle at which the leg's swing starts): the diagonal pair
LF+RH swings at 0.0 s, RF+LH at 1.5 s (which pair gets which is not in the text; trot = diagonal pairs in
phase). Taken literally (seconds, not a phase), the pairs alternate exactly only at cycle 3.0 s; at other
cycles their swings overlap or leave a four-leg gap — the GA sees that.

**Fitness (§5.6.2: "前進量，ボディのねじれの平均，遊脚の高さの重み付きの和"; weights and signs not in the text,
ours).** fitness = forward distance [mm] − W_TWIST · mean |spine twist| [deg] − W_SWING · mean swing-foot peak
height [mm]. Forward distance dominates (walking forward is the goal); W_TWIST = 2 mm/deg makes a 5° mean twist
cost about a fifth of the shortest stride (40 mm / 2 cycles), so twisting gaits lose but a gait is never
traded for stillness; W_SWING = 0.5 mm/mm penalises high foot lifts mildly (effort, and the time the
diagonal support is needed): a 25 mm lift costs 12.5 mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import mujoco
import numpy as np
from mujoco import rollout

from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.sq43.body import (
    BODY,
    LEGS,
    SQ43Body,
    SQ43BodySpec,
    build_spec,
    leg_ik,
    leg_root,
    relative_twist,
    servo_ctrl,
    standing_angles,
)
from shintai.spine.sq43.constants import DUTY, RAMP_S, TROT_DURATION_S, W_SWING, W_TWIST_MM_PER_DEG

# ------------------------------------------------------------------------------------------------ trot

GENES = ("cycle_s", "fore_mm", "natural_length_mm", "height_mm", "centre_front_mm", "centre_rear_mm")
START_TIME_S = {"LF": 0.0, "RH": 0.0, "RF": 1.5, "LH": 1.5}  # §5.6.2: 0.0 and 1.5 s, diagonal pairs


def swing_phase(t, cycle: float, start: float, duty: float = DUTY) -> np.ndarray:
    """Phase in the swing ∈ [0, 1) while the leg swings, NaN in stance (t and start in seconds)."""
    swing = (1.0 - duty) * cycle
    since = np.mod(np.asarray(t, dtype=float) - start, cycle)
    return np.where(since < swing, since / swing, np.nan)


def foot_path(genome, t, leg: str) -> np.ndarray:
    """The foot tip relative to its leg root (x forward, z up) [m], (len(t), 3), for genes ``genome``
    (GENES order) at gait times ``t`` [s] (module docstring)."""
    cycle, fore, natural, height, c_front, c_rear = np.asarray(genome, dtype=float)
    fore, natural, height = fore * 1e-3, natural * 1e-3, height * 1e-3
    centre = 1e-3 * (c_front if leg[1] == "F" else c_rear)
    t = np.asarray(t, dtype=float)
    start = START_TIME_S[leg]
    swing_t = (1.0 - DUTY) * cycle
    since = np.mod(t - start, cycle)
    in_swing = since < swing_t
    u = np.where(in_swing, since / swing_t, (since - swing_t) / (cycle - swing_t))
    x = np.where(in_swing, -fore / 2 + fore * u, fore / 2 - fore * u)
    lift = np.clip(np.minimum(u, 1.0 - u) * 4.0, 0.0, 1.0)  # rise in the first quarter, lower in the last
    z = -natural + np.where(in_swing, height * lift, 0.0)
    return np.stack((centre + x, np.zeros_like(x), z), axis=-1)


def trot_angles(genome, t, spec: SQ43BodySpec = BODY) -> dict[str, np.ndarray]:
    """Joint angle targets {leg: (len(t), 3)} of the trot at gait times t."""
    return {leg: leg_ik(leg, foot_path(genome, t, leg), spec) for leg in LEGS}


def trot_ctrl(model: mujoco.MjModel, genome, duration: float = TROT_DURATION_S, spec: SQ43BodySpec = BODY
              ) -> np.ndarray:
    """The open-loop ctrl sequence (nstep, nu), one row per physics step: RAMP_S from the standing pose
    into the gait's first pose, then ``duration`` of gait. Spine servos straight."""
    dt = model.opt.timestep
    n_ramp, n_gait = round(RAMP_S / dt), round(duration / dt)
    gait = trot_angles(genome, np.arange(n_gait) * dt, spec)
    stand = standing_angles(spec)
    w = (np.arange(n_ramp) / n_ramp)[:, None]
    ramp = {leg: (1 - w) * stand[leg] + w * gait[leg][0] for leg in LEGS}
    return servo_ctrl(model, {leg: np.vstack((ramp[leg], gait[leg])) for leg in LEGS})


@lru_cache(maxsize=4)
def _sim(spec: SQ43BodySpec) -> tuple[mujoco.MjModel, mujoco.MjData, np.ndarray, dict]:
    """One model and one MjData per process (cached), the standing initial state and the sensor slices."""
    model = build_spec(spec).compile()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    state = np.zeros(mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS))
    mujoco.mj_getState(model, data, state, mujoco.mjtState.mjSTATE_FULLPHYSICS)
    slices = {}
    for i in range(model.nsensor):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SENSOR, i)
        slices[name] = slice(model.sensor_adr[i], model.sensor_adr[i] + model.sensor_dim[i])
    return model, data, state, slices


def simulate_trot(genome, duration: float = TROT_DURATION_S, spec: SQ43BodySpec = BODY) -> dict:
    """Roll the trot out open loop in C (mujoco.rollout, no Python per step); returns the sensor series
    (after the ramp) and the gait metrics."""
    model, data, state, sl = _sim(spec)
    ctrl = trot_ctrl(model, genome, duration, spec)
    _, sensors = rollout.rollout(model, data, state[None], ctrl[None], initial_warmstart=np.zeros((1, model.nv)))
    s = sensors[0, round(RAMP_S / model.opt.timestep) - 1:]
    return trot_metrics(genome, s, sl, model.opt.timestep)


def trot_metrics(genome, s: np.ndarray, sl: dict, dt: float) -> dict:
    """distance_mm (trunk centre's forward travel), twist_deg (mean |shoulder–hip twist|), swing_mm (mean
    over the swings of the swing foot's peak height above the floor), fitness, and the series."""
    trunk = 0.5 * (s[:, sl["shoulder_pos"]] + s[:, sl["hip_pos"]])
    twist = relative_twist(s[:, sl["shoulder_quat"]], s[:, sl["hip_quat"]])
    t = np.arange(len(s)) * dt
    cycle = float(genome[0])
    peaks = []
    for leg in LEGS:
        phase = swing_phase(t, cycle, START_TIME_S[leg])
        z = s[:, sl[f"{leg}_foot"]][:, 2]
        swing_id = np.floor((t - START_TIME_S[leg]) / cycle)
        for k in np.unique(swing_id[np.isfinite(phase)]):
            mask = np.isfinite(phase) & (swing_id == k)
            if mask.sum() > 2:
                peaks.append(z[mask].max())
    distance = 1e3 * (trunk[-1, 0] - trunk[0, 0])
    twist_deg = float(np.degrees(np.mean(np.abs(twist))))
    swing = 1e3 * float(np.mean(peaks)) if peaks else 0.0
    return {"distance_mm": float(distance), "twist_deg": twist_deg, "swing_mm": swing,
            "fitness": float(distance - W_TWIST_MM_PER_DEG * twist_deg - W_SWING * swing),
            "lateral_mm": float(1e3 * (trunk[-1, 1] - trunk[0, 1])), "min_trunk_height_mm": float(1e3 * trunk[:, 2].min()),
            "series": {"t": t, "trunk": trunk, "twist_deg": np.degrees(twist)}}


@dataclass(frozen=True)
class TrotFitness:
    """The GA's fitness for one genome (picklable: the process and Ray executors ship it)."""

    duration_s: float = TROT_DURATION_S

    def __call__(self, genome) -> float:
        value = simulate_trot(np.asarray(genome, dtype=float), self.duration_s)["fitness"]
        return value if math.isfinite(value) else -math.inf


def trot_rig(genome, duration: float = TROT_DURATION_S, spec: SQ43BodySpec = BODY, view=None) -> Rig:
    """A trot replayed on an :class:`SQ43Body` (the filmed replay; identical physics to :func:`simulate_trot`: same
    model, same initial state, the same ctrl row per physics step); the sensors recorded after every step."""
    body = SQ43Body(spec)
    ctrl = trot_ctrl(body.model, genome, duration, spec)
    return Rig(body, [CtrlSchedule(ctrl)], duration=len(ctrl) * body.dt,
               record={1: lambda snap: {"sensors": body.data.sensordata}}, view=view or {}, state=np.asarray(genome))


def trot_result(log, genome, spec: SQ43BodySpec = BODY) -> dict:
    """:func:`trot_metrics` of a replayed trot (after the ramp)."""
    model, _, _, sl = _sim(spec)
    return trot_metrics(genome, log.values("sensors")[round(RAMP_S / model.opt.timestep) - 1:], sl, model.opt.timestep)


class CtrlSchedule(Module):
    """Writes row ``k`` of a ctrl sequence (one row per body step) at the ``k``-th tick: an open-loop replay."""

    def __init__(self, ctrl: np.ndarray, name: str = "schedule"):
        super().__init__(name)
        self.ctrl, self.k = ctrl, 0

    def update(self, snapshot: Snapshot):
        row = self.ctrl[self.k]
        self.k += 1
        return {"ctrl": row}


# ----------------------------------------------------------------------------------------------- crawl

CRAWL_ORDER = ("RF", "LH", "LF", "RH")  # Fig. 3.7: right front, then left hind (…, the other side mirrored)
OPPOSITE_REAR = {"RF": "LH", "LF": "RH", "LH": "RF", "RH": "LF"}  # the support foot the CoM moves toward


@dataclass(frozen=True)
class CrawlPlan:
    """The statically planned crawl of §3.2.4: per swing leg, shift the trunk toward the diagonally opposite
    foot ("持ち上げようとする脚から重心をなるべく遠ざけた姿勢 … 重心を左後ろ脚の真上付近に近づける"), lift the
    leg quickly, carry it forward before the twisting spine lets it touch down ("素早く脚を上げ … 素早くその脚を
    前に運ぶ"), put it down and return the trunk. Times and sizes chosen (not in the text)."""

    shift_fraction: float = 0.5  # of the way from the trunk centre toward the opposite foot
    shift_s: float = 1.0  # slow: statically planned (a 0.6 s shift tips the body over on the third leg)
    lift_mm: float = 30.0
    lift_s: float = 0.08
    carry_s: float = 0.12
    down_s: float = 0.08
    settle_s: float = 0.6
    stride_mm: float = 40.0


def _shift_toward(leg: str, fraction: float, spec: SQ43BodySpec) -> np.ndarray:
    return fraction * leg_root(OPPOSITE_REAR[leg], spec)[:2]


def crawl_schedule(plan: CrawlPlan, legs: tuple[str, ...], spec: SQ43BodySpec = BODY, shift: bool = True,
                   hold_s: float = 0.0, dt: float = 0.01) -> tuple[np.ndarray, dict, dict]:
    """The planned foot targets (relative to the leg roots, trunk frame) for swinging ``legs`` one after the
    other (or, with a tuple of two legs per entry, together). Returns t, {leg: (T, 3)}, and the swing
    windows {leg: [(t_up, t_down), ...]}. ``hold_s`` > 0 holds each lifted leg up instead of carrying it
    (the "can it be held" test)."""
    h = spec.natural_length_m
    feet = {leg: np.array([0.0, 0.0, -h]) for leg in LEGS}  # foot rel. root; trunk centre over the feet
    times, rows, windows = [0.0], [{k: v.copy() for k, v in feet.items()}], {leg: [] for leg in LEGS}

    def move(duration: float, target: dict) -> None:
        start = rows[-1]
        n = max(1, round(duration / dt))
        for i in range(1, n + 1):
            w = 0.5 - 0.5 * math.cos(math.pi * i / n)
            rows.append({k: start[k] + w * (target[k] - start[k]) for k in LEGS})
            times.append(times[-1] + dt)

    move(0.5, rows[-1])
    for entry in legs:
        group = entry if isinstance(entry, tuple) else (entry,)
        s = _shift_toward(group[0], plan.shift_fraction, spec) if shift and len(group) == 1 else np.zeros(2)
        base = {k: v.copy() for k, v in rows[-1].items()}
        shifted = {k: v - np.r_[s, 0.0] for k, v in base.items()}
        move(plan.shift_s, shifted)
        up = {k: v.copy() for k, v in shifted.items()}
        for leg in group:
            up[leg] = up[leg] + [0.0, 0.0, 1e-3 * plan.lift_mm]
        t_up = times[-1]
        move(plan.lift_s, up)
        if hold_s > 0:
            move(hold_s, up)
            down = {k: v.copy() for k, v in up.items()}
            for leg in group:
                down[leg] = shifted[leg].copy()
        else:
            fwd = {k: v.copy() for k, v in up.items()}
            for leg in group:
                fwd[leg] = fwd[leg] + [1e-3 * plan.stride_mm, 0.0, 0.0]
            move(plan.carry_s, fwd)
            down = {k: v.copy() for k, v in fwd.items()}
            for leg in group:
                down[leg] = down[leg] - [0.0, 0.0, 1e-3 * plan.lift_mm]
        move(plan.down_s, down)
        for leg in group:
            windows[leg].append((t_up, times[-1]))
        # trunk back over the feet: the planted feet move back by the shift, the trunk forward by the stride/4
        back = {k: v + np.r_[s, 0.0] - [1e-3 * plan.stride_mm / 4 if hold_s <= 0 else 0.0, 0.0, 0.0]
                for k, v in down.items()}
        move(plan.settle_s, back)
    return np.array(times), {leg: np.array([r[leg] for r in rows]) for leg in LEGS}, windows


@dataclass
class Crawl:
    """What a crawl rig leaves for :func:`crawl_result`: the plan, the swing windows, the sensor slices."""

    plan: CrawlPlan
    windows: dict
    slices: dict


def crawl_rig(plan: CrawlPlan, legs, shift: bool = True, hold_s: float = 0.0, spec: SQ43BodySpec = BODY,
              view=None) -> Rig:
    """A crawl schedule replayed on the body, its targets every 10 ms (one body step of 5 physics steps); the
    sensors recorded after every step (``sensors``)."""
    body = SQ43Body(spec, substeps=round(0.01 / spec.timestep))
    model, data = body.model, body.data
    t, targets, windows = crawl_schedule(plan, tuple(legs), spec, shift, hold_s)
    angles = {leg: leg_ik(leg, targets[leg], spec) for leg in LEGS}
    sl = {n: slice(model.sensor(n).adr[0], model.sensor(n).adr[0] + model.sensor(n).dim[0])
          for n in ("shoulder_pos", "hip_pos", "shoulder_quat", "hip_quat", *[f"{leg}_foot" for leg in LEGS])}
    return Rig(body, [CtrlSchedule(servo_ctrl(model, angles))], duration=len(t) * body.dt,
               record={1: lambda snap: {"sensors": data.sensordata}}, view=view or {}, state=Crawl(plan, windows, sl))


def crawl_result(log, run: Crawl) -> dict:
    """The clearance each swing reached (peak foot-tip height above the floor in its window) [mm], the height held
    in the hold test, the trunk's forward travel [mm], the peak twist [deg] and the series."""
    rec, sl, plan, windows = log.values("sensors"), run.slices, run.plan, run.windows
    ts = np.arange(1, len(rec) + 1) * 0.01
    feet_z = {leg: 1e3 * rec[:, sl[f"{leg}_foot"]][:, 2] for leg in LEGS}
    clear = {leg: [float(feet_z[leg][(ts >= a) & (ts <= b)].max()) for a, b in windows[leg]] for leg in LEGS}
    held = {leg: [float(feet_z[leg][(ts >= b - 0.1 - plan.down_s) & (ts <= b - plan.down_s)].mean())
                  for a, b in windows[leg]] for leg in LEGS}
    trunk = 0.5 * (rec[:, sl["shoulder_pos"]] + rec[:, sl["hip_pos"]])
    twist = np.degrees(relative_twist(rec[:, sl["shoulder_quat"]], rec[:, sl["hip_quat"]]))
    return {"clearance_mm": clear, "held_mm": held, "forward_mm": float(1e3 * (trunk[-1, 0] - trunk[0, 0])),
            "max_twist_deg": float(np.abs(twist).max()), "t": ts, "feet_z_mm": feet_z, "twist_deg": twist,
            "windows": windows}
