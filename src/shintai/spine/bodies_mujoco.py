"""A muscle-driven spine as a MuJoCo body generated in code (MjSpec) — seed 003 §3.6, §4.4, §4.6–4.7.

Model (spec 003 §5.2):

* **Vertebrae.** Link 0 (pelvis) is fixed to the world; links 1 … n hang on joints with the
  thesis's rpy convention: three hinges per joint in the order yaw (z), pitch (y), roll (x), which
  MuJoCo composes as R = Rz(ψ) Ry(θ) Rx(φ) — the posture θ of eq. 4.1 is ``qpos`` directly — or
  one ``ball`` joint (``joint="ball"``). The disc is the joint's stiffness and damping (linear;
  :meth:`SpineBody.set_disc` changes it at run time). The joints are limited at the chain's limits
  (§3.6.1: ±18° for Cla, §3.7.1: ±10° for Kenta), soft like every MuJoCo limit; the spec is built
  with ``compiler.degree = False``, so these ranges (and every angle) are in radians.
* **Muscles = spatial tendons through sites.** A tendon runs from the motor's reel through the
  pull point and every via point to the attachment point: without wrapping its length minus the
  reel part is exactly eq. 4.25.
* **Motor + gear + pulley = a reel.** Each motor winds its wire onto a reel, modelled as a slide
  joint inside the motor's block along which the wire's inner end moves: ``qpos`` is the wire
  wound in (s), the joint's armature is the rotor inertia seen at the wire (J N²/r²), its damping
  the back-EMF slope F_stall/v0 (the driver shorts the motor at o = 0: braking, chosen), its
  frictionloss the back-drive threshold, and a ``motor`` actuator of gear F_stall takes the duty
  o ∈ [−1, 1]: F = F_stall (o − v/v0), the linear torque–speed line of
  :class:`~shintai.spine.actuators.DCMotorDrive`.
* **The wire can only pull.** The tendon is a spring with a dead band, ``springlength = (0, L)``:
  stiffness k_w (wire + tension sensor, :class:`~shintai.spine.robots.TensionSensorSpec`) beyond
  its free length L, no force when slack. No tendon damping (MuJoCo's is bilateral).
* **Interference** (§4.7.1), optional: a wrap geom of radius ``WRAP_RADIUS_M`` (vertebral body +
  wire) on the middle vertebra that every straight muscle must wrap around, on the side the muscle
  passes at rest: ``wrap="sphere"``, or ``wrap="column"``, a cylinder along the middle vertebra's axis —
  MuJoCo wraps a cylinder as infinite, so a muscle bears on the column at whatever height it meets it (Fig.
  3.31's diagonal muscles meet it off the middle, and in twist wind round it). When the spine bends, the
  muscles on its convex side are pushed out and become longer than eq. 4.25 predicts — the thesis's hypothesis
  (§4.7.2: "筋が物理的に他の筋や構造材と干渉すると、その筋は式 (4.25) で求めた長さより長くなると思われる"). Muscle–muscle
  interference is not representable: MuJoCo tendons pass through each other.
* **Sensors.** Accelerometers on the pelvis and the clavicle (eq. 3.4); encoders, tension sensors
  and motor currents are computed from the reel and tendon state in :meth:`SpineBody.snapshot`.
* **Ligaments** (Kenta, §3.7.1), optional: extension springs between neighbouring vertebrae as
  spatial tendons that pull only beyond their natural length (``ligaments=KENTA_LIGAMENTS``).
* **A human hand**: a mocap body welded to the top link while the ``hand`` channel (a set channel:
  the posture θ whose top-link pose the hand holds) is written, used to zero the encoders (§4.6.4),
  push the spine (E10) or teach it (E9); a tick without a writer lets go.
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.core.runtime import SET, declare, whole_multiple
from shintai.sim.body import MujocoBody
from shintai.spine.actuators import DCMotorDrive, Encoder, TensionSensor, posture_from_accelerometers
from shintai.spine.geometry import matrix_rpy, rpy_matrix
from shintai.spine.robots import (
    HAND_SOLREF, PELVIS_HEIGHT_M, REEL_OFFSET_M, WRAP_RADIUS_M, DiscSpec, LigamentSpec, Load, SpineRobot,
)


def _quat(R: np.ndarray) -> np.ndarray:
    q = np.zeros(4)
    mujoco.mju_mat2Quat(q, np.asarray(R, dtype=float).reshape(9))
    return q


def build_spec(robot: SpineRobot, loads: tuple[Load, ...] | None = None, joint: str = "hinge",
               interference: bool = True, timestep: float = 5e-4,
               ligaments: LigamentSpec | None = None, wrap: str = "sphere") -> mujoco.MjSpec:
    """The MjSpec of ``robot``'s spine (see the module docstring)."""
    if joint not in ("hinge", "ball"):
        raise ValueError(f"joint must be 'hinge' or 'ball', got {joint!r}")
    if wrap not in WRAPS:
        raise ValueError(f"wrap must be one of {WRAPS}, got {wrap!r}")
    if not isinstance(robot.disc, DiscSpec):
        raise ValueError(f"{robot.name}: the MuJoCo body needs a linear DiscSpec, got {type(robot.disc).__name__}")
    spec = mujoco.MjSpec()
    spec.modelname = robot.name.lower()
    spec.compiler.degree = False  # every angle in radians (MjSpec, like MJCF, defaults to degrees)
    spec.option.timestep = timestep
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.visual.global_.offwidth, spec.visual.global_.offheight = 640, 480
    spec.visual.headlight.ambient = [0.4, 0.4, 0.4]
    spec.visual.headlight.diffuse = [0.6, 0.6, 0.6]
    world = spec.worldbody
    world.add_light(pos=[0.4, -0.6, 1.4], dir=[-0.3, 0.5, -1.0], diffuse=[0.8, 0.8, 0.8])
    world.add_geom(name="ground", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0.6, 0.6, 0.02],
                   rgba=[0.85, 0.85, 0.85, 1], contype=0, conaffinity=0)
    links = _add_links(spec, robot, joint, loads if loads is not None else robot.loads)
    _add_muscles(spec, robot, links, interference, wrap)
    _add_hand(spec, robot, links[-1])
    if ligaments is not None:
        _add_ligaments(spec, links, ligaments)
    for name, link in (("acc_waist", links[0]), ("acc_chest", links[-1])):
        link.add_site(name=name, pos=[0, 0, 0], size=[0.004, 0, 0])
        spec.add_sensor(name=name, type=mujoco.mjtSensor.mjSENS_ACCELEROMETER,
                        objtype=mujoco.mjtObj.mjOBJ_SITE, objname=name)
    return spec


def _add_links(spec, robot: SpineRobot, joint: str, loads) -> list:
    chain, disc = robot.model.chain, robot.disc
    bx, by = robot.block_half_m
    pelvis = spec.worldbody.add_body(name="link0", pos=[0, 0, PELVIS_HEIGHT_M])
    pelvis.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[bx, by, 0.012], pos=[0, 0, -0.012],
                    rgba=[0.45, 0.45, 0.5, 1], contype=0, conaffinity=0)
    spec.worldbody.add_geom(name="pedestal", type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                            size=[0.015, PELVIS_HEIGHT_M / 2 - 0.012],
                            pos=[0, 0, PELVIS_HEIGHT_M / 2 - 0.012], rgba=[0.6, 0.6, 0.65, 1], contype=0, conaffinity=0)
    links = [pelvis]
    r = robot.vertebra_radius_m
    limit = chain.upper.reshape(-1, 3)  # stops at the joint limits [rad] (§3.6.1: about ±18°; §3.7.1: ±10°)
    for i in range(chain.n):
        body = links[-1].add_body(name=f"link{i + 1}", pos=chain.offsets[i].tolist(), quat=_quat(chain.rest[i]).tolist())
        if joint == "hinge":
            for axis_name, axis, k, lim in (("yaw", [0, 0, 1], disc.k_twist_nm_rad, limit[i, 2]),
                                            ("pitch", [0, 1, 0], disc.k_bend_nm_rad, limit[i, 1]),
                                            ("roll", [1, 0, 0], disc.k_bend_nm_rad, limit[i, 0])):
                body.add_joint(name=f"j{i + 1}_{axis_name}", type=mujoco.mjtJoint.mjJNT_HINGE, axis=axis,
                               stiffness=k, damping=disc.damping_nms_rad, armature=1e-6, limited=True,
                               range=[-lim, lim])
        else:
            body.add_joint(name=f"j{i + 1}", type=mujoco.mjtJoint.mjJNT_BALL, stiffness=disc.k_bend_nm_rad,
                           damping=disc.damping_nms_rad, armature=1e-6, limited=True,
                           range=[0.0, limit[i].max()])
        height = chain.offsets[i + 1, 2] if i + 1 < chain.n else 0.02
        mass = robot.link_mass_kg[i + 1]
        if mass > 0:
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_CYLINDER, size=[r, 0.35 * height], pos=[0, 0, 0.5 * height],
                          mass=mass, rgba=[0.93, 0.9, 0.8, 1], contype=0, conaffinity=0)
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.6 * r], mass=0.0, rgba=[0.7, 0.7, 0.75, 1],
                      contype=0, conaffinity=0)
        links.append(body)
    top = links[-1]
    top.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[bx, by, 0.01], pos=[0, 0, 0.02], mass=1e-3,
                 rgba=[0.45, 0.45, 0.5, 1], contype=0, conaffinity=0)
    for load in loads:
        links[load.link].add_geom(name=load.name, type=mujoco.mjtGeom.mjGEOM_BOX, size=list(load.size_m),
                                  pos=list(load.com_m), mass=load.mass_kg, rgba=[0.55, 0.6, 0.75, 0.3],
                                  contype=0, conaffinity=0)
    return links


WRAPS = ("sphere", "column")  # the interference geom: a sphere, or a cylinder along the middle vertebra


def _inward(point) -> np.ndarray:
    """Horizontal unit vector from a pull point toward its block's centre: the reel's slide axis."""
    v = -np.array([point[0], point[1], 0.0])
    norm = np.linalg.norm(v)
    return v / norm if norm > 1e-9 else np.array([1.0, 0.0, 0.0])


def _add_muscles(spec, robot: SpineRobot, links: list, interference: bool, wrap: str) -> None:
    model, sensor, drive = robot.model, robot.sensor, DCMotorDrive(robot.motors)
    muscles = model.muscles
    rest = model.lengths(np.zeros(3 * model.n))
    middle = (model.n + 1) // 2
    R_rest, p_rest, _ = model.chain.frames(np.zeros(3 * model.n))
    if interference:
        shape = mujoco.mjtGeom.mjGEOM_SPHERE if wrap == "sphere" else mujoco.mjtGeom.mjGEOM_CYLINDER
        half = 0.5 * model.chain.offsets[middle, 2] if middle < model.n else 0.015  # the picture's length only
        links[middle].add_geom(name="wrap", type=shape, size=[WRAP_RADIUS_M, half, 0.0], mass=0.0,
                               rgba=[0.9, 0.6, 0.3, 0.35], contype=0, conaffinity=0)
    for j, name in enumerate(muscles.names):
        path = muscles.paths[j]
        pull_link, pull_point = path[0]
        u = _inward(pull_point)
        reel = links[pull_link].add_body(name=f"{name}:reel", pos=(np.array(pull_point) + u * REEL_OFFSET_M).tolist())
        reel.add_joint(name=f"{name}:reel", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=u.tolist(),
                       armature=drive.reflected_mass_kg[j], damping=drive.damping_n_s_m[j],
                       frictionloss=drive.backdrive_force_n[j], limited=True, range=[-0.9 * REEL_OFFSET_M, 0.2])
        reel.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.002], mass=1e-3, contype=0, conaffinity=0, group=3)
        reel.add_site(name=f"{name}:reel", size=[0.002, 0, 0])
        sites = []
        for k, (link, point) in enumerate(path):
            site = f"{name}:p{k}"
            links[link].add_site(name=site, pos=list(point), size=[0.003, 0, 0], rgba=[0.8, 0.2, 0.2, 1])
            sites.append((link, site))
        tendon = spec.add_tendon(name=name, stiffness=sensor.wire_stiffness_n_m,
                                 springlength=[0.0, rest[j] + REEL_OFFSET_M], width=0.0015,
                                 rgba=[0.85, 0.25, 0.2, 1])
        tendon.wrap_site(f"{name}:reel")
        for k, (link, site) in enumerate(sites):
            tendon.wrap_site(site)
            if interference and k + 1 < len(sites) and min(link, sites[k + 1][0]) < middle <= max(link, sites[k + 1][0]):
                a, b = (R_rest[lk] @ np.array(pt) + p_rest[lk] for lk, pt in path[k:k + 2])
                tendon.wrap_geom("wrap", _side_site(links[middle], name, a, b, p_rest[middle]))
        spec.add_actuator(name=f"{name}:motor", target=f"{name}:reel", trntype=mujoco.mjtTrn.mjTRN_JOINT,
                          gear=[drive.stall_force_n[j], 0, 0, 0, 0, 0], ctrllimited=True, ctrlrange=[-1.0, 1.0])


def _add_ligaments(spec, links: list, ligaments: LigamentSpec) -> None:
    """Kenta's ligaments (§3.7.1) as extension springs: a spatial tendon between the two anchor
    sites with stiffness k and ``springlength = (0, natural length)``, so it pulls only when
    stretched past its natural length (pre-stretched at rest: the chosen natural lengths are 1–2 mm
    short, :func:`~shintai.spine.robots._kenta_ligaments`)."""
    names, paths = ligaments.springs.names, ligaments.springs.paths
    for j, name in enumerate(names):
        tendon = spec.add_tendon(name=name, stiffness=float(ligaments.stiffness_n_m[j]),
                                 springlength=[0.0, float(ligaments.natural_length_m[j])], width=0.0008,
                                 rgba=[0.3, 0.6, 0.3, 1])
        for k, (link, point) in enumerate(paths[j]):
            site = f"{name}:p{k}"
            links[link].add_site(name=site, pos=list(point), size=[0.002, 0, 0], group=3)
            tendon.wrap_site(site)


def _side_site(link, name: str, a, b, centre) -> str:
    """A site beside the wrap sphere on the side where the segment a–b passes it at rest (MuJoCo's
    ``sidesite``: the tendon wraps around that side)."""
    t = np.clip(np.dot(centre - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0)
    offset = a + t * (b - a) - centre
    offset[2] = 0.0
    direction = offset / max(np.linalg.norm(offset), 1e-9)
    site = f"{name}:side"
    link.add_site(name=site, pos=(direction * 2 * WRAP_RADIUS_M).tolist(), size=[0.001, 0, 0], group=3)
    return site


def _add_hand(spec, robot: SpineRobot, top) -> None:
    """A mocap 'hand' at the top link's rest pose, welded to it when active (inactive at start)."""
    R, p, _ = robot.model.chain.frames(np.zeros(3 * robot.n))
    hand = spec.worldbody.add_body(name="hand", mocap=True, pos=(p[-1] + [0, 0, PELVIS_HEIGHT_M]).tolist(),
                                   quat=_quat(R[-1]).tolist())
    hand.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.008], rgba=[0.95, 0.75, 0.6, 0.6], contype=0,
                  conaffinity=0, group=2)
    spec.add_equality(name="hand", type=mujoco.mjtEq.mjEQ_WELD, name1="hand", name2=top.name,
                      objtype=mujoco.mjtObj.mjOBJ_BODY, active=False, solref=list(HAND_SOLREF))


class SpineBody(MujocoBody):
    """A :class:`MujocoBody` of a muscle-driven spine with the muscle sensors of §3.6.

    Snapshot adds: ``encoder`` (m,) wire wound in since the encoder zero [m, quantised];
    ``tension`` (m,) the tension sensors' reading [N]; ``tension_true`` (m,); ``current`` (m,)
    motor currents [A]; ``posture`` (2,) (roll, pitch) of the top link seen from the pelvis by the
    accelerometers (eq. 3.4) [rad]; ``theta`` (3n,) the true joint angles (eq. 4.1) [rad];
    ``lengths`` (m,) the muscles' external path lengths [m] (eq. 4.25 when nothing wraps).
    Command: ``duty`` (m,) PWM duties o ∈ [−1, 1] (o > 0 winds in), besides MujocoBody's channels;
    ``hand`` (3n,), a set channel: the hand holds the top link at its pose for posture θ this tick,
    and lets go on a tick nobody writes it (:meth:`hold`).
    """

    def __init__(self, robot: SpineRobot, loads: tuple[Load, ...] | None = None, joint: str = "hinge",
                 interference: bool = True, timestep: float = 5e-4, control_period: float | None = None,
                 ligaments: LigamentSpec | None = None, spec: mujoco.MjSpec | None = None, wrap: str = "sphere"):
        period = control_period if control_period is not None else robot.control_period_s
        substeps = whole_multiple(period, timestep, "control period")
        self.robot = robot
        self.joint_type = joint
        self.drive = DCMotorDrive(robot.motors)
        self.encoder = Encoder(robot.motors)
        self.sensor = TensionSensor(robot.sensor)
        if spec is None:  # a whole body (cla_body) passes its own spec, built on build_spec's spine
            spec = build_spec(robot, loads, joint, interference, timestep, ligaments, wrap)
        super().__init__(spec, substeps=substeps)
        self.channels = {**self.channels, **declare("duty"), **declare("hand", kind=SET)}
        m = self.model
        names = robot.muscle_names
        self.tendon_ids = np.array([mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_TENDON, nm) for nm in names])
        reels = [self.id("joint", f"{nm}:reel") for nm in names]
        self._reel_q = m.jnt_qposadr[reels]
        self._reel_v = m.jnt_dofadr[reels]
        self._motor = np.array([self.id("actuator", f"{nm}:motor") for nm in names])
        self._free_length = m.tendon_lengthspring[self.tendon_ids, 1].copy()
        self._k_wire = m.tendon_stiffness[self.tendon_ids].copy()
        self._reel_offset = REEL_OFFSET_M
        self.spine_qpos = self._spine_qpos_addresses()  # θ's qpos addresses, in eq. 4.1's order
        self._acc = (self._views_of("acc_chest"), self._views_of("acc_waist"))
        self._hand = self.id("equality", "hand")
        self._hand_mocap = m.body_mocapid[self.id("body", "hand")]
        self._pelvis = self.id("body", "link0")
        self._spine_views = [(key, where) for key, where in self._views if not key.startswith(("q:", "dq:"))]

    # -- layout helpers ---------------------------------------------------------------------------

    def _spine_qpos_addresses(self) -> np.ndarray:
        n = self.robot.n
        if self.joint_type == "hinge":
            order = [f"j{i}_{ax}" for i in range(1, n + 1) for ax in ("roll", "pitch", "yaw")]
            return self.model.jnt_qposadr[[self.id("joint", nm) for nm in order]]
        return self.model.jnt_qposadr[[self.id("joint", f"j{i}") for i in range(1, n + 1)]]

    def _views_of(self, sensor: str) -> slice:
        i = self.id("sensor", sensor)
        adr = self.model.sensor_adr[i]
        return slice(adr, adr + self.model.sensor_dim[i])

    # -- state ------------------------------------------------------------------------------------

    def theta(self) -> np.ndarray:
        """The true posture θ (3n,) [rad] (eq. 4.1)."""
        q = self.data.qpos
        if self.joint_type == "hinge":
            return q[self.spine_qpos]  # fancy indexing copies
        mats = np.zeros((self.robot.n, 9))
        for i, adr in enumerate(self.spine_qpos):
            mujoco.mju_quat2Mat(mats[i], q[adr:adr + 4])
        return matrix_rpy(mats.reshape(-1, 3, 3)).reshape(-1)

    def set_theta(self, theta) -> None:
        """Put the spine at posture θ with the reels at rest (for tests and initial states)."""
        theta = np.asarray(theta, dtype=float)
        q = self.data.qpos
        if self.joint_type == "hinge":
            q[self.spine_qpos] = theta
        else:
            for i, adr in enumerate(self.spine_qpos):
                q[adr:adr + 4] = _quat(rpy_matrix(theta[3 * i:3 * i + 3]))
        self.data.qvel[:] = 0.0
        self.forward()

    def wound(self) -> np.ndarray:
        """Wire wound in by each reel since the start, s [m] (the reel joints' qpos)."""
        return self.data.qpos[self._reel_q].copy()

    def path_lengths(self) -> np.ndarray:
        """The muscles' external path lengths: tendon length minus the wire inside the block."""
        return self.data.ten_length[self.tendon_ids] - self._reel_offset - self.data.qpos[self._reel_q]

    def wire_tension(self) -> np.ndarray:
        """True wire tension [N]: k_w · max(0, tendon length − free length)."""
        return self._k_wire * np.maximum(self.data.ten_length[self.tendon_ids] - self._free_length, 0.0)

    def reel_speed(self) -> np.ndarray:
        return self.data.qvel[self._reel_v].copy()

    def currents(self) -> np.ndarray:
        return self.drive.current(self.data.ctrl[self._motor], self.data.qvel[self._reel_v])

    def zero_encoders(self) -> None:
        """Encoder zero calibration (§4.6.4): the present reels read zero."""
        self.encoder.set_zero(self.wound())

    # -- disc and hand ----------------------------------------------------------------------------

    def set_disc(self, k_bend: float, k_twist: float | None = None) -> None:
        """Change the disc stiffness at run time [N m/rad] (a stiffer or softer spine)."""
        k_twist = k_bend if k_twist is None else k_twist
        for jnt in range(self.model.njnt):
            name = mujoco.mj_id2name(self.model, mujoco.mjtObj.mjOBJ_JOINT, jnt) or ""
            if name.startswith("j") and ":" not in name:
                self.model.jnt_stiffness[jnt] = k_twist if name.endswith("_yaw") else k_bend

    def hold(self, theta=None) -> None:
        """A human hand holds the top link at the pose it has at posture θ (3n,), or lets go (None):
        what the ``hand`` channel does each tick (:meth:`apply`)."""
        if theta is None:
            self.data.eq_active[self._hand] = False
            return
        R, p, _ = self.robot.model.chain.frames(np.asarray(theta, dtype=float))
        pelvis = self._pelvis  # the pose relative to the pelvis where it is now (fixed, or free when standing)
        R0 = self.data.xmat[pelvis].reshape(3, 3)
        self.data.mocap_pos[self._hand_mocap] = self.data.xpos[pelvis] + R0 @ p[-1]
        self.data.mocap_quat[self._hand_mocap] = _quat(R0 @ R[-1])
        self.data.eq_active[self._hand] = True

    # -- Body interface ---------------------------------------------------------------------------

    def snapshot(self):
        """MujocoBody's snapshot (t, qpos, qvel, ctrl, the accelerometers) without its per-joint
        ``q:``/``dq:`` scalars (θ is ``theta``; the reels are ``encoder``) — they cost a tenth of
        the 1 ms tick — plus the muscle sensors (class docstring)."""
        d = self.data
        values = np.concatenate((d.qpos, d.qvel, d.ctrl, d.sensordata))
        snap = {"t": d.time}
        for key, where in self._spine_views:
            snap[key] = values[where]
        reel = d.qpos[self._reel_q]
        ten = d.ten_length[self.tendon_ids]
        tension = self._k_wire * np.maximum(ten - self._free_length, 0.0)  # = wire_tension()
        snap["encoder"] = self.encoder.read(reel)
        snap["tension"] = self.sensor.read(tension)
        snap["tension_true"] = tension
        snap["current"] = self.drive.current(d.ctrl[self._motor], d.qvel[self._reel_v])  # = currents()
        chest, waist = self._acc
        snap["posture"] = posture_from_accelerometers(d.sensordata[chest], d.sensordata[waist])
        snap["theta"] = self.theta()
        snap["lengths"] = ten - self._reel_offset - reel  # = path_lengths()
        return snap

    def apply(self, command) -> None:
        hand = command.get("hand")
        if hand is not None or self.data.eq_active[self._hand]:
            self.hold(hand)
        duty = command.get("duty")
        if duty is not None:
            duty = np.asarray(duty, dtype=float)
            if duty.shape != self._motor.shape:
                raise ValueError(f"command 'duty' has shape {duty.shape}, the spine has {self._motor.size} muscles")
            self.data.ctrl[self._motor] = np.minimum(np.maximum(duty, -1.0), 1.0)  # = np.clip, NaN included
        if len(command) > ("hand" in command) + ("duty" in command):
            super().apply({k: v for k, v in command.items() if k not in ("hand", "duty")})
