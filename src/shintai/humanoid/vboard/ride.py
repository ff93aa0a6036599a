"""HRP2-JSK riding the V-BOARD standing still (seed 000 ch. 6: §6.2.1 behaviour levels, §6.2.2 Fig. 6.6,
Table 6.1), for the scenarios ``humanoid.vboard-*`` and the speed-governing ones after them.

The robot is lowered onto the pads by the care lift (§6.4.1, Fig. 6.15; :class:`~shintai.humanoid.balance.scooter.Lift`);
t = 0 is the start of the lowering, ``Lift.t_release`` the hand-over ("t = 0.0 [s] at boarding" of Figs. 6.3–6.4).
Behaviour levels (§6.2.1): 1 a fixed posture (the leg IK holds it; all balance is the scooter's); 2 level 1 + the
balance stack (LIP tracking, ZMP distributor, foot torque damping Eqs. 5.1–5.3 with SLC's gain on the board
``D_VBOARD``, force difference control); 3 level 2 + speed governing (Fig. 6.6): sensors (Table 6.1, Eq. 6.3) →
:class:`~shintai.humanoid.vboard.governor.SpeedGovernor` (PID Eq. 6.2) → foot-pitch increments (Eq. 6.5) →
:class:`~shintai.humanoid.balance.scooter.FootPitch` (Eq. 6.7), added to the damping's δ (Eq. 6.5's d).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from shintai.core.runtime import Module
from shintai.humanoid.balance.foot_attitude import measured_zmp
from shintai.humanoid.balance.scooter import CHANNELS, ChestPitchControl, ChestPitchIK, FootPitch, Lift, ScooterSensors
from shintai.humanoid.balance.stabilizer import StabilizerModule
from shintai.humanoid.balance.standing import Standing
from shintai.humanoid.constants import ATTITUDE_TAU, CONTROL_PERIOD, LIFT_GAP, LIFT_SPEED, VBOARD
from shintai.humanoid.law_params import check_real
from shintai.humanoid.vboard.ankle_pivot import AnklePivotIK
from shintai.humanoid.vboard.constants import (COM_READING, D_VBOARD, EXCITE_AMPLITUDE, EXCITE_PERIOD, FIRMWARE_LAW, LEVELS,
                                             PLACEMENT, PLACEMENTS)
from shintai.humanoid.vboard.governor import SpeedGovernor
from shintai.humanoid.vboard.stand import build_vboard_stand
from shintai.humanoid.vboard.vehicle import board_pitch, scooter_velocity


def square_wave(amplitude: float = EXCITE_AMPLITUDE, period: float = EXCITE_PERIOD, t0: float = 0.0):
    """u(t) = ±amplitude, + for the first half of each period from ``t0`` (0 before ``t0``)."""
    def u(t: float) -> float:
        if t < t0:
            return 0.0
        return amplitude if ((t - t0) % period) < period / 2 else -amplitude
    return u


def scooter_spec(theta_o_error_deg: float = 0.0):
    """The V-BOARD whose true θ_O is the regression intercept (Eq. A.1) plus ``theta_o_error_deg`` on both sides."""
    err = check_real("theta_o_error_deg", theta_o_error_deg, -3.0, 3.0)
    return dataclasses.replace(VBOARD, theta_o_deg=tuple((s, d + err) for s, d in VBOARD.theta_o_deg))


class VboardRide:
    """HRP2 lowered onto the V-BOARD and riding standing still at behaviour ``level`` 1, 2 or 3, composed once.

    ``theta_o_error_deg``: the scooter's true θ_O minus the regression intercept (Eq. A.1; both sides), the
    controllers keep the nominal values (§6.2.1); ``D`` the damping gain (levels 2–3); ``excite`` → (u_v, u_ω) a
    known input added at levels 2–3; ``lift=False`` starts standing on the pads (no lowering); ``seed`` the
    sensors' noise; ``com_reading``, ``attitude_tau`` the stabilizer's CoM reading (lift-placed start; default
    :data:`~shintai.humanoid.vboard.constants.COM_READING`), ``foot_origin`` its frame's origin (``"sole"``, ``"ankle"``);
    ``placement`` the references of the lift-placed start (:data:`~shintai.humanoid.vboard.constants.PLACEMENT`:
    ``"fig6.1"`` puts them on the scooter's centre at the hand-over, :class:`CentreReference`); ``firmware`` the scooter's law (:class:`~shintai.humanoid.vboard.vehicle.VboardFirmware`'s ``law``; lift-placed start);
    ``foot_pitch_about`` ``"ankle"`` turns the commanded pitch about the ankles, as an ankle joint angle
    (:mod:`~shintai.humanoid.vboard.ankle_pivot`; needs ``foot_origin="ankle"``; default ``"sole"``);
    ``posture`` §4.3.3's chest posture control (Fig. 4.10 (B)); ``sole_creep`` turns MuJoCo's no-slip passes off,
    so that the soles creep on the pads as soft contacts let them (the rides before issue 26 item 5,
    :mod:`~shintai.humanoid.vboard.sole_creep`). The governor slot (level 3):
    ``governor(lift)`` → the module (the lift, or None, for its start gate), default a
    :class:`~shintai.humanoid.vboard.governor.SpeedGovernor` on ``gains`` ((K_P, K_I, K_D) for v, for ω) with MLC
    if ``learn``. ``standing``: instead of the lift-placed start, a
    :class:`~shintai.humanoid.balance.standing.Standing` stack that gets onto the scooter by itself (the
    self-boarding of :func:`~shintai.humanoid.vboard.boarding.boarding_stack`, Fig. 6.16) with its body, its
    damping gains and SLC (no ``D``), no lift; levels 2–3. ``supervisor``: a module in a stage after the
    stabilizer (SOLC's switcher, :mod:`~shintai.humanoid.vboard.solc`). ``stages`` and ``channels`` make the Loop.
    """

    def __init__(self, level: int = 2, theta_o_error_deg: float = 0.0, D: float = D_VBOARD, gains=((0.0,) * 3,) * 2,
                 learn: bool = False, governor=None, excite=None, lift: bool = True, gap: float = LIFT_GAP,
                 speed: float = LIFT_SPEED, seed: int = 0, noise: bool = True, posture: bool = False,
                 standing: Standing | None = None, supervisor: Module | None = None,
                 com_reading: str = COM_READING, attitude_tau: float = ATTITUDE_TAU, foot_origin: str = "sole",
                 placement: str = PLACEMENT, firmware: str = FIRMWARE_LAW, foot_pitch_about: str = "sole",
                 sole_creep: bool = False):
        if level not in LEVELS:
            raise ValueError(f"level must be one of {LEVELS}, got {level!r}")
        if placement not in PLACEMENTS:
            raise ValueError(f"placement must be one of {PLACEMENTS}, got {placement!r}")
        if firmware != FIRMWARE_LAW and standing is not None:
            raise ValueError("firmware sets the lift-placed start's scooter; a standing stack brings its own body")
        if placement == "fig6.1" and (standing is not None or not lift):
            raise ValueError("placement='fig6.1' sets the target ZMP and the soles' reference at the lift's hand-over: "
                             "it needs lift=True and no standing stack passed in")
        if foot_pitch_about not in ("sole", "ankle"):
            raise ValueError(f"foot_pitch_about must be 'sole' or 'ankle', got {foot_pitch_about!r}")
        if foot_pitch_about == "ankle" and (standing is not None or posture or foot_origin != "ankle"):
            raise ValueError("foot_pitch_about='ankle' (the pitch as an ankle joint angle) rides the lift-placed start, "
                             "without chest posture control, with foot_origin='ankle'")
        fig61 = placement == "fig6.1"
        theta0 = (VBOARD.theta_o("r"), VBOARD.theta_o("l")) if fig61 else (0.0, 0.0)
        check_real("D", D, 0.0, low_open=True)
        self.level = level
        self.scooter = scooter_spec(theta_o_error_deg)
        self.lift = None
        if standing is None:
            body = build_vboard_stand(self.scooter, law=firmware)
            if lift:
                root = body.model.joint("root").qposadr[0]
                body.model.key("stand").qpos[root + 2] += check_real("lift gap", gap, 0.0, 0.2)
                self.lift = Lift(body, gap, speed)
                body.before_physics.insert(0, self.lift)
                body.reset("stand")
                self.lift.hold()
            stack = {"D": D} if level >= 2 else {"damping": False, "lip": False, "force_difference": False}
            # §4.3.3, Fig. 4.10 (B): with chest posture control the IK turns the upper body about the feet
            ik = ChestPitchIK if posture else None
            pivot = foot_pitch_about == "ankle"  # the commanded pitch as an ankle joint angle (vboard.ankle_pivot)
            if pivot:
                ik = functools.partial(AnklePivotIK, pitch0=theta0)
            stab = functools.partial(StabilizerModule, com_reading=com_reading, attitude_tau=attitude_tau,
                                     foot_origin=foot_origin, ref_ankle_pitch=theta0 if pivot else None)
            self.standing = Standing(body=body, ik=ik, stabilizer=stab, **stack)  # settles 0.1 s (held by the lift, if any), clock to 0
            if self.lift is not None:
                self.lift.lowering = True
        else:
            if level < 2 or standing.damping is None:
                raise ValueError("a self-boarding stack rides at level 2 or 3, with its foot damping")
            if posture:
                raise ValueError("chest posture control rides the lift-placed start only")
            self.standing, body = standing, standing.body
        if sole_creep:  # MuJoCo's soft contacts alone: the soles creep on the pads (vboard.constants.NOSLIP_ITERATIONS)
            body.model.opt.noslip_iterations = 0
        self.body = body
        self.sensors = ScooterSensors(body, scooter_velocity, seed=seed, noise=noise)
        self.posture = ChestPitchControl() if posture else None
        self.governor = None
        if level == 3:
            self.governor = (governor or (lambda lift: SpeedGovernor(gains0=gains, learn=learn)))(self.lift)
        self.foot_pitch = FootPitch(excite, theta0=theta0) if level >= 2 else None
        self.centre = CentreReference(self) if fig61 else None
        self.stages = self.standing.stages(
            references=[self.sensors, *([self.posture] if self.posture else []), *([self.centre] if self.centre else [])],
            governor=[self.governor] if self.governor else (),
            supervisor=[supervisor] if supervisor else (),
            beside_damping=[self.foot_pitch] if self.foot_pitch else ())
        self.channels = list(CHANNELS.values())

    def fallen(self) -> bool:
        return self.standing.fallen()

    def zmp(self, snapshot) -> np.ndarray:
        """The measured ZMP (x, y) in the scooter's frame (origin = its centre, Fig. 6.1), NaN without contact."""
        z = measured_zmp(self.body, snapshot).zmp
        c = self.body.site_pos("vboard_centre")
        R = self.body.data.body("vboard").xmat.reshape(3, 3)
        return (R.T @ np.array([z[0] - c[0], z[1] - c[1], 0.0]))[:2]

    def signals(self, snapshot) -> dict:
        """What Figs. 6.3–6.4 plot, and the scooter's travel: ZMP (scooter frame), θ_R, θ_L, x, v, ω."""
        th = board_pitch(snapshot)
        v, w = scooter_velocity(snapshot)
        z = self.zmp(snapshot)
        return {"zmp_x": z[0], "zmp_y": z[1], "theta_R": th["r"], "theta_L": th["l"],
                "x": float(self.body.site_pos("vboard_centre")[0]), "true_v": v, "true_omega": w,
                "lift_fz": float(self.lift.force[2]) if self.lift is not None else 0.0}


class CentreReference(Module):
    """§6.2.1's target ZMP (0, 0) at the scooter's centre (Fig. 6.1): once, at the lift's hand-over, the preview's
    CoM and ZMP references are moved by the scooter centre's offset from the soles' midpoint (world x, y; the
    stabilizer then holds them there relative to the feet). Writes nothing; ``offset`` keeps the move (m)."""

    def __init__(self, ride: "VboardRide", name: str = "centre_reference"):
        super().__init__(name, CONTROL_PERIOD)
        self.ride, self.offset = ride, None

    def update(self, snapshot):
        lift = self.ride.lift
        if self.offset is None and lift is not None and lift.released:
            b = self.ride.body
            mid = np.mean([b.site_pos(f"{s}_sole") for s in ("l", "r")], axis=0)
            self.offset = (b.site_pos("vboard_centre") - mid)[:2].copy()
            self.ride.standing.preview.offset = self.offset
        return {}


def theta_o(side: str) -> float:
    """The nominal θ_sO (rad) the thesis compares against (Eq. A.1's regression intercept)."""
    return VBOARD.theta_o(side)


def touchdown(run) -> float:
    """Boarding, t = 0 of Figs. 6.3–6.4 (chosen): the first recorded instant with a measured ZMP, i.e. the soles
    loaded past the F/T contact threshold while the lift still holds part of the weight (the thesis's plots
    start with a ZMP; from the lift going slack instead, level 1's early ZMP-x peak is 9 mm, not 80 mm)."""
    t, zx = run.log.times("x"), run.log.values("zmp_x")
    ok = np.isfinite(zx)
    return float(t[ok][0]) if ok.any() else float("nan")
