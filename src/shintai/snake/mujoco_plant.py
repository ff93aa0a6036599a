"""MuJoCo plant of the wheeled snake: the robot of seed 001 §2.1 as a physical model, with the same
snapshot/command interface as the kinematic plant (plant.KinematicSnake), so the two-point controller of
ch. 3 runs on it unchanged.

Body (§2.1, spec §1.1): 2n links of length l in series, head link first; odd joints yaw, even joints pitch;
a pair of free-spinning passive wheels coaxial with each pitch joint 2i (wheel i < n) and one pair at the
tail tip (wheel n). Every joint is a position servo commanded by angle and angular velocity like the
XH430-V350-R of §3.3 (PD with velocity feed-forward, clamped at the stall torque). Dimensions, masses and
gains are in constants.MujocoSnakeSettings, each with the reason for its value.

No-slip is *not* imposed: MuJoCo has no velocity (nonholonomic) constraint. The wheels get it from friction
(condim 6, elliptic cones, impratio ≈ 10, STACK.md); what is left is measured. So the plant is a dynamic
check of the thesis's kinematic model (2.7)–(2.10).

Lifting (§2.3, Fig. 2.5): a lifted wheel is raised by pitching the pitch joints around it, never by
switching contacts off (:func:`lift_profile`: on a straight body exactly Fig. 2.5's −α, +2α, −α; on a
curved body the pitch axes are not parallel and a least-squares fit keeps the axles level).

Interface (as KinematicSnake): command ``phi_dot`` (n yaw rates, integrated into the yaw servos'
targets) and ``grounded`` (the mode σ, turned into pitch targets approached at most at
``settings.lift_rate``, so a switch lifts and lowers wheels over a few control periods), and one set
channel per equality the scene lets the experiment switch (``Scene.switches``: the door's hook);
snapshot ``t, w_h, phi, psi, grounded, slip`` plus ``wheel_contact`` (n, measured wheel–floor contact)
and ``head_pose`` (6D). For the 3D models of §2.5 the command may instead be ``psi_dot`` (all 2n−1
joint rates; ``grounded`` then only labels the wheels).

* ``w_h`` — head pose [x_h, y_h, θ_{y,h}] from a motion-capture-like sensor (framepos/framequat of the
  head site, §3.3's OptiTrack), heading unwrapped, optional Gaussian noise; or, with
  ``head_pose="model"``, estimated from the internal kinematic model and the measured joint angles, as in
  the door simulation of §3.4.3 ("the head pose is not read from the simulator").
* ``phi``/``psi`` — joint encoders (jointpos sensors).
* ``slip`` — largest measured axle-direction speed (2.6) of a wheel touching the floor during the last
  period, m/s (the kinematic plant reports its constraint residual in the same unit).

Slip statistics over a run: :meth:`MujocoSnake.slip_summary` — the sideways distance the floor-touching
axles slid divided by the distance they rolled (the lateral slip fraction). Both are net displacements per
control period δt (the axle velocity integrated with its sign over the period, then the magnitude): the
constraint (2.7) is about where a wheel goes, and the contact's vibration about its rest point (the
tyre's elastic micro-motion at ~0.3 mm/s, which at the thesis's 5 mm/s crawl was 5–6 % of the speed when
summed as a path length) is not sliding. The path-length ratio is kept as ``lateral_jitter_fraction``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.core.geometry import rot_z, wrap
from shintai.core.integrators import midpoint
from shintai.core.runtime import SET, Body, declare, whole_multiple
from shintai.sim.body import MujocoBody
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, MUJOCO_SNAKE, MujocoSnakeSettings, SnakeGeometry
from shintai.snake.model import check_mode, configuration, constraint_terms, wheel_poses

CONTYPE_SNAKE, CONTYPE_WORLD = 2, 1  # snake geoms touch the world and objects, never each other (A16)
TYRE_RGBA, LIFTED_TYRE_RGBA = (0.1, 0.1, 0.1, 1.0), (0.2, 0.45, 0.9, 1.0)


@dataclass(frozen=True)
class Scene:
    """MJCF fragments added to the snake's model: objects (box, cart, door), equalities, sensors.

    Object geoms should use ``class="object"`` (collides with the floor, objects and the snake).
    ``switches``: equalities an experiment turns on and off through the body's set channel of the same
    name (a value > 0.5 on), never by calling into MuJoCo.
    """

    worldbody: str = ""
    equality: str = ""
    sensor: str = ""
    switches: tuple[str, ...] = ()


def lift_profile(phi, grounded, l: float, settings: MujocoSnakeSettings = MUJOCO_SNAKE) -> np.ndarray:
    """Pitch-joint targets ψ_2, ψ_4, …, ψ_{2n−2} that lift the lifted wheels by ``settings.lift_height`` and keep
    the grounded ones on the floor, for yaw angles ``phi`` and link length ``l`` (Fig. 2.5, §2.3; the angles
    are small, so first order).

    A pitch ψ_{2j} turns everything behind wheel j about its axle e_{y,j} (positive: the rear goes down).
    For a point d behind wheel j this changes the height by −ψ_{2j} (d·e_{x,j}) and tilts the axle of a
    wheel i behind it by ψ_{2j} sin(θ_i − θ_j) (the axle tilt κ of (2.37), times tread/2 in metres at the
    wheel). The body's own height z_h, roll ρ and pitch β at the head are not commanded (it settles on its
    wheels) but enter the same way. Wheel heights h_i (0 grounded, lift_height lifted) and level axles are
    2n conditions for n + 2 unknowns, solved in least squares with the grounded wheels' rows weighted
    ``settings.lift_ground_weight``: residuals on the support make the rigid body rock onto other wheels, which dips the
    long lifted tail onto the floor; a lifted wheel only needs clearance.
    On a straight body this is Fig. 2.5's rule (−α, +2α, −α at the lifted wheel's and its neighbours'
    pitch joints, α = lift_height / 2l); on a curved body the pitch axes are not parallel, and that rule tilts the
    axles by several mm (a lifted pair then touches on one side).
    """
    cfg = configuration(np.zeros(3), phi, l)  # head at the origin, heading 0
    n, th = cfg.n, cfg.theta
    wheels = wheel_poses(cfg)[:, :2]
    behind = np.tri(n, n - 1, k=-1, dtype=bool)  # wheel i is behind the pitch joint of wheel j < i
    reach = np.einsum("ijk,jk->ij", wheels[:, None, :] - wheels[None, :-1, :], np.column_stack((cfg.cos, cfg.sin))[:-1])
    height = np.zeros((n, n + 2))  # unknowns: ψ_2 … ψ_{2n−2}, z_h, ρ, β
    height[:, :n - 1] = np.where(behind, -reach, 0.0)
    height[:, n - 1] = 1.0
    height[:, n], height[:, n + 1] = wheels[:, 1], -wheels[:, 0]  # (ρ e_x × d)_z, (β e_y × d)_z
    tilt = np.zeros((n, n + 2))
    tilt[:, :n - 1] = np.where(behind, np.sin(th[:, None] - th[None, :-1]), 0.0)
    tilt[:, n], tilt[:, n + 1] = np.cos(th), np.sin(th)
    lifted = ~np.asarray(grounded, dtype=bool)
    weight = np.where(lifted, 1.0, settings.lift_ground_weight)[:, None]
    A = weight * np.stack((height, 0.5 * settings.tread * tilt))
    b = weight[:, 0] * np.stack((settings.lift_height * lifted, np.zeros(n)))
    return np.linalg.lstsq(A.reshape(2 * n, n + 2), b.reshape(2 * n), rcond=None)[0][:n - 1]


def snake_mjcf(geometry: SnakeGeometry = CH3_ROBOT, settings: MujocoSnakeSettings = MUJOCO_SNAKE,
               scene: Scene = Scene()) -> str:
    """The MJCF of the snake on a floor, with ``scene`` added. Names: links ``link1..link2n``, joints
    ``psi1..psi{2n−1}``, servos ``pos<j>``/``vel<j>``, encoders ``enc<j>``, wheels ``wheel<i>L/R``, head site
    ``head`` with mocap sensors ``head_pos``/``head_quat``, axle sites ``axle<i>`` with ``axle<i>_vel``."""
    s, l, n = settings, geometry.l, geometry.n
    lim = geometry.joint_limit
    wheel_mass = s.wheel_mass

    def wheel_pair(i: int, x: float) -> str:
        pair = [f'<site name="axle{i}" pos="{x} 0 0"/>']
        for side, y in (("L", s.tread / 2), ("R", -s.tread / 2)):
            pair.append(
                f'<body name="wheel{i}{side}" pos="{x} {y} 0"><joint name="spin{i}{side}" class="wheel"/>'
                f'<geom name="wheel{i}{side}" class="wheel" mass="{wheel_mass}"/></body>')
        return "".join(pair)

    def link(j: int) -> str:
        joint = ""
        if j > 1:
            axis = "0 0 1" if (j - 1) % 2 else "0 1 0"  # joint j−1: odd yaw, even pitch (§2.1)
            joint = f'<joint name="psi{j - 1}" class="servo" axis="{axis}"/>'
        parts = [f'<body name="link{j}" pos="{0 if j == 1 else l} 0 0">', joint]
        if j == 1:
            parts.append('<freejoint name="root"/><site name="head" pos="0 0 0" size="0.01" rgba="1 .5 0 1"/>')
        head = ' rgba=".9 .5 .1 1"' if j == 1 else ""  # the head link drawn orange
        parts.append(f'<geom name="link{j}" class="link" fromto="0 0 0 {l} 0 0"{head}/>')
        if j % 2 == 1 and j > 1:
            parts.append(wheel_pair((j - 1) // 2, 0.0))  # wheel i on pitch joint 2i, frame of link 2i+1
        if j == 2 * n:
            parts.append(wheel_pair(n, l))  # wheel n at the tail tip
        return "".join(parts)

    chain = "".join(link(j) for j in range(1, 2 * n + 1)) + "</body>" * (2 * n)
    joints = range(1, 2 * n)
    actuators = "".join(f'<position name="pos{j}" joint="psi{j}" kp="{s.servo_kp}"/>'
                        f'<velocity name="vel{j}" joint="psi{j}" kv="{s.servo_kv}"/>' for j in joints)
    encoders = "".join(f'<jointpos name="enc{j}" joint="psi{j}"/>' for j in joints)
    axles = "".join(f'<velocimeter name="axle{i}_vel" site="axle{i}"/><gyro name="axle{i}_gyro" site="axle{i}"/>'
                    for i in range(1, n + 1))
    wf = " ".join(str(v) for v in s.wheel_friction)
    return f"""
<mujoco model="wheeled-snake-{n}">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="{s.timestep}" integrator="implicitfast" cone="elliptic" impratio="{s.impratio}"/>
  <visual><global offwidth="640" offheight="480"/><headlight ambient=".35 .35 .35" diffuse=".5 .5 .5"/></visual>
  <default>
    <geom contype="{CONTYPE_WORLD}" conaffinity="{CONTYPE_WORLD | CONTYPE_SNAKE}"
          friction="{s.body_friction} 0.005 0.0001"/>
    <default class="link">
      <geom type="capsule" size="{s.link_radius}" mass="{s.link_mass}" contype="{CONTYPE_SNAKE}"
            conaffinity="{CONTYPE_WORLD}" rgba=".25 .3 .35 1"/>
    </default>
    <default class="wheel">
      <geom type="cylinder" size="{s.wheel_radius} {s.wheel_half_width}" quat="0.70710678 0.70710678 0 0"
            contype="{CONTYPE_SNAKE}" conaffinity="{CONTYPE_WORLD}" condim="{s.wheel_condim}" friction="{wf}"
            rgba="{" ".join(map(str, TYRE_RGBA))}"/>
      <joint type="hinge" axis="0 1 0" damping="{s.wheel_damping}"/>
    </default>
    <default class="servo">
      <joint type="hinge" range="{-lim} {lim}" armature="{s.servo_armature}"
             actuatorfrcrange="{-s.servo_torque} {s.servo_torque}"/>
    </default>
    <default class="object"><geom rgba=".85 .85 .8 1"/></default>
  </default>
  <asset>
    <texture name="grid" type="2d" builtin="checker" rgb1=".82 .82 .8" rgb2=".72 .72 .7" width="300" height="300"/>
    <material name="grid" texture="grid" texrepeat="10 10"/>
  </asset>
  <worldbody>
    <light pos="0 0 3" dir="0 0 -1" directional="true" castshadow="false"/>  <!-- shadows: 3× render time -->
    <geom name="floor" type="plane" size="6 6 0.05" material="grid"/>
    {chain}
    {scene.worldbody}
  </worldbody>
  <equality>{scene.equality}</equality>
  <actuator>{actuators}</actuator>
  <sensor>
    <framepos name="head_pos" objtype="site" objname="head"/>
    <framequat name="head_quat" objtype="site" objname="head"/>
    {encoders}{axles}{scene.sensor}
  </sensor>
</mujoco>"""


def planar_heading(quat) -> float:
    """Yaw of the frame's x axis in the world x–y plane (θ_{y,h} of (2.1)) from a unit quaternion (w, x, y, z)."""
    w, x, y, z = quat
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


class MujocoSnake(Body):
    """The snake in MuJoCo as a Body: command ``phi_dot`` or ``psi_dot``, ``grounded`` and the scene's
    switches; snapshot as KinematicSnake plus ``wheel_contact`` and ``head_pose`` (see the module docstring).
    ``mocap_noise`` is the head-position noise σ (m; the heading gets σ / marker_span rad); ``head_pose``
    is ``"mocap"`` or ``"model"``."""

    channels = {**declare("phi_dot", "psi_dot"), **declare("grounded", kind=SET)}  # σ: on the floor (1) / lifted

    def __init__(self, w_h0, phi0, geometry: SnakeGeometry = CH3_ROBOT, dt: float = CH3_GAINS.dt,
                 settings: MujocoSnakeSettings = MUJOCO_SNAKE, scene: Scene = Scene(), mocap_noise: float = 0.0,
                 head_pose: str = "mocap", rng: np.random.Generator | None = None):
        if head_pose not in ("mocap", "model"):
            raise ValueError(f"head_pose must be 'mocap' or 'model', got {head_pose!r}")
        if mocap_noise < 0:
            raise ValueError(f"mocap_noise must be >= 0 m, got {mocap_noise!r}")
        servo_steps = whole_multiple(dt, settings.servo_period, "dt")
        cfg = configuration(w_h0, phi0, geometry.l)
        if cfg.n != geometry.n:
            raise ValueError(f"phi0 must have n = {geometry.n} yaw angles, got {cfg.n}")
        self.geometry, self.settings, self.dt = geometry, settings, float(dt)
        self.head_pose, self.mocap_noise = head_pose, float(mocap_noise)
        self.rng = rng if rng is not None else np.random.default_rng(0)
        self.mj = MujocoBody(snake_mjcf(geometry, settings, scene),
                             substeps=int(round(settings.servo_period / settings.timestep)))
        self.switches = tuple(scene.switches)
        self.channels = {**MujocoSnake.channels, **declare(*self.switches, kind=SET)}
        self._servo_steps = servo_steps
        self._index()
        self.steps = 0
        self.t = 0.0
        self.grounded = np.ones(geometry.n, dtype=bool)
        psi0 = np.zeros(geometry.joints)
        psi0[::2] = cfg.phi
        self.place([cfg.w_h[0], cfg.w_h[1], settings.wheel_radius], rot_z(cfg.w_h[2]), psi0, heading=float(cfg.w_h[2]))
        self.slip = 0.0
        self.wheel_contact = np.zeros(geometry.n, dtype=bool)
        self._slid = self._rolled = 0.0  # m, net per control period, summed over floor-touching axles
        self._jitter = self._path = 0.0  # m, the same as path lengths (|v| h summed at every servo step)
        self._window = np.zeros((geometry.n, 2))  # this period's signed [forward, sideways] travel per axle
        self._steady = np.zeros(2)  # [rolled, slid] in the periods at least switch_settle after a mode switch
        self._switched = -math.inf  # time of the last mode switch
        self._slip_max = 0.0
        self._mismatch = 0.0  # wheel·seconds in which a wheel's floor contact differs from the mode

    # -- construction ------------------------------------------------------------------------------

    def _index(self) -> None:
        m, mj, n = self.mj.model, self.mj, self.geometry.n
        joints = range(1, 2 * n)
        self._pos = np.array([mj.id("actuator", f"pos{j}") for j in joints])
        self._vel = np.array([mj.id("actuator", f"vel{j}") for j in joints])
        self._qadr = np.array([m.jnt_qposadr[mj.id("joint", f"psi{j}")] for j in joints])
        self._enc = np.array([m.sensor_adr[mj.id("sensor", f"enc{j}")] for j in joints])
        self._axle_vel = np.array([m.sensor_adr[mj.id("sensor", f"axle{i}_vel")] for i in range(1, n + 1)])
        self._axle_gyro = np.array([m.sensor_adr[mj.id("sensor", f"axle{i}_gyro")] for i in range(1, n + 1)])
        self._head = (m.sensor_adr[mj.id("sensor", "head_pos")], m.sensor_adr[mj.id("sensor", "head_quat")])
        self._floor = mj.id("geom", "floor")
        self._geom_wheel = np.full(m.ngeom, -1)
        for i in range(1, n + 1):
            for side in "LR":
                self._geom_wheel[mj.id("geom", f"wheel{i}{side}")] = i - 1

    def place(self, p_h, R_h, psi, heading: float | None = None) -> None:
        """Put the head tip at ``p_h`` with frame ``R_h`` (e_x tail-ward) and the joints at ``psi`` (2n−1), at
        rest; servo commands, head estimates and the mocap heading (``heading``: its 2π-branch, default the
        one in (−π, π]) start there. The constructor places (w̃_h0, φ0) with every wheel on the floor."""
        d = self.mj.data
        psi = np.asarray(psi, dtype=float)
        if psi.shape != (self.geometry.joints,):
            raise ValueError(f"psi must hold 2n−1 = {self.geometry.joints} joint angles, got shape {psi.shape}")
        root = self.mj.model.jnt_qposadr[self.mj.id("joint", "root")]
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, np.asarray(R_h, dtype=float).reshape(9))
        d.qpos[root:root + 3], d.qpos[root + 3:root + 7] = p_h, quat
        d.qpos[self._qadr] = psi
        d.qvel[:] = 0.0
        d.ctrl[self._pos], d.ctrl[self._vel] = psi, 0.0
        self.mj.forward()
        self._psi_cmd, self._rate = psi.copy(), np.zeros_like(psi)
        self._heading = planar_heading(quat) if heading is None else heading  # unwrapped mocap heading
        self._w_model = np.array([p_h[0], p_h[1], self._heading])  # internal-model estimate (head_pose="model")
        self._phi_prev = psi[::2].copy()

    def settle(self, duration: float) -> None:
        """Let the body come to rest under gravity for ``duration`` s with the servos holding their commands,
        then start the clock (t = 0) and the slip statistics there. A body put down by :meth:`place` is
        unloaded; raised parts (the handcart's arms) then sag by centimetres in the first 0.1 s. An experiment
        starts from the robot at rest, its initial controlled variables measured there ((3.21), (3.26))."""
        grounded = self.grounded.copy()
        # The body's own steps, not a Loop: a Loop would read the snapshot every period, which advances the mocap
        # heading's unwrapping and noise draws before the experiment starts.
        for _ in range(int(round(duration / self.dt))):
            self.apply({"psi_dot": np.zeros(self.geometry.joints), "grounded": grounded})
            self.step()
        self.steps, self.t = 0, 0.0
        self.slip, self._slid, self._rolled, self._jitter, self._path, self._slip_max = (0.0,) * 6
        self._steady[:], self._window[:], self._mismatch, self._switched = 0.0, 0.0, 0.0, -math.inf
        self._phi_prev = self.mj.data.sensordata[self._enc][::2].copy()

    # -- Body interface ----------------------------------------------------------------------------

    def snapshot(self) -> dict:
        psi = self.mj.data.sensordata[self._enc].copy()
        w_h = self._head_estimate()
        return {"t": self.t, "w_h": w_h, "phi": psi[::2].copy(), "psi": psi, "grounded": self.grounded.copy(),
                "slip": self.slip, "wheel_contact": self.wheel_contact.copy(), "head_pose": self._head_pose(w_h)}

    def apply(self, command: dict) -> None:
        n = self.geometry.n
        for name in self.switches:
            if name in command:
                self.mj.set_equality(name, float(command[name]) > 0.5)
        if "grounded" in command:
            grounded = check_mode(command["grounded"], n)
            if not np.array_equal(grounded, self.grounded):
                self._switched = self.t
            self.grounded = grounded
        if "psi_dot" in command:  # every joint rate-commanded (3D models); "grounded" only labels the wheels
            if "phi_dot" in command:
                raise ValueError("give phi_dot (planar; pitch joints lift the wheels) or psi_dot (all joints), not both")
            self._rate = self._checked("psi_dot", command["psi_dot"], self.geometry.joints)
        else:
            phi_dot = self._checked("phi_dot", command.get("phi_dot", np.zeros(n)), n)
            phi = self.mj.data.sensordata[self._enc][::2] + phi_dot * self.dt  # yaw at the period's end
            self._rate = np.empty(self.geometry.joints)
            self._rate[::2] = phi_dot
            lift = lift_profile(phi, self.grounded, self.geometry.l, self.settings)
            limit = self.settings.lift_rate
            self._rate[1::2] = np.clip((lift - self._psi_cmd[1::2]) / self.dt, -limit, limit)
        wheels = self._geom_wheel >= 0  # tyres of lifted wheels drawn blue (as the plots' hollow markers)
        self.mj.model.geom_rgba[wheels] = np.where(self.grounded[self._geom_wheel[wheels]][:, None],
                                                   TYRE_RGBA, LIFTED_TYRE_RGBA)

    @staticmethod
    def _checked(channel: str, value, size: int) -> np.ndarray:
        value = np.asarray(value, dtype=float)
        if value.shape != (size,):
            raise ValueError(f"{channel} must have {size} entries, got shape {value.shape}")
        return value

    def step(self) -> None:
        """One control period δt: servo targets ramped in ``servo_period`` steps; slip measured at each."""
        d, h = self.mj.data, self.settings.servo_period
        self.slip = 0.0
        d.ctrl[self._vel] = self._rate
        for k in range(1, self._servo_steps + 1):
            d.ctrl[self._pos] = self._psi_cmd + self._rate * h * k
            self.mj.step()
            self._measure_slip(h)
        self._psi_cmd = self._psi_cmd + self._rate * self.dt
        rolled, slid = np.abs(self._window).sum(axis=0)
        self._rolled += rolled
        self._slid += slid
        if self.t - self._switched >= self.settings.switch_settle:  # this period is clear of a mode switch
            self._steady += np.array([rolled, slid])
        self._window[:] = 0.0
        self.mj.forward()  # sensors of the state reached (MuJoCo computes them at the start of a step)
        self.steps += 1
        self.t = self.steps * self.dt
        if self.head_pose == "model":
            self._advance_model_estimate()

    # -- measurements ------------------------------------------------------------------------------

    def _measure_slip(self, h: float) -> None:
        d = self.mj.data
        contact = np.zeros(self.geometry.n, dtype=bool)
        if d.ncon:
            g = d.contact.geom
            for a, b in ((0, 1), (1, 0)):
                on_floor = g[:, a] == self._floor
                wheels = self._geom_wheel[g[on_floor, b]]
                contact[wheels[wheels >= 0]] = True
        self.wheel_contact = contact
        self._mismatch += float(np.count_nonzero(contact != self.grounded)) * h
        if contact.any():
            # axle frame: x along the body, y the axle. The contact point is r_w below the axle, so the
            # link's roll rate ω_x adds ω_x r_w to its sideways speed (the axle's own is polluted by roll).
            v = d.sensordata[self._axle_vel[contact, None] + np.arange(3)]
            roll_rate = d.sensordata[self._axle_gyro[contact]]
            lateral = v[:, 1] + roll_rate * self.settings.wheel_radius
            self.slip = max(self.slip, float(np.abs(lateral).max()))
            self._slip_max = max(self._slip_max, self.slip)
            self._window[contact] += np.column_stack((v[:, 0], lateral)) * h
            self._jitter += float(np.abs(lateral).sum()) * h
            self._path += float(np.abs(v[:, 0]).sum()) * h

    def _head_estimate(self) -> np.ndarray:
        if self.head_pose == "model":
            return self._w_model.copy()
        d = self.mj.data
        p_adr, q_adr = self._head
        heading = planar_heading(d.sensordata[q_adr:q_adr + 4])
        self._heading += wrap(heading - self._heading)  # unwrap
        w = np.array([d.sensordata[p_adr], d.sensordata[p_adr + 1], self._heading])
        if self.mocap_noise:
            sigma = self.mocap_noise
            w += self.rng.normal(0.0, [sigma, sigma, sigma / self.settings.marker_span])
        return w

    def _head_pose(self, w_h: np.ndarray) -> np.ndarray:
        """6D head pose [x, y, z, roll, pitch, yaw] (2.1) from the mocap (the planar part as in ``w_h``)."""
        q = self.mj.data.sensordata[self._head[1]:self._head[1] + 4]
        R = np.zeros(9)
        mujoco.mju_quat2Mat(R, q)
        R = R.reshape(3, 3)
        z = self.mj.data.sensordata[self._head[0] + 2]
        return np.array([w_h[0], w_h[1], z, math.atan2(R[2, 1], R[2, 2]), -math.asin(max(-1.0, min(1.0, R[2, 0]))),
                         w_h[2]])

    def _advance_model_estimate(self) -> None:
        """Internal-model odometry (§3.4.3): A_σ ẇ̃_h = B_σ φ̇ (2.10) with the measured joint motion over δt,
        solved at the period's midpoint angles."""
        phi = self.mj.data.sensordata[self._enc][::2]
        self._w_model = odometry_step(self._w_model, self._phi_prev, phi, self.grounded, self.geometry.l, self.dt)
        self._phi_prev = phi

    def true_head(self) -> np.ndarray:
        """The simulator's head pose [x_h, y_h, θ_{y,h}] (no noise, heading unwrapped near the last reading)."""
        d = self.mj.data
        q = d.sensordata[self._head[1]:self._head[1] + 4]
        heading = planar_heading(q)
        heading = self._heading + wrap(heading - self._heading)
        p = d.sensordata[self._head[0]:self._head[0] + 3]
        return np.array([p[0], p[1], heading])

    def wheel_positions(self) -> np.ndarray:
        """World positions of the n axle centres, shape (n, 3)."""
        return np.array([self.mj.site_pos(f"axle{i}") for i in range(1, self.geometry.n + 1)])

    def slip_summary(self) -> dict:
        """``lateral_slip_fraction`` = sideways distance slid / distance rolled by the floor-touching axles
        (net per control period, see the module docstring); ``lateral_slip_fraction_steady`` the same over
        the periods at least ``settings.switch_settle`` after a mode switch (no lift transient);
        ``lateral_jitter_fraction`` the same as path
        lengths at every servo step (contact vibration included); ``max_lateral_slip_m_s``; ``rolled_m``
        (summed over axles); ``contact_mismatch_fraction`` = share of wheel-time in which a wheel touched
        the floor while lifted or did not while grounded."""
        wheel_time = self.geometry.n * self.t
        steady_rolled, steady_slid = self._steady
        return {"lateral_slip_fraction": self._slid / self._rolled if self._rolled > 0 else 0.0,
                "lateral_slip_fraction_steady": steady_slid / steady_rolled if steady_rolled > 0 else 0.0,
                "lateral_jitter_fraction": self._jitter / self._path if self._path > 0 else 0.0,
                "max_lateral_slip_m_s": self._slip_max, "rolled_m": self._rolled,
                "contact_mismatch_fraction": self._mismatch / wheel_time if wheel_time > 0 else 0.0}

    def link_points(self) -> np.ndarray:
        """Head tip, link origins (joints) and tail tip of the simulated body in the plane, shape (2n+1, 2)."""
        n = self.geometry.n
        points = [self.mj.body_pos(f"link{j}")[:2] for j in range(1, 2 * n + 1)]
        return np.array(points + [self.mj.site_pos(f"axle{n}")[:2]])

    def view(self, **overrides) -> dict:
        """Camera options for ``--video`` (scenarios.experiment.film): following the middle of the body."""
        return {"fps": 20, "width": 640, "height": 480, "track": f"link{self.geometry.n}",
                "distance": 1.2 * self.geometry.length, "elevation": -60.0, "azimuth": 90.0, **overrides}


def head_path_difference(c_a: np.ndarray, c_b: np.ndarray) -> float:
    """Largest distance between the head positions of two runs sampled at the same control periods (m)."""
    k = min(len(c_a), len(c_b))
    return float(np.hypot(*(c_a[:k, :2] - c_b[:k, :2]).T).max())


def odometry_step(w_h: np.ndarray, phi_0: np.ndarray, phi_1: np.ndarray, grounded, l: float, dt: float) -> np.ndarray:
    """The head pose after one period δt by the internal model (2.10), A_σ ẇ̃_h = B_σ φ̇, from the measured joint
    angles at its start and end (φ̇ = Δφ/δt, the angles at mid-period), by the explicit midpoint rule."""
    rate = (phi_1 - phi_0) / dt
    mid = 0.5 * (phi_1 + phi_0)

    def w_dot(w):
        A, b = constraint_terms(w[2], mid, l, rate)
        return np.linalg.lstsq(A[grounded], b[grounded], rcond=None)[0]

    return midpoint(w_dot, w_h, dt)


def replay_error(w_h: np.ndarray, phi: np.ndarray, grounded: np.ndarray, l: float, dt: float, window: int) -> float:
    """The kinematic model (2.10) as a predictor of the measured motion: from the measured head pose at the
    start of each ``window`` of control periods, integrate ẇ̃_h = A_σ^† B_σ φ̇ with the *measured* joint
    motion (φ̇ = Δφ/δt per period, midpoint rule) and the commanded modes; return the largest head-position
    error at a window's end (m). Zero for a plant that obeys the no-slip constraints exactly.
    """
    worst = 0.0
    for start in range(0, len(grounded) - window + 1, window):
        w = np.asarray(w_h[start], dtype=float).copy()
        for k in range(start, start + window):
            w = odometry_step(w, phi[k], phi[k + 1], grounded[k], l, dt)
        worst = max(worst, float(np.hypot(*(w[:2] - w_h[start + window][:2]))))
    return worst
