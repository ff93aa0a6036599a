"""Standing on a two-wheeled scooter, shared by the V-BOARD (ch. 6) and the Ninebot (§7.3.3).

* :class:`Lift` — the care lift that lowers the robot onto the pads (§6.4.1, Fig. 6.15: "リフトから下ろして搭乗させる").
* :class:`ScooterSensors` — v and ω from the robot's own sensors (Table 6.1, Eq. 6.3).
* :class:`FootPitch` — the foot-pitch increments integrated into the soles' pitch (Eqs. 6.5, 6.7).
* :class:`ChestPitchControl`, :class:`ChestPitchIK` — §4.3.3's chest posture control on pitch (Eqs. 4.8–4.9).
* :func:`posture_on_pads` — HRP2 standing with its soles on a vehicle's pads, mass centre over its axle (§6.2.1).

Sensors (Table 6.1; chosen where it gives no number): ω = the chest gyro's yaw rate (4 ms) with white noise
``GYRO_NOISE``; v = Eq. 6.3's filter on a_x (chest accelerometer, gravity removed, along the robot's heading;
noise ``ACC_NOISE``) and x_VO (the head camera's position, 10 ms samples, ``VO_LATENCY`` late, noise
``VO_NOISE``); v is published every 24 ms with a 24 ms latency (Table 6.1's ``*``). Seeded.
"""

from __future__ import annotations

import math
from collections import deque

import mujoco
import numpy as np

from shintai.core.constants import GRAVITY
from shintai.core.geometry import rot_xy, rot_y
from shintai.core.runtime import SET, Module, declare
from shintai.humanoid.balance.foot_attitude import pitch as rot_pitch
from shintai.humanoid.balance.foot_attitude import quat_to_rot
from shintai.humanoid.balance.stabilizer import SIDES as FEET
from shintai.humanoid.balance.standing import CHANNELS as STANDING_CHANNELS
from shintai.humanoid.balance.standing import LegIKModule
from shintai.humanoid.constants import (
    ACC_NOISE,
    COM_ITERATIONS,
    CONTROL_PERIOD,
    GYRO_NOISE,
    HRP2_LINKS,
    LIFT_C,
    LIFT_CR,
    LIFT_GAP,
    LIFT_K,
    LIFT_KR,
    LIFT_SPEED,
    STANDING_POSTURE,
    VO_LATENCY,
    VO_NOISE,
    VO_PERIOD,
    V_PERIOD,
)
from shintai.humanoid.corrections import ChestPostureControl
from shintai.humanoid.law_params import check_real
from shintai.humanoid.learning.speed_governing import LinearVelocityFilter, plant_inputs
from shintai.humanoid.robots.hrp2 import LEG, SIDES, side_posture
from shintai.humanoid.robots.leg_ik import leg_ik
from shintai.sim import ik
from shintai.sim.spec import set_joints

SOLE = {s: f"{s}_sole" for s in SIDES}  # sole sites
CHANNELS = {**STANDING_CHANNELS, **declare("v", "omega", kind=SET), **declare("foot_pitch", "ref:chest_pitch"),
            # the commanded soles' pitch (R, L) without δ, one tick late: the reference feet of a foot-origin frame
            # at the ankles (balance.stabilizer's foot_origin="ankle")
            **declare("foot_pitch_ref", kind=SET, delay=1)}


class Lift:
    """The care lift holding the waist: a spring-damper to a pose whose height descends at ``speed``; its vertical
    force is a strap's (≥ 0), and it lets go for good once the feet carry the weight (the strap slack). Call
    before every physics step."""

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
    """v and ω from the robot's simulated sensors (Table 6.1, Eq. 6.3; module docstring; ``truth``: snapshot → the vehicle's true (v, ω)). Writes ``v``
    (24 ms, 24 ms late) and ``omega`` (4 ms); keeps the truth (``true_v``, ``true_omega``) for evaluation."""

    def __init__(self, body, truth, seed: int = 0, noise: bool = True, name: str = "sensors"):
        super().__init__(name, CONTROL_PERIOD)
        self.truth = truth  # snapshot → the true (v, ω) of the vehicle
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
    drives the scooter forward (Eq. A.1). ``excite(t)`` → (u_v, u_ω) adds a known input through Eq. 6.5;
    ``theta0`` (R, L) the soles' reference pitch it starts from (the boarding posture's). Writes also ``foot_pitch_ref``."""

    def __init__(self, excite=None, name: str = "foot_pitch", theta0=(0.0, 0.0)):
        super().__init__(name, CONTROL_PERIOD)
        self.theta = np.asarray(theta0, float).copy()  # accumulated (R, L), from the reference soles' pitch theta0
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
        return {"foot_damping": np.array([0.0, self.theta[1], 0.0, self.theta[0]]), "foot_pitch_ref": self.theta.copy()}


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
                sole_rot = rot_xy(float(delta[2 * i]), float(delta[2 * i + 1]))
            if dz is not None:
                pos[2] += float(dz[i])
            res = leg_ik(side, waist, rot, pos, sole_rot)
            if not res.reachable:
                self.unreachable += 1
            ctrl[self.index[side]] = res.q
        return {"ctrl": ctrl}


def posture_on_pads(model: mujoco.MjModel, qpos: np.ndarray, deck_height: float, pads: dict[str, str],
                    centre_site: str, where: str, flat_soles: bool = False) -> np.ndarray:
    """HRP2 standing with each sole on its pad site (the pads' orientation, or level with ``flat_soles``) and its
    mass centre over ``centre_site`` in x: the standing knee bend, the waist lowered to the deck, then
    :data:`COM_ITERATIONS` rounds of leg IK and a waist shift. Shared by the V-BOARD and the Ninebot.

    Raises ValueError if the IK does not reach the pads.
    """
    posture = side_posture(STANDING_POSTURE)
    set_joints(model, qpos, posture)
    hip, knee = posture["l_hip_pitch"], posture["l_knee_pitch"]
    leg = HRP2_LINKS.thigh * np.cos(hip) + HRP2_LINKS.shank * np.cos(hip + knee)
    root = model.joint("root").qposadr[0]
    qpos[root:root + 3] = [0.0, 0.0, deck_height - HRP2_LINKS.hip_z + leg + HRP2_LINKS.ankle_height]
    data = mujoco.MjData(model)
    waist = model.body("waist").id
    for _ in range(COM_ITERATIONS):
        data.qpos[:] = qpos
        mujoco.mj_kinematics(model, data)
        targets = {SOLE[s]: (data.site(pads[s]).xpos.copy(),
                             np.eye(3) if flat_soles else data.site(pads[s]).xmat.reshape(3, 3).copy())
                   for s in SIDES}
        result = ik.solve(model, targets, qpos, LEG, posture={j: posture[j] for j in LEG if j in posture})
        if not result.ok:
            raise ValueError(f"standing posture {where} not reachable: residual {result.residual[0]:.4f} m, "
                             f"{result.residual[1]:.4f} rad")
        qpos = result.q
        data.qpos[:] = qpos
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        qpos[root] -= data.subtree_com[waist][0] - data.site(centre_site).xpos[0]
    return qpos


