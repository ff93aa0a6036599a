"""Driving the ch. 4 rig (seed 000 §4.3–4.4, §7.3–7.4): who turns the crank, the navigator, the seat
slip, PPDM's back-pedalling, and what the ch. 4 experiments measure on the vehicle.

**Drive.** Every ch. 4 experiment has ``drive``: ``legs`` — the humanoid pedals with its own legs;
``motor`` — a crank motor (velocity servo) *stands in for the legs*, the feet riding the pedals under
the active leg impedance with Table 3.4's 150 N. The motor is not the thesis's method; the metrics'
``note`` says which drive ran. With ``legs``, ``humanoid.sitting-recovery`` runs the ch. 3 operation
modules (the Fig. 3.16 schedule, role-switched active/passive legs,
:func:`~shintai.humanoid.tricycle.rig.legs_pedalling`); the other three place both soles on the pedals
at Eq. 4.22's crank target (:class:`LeadPedal`), because the detection method must turn the crank
*back* (Table 4.7: ρ = θ_c^ref) and the navigator must set the crank rate (Eq. 4.18, 0 at the goal),
neither of which the forward Fig. 3.16 schedule can. The arms always steer by the humanoid's own
whole-body IK (:class:`~shintai.humanoid.tricycle.ch4_riding.Rider`).

Every module here talks through the loop's reference channels
(:data:`~shintai.humanoid.tricycle.ch4_riding.REF_CHANNELS`).
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.core.runtime import Module
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    DEG,
    DELTA_C,
    LEAD_DT,
    LEGS_FZ,
    NAVIGATION,
    OVERTURN_ROLL,
    SLIP_START_S,
)
from shintai.humanoid.corrections import push_down_angle
from shintai.humanoid.tricycle import ch4_riding as cr
from shintai.humanoid.tricycle.ch4_riding import Rider, vehicle_pose2d, vehicle_roll
from shintai.humanoid.tricycle.navigation import (
    Costmap,
    DepthSensor,
    DynamicWindow,
    crank_rate,
    crank_reference,
    global_path,
    handle_reference,
)
from shintai.humanoid.tricycle.rig import CrankEstimate
from shintai.humanoid.tricycle.switching import active_leg
from shintai.scenarios.registry import Param

DRIVES = ("motor", "legs")
# the ch. 4 scenarios' crank driver choice (one declaration for every scenario that drives with Eq. 4.22's target)
DRIVE_PARAM = Param("drive", "legs", "who turns the crank: legs (Eq. 4.22 crank target from ω_c^ref) or motor "
                    "(stand-in)", choices=DRIVES)
MOTOR_NOTE = ("drive=motor: a crank motor stands in for the legs (NOT the thesis's pedalling); the arms steer by "
              "the humanoid's own IK")
LEGS_NOTE = "drive=legs: the humanoid pedals with its own legs (ch. 3 active/passive role switching)"
LEAD_NOTE = ("drive=legs: the humanoid's legs turn the crank at the commanded rate (both soles placed on the "
             "pedals at Eq. 4.22's crank target from ω_c^ref, leg impedance, 150 N)")
CH4_VIEW = {"track": "waist", "distance": 3.0, "azimuth": 150.0, "elevation": -20.0}


# --- who turns the crank ---------------------------------------------------------------------------


class LeadPedal(Module):
    """The legs turn the crank: every Δt a new target θ_c^ref = θ_c + (2π Δt / D_c) ẋ^ref (Eq. 4.22,
    θ_c measured by method (a), ẋ^ref taken at the sample's start), approached linearly over the
    sample and then held; both soles are placed on the pedals there under the leg impedance
    (:class:`~shintai.humanoid.tricycle.ch4_riding.Rider`), the foot on the downstroke pushing the crank.
    ``speed``: ẋ^ref [m/s], or ``None`` to follow the crank-rate command ``ref:crank_rate`` of another
    module (ω_c^ref of Eq. 4.18, e.g. the navigator's; ẋ^ref = D_c ω_c^ref / 2π) — at ω_c^ref = 0 the
    target stays at the measured angle and the legs hold the crank (the tricycle stops).
    ``extra_active`` adds force to the active (stepping) leg of the §3.5.2 role table (Eq. 3.19's
    switching angles θ_c^init + kπ) — PPDM's "push harder"."""

    def __init__(self, name: str, crank: CrankEstimate, speed: float | None, extra_active: float = 0.0):
        super().__init__(name, CONTROL_PERIOD)
        self.crank, self.speed, self.extra = crank, speed, extra_active

    def xdot_ref(self, snapshot) -> float:
        if self.speed is not None:
            return self.speed
        return max(cr.travel_of_crank(float(snapshot.get("ref:crank_rate", 0.0))), 0.0)

    def reset(self, snapshot) -> None:
        self.start = self.crank(snapshot)
        self.t_k, self.theta_k = float(snapshot["t"]), self.start
        self.xdot_k = self.xdot_ref(snapshot)

    def update(self, snapshot):
        t, theta = float(snapshot["t"]), self.crank(snapshot)
        if t - self.t_k >= LEAD_DT:  # a new sample: Eq. 4.22 from the measured angle
            self.t_k, self.theta_k, self.xdot_k = t, theta, self.xdot_ref(snapshot)
        # reached linearly over the sample (the transition Δt of Fig. 3.16), then held
        frac = min((t - self.t_k) / LEAD_DT, 1.0)
        target = self.theta_k + frac * (crank_reference(self.theta_k, self.xdot_k, LEAD_DT) - self.theta_k)
        out = {"ref:crank_target": target}
        if self.extra:
            out[f"ref:foot_fz_{active_leg(theta, DELTA_C)[0]}"] = self.extra
        return out


def drive_modules(body, drive: str):
    """The modules that move the tricycle: (rider, [modules]) for ``drive`` = motor or legs. Both
    follow the crank-rate command ``ref:crank_rate`` (ω_c^ref, Eq. 4.18) of another module: the motor
    as its velocity target, the legs through Eq. 4.22's crank target (:class:`LeadPedal`, both soles on
    the pedals, 150 N)."""
    if drive == "motor":
        rider = Rider(body, feet=True)
        return rider, [rider, cr.CrankMotor()]
    rider = Rider(body, feet=True, crank_of=lambda s: s["ref:crank_target"], base_fz=LEGS_FZ)
    return rider, [rider, LeadPedal("legs", CrankEstimate(body), None)]


class BackPedal(Module):
    """PPDM's reaction (§4.4.3): crank backwards to the push-down posture θ_c^SW = θ_c^init + kπ below
    the angle at the impact; the soles are placed on the pedals along the way, the target moving back
    at the driving crank rate ``rate`` (chosen: as fast as the legs pedal forward)."""

    def __init__(self, crank: CrankEstimate, rate: float, name: str = "back"):
        super().__init__(name, CONTROL_PERIOD)
        self.crank, self.rate = crank, rate
        self.goal = 0.0

    def reset(self, snapshot) -> None:
        self.t0, self.entry = float(snapshot["t"]), self.crank(snapshot)
        self.goal = push_down_angle(self.entry)

    def arrived(self, snapshot, tol: float = 5 * DEG, wait: float = 1.0) -> bool:
        """The push-down posture is reached: the crank within ``tol`` of it, or the target there for
        ``wait`` seconds (a crank that cannot go the last degrees back starts pushing from there)."""
        t_goal = self.t0 + (self.entry - self.goal) / self.rate
        return abs(self.crank(snapshot) - self.goal) < tol or float(snapshot["t"]) > t_goal + wait

    def update(self, snapshot):
        back = min(self.rate * (float(snapshot["t"]) - self.t0), self.entry - self.goal)
        return {"ref:crank_target": self.entry - back}


# --- the navigator (§4.4.2) ---------------------------------------------------------------------------


class Navigator(Module):
    """§4.4.2 / Fig. 4.17 steps 1–4 at the planner period: scan (depth sensor) → costmap → global path
    (every ``replan_s``) → DWA (ẋ^ref, θ̇^ref) → θ_h^ref (Eq. 4.21) and ω_c^ref (Eq. 4.18).

    The vehicle pose: the simulator's (``localiser=None``, a stand-in), or §7.3.2's closed loop of
    self-localisation (Fig. 7.3): a :class:`~shintai.humanoid.tricycle.localisation.Localiser` updated with the
    same scan, whose estimate both places the scan in the costmap and is the pose the planner starts from."""

    def __init__(self, body, goal, spec=NAVIGATION, replan_s: float = 1.0, localiser=None):
        super().__init__("navigator", spec.period)
        self.body, self.goal, self.spec = body, np.asarray(goal, dtype=float), spec
        self.sensor, self.costmap = DepthSensor(spec), Costmap(spec)
        self.localiser = localiser
        if localiser is not None:
            localiser.sensor = self.sensor
        self.dwa = DynamicWindow(spec)
        self.replan_every = max(1, int(round(replan_s / spec.period)))
        self.calls = 0
        self.path = None
        self.command = (0.0, 0.0)
        self.trace: list[tuple] = []

    def update(self, snapshot):
        if self.localiser is None:
            pose = vehicle_pose2d(self.body)  # self-localisation stand-in (the thesis: SLAM odometry)
            points = self.sensor.scan(self.body.model, self.body.data)
        else:  # the scan in the vehicle frame, placed in the world by the estimated pose
            local = self.localiser.scan_vehicle()
            pose = self.localiser.update(snapshot, local)
            c, s = np.cos(pose[2]), np.sin(pose[2])
            points = np.stack([pose[0] + c * local[:, 0] - s * local[:, 1],
                               pose[1] + s * local[:, 0] + c * local[:, 1]], axis=-1)
        new = self.costmap.mark(points)
        if new or self.path is None or self.calls % self.replan_every == 0:
            path = global_path(self.costmap, pose[:2], self.goal, self.spec.footprint_r, self.spec.path_margin)
            self.path = path if path is not None else self.path
        self.calls += 1
        v, w, _ = self.dwa.plan(self.costmap, pose, self.command, self.goal, self.path)
        self.command = (v, w)
        self.trace.append((float(snapshot["t"]), *pose, v, w))
        return {"ref:theta_h": handle_reference(v, w), "ref:crank_rate": crank_rate(v)}


# --- the seat slip (§4.3.2, §7.4.1) ----------------------------------------------------------------------


def lean_left(snapshot) -> float:
    """θ_roll in the sign of Fig. 4.6 / Eq. 4.6, chosen so that sgn[y_g, θ_roll] = −1 holds *in our
    plant*: it is our right-handed trunk roll about +x (:func:`~shintai.humanoid.tricycle.ch4_riding.trunk_roll`,
    positive when the trunk leans to −y). With the hands gripping the bar (they can turn in it) a seat
    slip of the hip to +y (y_g up) leans the trunk to +y with the CoM — θ_roll falls, as Eq. 4.6 states
    — so Eq. 4.7's y_g(n+1) = y_g(n) + L sin θ_roll moves the CoM back toward −y. (With 6-DoF welded
    hands the held trunk leaned the other way; the earlier sign followed that.) The name is kept for
    the logs: the logged ``roll`` is this θ_roll."""
    return cr.trunk_roll(snapshot)


class SeatSlip:
    """The disturbance (ours). The thesis gives none: in §7.4.1 the seat displacement "accumulates
    gradually during driving" (fail-1..3) and the recovery removes it (Fig. 7.15, 4th snapshot); when
    it accumulates again the interrupt runs again (§7.5's discussion of repeated interrupts). We model
    its cause as a lateral force pair between hip and saddle, +F on the waist and −F on the saddle,
    that grows by ``rate`` N per second *of driving* (the crank turning faster than ``turning``
    rad/s) while the hip sits, up to ``f_max`` — a creeping seat slip produced by the pedalling.
    It acts only while the hip sits (saddle normal force above ``seated_n``); once the hip has left
    the saddle (STAND) it sits down afresh and the slip starts again from zero. Nothing grows before
    ``start``."""

    def __init__(self, body, rate: float, f_max: float, start: float = SLIP_START_S, seated_n: float = 50.0,
                 turning: float = 0.2):
        self.body, self.rate, self.f_max, self.start = body, rate, f_max, start
        self.seated_n, self.turning = seated_n, turning
        self.waist, self.saddle = body.id("body", "waist"), body.id("body", "saddle")
        self.crank_dof = body.model.joint("crank").dofadr[0]
        self.force, self.driven_s, self.t_last, self.resets = 0.0, 0.0, None, 0

    def __call__(self, snapshot):
        xf = self.body.data.xfrc_applied
        xf[[self.waist, self.saddle], :] = 0.0
        t = float(snapshot["t"])
        dt = 0.0 if self.t_last is None else t - self.t_last
        self.t_last = t
        seated = self.body.contact_force("waist")[2] > self.seated_n
        if not seated:
            self.resets += int(self.driven_s > 0)
            self.driven_s = 0.0
        elif t > self.start and abs(self.body.data.qvel[self.crank_dof]) > self.turning:
            self.driven_s += dt
        self.force = min(self.rate * self.driven_s, self.f_max) if seated else 0.0
        frame = self.body.data.body("tricycle").xmat.reshape(3, 3)
        xf[self.waist, :3] = self.force * frame[:, 1]
        xf[self.saddle, :3] = -self.force * frame[:, 1]
        return None


def hip_to_com(body) -> float:
    """L_hip→COG (Eq. 4.3): the seated robot's CoM distance from the hip–saddle contact (keyframe)."""
    data = mujoco.MjData(body.model)
    mujoco.mj_resetDataKeyframe(body.model, data, body.model.key("ride").id)
    mujoco.mj_forward(body.model, data)
    com = data.subtree_com[body.id("body", "waist")]
    return float(np.linalg.norm(com - data.site("saddle_top").xpos))


# --- what the experiments measure on the vehicle ----------------------------------------------------------


def overturned(body) -> bool:
    """The tricycle lies on its side (frame roll beyond 45°) — a fall."""
    return abs(vehicle_roll(body)) > OVERTURN_ROLL


def foot_off_pedal(body) -> float:
    """The larger distance of a sole centre from its pedal's platform centre (vehicle frame) [m]."""
    rot = body.data.body("tricycle").xmat.reshape(3, 3)
    return float(max(np.linalg.norm((rot.T @ (body.site_pos(f"{s}_sole") - body.site_pos(f"pedal_{s}_top")))[:2])
                     for s in ("l", "r")))


def min_distance(model, data, geom: int, others, distmax: float = 2.0) -> float:
    """Smallest signed distance between ``geom`` and any of ``others`` (mj_geomDistance)."""
    return min(mujoco.mj_geomDistance(model, data, geom, int(g), distmax, None) for g in others)


def vehicle_geoms(model) -> np.ndarray:
    """Every geom of the tricycle and the robot (not the world's)."""
    return np.flatnonzero(model.geom_bodyid != 0)
