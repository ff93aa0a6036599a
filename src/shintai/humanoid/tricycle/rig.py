"""HRP2 on the tricycle wired to the operation algorithm (seed 000 §3.4–3.5, Fig. 3.16): the wiring the
tricycle experiments (E1–E7), the ch. 4 legs drive and the benchmarks share.

The robot (:mod:`~shintai.humanoid.tricycle.riding`) plugs into the operation algorithm
(:mod:`~shintai.humanoid.tricycle.operation`) through :class:`~shintai.humanoid.tricycle.hrp2_limbs.Hrp2Limb`: the active
limb follows its plan from the tricycle's *nominal* kinematic model (Eq. 3.7 for a foot, the grip at θ_h
for a hand, §3.4.2) under the active impedance, the passive limb runs the passive impedance (Eq. 3.13)
and acquires its reference once per passive phase (Eq. 3.14), and the roles swap when the angle measured
from the robot's own FK (method (a), §3.4.4) passes a switching angle (Eq. 3.19). Gains and force targets
are Table 3.4's; Δθ_h = 5°, Δθ_c = 10° (§3.5.1).

Here: the limbs' plans, the method-(a) angles and their switching diagnostics, the schedules, the
rigs of one pedalling or steering run (a role switcher or a both-active pair, logging every control
tick) and the analysis of what such a run recorded.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from shintai.core.geometry import unwrap_from, wrap_pi
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    D_THETA_C,
    D_THETA_H,
    DELTA_C,
    IMPEDANCE,
    SWITCH_HYSTERESIS,
    TRICYCLE,
)
from shintai.humanoid.tricycle.active import grip_plan
from shintai.humanoid.tricycle.hrp2_limbs import riding_limbs
from shintai.humanoid.tricycle.operation import SIDES, OperationSchedule, role_switcher
from shintai.humanoid.tricycle.riding import PEDAL, SOLE
from shintai.humanoid.tricycle.switching import (
    Y_AXIS,
    SwitchingDiagnostic,
    active_arm,
    active_leg,
    axle_fit_terms,
    crank_zero,
    estimate_crank_angle,
    estimate_handle_angle,
    fit_angle_of,
)
from shintai.humanoid.tricycle.vehicle import crank_centre, pedal_position
from shintai.scenarios.experiment import Rig

LEG_GAINS = {"active": IMPEDANCE["active_leg"], "passive": IMPEDANCE["passive_leg"]}
ARM_GAINS = {"active": IMPEDANCE["active_arm"], "passive": IMPEDANCE["passive_arm"]}
F_TRG = IMPEDANCE["passive_leg"].f_trg[2]  # 150 N (Table 3.4)
PEDAL_HALF_THICKNESS = TRICYCLE.pedal_size[2] / 2
TRICYCLE_VIEW = {"track": "waist", "distance": 2.6, "azimuth": 140.0, "elevation": -15.0}  # three-quarter view


# --- the limbs' plans and the measured angles (vehicle frame) -------------------------------------


def foot_plan(leg: str):
    """X_active^ref of a foot: Eq. 3.7's pedal point at the target crank angle, on the nominal crank
    circle (the sole on the level platform top, :func:`~shintai.humanoid.tricycle.vehicle.pedal_position`)."""
    return lambda theta_c: pedal_position(theta_c, leg[0])


def hand_plan(arm: str):
    """X_active^ref of a hand: its grip at the target θ_h on the nominal handle (§3.4.2)."""
    return lambda theta_h: grip_plan(theta_h, arm)


def pedal_axles(feet: dict, snapshot) -> dict:
    """Each foot's pedal-axle point: the sole point less the platform's half thickness along the
    sole normal (vehicle frame), so that method (a) sees points on the crank circle."""
    axles = {}
    h = PEDAL_HALF_THICKNESS
    for leg, limb in feet.items():
        xmat = getattr(limb, "site_rot", None)  # an Hrp2Limb's view of its site's orientation
        if xmat is None:
            xmat = limb.body.site_xmat(limb.site)
        n0, n1, n2 = limb.frame.rotate_to_vehicle(xmat[:, 2]).tolist()
        p0, p1, p2 = limb.point(snapshot).tolist()
        axles[leg] = np.array([p0 - h * n0, p1 - h * n1, p2 - h * n2])  # p − h n, elementwise on Python floats
    return axles


class FeetCrankAngle:
    """θ_c ∈ [0, 2π) by method (a) from the feet's pedal-axle points about the nominal crank centre: the number
    ``estimate_crank_angle(pedal_axles(feet, snapshot), crank_centre())`` gives, with the sums compiled
    (:func:`~shintai.humanoid.tricycle.switching.axle_fit_terms`: bit for bit on a BLAS that sums 3-vector products
    left to right; the legs' switching diagnostic runs it every control tick). ``feet``:
    :class:`~shintai.humanoid.tricycle.hrp2_limbs.Hrp2Limb` feet sharing one vehicle frame; it reads their sole sites
    from the body's data when called, as their ``point`` does at its first call in a tick."""

    def __init__(self, feet: dict):
        limbs = list(feet.values())
        self.frame, self.body = limbs[0].frame, limbs[0].body
        if any(limb.frame is not self.frame for limb in limbs):
            raise ValueError("FeetCrankAngle: the feet share one vehicle frame")
        self.sites = np.array([self.body.id("site", limb.site) for limb in limbs])
        self.centre = crank_centre()  # the nominal model's (constant)
        zero = [crank_zero(leg, Y_AXIS) for leg in feet]
        self.axis, self.zs = zero[0][0], np.array([z for _, z in zero])
        self._data = None

    def __call__(self, snapshot) -> float:
        if self._data is not self.body.data:  # the data's rows, as views taken once (each access builds an array)
            d = self._data = self.body.data
            self._xpos, self._xmat = d.site_xpos, d.site_xmat
        p, r = self.frame.pose()
        num, den = axle_fit_terms(p, r, self._xpos, self._xmat, self.sites, PEDAL_HALF_THICKNESS, self.centre,
                                  self.axis, self.zs)
        return fit_angle_of(num, den) % (2 * np.pi)  # estimate_crank_angle's last steps


def crank_diagnostic(feet: dict) -> SwitchingDiagnostic:
    """Fig. 3.14 for the legs: θ_c by method (a) from both feet about the nominal crank centre."""
    return SwitchingDiagnostic(FeetCrankAngle(feet), lambda a: active_leg(a, DELTA_C), SWITCH_HYSTERESIS)


def handle_diagnostic(hands: dict) -> SwitchingDiagnostic:
    """Fig. 3.14 for the arms: θ_h by method (a) from both hands about the nominal steering axis."""
    return SwitchingDiagnostic(lambda s: estimate_handle_angle({k: h.point(s) for k, h in hands.items()}),
                               active_arm, SWITCH_HYSTERESIS)


class CrankEstimate:
    """θ_c by method (a) from both feet (§3.4.4), unwrapped; evaluated once per snapshot time."""

    def __init__(self, body):
        self.feet = riding_limbs(body, "foot")
        self._measure = FeetCrankAngle(self.feet)
        self.t, self.angle = None, None

    def __call__(self, snapshot) -> float:
        if snapshot["t"] != self.t:
            measured = self._measure(snapshot)
            self.angle = measured if self.angle is None else self.angle + wrap_pi(measured - self.angle)
            self.t = snapshot["t"]
        return self.angle

    def fz(self, snapshot) -> dict:
        return {side[0]: float(limb.force(snapshot)[2]) for side, limb in self.feet.items()}


# --- schedules and the legs' role switcher -------------------------------------------------------


def crank_schedule(revolutions: float, dt_transition: float) -> OperationSchedule:
    """Fig. 3.16 samples turning the crank forward from θ_c = 0 by ``revolutions`` (handle straight)."""
    return OperationSchedule(0.0, 0.0, [(0.0, 2 * np.pi * revolutions)], dt_transition, D_THETA_H, D_THETA_C)


def steer_schedule(dt_transition: float, limit: float) -> OperationSchedule:
    """E1's command: θ_h from 0 to −limit, then to +limit, by Δθ_h (§3.5.2)."""
    return OperationSchedule(0.0, 0.0, [(-limit, 0.0), (limit, 0.0)], dt_transition, D_THETA_H, D_THETA_C)


def legs_switcher(feet: dict, schedule: OperationSchedule, gains: dict = LEG_GAINS, theta_c0: float = 0.0):
    """The legs' role switcher on ``schedule`` (Fig. 3.16, Eq. 3.19; the left leg active at θ_c = 0,
    §3.5.2) and its diagnostic: (switcher, diagnostic)."""
    diag = crank_diagnostic(feet)
    legs = role_switcher("legs", "crank", feet, {leg: foot_plan(leg) for leg in SIDES}, diag,
                         active_leg(theta_c0, DELTA_C), schedule, gains, CONTROL_PERIOD,
                         {leg: limb.reachable for leg, limb in feet.items()})
    return legs, diag


def legs_pedalling(body, revolutions: float, dt_transition: float):
    """The ch. 3 pedalling on ``body``: the legs' role switcher turning the crank forward by
    ``revolutions`` from θ_c = 0 (Δt = ``dt_transition``). Returns (switcher, feet, schedule)."""
    schedule = crank_schedule(revolutions, dt_transition)
    feet = riding_limbs(body, "foot")
    legs, _ = legs_switcher(feet, schedule)
    return legs, feet, schedule


# --- one run: its rig and the signals it records every control tick --------------------------------


def pedal_rig(body, module, feet, schedule, active_of, diag=None) -> Rig:
    """Pedal through ``schedule`` (plus one sample to settle), recording every tick: crank angle (true
    and estimated), each foot's f_z and f_x (vehicle frame), whether it is active (``active_of(side)``)
    and where its sole sits on its pedal. ``state``: feet, schedule, diagnostic."""
    start = body.body_pos("tricycle")
    # ids, data views and the logged names, looked up once (the log runs every control tick)
    vehicle_xy = body.data.xpos[body.id("body", "tricycle")][:2]
    start_xy = start[:2]
    pedal_xpos = {side: body.data.site_xpos[body.id("site", PEDAL[side[0]])] for side in feet}
    sole_xpos = {side: body.data.site_xpos[body.id("site", SOLE[side[0]])] for side in feet}
    side_keys = {side: tuple(f"{k}_{side}" for k in ("fz", "fx", "active", "on_pedal")) for side in feet}
    centre = crank_centre()

    def signals(snap):
        est = diag.angle if diag is not None and diag.angle is not None else estimate_crank_angle(
            pedal_axles(feet, snap), centre)
        travel = vehicle_xy - start_xy
        out = {"crank_true": snap["q:crank"], "crank_est": est,
               "travel": np.sqrt(travel.dot(travel))}  # = np.linalg.norm of the 2-vector
        for side, limb in feet.items():
            k_fz, k_fx, k_active, k_on = side_keys[side]
            force = limb.force(snap)
            out[k_fz] = force[2]
            out[k_fx] = force[0]  # along the crank tangent at the dead centres
            out[k_active] = float(active_of(side))
            # evaluation only: where the sole sits on its pedal (the pedal's top site, vehicle frame), both from the FK
            # at the recording (of the snapshot's state; the control's limb.point is one physics step older)
            out[k_on] = limb.frame.to_vehicle(sole_xpos[side]) - limb.frame.to_vehicle(pedal_xpos[side])
        return out

    return Rig(body, [module], duration=schedule.duration + 2 * schedule.phase, record={1: signals},
               view=TRICYCLE_VIEW, state=SimpleNamespace(feet=feet, schedule=schedule, diag=diag, module=module))


def hand_forces(hands: dict, snapshot) -> dict:
    """The two-hand grasp's forces (vehicle frame, N): ``internal`` ‖(f_L − f_R)/2‖, the classic
    internal force of a two-hand grasp; ``squeeze``, its part along the hand-to-hand line, positive
    when the hands press the handle together (the environment pushes each hand outward); ``net``
    ‖f_L + f_R‖, the force the hands put on the handle, which its bearing takes except for the part
    that turns it. f are the environment's forces on the hands (f^trg = 0 for both arms, Table 3.4)."""
    f_l, f_r = hands["left"].force(snapshot), hands["right"].force(snapshot)
    u = hands["left"].point(snapshot) - hands["right"].point(snapshot)
    half, net = (f_l - f_r) / 2, f_l + f_r
    # ‖x‖ as np.linalg.norm forms it for a vector (√(x·x)), without its dispatch
    return {"internal": float(np.sqrt(half.dot(half))), "squeeze": float(half.dot(u) / np.sqrt(u.dot(u))),
            "net": float(np.sqrt(net.dot(net)))}


def internal_force(hands: dict, snapshot) -> float:
    """:func:`hand_forces`' ``internal`` alone (a ride records it every tick)."""
    half = (hands["left"].force(snapshot) - hands["right"].force(snapshot)) / 2
    return float(np.sqrt(half.dot(half)))


def steer_rig(body, module, hands, schedule, active_of, diag=None, view=None) -> Rig:
    """Steer through ``schedule`` (plus one sample to settle), recording every tick: handle angle
    (true and estimated), the forces between the hands, which arm is active and each hand's ‖f‖."""

    def signals(snap):
        est = diag.angle if diag is not None and diag.angle is not None else estimate_handle_angle(
            {k: h.point(snap) for k, h in hands.items()})
        out = {"handle_true": snap["q:handle"], "handle_est": est, **hand_forces(hands, snap)}
        out.update({f"active_{side}": float(active_of(side)) for side in SIDES})
        out.update({f"f_{side}": float(np.linalg.norm(hands[side].force(snap))) for side in SIDES})
        return out

    return Rig(body, [module], duration=schedule.duration + 2 * schedule.phase, record={1: signals},
               view={**TRICYCLE_VIEW, **(view or {})},
               state=SimpleNamespace(hands=hands, schedule=schedule, diag=diag, module=module))


# --- what a run recorded -----------------------------------------------------------------------------


def settled(t: np.ndarray, active: np.ndarray, wait: float) -> np.ndarray:
    """Ticks at least ``wait`` after the start and after the limb's last role change (transients)."""
    change = np.concatenate([[t[0]], t[1:][np.diff(active) != 0]])
    last = change[np.searchsorted(change, t, side="right") - 1]
    return (t - t[0] >= wait) & (t - last >= wait)


def force_errors(rec, prefix: str, wait: float, role: float) -> np.ndarray:
    """f_z of every foot while its role flag equals ``role`` (1 active, 0 passive), after transients."""
    t = rec.times(f"{prefix}fz_left")
    parts = []
    for side in SIDES:
        active = rec.values(f"{prefix}active_{side}")
        parts.append(rec.values(f"{prefix}fz_{side}")[settled(t, active, wait) & (active == role)])
    return np.concatenate(parts)


def active_samples(rec, prefix: str, wait: float, axis: str = "fz") -> tuple[np.ndarray, np.ndarray]:
    """The active foot's f_z (``axis="fx"``: f_x) after transients and 1/|cos θ_c| at the same ticks
    (true θ_c, §3.5.3)."""
    t = rec.times(f"{prefix}crank_true")
    inv_cos = 1 / np.maximum(np.abs(np.cos(rec.values(f"{prefix}crank_true"))), 1e-3)
    fz, term = [], []
    for side in SIDES:
        active = rec.values(f"{prefix}active_{side}")
        keep = settled(t, active, wait) & (active == 1.0)
        fz.append(rec.values(f"{prefix}{axis}_{side}")[keep])
        term.append(inv_cos[keep])
    return np.concatenate(fz), np.concatenate(term)


def crank_estimate_error(rec) -> float:
    """The largest |θ_c estimated − θ_c true| of a run [rad] (the estimate unwrapped from the true start)."""
    true = rec.values("crank_true")
    return float(np.abs(unwrap_from(rec.values("crank_est"), true[0]) - true).max())


def sample_end_errors(rec, schedule: OperationSchedule) -> np.ndarray:
    """True θ_h minus the commanded θ_h at the end of each sample (after its passive phase)."""
    t, true = rec.times("handle_true"), rec.values("handle_true")
    ends = np.searchsorted(t, [s.t0 + 2 * schedule.phase - 1e-9 for s in schedule.samples])
    return true[np.minimum(ends, len(t) - 1)] - np.array([s.theta_h for s in schedule.samples])
