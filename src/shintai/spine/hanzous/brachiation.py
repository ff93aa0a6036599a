"""HanzouS's brachiation (seed 003 §3.3.3, §5.7.3–5.7.5): 8 key postures spline-interpolated, position servos
tracking them, grasp and release events, the trunk stiffness policies, and the GA's 70-gene adjustment and
fitness.

* **Postures** (:data:`POSTURES`): the thesis uses the real robot's sequence [54] as the initial posture
  list (§5.7.3) but prints none of its angles; ours follow the frames of Fig. 3.13 as §3.3.3 describes them:
  1 hang from bar 0 with both hands, 2 legs pulled back (stiffest, '両足を後ろに引き'), 3 legs swung forward
  and the right hand released ('右手が後のバーから離れた瞬間'), 4–5 the right arm swings toward the next
  bar, 6 just before the bar ('次バーに届く直前'), 7 the right gripper closes on it, 8 hang from both bars.
  Only the 9 joints the GA adjusts move ('両手の肩・肘，片手のグリッパ関節，両足の股関節・膝関節の計9関節');
  the other 9 hold zero.
* **Spline**: a clamped cubic spline through the 8 postures at the cumulated transition times
  (:func:`reference`); the right gripper is commanded closed while its spline value is below half-open.
* **Stiffness policies** (§5.7.5): ``stiff`` (cam 0°, shortest leaf), ``soft`` (cam 180°, longest) and
  ``real`` — stiffest until the right hand leaves the rear bar, then the cam turns to softest (at the cam
  servo's speed) and stays there through the grasp ('足を後に引くときは硬く，手を離して次のバーを把持するまでの
  間に最も柔らかい状態にする').
* **Genes** (§5.7.3): per transition k = 1…7, the 9 joint adjustments of posture k+1 and the adjustment of
  the transition's time step: (9 + 1) × 7 = 70.
* **Fitness** (§5.7.3 lists four criteria of a weighted sum; the weights are ours, :data:`WEIGHTS`): mean trunk
  height (chest above its start), the right hand's holding of the next bar (the fraction of the final hold
  window during which the right hand carries a bar force), the fluctuation of the two hands' contact force
  (standard deviation of their sum, smaller is better) and the forward distance of the chest.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np
from scipy.interpolate import CubicSpline

from shintai.spine.hanzous.body import Grasps, Trunk, build_spec
from shintai.spine.hanzous.constants import (
    CONTROL_S,
    DURATIONS_S,
    GRIPPER_OPEN_RAD,
    HOLD_S,
    IMPACT_S,
    JOINT_GENE_RAD,
    TIME_GENE,
)
from shintai.spine.robots import HANZOUS

GA_JOINTS = ("shoulder_pitch_L", "shoulder_pitch_R", "elbow_L", "elbow_R", "gripper_R", "hip_pitch_L",
             "hip_pitch_R", "knee_L", "knee_R")
O = GRIPPER_OPEN_RAD
# rad, in GA_JOINTS order. Shoulders: + swings the raised arm forward (toward bar 1); hips: + swings the legs
# back; knees: + bends the shank back; gripper: 0 closed, 1 open. Designed (the thesis prints no angles).
POSTURES = np.array([
    # sh_L  sh_R  el_L  el_R  grip_R hip_L hip_R knee_L knee_R
    [0.00, 0.00, 0.00, 0.00, 0.0, 0.00, 0.00, 0.00, 0.00],  # 1 hang from bar 0
    [-0.30, -0.30, 0.00, 0.00, 0.0, 0.70, 0.70, 1.20, 1.20],  # 2 legs pulled back, trunk stiff
    [0.20, 0.20, 0.00, 0.00, O, -0.90, -0.90, 0.30, 0.30],  # 3 legs swung forward, right hand released
    [0.20, 0.90, 0.40, 0.30, O, -1.00, -1.00, 0.20, 0.20],  # 4 right arm swings forward
    [0.10, 1.30, 0.60, 0.20, O, -0.80, -0.80, 0.20, 0.20],  # 5
    [-0.10, 1.30, 0.60, 0.00, O, -0.50, -0.50, 0.20, 0.20],  # 6 just before the next bar (softest)
    [-0.30, 1.00, 0.30, 0.00, 0.0, -0.20, -0.20, 0.20, 0.20],  # 7 the right gripper closes on bar 1
    [-0.60, 0.60, 0.00, 0.00, 0.0, 0.00, 0.00, 0.00, 0.00],  # 8 hang from both bars
])
N_GENES = (len(GA_JOINTS) + 1) * (len(POSTURES) - 1)  # 70 (§5.7.3)
POLICIES = ("stiff", "soft", "real")
CAM_STIFF_DEG, CAM_SOFT_DEG = 0.0, HANZOUS.cam_range_deg
WEIGHTS = {"height_per_m": 2.0, "grasp": 2.0, "force_std_per_n": -0.02, "forward_per_m": 5.0, "fall": -1.0}


def gene_bounds() -> tuple[np.ndarray, np.ndarray]:
    per = np.r_[np.full(len(GA_JOINTS), -JOINT_GENE_RAD), -TIME_GENE]
    lo = np.tile(per, len(POSTURES) - 1)
    return lo, -lo


def sequence(genome: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The adjusted postures (8, 9) and knot times (8,) of a genome (None: the designed sequence)."""
    postures, durations = POSTURES.copy(), DURATIONS_S.copy()
    if genome is not None:
        g = np.asarray(genome, dtype=float).reshape(len(POSTURES) - 1, len(GA_JOINTS) + 1)
        postures[1:] += g[:, :-1]
        durations = durations * (1.0 + g[:, -1])
    postures[:, GA_JOINTS.index("gripper_R")] = np.clip(postures[:, GA_JOINTS.index("gripper_R")], 0.0, O)
    return postures, np.r_[0.0, np.cumsum(durations)]


def reference(postures: np.ndarray, knots: np.ndarray) -> CubicSpline:
    """The clamped cubic spline through the postures at the knot times (zero velocity at both ends)."""
    return CubicSpline(knots, postures, axis=0, bc_type="clamped")


def cam_target(policy: str, released: bool) -> float:
    if policy == "stiff":
        return CAM_STIFF_DEG
    if policy == "soft":
        return CAM_SOFT_DEG
    return CAM_SOFT_DEG if released else CAM_STIFF_DEG


@dataclass
class Outcome:
    """What one brachiation did (the fitness terms and the scenario's metrics); ``log`` when recorded."""

    success: bool
    fell: bool
    grasp_fraction: float
    forward_m: float
    mean_height_m: float
    force_std_n: float
    peak_trunk_force_n: float
    peak_trunk_moment_nm: float
    release_s: float
    grasp_s: float
    impact_peak_n: float
    rearmost_com_m: float
    sim_s: float
    closest_to_next_bar_m: float
    log: dict = field(default_factory=dict)

    def fitness(self) -> float:
        w = WEIGHTS
        return (w["height_per_m"] * self.mean_height_m + w["grasp"] * self.grasp_fraction
                + w["force_std_per_n"] * self.force_std_n + w["forward_per_m"] * self.forward_m
                + w["fall"] * self.fell)


class Brachiator:
    """One HanzouS model and data, reused for many brachiations (one per GA worker)."""

    def __init__(self, body=None):
        if body is None:
            self.model = build_spec().compile()
            self.data = mujoco.MjData(self.model)
            self.after_step = []
        else:  # a MujocoBody to film (its after_step callbacks run at every control tick)
            self.model, self.data, self.after_step = body.model, body.data, body.after_step
        m = self.model
        self.trunk = Trunk(m)
        self.grasps = Grasps(m, self.data)
        self.eq_data0 = m.eq_data.copy()
        self.act = np.array([m.actuator(j).id for j in GA_JOINTS])
        self.substeps = round(CONTROL_S / m.opt.timestep)
        self.chest = m.body("chest").id
        self.force_sensor = m.sensor("trunk_root_force").adr[0]
        self.moment_sensor = m.sensor("trunk_root_torque").adr[0] + 1  # the bending (pitch, y) component
        self.grip_col = GA_JOINTS.index("gripper_R")

    def reset(self) -> None:
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)
        m.eq_data[:] = self.eq_data0
        d.eq_active[:] = m.eq_active0
        self.trunk.set_cam(0.0)
        mujoco.mj_forward(m, d)

    def run(self, genome: np.ndarray | None, policy: str, record: bool = False) -> Outcome:
        """Play the (adjusted) sequence under a stiffness policy and measure it."""
        if policy not in POLICIES:
            raise ValueError(f"policy must be one of {POLICIES}, got {policy!r}")
        self.reset()
        m, d = self.model, self.data
        self.trunk.set_cam(cam_target(policy, released=False))  # the policy's stiffness from the start
        postures, knots = sequence(genome)
        spline = reference(postures, knots)
        end = knots[-1]
        ticks = int(np.ceil((end + HOLD_S) / CONTROL_S))
        times = np.minimum(np.arange(ticks) * CONTROL_S, end)
        targets = spline(times)
        cam_step = HANZOUS.cam_speed_deg_s * CONTROL_S
        x0, z0 = d.xpos[self.chest, 0], d.xpos[self.chest, 2]
        heights, hand_force, trunk_force, com_x, moment, reach = (np.empty(ticks) for _ in range(6))
        held_r = np.zeros(ticks, dtype=bool)
        released, release_s, grasp_s, fell, n = False, np.nan, np.nan, False, ticks
        log = {k: np.empty(ticks) for k in ("t", "cam_deg", "stiffness_nm_rad", "trunk_deflection_rad",
                                             "hand_force_L_n", "hand_force_R_n")} if record else {}
        trunk_q = m.jnt_qposadr[self.trunk.joint]
        for i in range(ticks):
            q = targets[i]
            d.ctrl[self.act] = q
            closed = q[self.grip_col] < 0.5 * O
            before = self.grasps.held("R")
            self.grasps.update("R", closed)
            after = self.grasps.held("R")
            if before == 0 and after is None and not released:
                released, release_s = True, d.time
            if after == 1 and np.isnan(grasp_s):
                grasp_s = d.time
            cam = self.trunk.cam_deg
            self.trunk.set_cam(cam + np.clip(cam_target(policy, released) - cam, -cam_step, cam_step))
            mujoco.mj_step(m, d, self.substeps)
            for callback in self.after_step:
                callback()
            fl, fr = self.grasps.force_n("L"), self.grasps.force_n("R")
            heights[i] = d.xpos[self.chest, 2] - z0
            com_x[i] = d.subtree_com[self.chest, 0]
            moment[i] = abs(d.sensordata[self.moment_sensor])
            reach[i] = self.grasps.distance("R", 1)
            hand_force[i] = fl + fr
            trunk_force[i] = np.linalg.norm(d.sensordata[self.force_sensor:self.force_sensor + 3])
            held_r[i] = self.grasps.held("R") == 1 and fr > 0.0
            if record:
                for k, v in zip(log, (d.time, self.trunk.cam_deg, self.trunk.stiffness(self.trunk.cam_deg),
                                      d.qpos[trunk_q], fl, fr)):
                    log[k][i] = v
            if self.grasps.held("L") is None and self.grasps.held("R") is None or not np.isfinite(d.qpos).all():
                fell, n = True, i + 1
                break
        hold = times[:n] >= end
        hold_total = int(np.sum(times >= end))
        grasp_fraction = float(np.sum(held_r[:n] & hold) / max(hold_total, 1))
        if record:
            log = {k: v[:n] for k, v in (log | {"trunk_root_force_n": trunk_force, "height_m": heights,
                                                "com_x_m": com_x, "trunk_root_moment_nm": moment}).items()}
        t = np.arange(1, n + 1) * CONTROL_S
        after = (t >= grasp_s) & (t <= grasp_s + IMPACT_S)
        before = t < (release_s if np.isfinite(release_s) else knots[2])
        return Outcome(
            success=bool(not fell and self.grasps.held("R") == 1 and self.grasps.held("L") == 0),
            fell=fell, grasp_fraction=grasp_fraction,
            forward_m=float(d.xpos[self.chest, 0] - x0) if np.isfinite(d.qpos).all() else -1.0,
            mean_height_m=float(np.mean(heights[:n])) if np.isfinite(heights[:n]).all() else -1.0,
            force_std_n=float(np.std(hand_force[:n])) if np.isfinite(hand_force[:n]).all() else 1e3,
            peak_trunk_force_n=float(np.max(trunk_force[:n])), peak_trunk_moment_nm=float(np.max(moment[:n])),
            release_s=float(release_s), grasp_s=float(grasp_s),
            impact_peak_n=float(np.max(trunk_force[:n][after])) if after.any() else float("nan"),
            rearmost_com_m=float(np.min(com_x[:n][before])) if before.any() else float("nan"), sim_s=float(d.time),
            closest_to_next_bar_m=float(np.min(reach[:n])),
            log=log)


SHIPPED = Path(__file__).parent / "trained" / "hanzous_brachiation.npz"


def shipped_genome(evolved_under: str = "real") -> np.ndarray:
    """The best genome ``spine.hanzous-ga`` evolved under one stiffness policy (10 generations, population 105,
    seed 0; the settings are stored beside the genomes in the file), shipped with the package."""
    if evolved_under not in POLICIES:
        raise ValueError(f"evolved_under must be one of {POLICIES}, got {evolved_under!r}")
    with np.load(SHIPPED) as f:
        return np.array(f[evolved_under])


_WORKER: dict[str, Brachiator] = {}


def _brachiator() -> Brachiator:
    """The process's one Brachiator (one MjData per worker)."""
    if "b" not in _WORKER:
        _WORKER["b"] = Brachiator()
    return _WORKER["b"]


@dataclass(frozen=True)
class BrachiationFitness:
    """The GA's fitness under one stiffness policy (picklable for the process and Ray executors)."""

    policy: str

    def __call__(self, genome: np.ndarray) -> float:
        return _brachiator().run(genome, self.policy).fitness()

