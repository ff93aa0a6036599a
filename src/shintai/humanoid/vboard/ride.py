"""HRP2-JSK riding the V-BOARD standing still: the rig of seed 000 ch. 6 (§6.2.1 behaviour levels, §6.2.2
Fig. 6.6, Table 6.1), for the scenarios ``humanoid.vboard-*`` and the speed-governing ones after them.

**Start** (§6.2.1, §6.4.1 Fig. 6.15): the robot takes the statically stable riding posture
(:func:`~shintai.humanoid.vboard.stand.build_vboard_stand`) hanging from a lift, its soles ``gap`` above the
pads, and is lowered onto the boards ("リフトから下ろして搭乗させる"). The lift (:class:`Lift`, a hook run before
every physics step) is a harness on the waist: a spring-damper to a pose whose height descends at
``LIFT_SPEED``; its vertical force is a strap's (≥ 0), and it lets go for good once the feet carry the weight
(the strap slack). t = 0 is the start of the lowering; ``Lift.t_release`` the hand-over ("t = 0.0 [s] at
boarding" of Figs. 6.3–6.4 is that instant: the scenarios report times from it).

**Behaviour levels** (§6.2.1, definitions quoted in the scenario notes):

1. a fixed posture: the standing stack (:class:`~shintai.humanoid.balance.standing.Standing`) with the foot
   damping, LIP tracking and force difference off — the leg IK holds the posture (position control), all
   balance is the scooter's;
2. level 1 + the balance stack: LIP tracking ([55]) → ZMP distributor → foot torque damping (Eqs. 5.1–5.3)
   with the damping gain SLC reached on the board (``D_VBOARD`` = 40, §5.4.2) and force difference control;
3. level 2 + speed governing (Fig. 6.6): :class:`ScooterSensors` (Table 6.1, Eq. 6.3) write ``v`` and
   ``omega``; :class:`~shintai.humanoid.learning.mlc.SpeedGovernor` (PID Eq. 6.2, learning or fixed gains) writes the
   foot-pitch increments ``foot_pitch`` = [Δθ_R, Δθ_L] (Eq. 6.5); :class:`FootPitch` integrates them
   (θ̇ ≈ Δθ/Δt, Eq. 6.7) into the soles' pitch, added to the damping's δ on ``foot_damping`` (δ is the
   disturbance d of Eq. 6.5). ``excite`` adds a known u (plant identification, Eqs. 6.14–6.16).

Usage (the API a scenario uses)::

    ride = VboardRide(level=3, gains=((kp, ki, kd), (kp, ki, kd)), learn=False)
    loop = Loop(ride.body, stages=ride.stages, channels=ride.channels)   # or Rig(stages=..., channels=...)
    loop.run(10.0)                 # ride.lift.t_release, ride.sensors.true_v, ride.fallen(), ride.zmp(snapshot)

**Measured** (seeded, deterministic; the scenarios' notes give more): the lift lets go ≈1.0 s after the lowering
starts (≈0.5 s after the soles take load). Level 1 rolls off backwards, accelerating, and falls ≈6 s after
boarding; level 2 keeps the ZMP on the scooter's centre and drifts back ≈2 cm/s. **Level 3 caveat** (for the
speed-governing scenarios): the foot damping (Eq. 5.1, D = 40) cancels the governor's foot pitch within ≈0.2 s —
a 1.15° toes-down step moves the boards 0.11° and the scooter +3 cm/s for ≈0.1 s, then back — so u has little
and, below ≈1 Hz, wrong-signed authority over v (``humanoid.vboard-plant-id``: R² 0.003 from u, 0.98 from the
boards' own pitch); fixed PID gains (2e-3, 1e-3, 0) integrate tens of degrees of foot pitch and the robot falls
within 6 s. Zero gains ride as level 2. The wiring is the thesis's (Eq. 6.5's d is the damping's δ).

**Sensors** (Table 6.1; chosen where it gives no number): ω = the chest gyro's yaw rate (4 ms) with white
noise ``GYRO_NOISE``; v = Eq. 6.3's filter (:class:`~shintai.humanoid.learning.speed_governing.LinearVelocityFilter`)
on a_x (chest accelerometer, gravity removed, along the robot's heading; 4 ms, noise ``ACC_NOISE``) and x_VO
(the head camera's position, 10 ms samples with ``VO_LATENCY`` and noise ``VO_NOISE``); v is published
every 24 ms with a 24 ms latency (Table 6.1's ``*``). Seeded.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque

import numpy as np

from shintai.core.constants import GRAVITY
from shintai.core.geometry import rot_y
from shintai.core.runtime import SET, Module, declare
from shintai.humanoid.constants import CONTROL_PERIOD, VBOARD
from shintai.humanoid.corrections import ChestPostureControl
from shintai.humanoid.balance.foot_attitude import measured_zmp, quat_to_rot
from shintai.humanoid.balance.foot_attitude import pitch as rot_pitch
from shintai.humanoid.balance.foot_damping import FootDamping
from shintai.humanoid.law_params import check_real
from shintai.humanoid.robots.leg_ik import leg_ik
from shintai.humanoid.learning.mlc import SpeedGovernor
from shintai.humanoid.learning.speed_governing import (
    VO_PERIOD,
    LinearVelocityFilter,
    plant_inputs,
)
from shintai.humanoid.balance.stabilizer import SIDES as FEET
from shintai.humanoid.balance.standing import CHANNELS as STANDING_CHANNELS
from shintai.humanoid.balance.standing import LegIKModule, Standing, _rot_xy
from shintai.humanoid.vboard.stand import build_vboard_stand
from shintai.humanoid.vboard.vehicle import board_pitch, scooter_velocity

# --- constants ------------------------------------------------------------------------------------------
D_VBOARD = 40.0  # N·m·s/rad, the damping gain SLC reached boarding the V-BOARD (§5.4.2: '約 D = 40.0'), and
# §6.4.1 rides with '第5章で獲得した足部トルクダンピング制御系まわりのゲイン/パラメータ'. Probe: D = 22 rocks the
# boards by ±15° (standing.py), D = 40 holds them within 0.15° rms
LIFT_GAP = 0.02  # m, chosen: the soles hang this far above the pads when the lowering starts
LIFT_SPEED = 0.05  # m/s, chosen: a hand-cranked care lift (§6.4.1 '介護用リフト') lowers at a few cm/s
LIFT_K, LIFT_C = 2.0e4, 2.0e3  # N/m, N·s/m, chosen: the harness's stiffness and damping (each axis)
LIFT_KR, LIFT_CR = 2.0e3, 2.0e2  # N·m/rad, N·m·s/rad, chosen: its hold of the waist's attitude
V_PERIOD = 0.024  # s, v's sampling period and latency (Table 6.1, '*': latency = period)
VO_LATENCY = 0.010  # s, chosen: the thesis gives x_VO's period (10 ms) only; one period, like the '*' rows
VO_NOISE = 1.0e-3  # m, chosen: ZED visual odometry's position jitter, white, per sample
ACC_NOISE = 0.05  # m/s², chosen: a MEMS accelerometer's white noise at 250 Hz
GYRO_NOISE = 0.005  # rad/s, chosen: a MEMS gyro's white noise at 250 Hz
EXCITE_AMPLITUDE = 6.0e-5  # rad per control period, chosen: a 1 s half-period moves the boards 0.86°, v ±0.3 m/s
EXCITE_PERIOD = 2.0  # s, chosen: the square wave's period (a triangle of θ, ≈ T_v of Table 6.2 per half)
LEVELS = (1, 2, 3)
CHANNELS = {**STANDING_CHANNELS, **declare("v", "omega", kind=SET), **declare("foot_pitch", "ref:chest_pitch")}


class Lift:
    """The lift holding the waist (module docstring); call before every physics step."""

    def __init__(self, body, gap: float = LIFT_GAP, speed: float = LIFT_SPEED):
        self.body, self.speed = body, check_real("lift speed", speed, 0.0, low_open=True)
        self.gap = check_real("lift gap", gap, 0.0, 0.2)
        self.id = body.id("body", "waist")
        self.mass = float(body.model.body_subtreemass[self.id])
        self.lowering, self.released, self.t_release = False, False, math.nan
        self.pose = None  # (position, rotation) of the waist to hold; set by hold()
        self.force = np.zeros(3)

    def hold(self) -> None:
        """Hold the waist where it is now (the strap takes the weight: its rest point is m g / k higher)."""
        d = self.body.data
        self.pose = (d.xpos[self.id].copy(), d.xmat[self.id].reshape(3, 3).copy())

    def __call__(self) -> None:
        d = self.body.data
        if self.released or self.pose is None:
            d.xfrc_applied[self.id] = 0.0
            return
        pos, rot = self.pose
        target = pos.copy()
        target[2] += self.mass * GRAVITY / LIFT_K - (self.speed * d.time if self.lowering else 0.0)
        vel = d.cvel[self.id]  # (angular, linear) at the subtree com, world frame: near enough for a harness
        f = LIFT_K * (target - d.xpos[self.id]) - LIFT_C * vel[3:]
        f[2] = max(f[2], 0.0)  # a strap pulls, never pushes
        err = rot @ d.xmat[self.id].reshape(3, 3).T  # world rotation from the current to the held attitude
        axis = 0.5 * np.array([err[2, 1] - err[1, 2], err[0, 2] - err[2, 0], err[1, 0] - err[0, 1]])
        tq = LIFT_KR * axis - LIFT_CR * vel[:3]
        if self.lowering and f[2] == 0.0:  # the feet carry the weight: the lift lets go
            self.released, self.t_release = True, float(d.time)
            f[:], tq[:] = 0.0, 0.0
        self.force = f
        d.xfrc_applied[self.id, :3], d.xfrc_applied[self.id, 3:] = f, tq


class ScooterSensors(Module):
    """v and ω from the robot's simulated sensors (Table 6.1, Eq. 6.3; module docstring). Writes ``v``
    (24 ms, 24 ms late) and ``omega`` (4 ms); keeps the truth (``true_v``, ``true_omega``) for evaluation."""

    def __init__(self, body, seed: int = 0, noise: bool = True, name: str = "sensors", truth=scooter_velocity):
        super().__init__(name, CONTROL_PERIOD)
        self.truth = truth  # snapshot → the true (v, ω) of the vehicle (the Ninebot's rig passes its own)
        self.body, self.rng, self.noise = body, np.random.default_rng(seed), float(noise)
        self.filter = LinearVelocityFilter()
        self.k = 0
        self.vo_every = round(VO_PERIOD / CONTROL_PERIOD)
        self.v_every = round(V_PERIOD / CONTROL_PERIOD)
        self._vo_queue: deque = deque()  # (t_deliver, t_sample, x)
        self._v_queue: deque = deque()
        self.v, self.true_v, self.true_omega = 0.0, 0.0, 0.0

    def heading(self, snapshot) -> np.ndarray:
        """The robot's forward direction, horizontal: the chest's x axis projected."""
        x = quat_to_rot(snapshot["imu_quat"])[:, 0]
        h = np.array([x[0], x[1], 0.0])
        return h / (np.linalg.norm(h) + 1e-12)

    def update(self, snapshot):
        t = float(snapshot["t"])
        rot = quat_to_rot(snapshot["imu_quat"])
        h = self.heading(snapshot)
        acc = rot @ np.asarray(snapshot["imu_acc"], float) - np.array([0.0, 0.0, GRAVITY])  # a_IMU − g_o, world
        a_x = float(acc @ h) + self.noise * ACC_NOISE * self.rng.standard_normal()
        omega = float((rot @ np.asarray(snapshot["imu_gyro"], float))[2])
        omega += self.noise * GYRO_NOISE * self.rng.standard_normal()
        if self.k % self.vo_every == 0:  # a camera frame: position now, delivered VO_LATENCY later
            x = float(self.body.site_pos("head_camera") @ h) + self.noise * VO_NOISE * self.rng.standard_normal()
            self._vo_queue.append((t + VO_LATENCY - 1e-9, t, x))
        while self._vo_queue and self._vo_queue[0][0] <= t:
            _, ts, x = self._vo_queue.popleft()
            self.filter.vo_sample(ts, x)
        v_now = self.filter.step(a_x)
        if self.k % self.v_every == 0:
            self._v_queue.append((t + V_PERIOD - 1e-9, v_now))
        while self._v_queue and self._v_queue[0][0] <= t:
            self.v = self._v_queue.popleft()[1]
        self.k += 1
        self.true_v, self.true_omega = self.truth(snapshot)
        self.log(t, **{f"{self.name}.v": self.v, f"{self.name}.omega": omega, f"{self.name}.true_v": self.true_v,
                       f"{self.name}.true_omega": self.true_omega})
        return {"v": self.v, "omega": omega}


class FootPitch(Module):
    """Integrates the ``foot_pitch`` increments [Δθ_R, Δθ_L] (Eq. 6.7: θ̇ ≈ Δθ/Δt) and adds the sums to the
    soles' pitch on ``foot_damping`` ([L roll, L pitch, R roll, R pitch]); positive tips the toes down and
    drives the scooter forward (Eq. A.1). ``excite(t)`` → (u_v, u_ω) adds a known input through Eq. 6.5."""

    def __init__(self, excite=None, name: str = "foot_pitch"):
        super().__init__(name, CONTROL_PERIOD)
        self.theta = np.zeros(2)  # accumulated (R, L)
        self.excite = excite
        self.u = np.zeros(2)

    def update(self, snapshot):
        inc = np.asarray(snapshot.get("foot_pitch", np.zeros(2)), float).copy()
        self.u = plant_inputs(inc)
        if self.excite is not None:
            ue = np.asarray(self.excite(float(snapshot["t"])), float)
            inc += np.array([ue[0] + ue[1], ue[0] - ue[1]])  # Eq. 6.5
            self.u = self.u + ue
        self.theta += inc
        n = self.name
        self.log(float(snapshot["t"]), **{f"{n}.u_v": self.u[0], f"{n}.u_omega": self.u[1],
                                          f"{n}.theta_R": self.theta[0], f"{n}.theta_L": self.theta[1]})
        return {"foot_damping": np.array([0.0, self.theta[1], 0.0, self.theta[0]])}


def chest_pitch(snapshot) -> float:
    """φ_C, the chest's pitch from its IMU (+ leaning forward, about +y)."""
    return rot_pitch(quat_to_rot(snapshot["imu_quat"]))


class ChestPitchControl(ChestPostureControl):
    """§4.3.3's real-time chest posture control (Eq. 4.8, Kajita's [55]) on the pitch component, as Fig. 4.10 (B)
    uses it on the V-BOARD: Δφ̇_C = k_C (φ_C^d − φ_C) − Δφ_C/T_C on φ_C = :func:`chest_pitch`; contribution
    ``ref:chest_pitch`` = Δφ_C. (The tricycle's :class:`~shintai.humanoid.corrections.ChestPostureControl` is
    the roll component; k_C, T_C are its chosen values, the thesis gives none.)"""

    def __init__(self, **kw):
        super().__init__(chest_pitch, name="posture", **kw)

    def update(self, snapshot):
        delta = self.step(self.roll_of(snapshot))
        self.log(snapshot["t"], **{"posture.delta": delta, "posture.phi": self.roll_of(snapshot)})
        return {"ref:chest_pitch": delta}



class ChestPitchIK(LegIKModule):
    """The leg IK with Eq. 4.9's target correction R_C^{d*} = R_C^d R^{centre}(0, Δφ_C, 0): the upper body (waist
    target, position and attitude) turned by Δφ_C = ``ref:chest_pitch`` about the midpoint of the two soles —
    on the V-BOARD the scooter's centre, the rotation centre §4.3.3 names for Fig. 4.10 (B). ``channel`` and
    ``rotation`` name the component (a subclass turns the roll: ``ref:chest_roll``, ``rot_x``)."""

    channel = "ref:chest_pitch"
    rotation = staticmethod(rot_y)

    def update(self, snapshot):
        d = float(snapshot.get(self.channel, 0.0))
        if d == 0.0:
            return super().update(snapshot)
        soles = np.asarray(snapshot["sole_ref"], float)
        centre = soles.mean(axis=0)
        rot = self.rotation(d)
        waist = centre + rot @ (np.asarray(snapshot["com_ref"], float) - self.com_offset - centre)
        delta = snapshot.get("foot_damping")
        dz = snapshot.get("sole_dz")
        ctrl = self.ctrl0.copy()
        for i, side in enumerate(FEET):
            pos, sole_rot = soles[i].copy(), self._eye
            if delta is not None:
                sole_rot = _rot_xy(float(delta[2 * i]), float(delta[2 * i + 1]))
            if dz is not None:
                pos[2] += float(dz[i])
            res = leg_ik(side, waist, rot, pos, sole_rot)
            if not res.reachable:
                self.unreachable += 1
            ctrl[self.index[side]] = res.q
        return {"ctrl": ctrl}


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
    """HRP2 lowered onto the V-BOARD and riding standing still at behaviour ``level`` 1, 2 or 3.

    ``theta_o_error_deg``: the scooter's true θ_O minus the regression intercept (Eq. A.1; both sides), the
    controllers keep the nominal values (§6.2.1); ``D`` the damping gain (levels 2–3); ``gains`` the PID gains
    ((K_P, K_I, K_D) for v, for ω) and ``learn`` MLC on them (level 3); ``excite`` → (u_v, u_ω) a known input
    added at levels 2–3; ``lift=False`` starts standing on the pads (no lowering); ``seed`` the sensors' noise.
    ``standing``: instead of the lift-placed start, a :class:`~shintai.humanoid.balance.standing.Standing` stack that gets
    onto the scooter by itself (the self-boarding of :func:`~shintai.humanoid.vboard.boarding.boarding_stack`, Fig. 6.16),
    kept as it is — its body (built with its own scooter), its damping gains (no ``D``), no lift; levels 2–3.
    ``stages`` and ``channels`` make the Loop.
    """

    def __init__(self, level: int = 2, theta_o_error_deg: float = 0.0, D: float = D_VBOARD, gains=((0.0,) * 3,) * 2,
                 learn: bool = False, excite=None, lift: bool = True, gap: float = LIFT_GAP, speed: float = LIFT_SPEED,
                 seed: int = 0, noise: bool = True, posture: bool = False, standing: Standing | None = None):
        if level not in LEVELS:
            raise ValueError(f"level must be one of {LEVELS}, got {level!r}")
        check_real("D", D, 0.0, low_open=True)
        self.level = level
        self.scooter = scooter_spec(theta_o_error_deg)
        self.lift = None
        if standing is None:
            body = build_vboard_stand(self.scooter)
            if lift:
                root = body.model.joint("root").qposadr[0]
                body.model.key("stand").qpos[root + 2] += check_real("lift gap", gap, 0.0, 0.2)
                self.lift = Lift(body, gap, speed)
                body.before_physics.insert(0, self.lift)
                body.reset("stand")
                self.lift.hold()
            stack = {} if level >= 2 else {"damping": False, "lip": False, "force_difference": False}
            self.standing = Standing(body=body, **stack)  # settles 0.1 s (held by the lift, if any), clock to 0
            if self.lift is not None:
                self.lift.lowering = True
            if level >= 2:
                self.standing.damping.feet = {"L": FootDamping(D=D), "R": FootDamping(D=D)}
        else:
            if level < 2 or standing.damping is None:
                raise ValueError("a self-boarding stack rides at level 2 or 3, with its foot damping")
            self.standing, body = standing, standing.body
        self.body = body
        st = self.standing
        stages = [list(s) for s in st.loop.stages]
        self.sensors = ScooterSensors(body, seed=seed, noise=noise)
        stages[0].append(self.sensors)
        self.governor, self.foot_pitch = None, None
        if level == 3:
            self.governor = SpeedGovernor(gains0=gains, learn=learn)
            stages.insert(1, [self.governor])
        if level >= 2:
            self.foot_pitch = FootPitch(excite)
            stages[-2].append(self.foot_pitch)  # beside the damping, before the IK
        self.posture = None
        if posture:  # §4.3.3, Fig. 4.10 (B): chest posture control, the IK turning the upper body about the feet
            self.posture = ChestPitchControl()
            stages[0].append(self.posture)
            ik = st.ik
            stages[-1] = [ChestPitchIK(body, ik.ctrl0, ik.com_offset) if m is ik else m for m in stages[-1]]
        self.stages = stages
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


def theta_o(side: str) -> float:
    """The nominal θ_sO (rad) the thesis compares against (Eq. A.1's regression intercept)."""
    return VBOARD.theta_o(side)
