"""Pedalling by the tendon-driven humanoid Kenshiro (seed 000 §3.5.5, Eqs. 3.21–3.26, Table 3.5,
App. A.2.2 Fig. A.17), on the planar leg model of :mod:`shintai.humanoid.robots.kenshiro` (Fig. 3.31).

Kenshiro has no impedance control, so the two functions become:

* **active leg** — the offline pedal trajectory p_i of Eq. 3.7 (T = 18 samples per half
  revolution), with the foot pitch chosen at every sample so that the step goes *into* the sole
  (Eq. 3.21): |(p_{i+1} − p_i) · u_i| > D_th, D_th = r √(2(1 − cos(π/T))) |cos(5π/6)| ≈ 0.0151 m
  (Eqs. 3.22–3.23), u_i the sole's unit normal (pointing from the sole into the foot). We keep the
  branch Φ > 5π/6 the thesis means (spec §6 item 13): −(p_{i+1} − p_i) · u_i > D_th. Among the
  pitches the leg can reach (joint ranges) we take the least tilt from level that satisfies it,
  and where none can, the one that comes closest (the thesis's ankle choice rule, Fig. 3.33, is
  not in the text). p_i is the pedal axle on the crank circle; the sole's contact point sits the
  pedal's half thickness above it along u_i.
* **passive leg** — q_{i+1} = q_i + K_n Δf_i, K_n = 2 mm/N (Eqs. 3.24–3.26), which is
  ρ ← ρ − A sgn (x − x_d) with ρ = q, x = f_i, x_d = f_{i−1}, sgn = −E (Eq. 3.17) and
  A = K_n E (Table 3.5: A = K(Δf_i) = K_n ‖Δf_i‖ on the unit index Δf̂_i — the same product), run
  through the core engine with the reachability hold of Eq. 3.14, every control period (16 ms), f read
  from the foot F/T sensor at its 0.25 N resolution. Δf_i's reference is not stated
  (``KENSHIRO_DELTA_F``): "start", the force at the passive phase's start (x_d = f_0 held), so the
  foot moves at a rate ∝ the force built since; or "previous", the last period's force (x_d = f_{i−1}),
  whose updates sum to q = q_0 + K_n (f − f_0), a 500 N/m admittance.

The passive leg's tendons are relaxed (constants ``KENSHIRO_RELAXED_TENDON``): the update is
stable only on a compliant leg. Roles swap by the switching diagnostic of Fig. 3.14 (crank angle
from the feet by method (a), Eq. 3.19), ``KENSHIRO_SWITCH_LEAD`` before the switching angle where
the active plan ends.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core.interpolation import SequencePlayer
from shintai.core.runtime import Loop, Module, Switcher
from shintai.core.search_index import SearchIndex
from shintai.humanoid.constants import (
    DEG,
    DELTA_C,
    GRAVITY,
    KENSHIRO,
    KENSHIRO_CONTACT_N,
    KENSHIRO_DELTA_F,
    KENSHIRO_DELTA_F_READINGS,
    KENSHIRO_ON_PEDAL_M,
    KENSHIRO_RELAXED_TENDON,
    KENSHIRO_SAMPLE_PERIOD,
    KENSHIRO_SETTLE_S,
    KENSHIRO_SWITCH_LEAD,
    KenshiroSpec,
)
from shintai.humanoid.robots.kenshiro import JOINTS, PEDAL_HALF_THICKNESS, leg_fk, leg_ik, pedal_axle
from shintai.humanoid.tricycle.active import R_y, crank_angle_of_phase, pedal_trajectory
from shintai.humanoid.tricycle.passive import PASSIVE_SGN
from shintai.humanoid.tricycle.switching import SwitchingDiagnostic, active_leg, estimate_crank_angle

SIDE = {"left": "l", "right": "r"}  # our leg names → the model's prefixes
PITCH_GRID = np.arange(-90.0, 90.25, 0.5) * DEG  # candidate foot pitches for Eq. 3.21
PITCHES_FROM_LEVEL = PITCH_GRID[np.argsort(np.abs(PITCH_GRID), kind="stable")]


def sole_normal(psi: float) -> np.ndarray:
    """u of Eq. 3.21 in the (x, z) hip frame: the sole's unit normal into the foot at pitch ψ."""
    return np.array([math.sin(psi), math.cos(psi)])


def crank_centre(k: KenshiroSpec = KENSHIRO) -> np.ndarray:
    """The crank centre in the (x, z) hip frame (Fig. 3.31)."""
    return np.array([k.d_cx, -k.d_cz])


def pedal_plan(leg: str, k: KenshiroSpec = KENSHIRO) -> np.ndarray:
    """Eq. 3.7 for ``leg`` in the (x, z) hip frame: p_0 the pedal axle δ_c past TDC, p_T δ_c past BDC."""
    theta_c = crank_angle_of_phase(DELTA_C, leg)
    x0, z0 = pedal_axle(theta_c, SIDE[leg], k)
    plan = pedal_trajectory([x0, 0.0, z0], k.crank_radius, DELTA_C, k.samples)
    return plan[:, [0, 2]]


def step_margin(p_i, p_next, psi: float, d_th: float) -> float:
    """Eq. 3.21 (branch Φ > 5π/6): −(p_{i+1} − p_i) · u_i − D_th; positive when satisfied."""
    return float(-(np.asarray(p_next) - np.asarray(p_i)) @ sole_normal(psi) - d_th)


@dataclass(frozen=True)
class PlanStep:
    """One active sample: pedal axle p_i, foot pitch ψ_i, joint angles, and the Eq. 3.21 margin."""

    p: np.ndarray
    psi: float
    q: np.ndarray
    margin: float


def contact_of(axle, psi: float) -> np.ndarray:
    """The sole's contact point when the sole (pitch ψ) lies on the pedal platform over ``axle``."""
    return np.asarray(axle, dtype=float) + PEDAL_HALF_THICKNESS * sole_normal(psi)


def select_foot_pitch(p_i, p_next, k: KenshiroSpec = KENSHIRO) -> PlanStep:
    """The active leg's ankle posture at sample i (Fig. 3.33): the least tilt from level among the
    reachable pitches satisfying Eq. 3.21, else the reachable pitch with the largest margin."""
    best = None
    for psi in PITCH_GRID:
        q = leg_ik(contact_of(p_i, psi), psi, k)
        if q is None:
            continue
        margin = step_margin(p_i, p_next, psi, k.d_th)
        key = (margin > 0, -abs(psi) if margin > 0 else margin)
        if best is None or key > best[0]:
            best = (key, PlanStep(np.asarray(p_i, dtype=float), float(psi), q, margin))
    if best is None:
        raise ValueError(f"Kenshiro's foot cannot reach the pedal point {np.round(p_i, 3).tolist()} at any pitch")
    return best[1]


def passive_posture(q, k: KenshiroSpec = KENSHIRO) -> np.ndarray | None:
    """Joint angles putting the passive foot's contact point at ``q`` with the foot as near level as
    the leg allows (chosen: the thesis gives the passive leg no ankle rule; the free pedal hangs
    level). None if no pitch reaches q — q is then outside the reachable set (Eq. 3.14)."""
    for psi in PITCHES_FROM_LEVEL:
        joints = leg_ik(q, psi, k)
        if joints is not None:
            return joints
    return None


def active_leg_plan(leg: str, k: KenshiroSpec = KENSHIRO) -> list[PlanStep]:
    """Samples i = 0 … T of the active half revolution; the step of p_T, which has no successor,
    takes the direction of the last step (the pedal goes on turning)."""
    p = pedal_plan(leg, k)
    after = np.vstack([p[1:], 2 * p[-1] - p[-2]])
    return [select_foot_pitch(p_i, p_next, k) for p_i, p_next in zip(p, after)]


class PassiveLegUpdate:
    """Eq. 3.24, q_{i+1} = q_i + K_n Δf_i, through the core engine (Table 3.5; module docstring).

    ``reachable(q)`` is the Eq. 3.14-style gate: an unreachable q_{i+1} keeps q_i.
    """

    def __init__(self, q0, f0, k_n: float, reachable, delta_f: str = KENSHIRO_DELTA_F):
        if delta_f not in KENSHIRO_DELTA_F_READINGS:
            raise ValueError(f"passive leg: delta_f is one of {KENSHIRO_DELTA_F_READINGS}, got {delta_f!r}")
        self.index = SearchIndex(q0, k_n, sgn=PASSIVE_SGN[:2, :2], x_d=f0, hold=lambda q: not reachable(q))
        self.delta_f = delta_f

    @property
    def q(self) -> np.ndarray:
        return self.index.rho.copy()

    def step(self, f) -> np.ndarray:
        """One control period with the measured force f_i; Δf_i = f_i − f_0 ("start") or f_i − f_{i−1}."""
        q = self.index.update(f)
        if self.delta_f == "previous":
            self.index.x_d = np.array(f, dtype=float)
        return q.copy()


# --- Kenshiro's body as the laws see it ---------------------------------------------------------


def leg_joints(snapshot, leg: str) -> np.ndarray:
    return np.array([snapshot[f"q:{SIDE[leg]}_{j}"] for j in JOINTS])


def foot_force(snapshot, leg: str, k: KenshiroSpec = KENSHIRO) -> np.ndarray:
    """f_i: the pedal's force on the foot, (x, z) world, from the foot F/T sensor at its resolution.

    The sensor gives what the shank exerts on the foot, in the foot frame (pitch ψ); quasi-statically
    shank + pedal + gravity balance, so f = −R_y(ψ) f_sensor + m_foot g ẑ.
    """
    psi = float(np.sum(leg_joints(snapshot, leg)))
    f = -R_y(psi) @ snapshot[f"{SIDE[leg]}_foot_force"] + np.array([0.0, 0.0, k.foot_mass * GRAVITY])
    return np.round(f[[0, 2]] / k.ft_resolution) * k.ft_resolution


def feet_axles(snapshot, k: KenshiroSpec = KENSHIRO) -> dict:
    """Method (a): each foot's pedal-axle point from the leg's forward kinematics (x, 0, z)."""
    axles = {}
    for leg in SIDE:
        contact, psi = leg_fk(leg_joints(snapshot, leg), k)
        x, z = contact - PEDAL_HALF_THICKNESS * sole_normal(psi)
        axles[leg] = np.array([x, 0.0, z])
    return axles


def crank_angle_from_feet(snapshot, k: KenshiroSpec = KENSHIRO) -> float:
    """θ_c ∈ [0, 2π) estimated from the feet alone (no sensor on the crank, §3.4.4): from the feet
    on their pedals — pressing with at least ``KENSHIRO_CONTACT_N`` and within
    ``KENSHIRO_ON_PEDAL_M`` of the crank circle — or from both if neither is: a lifted or fallen
    foot does not say where its pedal is."""
    axles = feet_axles(snapshot, k)
    cx, cz = crank_centre(k)
    centre = np.array([cx, 0.0, cz])
    on_pedal = {leg: p for leg, p in axles.items()
                if foot_force(snapshot, leg, k)[1] >= KENSHIRO_CONTACT_N
                and abs(np.linalg.norm(p - centre) - k.crank_radius) <= KENSHIRO_ON_PEDAL_M}
    return estimate_crank_angle(on_pedal or axles, centre)


class Tendons:
    """Each leg's tendon stiffness: its servos' gains at a fraction of the model's (muscle tone)."""

    def __init__(self, body):
        self.body = body
        self.ids = {leg: [body.id("actuator", f"{SIDE[leg]}_{j}") for j in JOINTS] for leg in SIDE}
        self.gain = body.model.actuator_gainprm[:, 0].copy()
        self.bias = body.model.actuator_biasprm[:, 1:3].copy()

    def set(self, leg: str, scale: float) -> None:
        """Scale the stiffness by ``scale`` and the damping by √scale (same damping ratio)."""
        m = self.body.model
        for i in self.ids[leg]:
            m.actuator_gainprm[i, 0] = self.gain[i] * scale
            m.actuator_biasprm[i, 1] = self.bias[i, 0] * scale
            m.actuator_biasprm[i, 2] = self.bias[i, 1] * math.sqrt(scale)


def joint_command(leg: str, q) -> dict:
    return {f"{SIDE[leg]}_{j}": float(v) for j, v in zip(JOINTS, q)}


class KenshiroLegs(Module):
    """One role configuration of Fig. A.17: ``active`` follows its plan sample by sample (the
    middle layer interpolating i → i+1 linearly in joint space), the other leg runs Eq. 3.24 every
    control period with relaxed tendons (:func:`passive_posture`)."""

    def __init__(self, active: str, plan: list[PlanStep], tendons: Tendons, k: KenshiroSpec = KENSHIRO,
                 sample_period: float = KENSHIRO_SAMPLE_PERIOD, relaxed: float = KENSHIRO_RELAXED_TENDON,
                 delta_f: str = KENSHIRO_DELTA_F):
        super().__init__(f"{active}-active", k.control_period)
        self.delta_f = delta_f
        self.active, self.passive = active, "left" if active == "right" else "right"
        self.plan, self.tendons, self.k = plan, tendons, k
        self.sample_period, self.relaxed = sample_period, relaxed

    def reset(self, snapshot) -> None:
        self.tendons.set(self.active, 1.0)
        self.tendons.set(self.passive, self.relaxed)
        self._t = float(snapshot["t"])
        self.player = SequencePlayer(leg_joints(snapshot, self.active), method="linear")
        for step in self.plan:
            self.player.push(step.q, self.sample_period)
        contact, _ = leg_fk(leg_joints(snapshot, self.passive), self.k)
        self.law = PassiveLegUpdate(contact, foot_force(snapshot, self.passive, self.k), self.k.k_n,
                                    lambda q: passive_posture(q, self.k) is not None, self.delta_f)

    def update(self, snapshot):
        t = float(snapshot["t"])
        q_active = self.player.advance(t - self._t)
        self._t = t
        q = self.law.step(foot_force(snapshot, self.passive, self.k))
        self.log(t, **{f"{self.passive}.q": q, "passive_holds": self.law.index.held_steps})
        q_passive = passive_posture(q, self.k)  # None only if the leg starts out of reach: hold it
        return {**joint_command(self.active, q_active),
                **({} if q_passive is None else joint_command(self.passive, q_passive))}


def pedalling_switcher(body, first_active: str = "right", k: KenshiroSpec = KENSHIRO,
                       sample_period: float = KENSHIRO_SAMPLE_PERIOD, relaxed: float = KENSHIRO_RELAXED_TENDON,
                       delta_f: str = KENSHIRO_DELTA_F) -> tuple[Switcher, SwitchingDiagnostic]:
    """The two role configurations and the switching diagnostic of Fig. 3.14 as a Switcher on
    Kenshiro's rig ``body``; the roles follow the §3.5.2 leg table shifted by
    ``KENSHIRO_SWITCH_LEAD`` with a hysteresis of half of it (a stalled crank near the switching
angle, or the change of the feet the estimate uses at a swap, moves the estimate by a degree or
two). ``relaxed`` scales the passive leg's tendon stiffness."""
    tendons = Tendons(body)
    children = [KenshiroLegs(leg, active_leg_plan(leg, k), tendons, k, sample_period, relaxed, delta_f) for leg in SIDE]
    diagnostic = SwitchingDiagnostic(lambda s: crank_angle_from_feet(s, k),
                                     lambda a: active_leg(a + KENSHIRO_SWITCH_LEAD, DELTA_C), KENSHIRO_SWITCH_LEAD / 2)
    transitions = [(f"{leg}-active", f"{other}-active", diagnostic.guard_to(other))
                   for leg, other in (("left", "right"), ("right", "left"))]
    return Switcher(children, transitions, initial=f"{first_active}-active", name="kenshiro",
                    period=k.control_period), diagnostic


def settle(body, seconds: float = KENSHIRO_SETTLE_S) -> None:
    """Let the rig come to rest on the pedals under its keyframe servos, no module running (before the
    pedalling starts)."""
    Loop(body, []).run(seconds)
