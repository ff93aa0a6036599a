"""SQ43 as a dynamic whole-body MuJoCo model (seed 003 §3.2.2, §5.6; spec 003-part1 §3.2).

The robot (§3.2.2): "各脚に3自由度，胴体部（脊椎部）に2自由度を配し，ロボット全体で14自由度を有する．
重量は1.9[kg]である", two 3-axis accelerometers "脊椎の前後に1個ずつ". The trunk is the shoulder part
(rigid part A1 with the front legs), the compliant spine, and the hip part (A4 with the hind legs).

**The compliant spine (our choice).** The thesis models the memory-foam spine by FEM modal reduction
(ANSYS → DADS, §5.4, §5.6.1); we do not have the mesh. Ours: the chain A1 B1 A2 B2 A3 B3 A4 of
:mod:`shintai.spine.sq43.design` with the four rigid parts A as bodies and each foam block B as a compliant
"ball joint" at its centre: three hinges (torsion about the body axis, lateral bending, vertical bending)
with the block's rotational stiffness of the quasi-static model (``sq43.SQ43Params``: k_torsion 6,
k_bend_lateral 60, k_bend_vertical 30 N·m/rad per block; chosen there, the foam is not characterised in
the text), so the dynamic spine's stiffness between the shoulder and hip ends equals the quasi-static
model's at a_i = 0 (the straight spine: 2 N·m/rad in torsion; test_sq43_body checks it). The blocks'
translational compliance is left out (rigid in translation). The servos act through the bending hinges:
servo A (lateral, styrene rods) and servo B (vertical, wires) set the rest angle of every block's lateral
or vertical hinge to a third of the commanded bend, with the block's bending stiffness as the position
gain (a spring whose rest point the servo moves, §3.2.1: the servo changes the rods' / wires' length
difference; torsion is passive, "変形の自由度を持たない受動変形軸", §3.2.3). So 14 actuated DOF (12 leg
servos + 2 spine servos) drive 18 position actuators (servo A and B each drive three hinges with one
command).

Frames: x forward, y left, z up (``sq43.py`` uses x right, y forward). Legs: LF, RF, LH, RH, each
abduction (about x), hip pitch and knee pitch (about y); a positive pitch swings the foot backward.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.sim.body import MujocoBody
from shintai.spine.robots import SQ43
from shintai.spine.sq43.design import SQ43Params

LEGS = ("LF", "RF", "LH", "RH")
LEG_JOINTS = ("abd", "hip", "knee")
SPINE_AXES = (("twist", (1, 0, 0)), ("lat", (0, 0, 1)), ("vert", (0, 1, 0)))


@dataclass(frozen=True)
class SQ43BodySpec:
    """Dimensions and masses of the MuJoCo SQ43. Only the total mass, the DOF and the foam block length are
    the thesis's; every other number is chosen (the text gives no dimensions) and says why."""

    mass_kg: float = SQ43.mass_kg  # §3.2.2
    spine_length_m: float = SQ43.spine_length_m  # L, chosen in robots.SQ43 (not in the text)
    block_length_m: float = SQ43.foam_length_m  # part B, 10 mm (§3.2.3)
    # between left and right leg roots: chosen 160 mm (sq43.py's quasi-static 100 mm tips the 218-mm-tall body over
    # sideways at a 17° shoulder roll, before any behaviour can be seen; the photos (Figs. 3.2, 5.18) show a trunk
    # about as wide as the legs are long, not measured)
    body_width_m: float = 0.16
    leg_offset_m: float = SQ43Params.leg_offset_m  # leg roots beyond the spine ends (chosen, as sq43.py)
    # chosen: each 120 mm, so the GA's natural length 208–228 mm (§5.6.2) leaves the knee bent (reach 252 mm
    # with the foot sphere) — the natural length is "脚が接地しているときの脚先と脚根本の鉛直方向の距離"
    thigh_m: float = 0.120
    shank_m: float = 0.120
    foot_radius_m: float = 0.012
    # masses (chosen, summing to 1.9 kg): the end parts carry the spine servos, board and battery
    shoulder_kg: float = 0.55
    hip_kg: float = 0.55
    vertebra_kg: float = 0.04  # each of the two middle rigid parts A2, A3
    coxa_kg: float = 0.05  # abduction servo + bracket, per leg
    thigh_kg: float = 0.09  # hip-pitch servo's horn + knee servo
    shank_kg: float = 0.04
    # leg servos (chosen: hobby servos of ~1 N·m; §3.2.4: "各脚のアクチュエータのトルクがそれほど大きくない")
    servo_kp_nm_rad: float = 10.0
    servo_damping_nms_rad: float = 0.15
    servo_torque_nm: float = 1.0
    servo_armature: float = 2e-3  # rotor inertia through the gear (chosen)
    # spine (sq43.SQ43Params' block stiffness per block; damping chosen: foam is lossy)
    k_torsion: float = SQ43Params.k_torsion
    k_bend_lateral: float = SQ43Params.k_bend_lateral
    k_bend_vertical: float = SQ43Params.k_bend_vertical
    spine_damping_nms_rad: float = 0.05
    spine_range_deg: float = 30.0  # a block cannot turn further (chosen)
    twist_free: bool = True  # False: no torsion hinges (an ablation: a trunk rigid in torsion)
    friction: float = 0.8  # foot–floor (chosen; DADS's contact parameters were found by trial, §5.6.3 考察)
    timestep: float = 0.002
    natural_length_m: float = 0.218  # standing height leg root → foot tip (middle of the GA range, §5.6.2)

    @property
    def part_length_m(self) -> float:
        """l of eq. 3.1 at a_i = 0: (L − 3 blocks) / 4."""
        return (self.spine_length_m - 3 * self.block_length_m) / 4

    @property
    def block_x(self) -> np.ndarray:
        """x of the three block centres (spine centre at 0, shoulder forward)."""
        l, b = self.part_length_m, self.block_length_m
        return np.array([self.spine_length_m / 2 - l - b / 2, 0.0, -(self.spine_length_m / 2 - l - b / 2)])

    @property
    def leg_x(self) -> float:
        return self.spine_length_m / 2 + self.leg_offset_m

    @property
    def total_mass_kg(self) -> float:
        return self.shoulder_kg + self.hip_kg + 2 * self.vertebra_kg + 4 * (self.coxa_kg + self.thigh_kg + self.shank_kg)


BODY = SQ43BodySpec()


def leg_root(leg: str, spec: SQ43BodySpec = BODY) -> np.ndarray:
    """The leg root in the trunk frame (spine centre, straight spine)."""
    sx = 1.0 if leg[1] == "F" else -1.0
    sy = 1.0 if leg[0] == "L" else -1.0
    return np.array([sx * spec.leg_x, sy * spec.body_width_m / 2, 0.0])


def knee_sign(leg: str) -> float:
    """Front knees point backward (elbows), hind knees forward (chosen, mammal-like)."""
    return -1.0 if leg[1] == "F" else 1.0


def build_spec(spec: SQ43BodySpec = BODY, board: bool = False, blocks=()) -> mujoco.MjSpec:
    """The MjSpec of SQ43 standing at ``spec.natural_length_m``. ``board``: a mocap board (the §3.2.4
    levelling experiment) under the left-front foot. ``blocks``: fixed boxes on the floor, each
    (x0, x1, y0, y1, height) [m] (the uneven ground of Fig. 3.8)."""
    s = mujoco.MjSpec()
    s.modelname = "sq43"
    s.compiler.degree = False  # every angle here is in radians
    s.option.timestep = spec.timestep
    s.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    s.visual.global_.offwidth, s.visual.global_.offheight = 640, 480
    world = s.worldbody
    world.add_light(pos=[0.3, -0.6, 1.5], dir=[-0.2, 0.4, -1.0], diffuse=[0.8, 0.8, 0.8])
    world.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[5, 5, 0.05], rgba=[0.8, 0.82, 0.85, 1],
                   friction=[spec.friction, 0.005, 0.0001])
    if board:
        b = world.add_body(name="board", mocap=True, pos=[spec.leg_x, spec.body_width_m / 2, -0.01])
        b.add_geom(name="board", type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.06, 0.04, 0.01], rgba=[0.7, 0.55, 0.35, 1],
                   friction=[spec.friction, 0.005, 0.0001])
    for x0, x1, y0, y1, h in blocks:
        world.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[(x1 - x0) / 2, (y1 - y0) / 2, h / 2],
                       pos=[(x0 + x1) / 2, (y0 + y1) / 2, h / 2], rgba=[0.7, 0.55, 0.35, 1],
                       friction=[spec.friction, 0.005, 0.0001])
    height = spec.natural_length_m
    x = spec.block_x
    grey = [0.45, 0.47, 0.52, 1]
    shoulder = world.add_body(name="shoulder", pos=[0, 0, height])
    shoulder.add_freejoint(name="root")
    end_len = spec.spine_length_m / 2 - x[0] + spec.leg_offset_m + 0.01
    shoulder.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[end_len / 2, spec.body_width_m / 2 + 0.01, 0.02],
                      pos=[x[0] + spec.block_length_m / 2 + end_len / 2 - 0.005, 0, 0], mass=spec.shoulder_kg, rgba=grey)
    shoulder.add_site(name="acc_shoulder", pos=[spec.spine_length_m / 2, 0, 0], size=[0.005, 0, 0])
    parent, parent_x = shoulder, 0.0
    names = ("A2", "A3", "hip")
    for k in range(3):
        body = parent.add_body(name=names[k], pos=[x[k] - parent_x, 0, 0])
        for axis_name, axis in SPINE_AXES:
            if axis_name == "twist" and not spec.twist_free:
                continue
            stiff = spec.k_torsion if axis_name == "twist" else 0.0  # bending: the servo's spring (actuator)
            lim = math.radians(spec.spine_range_deg)
            body.add_joint(name=f"B{k + 1}_{axis_name}", type=mujoco.mjtJoint.mjJNT_HINGE, axis=list(axis),
                           stiffness=stiff, damping=spec.spine_damping_nms_rad, armature=1e-5, limited=True,
                           range=[-lim, lim])
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[spec.block_length_m / 2, 0.03, 0.012],
                      rgba=[0.95, 0.85, 0.3, 0.9], mass=0.0, contype=0, conaffinity=0)  # the foam block
        if k < 2:
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[spec.part_length_m / 2, 0.025, 0.012],
                          pos=[-(spec.block_length_m + spec.part_length_m) / 2, 0, 0], mass=spec.vertebra_kg,
                          rgba=grey, contype=0, conaffinity=0)
        else:
            body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[end_len / 2, spec.body_width_m / 2 + 0.01, 0.02],
                          pos=[-(spec.block_length_m / 2 + end_len / 2 - 0.005), 0, 0], mass=spec.hip_kg, rgba=grey)
            body.add_site(name="acc_hip", pos=[-(spec.spine_length_m / 2 - x[0]), 0, 0], size=[0.005, 0, 0])
        parent, parent_x = body, x[k]
    trunk = {"F": (shoulder, 0.0), "H": (parent, x[2])}
    for leg in LEGS:
        body, bx = trunk[leg[1]]
        _add_leg(s, body, leg, leg_root(leg, spec) - [bx, 0, 0], spec)
    _add_spine_servos(s, spec)
    for name in ("acc_shoulder", "acc_hip"):
        s.add_sensor(name=name, type=mujoco.mjtSensor.mjSENS_ACCELEROMETER, objtype=mujoco.mjtObj.mjOBJ_SITE,
                     objname=name)
    for name in ("shoulder", "hip"):
        s.add_sensor(name=f"{name}_quat", type=mujoco.mjtSensor.mjSENS_FRAMEQUAT, objtype=mujoco.mjtObj.mjOBJ_BODY,
                     objname=name)
        s.add_sensor(name=f"{name}_pos", type=mujoco.mjtSensor.mjSENS_FRAMEPOS, objtype=mujoco.mjtObj.mjOBJ_BODY,
                     objname=name)
    for leg in LEGS:
        s.add_sensor(name=f"{leg}_foot", type=mujoco.mjtSensor.mjSENS_FRAMEPOS, objtype=mujoco.mjtObj.mjOBJ_SITE,
                     objname=f"{leg}_foot")
    key = s.add_key(name="stand")
    model = s.compile()
    q = np.zeros(model.nq)
    q[:3] = [0, 0, height]
    q[3] = 1.0
    stand = standing_angles(spec)
    for leg in LEGS:
        for j, name in enumerate(LEG_JOINTS):
            q[model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, f"{leg}_{name}")]] = stand[leg][j]
    key.qpos = q.tolist()
    key.ctrl = servo_ctrl(model, {leg: stand[leg] for leg in LEGS}).tolist()
    return s


def _add_leg(s: mujoco.MjSpec, trunk, leg: str, root: np.ndarray, spec: SQ43BodySpec) -> None:
    colour = [0.25, 0.35, 0.6, 1] if leg[0] == "L" else [0.6, 0.3, 0.25, 1]
    coxa = trunk.add_body(name=f"{leg}_coxa", pos=root.tolist())
    thigh = coxa.add_body(name=f"{leg}_thigh")
    shank = thigh.add_body(name=f"{leg}_shank", pos=[0, 0, -spec.thigh_m])
    for body, name, axis in ((coxa, "abd", [1, 0, 0]), (thigh, "hip", [0, 1, 0]), (shank, "knee", [0, 1, 0])):
        body.add_joint(name=f"{leg}_{name}", type=mujoco.mjtJoint.mjJNT_HINGE, axis=axis,
                       damping=spec.servo_damping_nms_rad, armature=spec.servo_armature, limited=True,
                       range=[-2.6, 2.6])
        s.add_actuator(name=f"{leg}_{name}", target=f"{leg}_{name}", trntype=mujoco.mjtTrn.mjTRN_JOINT,
                       gaintype=mujoco.mjtGain.mjGAIN_FIXED, biastype=mujoco.mjtBias.mjBIAS_AFFINE,
                       gainprm=[spec.servo_kp_nm_rad] + [0] * 9, biasprm=[0, -spec.servo_kp_nm_rad, 0] + [0] * 7,
                       forcelimited=True, forcerange=[-spec.servo_torque_nm, spec.servo_torque_nm],
                       ctrllimited=True, ctrlrange=[-2.6, 2.6])
    coxa.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.02, 0.012, 0.015], mass=spec.coxa_kg, rgba=colour,
                  contype=0, conaffinity=0)
    thigh.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, fromto=[0, 0, 0, 0, 0, -spec.thigh_m], size=[0.01, 0, 0],
                   mass=spec.thigh_kg, rgba=colour, contype=0, conaffinity=0)
    shank.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, fromto=[0, 0, 0, 0, 0, -spec.shank_m], size=[0.007, 0, 0],
                   mass=spec.shank_kg, rgba=colour, contype=0, conaffinity=0)
    shank.add_geom(name=f"{leg}_foot", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[spec.foot_radius_m, 0, 0],
                   pos=[0, 0, -spec.shank_m], mass=0.0, rgba=[0.15, 0.15, 0.15, 1],
                   friction=[spec.friction, 0.005, 0.0001], condim=3)
    shank.add_site(name=f"{leg}_foot", pos=[0, 0, -spec.shank_m - spec.foot_radius_m], size=[0.004, 0, 0])


def _add_spine_servos(s: mujoco.MjSpec, spec: SQ43BodySpec) -> None:
    """Servo A (lateral) and servo B (vertical): on each block's bending hinge a position actuator whose
    gain is the block's bending stiffness; the three share the servo's command (module docstring)."""
    for servo, axis, k in (("A", "lat", spec.k_bend_lateral), ("B", "vert", spec.k_bend_vertical)):
        for b in (1, 2, 3):
            s.add_actuator(name=f"servo{servo}_B{b}", target=f"B{b}_{axis}", trntype=mujoco.mjtTrn.mjTRN_JOINT,
                           gaintype=mujoco.mjtGain.mjGAIN_FIXED, biastype=mujoco.mjtBias.mjBIAS_AFFINE,
                           gainprm=[k] + [0] * 9, biasprm=[0, -k, 0] + [0] * 7, ctrllimited=True,
                           ctrlrange=[-math.radians(spec.spine_range_deg), math.radians(spec.spine_range_deg)])


# ------------------------------------------------------------------------------------------- kinematics

def leg_ik(leg: str, foot, spec: SQ43BodySpec = BODY) -> np.ndarray:
    """Joint angles (abd, hip, knee) [rad] that put the foot tip at ``foot`` (..., 3) relative to the leg
    root (trunk frame, straight spine). Vectorised over the leading axes; unreachable points are clipped
    to the leg's reach."""
    foot = np.asarray(foot, dtype=float)
    fx, fy, fz = foot[..., 0], foot[..., 1], foot[..., 2]
    # the foot tip is the sphere's bottom: the ankle point (sphere centre) is r above it
    fz = fz + spec.foot_radius_m
    abd = np.arctan2(fy, -fz)
    d = np.hypot(fy, fz)
    L1, L2 = spec.thigh_m, spec.shank_m
    r2 = np.clip(fx**2 + d**2, (L1 - L2) ** 2 + 1e-9, (L1 + L2) ** 2 * 0.9999)
    knee = knee_sign(leg) * np.arccos(np.clip((r2 - L1**2 - L2**2) / (2 * L1 * L2), -1.0, 1.0))
    hip = np.arctan2(-fx, d) - np.arctan2(L2 * np.sin(knee), L1 + L2 * np.cos(knee))
    return np.stack((abd, hip, knee), axis=-1)


def leg_fk(foot_angles, spec: SQ43BodySpec = BODY) -> np.ndarray:
    """Foot tip relative to the leg root for joint angles (abd, hip, knee) (..., 3) (the inverse of leg_ik)."""
    a = np.asarray(foot_angles, dtype=float)
    abd, hip, knee = a[..., 0], a[..., 1], a[..., 2]
    L1, L2 = spec.thigh_m, spec.shank_m
    x = -L1 * np.sin(hip) - L2 * np.sin(hip + knee)
    down = L1 * np.cos(hip) + L2 * np.cos(hip + knee)  # ankle below the root in the leg plane
    return np.stack((x, down * np.sin(abd), -down * np.cos(abd) - spec.foot_radius_m), axis=-1)


def standing_angles(spec: SQ43BodySpec = BODY, natural_length_m: float | None = None) -> dict[str, np.ndarray]:
    """Each leg's joint angles with the foot straight below its root at the natural length."""
    h = spec.natural_length_m if natural_length_m is None else natural_length_m
    return {leg: leg_ik(leg, [0.0, 0.0, -h], spec) for leg in LEGS}


def actuator_ids(model: mujoco.MjModel) -> tuple[np.ndarray, np.ndarray]:
    """(12 leg servo actuator ids in LEGS × LEG_JOINTS order, 6 spine actuator ids: A_B1..3, B_B1..3)."""
    legs = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, f"{leg}_{j}") for leg in LEGS for j in LEG_JOINTS]
    spine = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, f"servo{s}_B{b}") for s in "AB" for b in (1, 2, 3)]
    return np.array(legs), np.array(spine)


def servo_ctrl(model: mujoco.MjModel, legs: dict, spine_deg=(0.0, 0.0)) -> np.ndarray:
    """The ctrl vector for the 14 servos: leg angles {leg: (3,) or (T, 3)} [rad] and servo A, B bends [deg]
    (each spread evenly over the three blocks). Returns (nu,) or (T, nu)."""
    leg_ids, spine_ids = actuator_ids(model)
    angles = np.concatenate([np.asarray(legs[leg], dtype=float) for leg in LEGS], axis=-1)
    ctrl = np.zeros(angles.shape[:-1] + (model.nu,))
    ctrl[..., leg_ids] = angles
    ctrl[..., spine_ids[:3]] = math.radians(spine_deg[0]) / 3
    ctrl[..., spine_ids[3:]] = math.radians(spine_deg[1]) / 3
    return ctrl


def roll_of(quat) -> np.ndarray:
    """Roll about the body's x axis [rad] of unit quaternions (..., 4) (w, x, y, z): the tilt of the
    body's lateral axis y out of the horizontal, positive when the left side is up."""
    q = np.asarray(quat, dtype=float)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    # z component of the body's y axis in the world: 2(yz + wx)
    return np.arcsin(np.clip(2 * (y * z + w * x), -1.0, 1.0))


def relative_twist(q_shoulder, q_hip) -> np.ndarray:
    """Twist of the shoulder relative to the hip about the shoulder's x axis [rad] (the spine's torsion)."""
    qs, qh = np.asarray(q_shoulder, dtype=float), np.asarray(q_hip, dtype=float)
    # q_rel = conj(q_hip) ⊗ q_shoulder; twist angle about x = 2 atan2(x, w) of the swing-twist split
    w1, x1, y1, z1 = qh[..., 0], -qh[..., 1], -qh[..., 2], -qh[..., 3]
    w2, x2, y2, z2 = qs[..., 0], qs[..., 1], qs[..., 2], qs[..., 3]
    w = w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2
    x = w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2
    angle = 2 * np.arctan2(x, w)
    return (angle + np.pi) % (2 * np.pi) - np.pi


def accelerometer_roll(acc) -> np.ndarray:
    """Roll from a steady 3-axis accelerometer (specific force, body frame): gravity's direction
    (§3.2.4: '3軸加速度センサの情報を利用して重力方向を検知'); positive when the left side is up."""
    a = np.asarray(acc, dtype=float)
    return np.arctan2(a[..., 1], a[..., 2])  # R_x(φ)ᵀ(0, 0, g) = g (0, sin φ, cos φ)


class SQ43Body(MujocoBody):
    """The MuJoCo SQ43 (module docstring) standing on its feet, reset to the ``stand`` keyframe."""

    def __init__(self, spec: SQ43BodySpec = BODY, board: bool = False, substeps: int = 1, blocks=()):
        self.spec_values = spec
        super().__init__(build_spec(spec, board, blocks), substeps=substeps, keyframe="stand")
        self.leg_ids, self.spine_ids = actuator_ids(self.model)

    def set_servos(self, legs: dict, spine_deg=(0.0, 0.0)) -> None:
        self.data.ctrl[:] = servo_ctrl(self.model, legs, spine_deg)
