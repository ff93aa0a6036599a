"""HRP2 drives the tricycle, steering and pedalling together (seed 000 §3.5.2 E3, §3.5.4 E5–E7).

One ride is the operation algorithm of Fig. 3.16 for both devices: a joystick script gives operator
goals (θ_h, θ_c) (:class:`~shintai.humanoid.tricycle.operation.OperationSchedule`, steps 1 and 4, Δθ_h = 5°,
Δθ_c = 10°); the arms on the handle and the legs on the crank are two role
:class:`~shintai.core.runtime.Switcher` s of :class:`~shintai.humanoid.tricycle.operation.LimbPair` modules
(steps 2 and 3), running side by side in one :class:`~shintai.core.runtime.Loop` (parallel processing,
§7.3). Roles swap when the angle measured from the robot's FK (method (a), §3.4.4) passes a switching
angle (Eq. 3.19: θ_h = 0, θ_c = π/2 + δ_c + kπ). Gains and force targets are Table 3.4's.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from shintai.humanoid.constants import CONTROL_PERIOD, DEG, FALL_TILT, IMPEDANCE, MODEL_ERROR_MM, THETA_C_INIT
from shintai.humanoid.tricycle import riding
from shintai.humanoid.tricycle.hrp2_limbs import riding_limbs
from shintai.humanoid.tricycle.operation import SIDES, OperationSchedule, role_switcher
from shintai.humanoid.tricycle.rig import (
    ARM_GAINS,
    F_TRG,
    LEG_GAINS,
    hand_plan,
    handle_diagnostic,
    internal_force,
    legs_switcher,
    settled,
)
from shintai.humanoid.tricycle.switching import active_arm, switching_angles
from shintai.scenarios.experiment import Rig
from shintai.scenarios.registry import Param

# the model errors every ride experiment exposes (Ride's own defaults)
MODEL_ERROR_PARAMS = (
    Param("crank_error_mm", MODEL_ERROR_MM, "true crank centre ahead of the nominal model [mm]", lo=0.0, hi=30.0),
    Param("handle_error_mm", MODEL_ERROR_MM, "true steering axis ahead of the nominal model [mm]", lo=0.0, hi=30.0),
)
RIDE_VIEW = {"track": "tricycle", "distance": 3.2, "azimuth": 135.0, "elevation": -25.0}


def leg_gains(passive_f_trg: float) -> dict:
    """Table 3.4's leg columns with the passive leg's f^trg_z replaced (E7: 50 N, §3.5.4)."""
    passive = dataclasses.replace(IMPEDANCE["passive_leg"], f_trg=(0.0, 0.0, float(passive_f_trg)))
    return {"active": LEG_GAINS["active"], "passive": passive}


class Ride:
    """The seated robot with both role switchers on one schedule (Fig. 3.16 for handle and crank).

    ``schedule`` starts at θ_h = 0, θ_c = 0. The first active arm is the one on the side the first
    handle goal lies (:func:`~shintai.humanoid.tricycle.switching.active_arm`); the left leg starts active
    (θ_c = 0, §3.5.2 role table). The simulated tricycle's crank centre and steering axis sit
    ``crank_error_mm`` / ``handle_error_mm`` ahead of the nominal model the controllers use.
    """

    def __init__(self, schedule: OperationSchedule, passive_f_trg: float = F_TRG,
                 crank_error_mm: float = MODEL_ERROR_MM, handle_error_mm: float = MODEL_ERROR_MM):
        self.schedule, self.passive_f_trg = schedule, passive_f_trg
        self.body = riding.build_riding(crank_error=(crank_error_mm / 1000, 0.0),
                                        handle_error=(handle_error_mm / 1000, 0.0, 0.0))
        self.feet = riding_limbs(self.body, "foot")
        self.hands = riding_limbs(self.body, "hand")
        self.arm_diag = handle_diagnostic(self.hands)
        heading = next((s.theta_h for s in schedule.samples if s.theta_h != 0), 0.0)
        self.legs, self.leg_diag = legs_switcher(self.feet, schedule, leg_gains(passive_f_trg), schedule.theta_c0)
        self.arms = role_switcher("arms", "handle", self.hands, {arm: hand_plan(arm) for arm in SIDES}, self.arm_diag,
                                  active_arm(schedule.theta_h0, heading=heading), schedule, ARM_GAINS,
                                  CONTROL_PERIOD, {arm: limb.reachable for arm, limb in self.hands.items()})

    def rig(self) -> Rig:
        """The whole schedule plus one sample to settle, recording every control tick."""
        body, schedule = self.body, self.schedule
        wheel = body.id("body", "rear_l_wheel")
        # data views and ids taken once (the log runs every control tick)
        vehicle = body.id("body", "tricycle")
        rot, pos, wheel_pos = body.data.xmat[vehicle].reshape(3, 3), body.data.xpos[vehicle], body.data.xpos[wheel]
        side_keys = {side: (f"fz_{side}", f"leg_active_{side}", f"arm_active_{side}",
                            f"legs:{side}-active", f"arms:{side}-active") for side in SIDES}

        def signals(snap):
            now = schedule.at(snap["t"])
            sample = schedule.samples[now[0]] if now is not None else schedule.samples[-1]
            out = {"handle_true": snap["q:handle"], "crank_true": snap["q:crank"],
                   "handle_cmd": sample.theta_h, "crank_cmd": sample.theta_c,
                   "handle_est": self.arm_diag.angle if self.arm_diag.angle is not None else np.nan,
                   "crank_est": self.leg_diag.angle if self.leg_diag.angle is not None else np.nan,
                   "x": pos[0], "y": pos[1], "yaw": np.arctan2(rot[1, 0], rot[0, 0]),
                   "tilt": np.arccos(min(max(rot[2, 2], -1.0), 1.0)),  # = np.clip, without its dispatch
                   "wheel_x": wheel_pos[0], "wheel_y": wheel_pos[1],
                   "internal": internal_force(self.hands, snap)}
            for side in SIDES:
                k_fz, k_leg, k_arm, legs_active, arms_active = side_keys[side]
                out[k_fz] = self.feet[side].force(snap)[2]
                out[k_leg] = float(self.legs.active == legs_active)
                out[k_arm] = float(self.arms.active == arms_active)
            return out

        return Rig(body, [self.arms, self.legs], duration=schedule.duration + 2 * schedule.phase,
                   record={1: signals}, view=RIDE_VIEW, state=self)

    def unreachable(self) -> int:
        return sum(limb.unreachable for limb in (*self.feet.values(), *self.hands.values()))


# --- joystick scripts ----------------------------------------------------------------------------------


def slalom_goals(curve: float, limit: float, slalom: float = 2 * np.pi) -> list[tuple[float, float]]:
    """E3's joystick script (§3.5.2, Figs. 3.19–3.21): a curve at −Θ_H, a curve at +Θ_H (each
    ``curve`` of crank), then the slalom: −Θ_H for the first half of ``slalom`` (Fig. 3.21: θ_c over
    [0, π]), +Θ_H for the second half ([π, 2π])."""
    goals, c = [], 0.0
    for h, span in ((-limit, curve), (limit, curve), (-limit, slalom / 2), (limit, slalom / 2)):
        goals += [(h, c), (h, c + span)]
        c += span
    return goals


def route_goals(revolutions: float, limit: float) -> list[tuple[float, float]]:
    """The route driven in both outdoor runs (the thesis's route is not given; E7 steered through
    −25°, 0 and +25°, Fig. 3.29): steer to −Θ_H over the first quarter of the crank advance, to
    +Θ_H over the next half, back to 0 over the last quarter."""
    total = 2 * np.pi * revolutions
    return [(-limit, total / 4), (limit, 3 * total / 4), (0.0, total)]


# --- what a ride did -------------------------------------------------------------------------------------


def path_length(x: np.ndarray, y: np.ndarray) -> float:
    return float(np.sum(np.hypot(np.diff(x), np.diff(y))))


def signed_travel(x: np.ndarray, y: np.ndarray, yaw: np.ndarray) -> float:
    """Distance rolled forward (backward counts negative): each step projected on the heading."""
    return float(np.sum(np.diff(x) * np.cos(yaw[:-1]) + np.diff(y) * np.sin(yaw[:-1])))


def expected_swaps(start: float, advance: float, theta_init: float) -> int:
    """Switching angles (Eq. 3.19) strictly inside a monotone sweep from ``start`` by ``advance``."""
    lo, hi = sorted((start, start + advance))
    return len([a for a in switching_angles(theta_init, lo, hi) if lo < a < hi])


def handle_crossings(cmd: np.ndarray) -> int:
    """Times the commanded θ_h sequence passes through θ_h^init = 0 from one side to the other."""
    signs = np.sign(cmd[cmd != 0])
    return int(np.sum(signs[1:] != signs[:-1]))


def ride_metrics(rec, ride: Ride) -> dict:
    """What a ride did: distances, falls, handle tracking, role swaps, forces (after transients).
    ``distance_m`` is the path of the vehicle-frame origin (under the crank); ``drive_wheel_travel_m``
    the signed distance the driven left back wheel rolled along the heading; ``falls`` a tilt over
    ``FALL_TILT``."""
    schedule = ride.schedule
    t = rec.times("x")
    x, y = rec.values("x"), rec.values("y")
    crank = rec.values("crank_true")
    advance = crank[-1] - crank[0]
    drive_travel = signed_travel(rec.values("wheel_x"), rec.values("wheel_y"), rec.values("yaw"))
    tilt = rec.values("tilt")
    ends = np.searchsorted(t, [s.t0 + 2 * schedule.phase - 1e-9 for s in schedule.samples])
    handle_at_ends = rec.values("handle_true")[np.minimum(ends, len(t) - 1)]
    handle_err = handle_at_ends - [s.theta_h for s in schedule.samples]
    wait = 2 * schedule.phase
    passive, active = [], []
    for side in SIDES:
        flag = rec.values(f"leg_active_{side}")
        keep = settled(t, flag, wait)
        fz = rec.values(f"fz_{side}")
        passive.append(fz[keep & (flag == 0.0)])
        active.append(fz[keep & (flag == 1.0)])
    passive, active = np.concatenate(passive), np.concatenate(active)
    distance = path_length(x, y)
    yaw = np.unwrap(rec.values("yaw"))
    heading = np.degrees(yaw - yaw[0])
    return {
        "distance_m": distance,
        "displacement_m": float(np.hypot(x[-1] - x[0], y[-1] - y[0])),
        "duration_s": schedule.duration,
        "mean_speed_mps": distance / schedule.duration,
        "crank_advance_deg": float(advance / DEG),
        "drive_wheel_travel_m": drive_travel,
        "drive_wheel_travel_per_rev_m": drive_travel / (advance / (2 * np.pi)) if advance > 0 else float("nan"),
        "heading_change_deg": float(heading[-1]),
        "heading_range_deg": [float(heading.min()), float(heading.max())],
        "max_tilt_deg": float(tilt.max() / DEG),
        "falls": int(tilt.max() > FALL_TILT),
        "max_handle_error_deg": float(np.abs(handle_err).max() / DEG),
        "handle_range_deg": [float(rec.values("handle_true").min() / DEG),
                             float(rec.values("handle_true").max() / DEG)],
        "leg_role_swaps": len(ride.leg_diag.log),
        "leg_role_swaps_expected": expected_swaps(crank[0], advance, THETA_C_INIT),
        "arm_role_swaps": len(ride.arm_diag.log),
        "arm_role_swaps_expected": handle_crossings(np.array([s.theta_h for s in schedule.samples])),
        "passive_force_mean_n": float(passive.mean()) if passive.size else float("nan"),
        "passive_force_rms_error_n": float(np.sqrt(np.mean((passive - ride.passive_f_trg) ** 2)))
        if passive.size else float("nan"),
        "active_force_mean_n": float(active.mean()) if active.size else float("nan"),
        "min_foot_force_n": float(min(rec.values(f"fz_{s}")[t >= wait].min() for s in SIDES)),
        "internal_force_rms_n": float(np.sqrt(np.mean(rec.values("internal")[t >= wait] ** 2))),
        "unreachable_ticks": ride.unreachable(),
    }
