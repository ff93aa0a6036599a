"""Cla on the floor crawling on hands and knees, and the crawl whose spine roll a GA evolves (seed 003 §5.2.9,
Figs. 5.10–5.11; the model is Cla of §3.6 as a free body; §5.4.5's fast physics environment is MuJoCo here).

**The model** (:func:`build_spec`): a free pelvis, the spine's five joints (§3.6.1) as three hinges each in the
thesis's rpy order (yaw, pitch, roll: :mod:`shintai.spine.bodies_mujoco`'s convention) with the ±18° stops and
the silicone disc's stiffness and damping of :data:`~shintai.spine.robots.CLA`, the clavicle with head and two
arms (shoulder pitch, elbow), two legs (hip, knee) kneeling with the shins on the floor, and floor contacts with
friction. Constants: the ``CRAWL_*`` block of :mod:`shintai.spine.robots` (each with its source). The robot's
frame (x belly, y left, z toward the head) lies on the floor as x down, z forward: the spine's **roll** axis
(x, §4.3.1) is vertical, so a positive roll bends the head end to the right in the floor plane (lateral
flexion); pitch arches the back up or down, yaw twists about the spine.

**The spine is position-servoed joint by joint, not driven by its eight muscles.** The GA evaluates thousands
of 8-s crawls; the tendon model of :mod:`~shintai.spine.bodies_mujoco` needs 0.5-ms steps, reels and a
controller per step. The thesis's GA genes are posture-level commands (the spine's roll amounts and timings,
§5.2.9) that the muscles realise through the inverse model (§4.4), and its GA ran in FAST/Vortex, which
"回転関節と剛体から成る" bodies with "脊椎の 3 自由度球面関節のクラス" added (§5.4.5) — joints, not muscles.
So the posture is servoed directly (a stiff servo per joint axis, limited to a torque the muscles can give);
what is lost is the muscles' own compliance and co-contraction. The **rigid spine** is the same model with
every spine hinge locked at 0 by an equality constraint (:func:`model` ``lock_spine=True``): a trunk without a
spine, whose holding costs no actuator torque.

**The crawl** (:func:`controls`): four phases, one limb swinging in each (right arm, left knee, left arm,
right knee), the other three pushing back a third of their stroke per phase. The genes (§5.2.9: "脊椎の roll
方向の変形量と変形のタイミング … を正規化し, これを遺伝子とし"; the limbs "脊椎の変形タイミングにあわせて,
スピードが変わるようにした") are 8 numbers in [0, 1]: the spine's roll at the end of each phase (all five
joints alike, 0 → −18°, 1 → +18°) and each phase's duration (0 → 0.25 s, 1 → 1.25 s); within a phase the
spine moves from the previous phase's roll to its own by a cosine blend and the limbs' fixed motion is
stretched to the phase's duration. Fitness (§5.2.9: "(1) 前進量, (2) トルクの積分値, (3) 動作中の最大トルク,
の三種類の評価関数の線形和") = forward distance − :data:`W_TORQUE_INTEGRAL` × torque integral −
:data:`W_PEAK_TORQUE` × peak torque over :data:`~shintai.spine.robots.CRAWL_EVAL_S`.

**Evaluation** (:func:`evaluate`): the control tables are built with numpy and rolled out by
``mujoco.rollout`` from one settled state, one ``MjData`` per worker process: no Python per physics step.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import mujoco
import numpy as np
from mujoco import rollout

from shintai.sim.spec import add_capsule, add_position_actuator
from shintai.spine.cla.constants import FAILED_FITNESS, MAX_STEP_M, PHASES, SPINE_KV, W_PEAK_TORQUE, W_TORQUE_INTEGRAL
from shintai.spine.robots import (
    CLA,
    CLA_ARMS_DOWN,
    CLA_FIRST_BALL_M,
    CLA_JOINTS,
    CLA_LIMIT_RAD,
    CLA_SEGMENT_M,
    CLA_TRUNK_LOADS,
    CRAWL_ARM_KG,
    CRAWL_ELBOW_FLEX_DEG,
    CRAWL_EVAL_S,
    CRAWL_FOREARM_M,
    CRAWL_FRICTION,
    CRAWL_HAND_LIFT_M,
    CRAWL_HAND_MADE_PHASE_S,
    CRAWL_HAND_MADE_ROLL_DEG,
    CRAWL_HAND_RADIUS_M,
    CRAWL_HAND_STROKE_M,
    CRAWL_HIP_DROP_M,
    CRAWL_HIP_HALF_WIDTH_M,
    CRAWL_KNEE_RADIUS_M,
    CRAWL_LEG_KG,
    CRAWL_LIMB_KP,
    CRAWL_LIMB_KV,
    CRAWL_LIMB_TORQUE_NM,
    CRAWL_PELVIS_HALF_M,
    CRAWL_PHASE_S,
    CRAWL_SETTLE_S,
    CRAWL_SHIN_LIFT_DEG,
    CRAWL_SHIN_M,
    CRAWL_SHOULDER_ABOVE_BALL_M,
    CRAWL_SPINE_KP,
    CRAWL_SPINE_TORQUE_NM,
    CRAWL_THIGH_M,
    CRAWL_THIGH_STROKE_DEG,
    CRAWL_TIMESTEP_S,
    CRAWL_UPPER_ARM_M,
)

LIMBS = ("arm_r", "leg_l", "arm_l", "leg_r")  # the limb swinging in phase k (the infants' lateral sequence)
N_GENES = 2 * PHASES  # roll amounts, then durations
AXES = ("yaw", "pitch", "roll")
SPINE_JOINTS = tuple(f"j{i + 1}_{a}" for i in range(CLA_JOINTS) for a in AXES)
LIMB_JOINTS = ("shoulder_r", "elbow_r", "shoulder_l", "elbow_l", "hip_r", "knee_r", "hip_l", "knee_l")
ACTUATED = LIMB_JOINTS + SPINE_JOINTS

# Where the limbs attach (trunk frame: x toward the head, y left, z toward the back)
PELVIS_TO_BALL1 = CRAWL_PELVIS_HALF_M[0] + CLA_FIRST_BALL_M
# the shoulders (in the clavicle link) sit beside and in front of the spine as in CLA_ARMS_* (robot x front = −z)
SHOULDER = (CRAWL_SHOULDER_ABOVE_BALL_M, CLA_ARMS_DOWN[1].com_m[1], -CLA_ARMS_DOWN[1].com_m[0])
HIP = (0.0, CRAWL_HIP_HALF_WIDTH_M, -CRAWL_HIP_DROP_M)  # in the pelvis
TRUNK_M = PELVIS_TO_BALL1 + (CLA_JOINTS - 1) * CLA_SEGMENT_M + SHOULDER[0]  # hip to shoulder along the spine
PALM_DROP_M = math.sqrt(CRAWL_UPPER_ARM_M ** 2 + CRAWL_FOREARM_M ** 2
                        + 2 * CRAWL_UPPER_ARM_M * CRAWL_FOREARM_M * math.cos(math.radians(CRAWL_ELBOW_FLEX_DEG)))


def trunk_pitch() -> float:
    """The trunk's head-up pitch β [rad] on hands and knees: thighs vertical with the knee pads on the floor,
    palms under the shoulders with the elbows bent :data:`CRAWL_ELBOW_FLEX_DEG`, the spine straight."""
    dz = (CRAWL_HAND_RADIUS_M + PALM_DROP_M) - (CRAWL_THIGH_M + CRAWL_KNEE_RADIUS_M)
    a, b = TRUNK_M, SHOULDER[2] - HIP[2]  # a sin β + b cos β = dz
    return math.asin(dz / math.hypot(a, b)) - math.atan2(b, a)


BETA = trunk_pitch()


def build_spec() -> mujoco.MjSpec:
    """Cla kneeling on hands and knees (see the module docstring); every spine hinge also has a joint-equality
    lock at 0, inactive (``lock_spine`` of :func:`model` activates them)."""
    spec = mujoco.MjSpec()
    spec.modelname = "cla_crawl"
    spec.compiler.degree = False  # joint ranges in radians (MjSpec's default unit is degrees)
    spec.option.timestep = CRAWL_TIMESTEP_S
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.visual.global_.offwidth, spec.visual.global_.offheight = 640, 480
    spec.visual.headlight.ambient = [0.4, 0.4, 0.4]
    world = spec.worldbody
    world.add_light(pos=[0.5, -1.0, 2.0], dir=[-0.2, 0.5, -1.0], diffuse=[0.8, 0.8, 0.8])
    spec.add_texture(name="grid", type=mujoco.mjtTexture.mjTEXTURE_2D, builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER,
                     rgb1=[0.85, 0.85, 0.87], rgb2=[0.72, 0.73, 0.76], width=256, height=256)
    spec.add_material(name="grid", textures=["", "grid"], texrepeat=[10, 10], texuniform=True)  # 10-cm squares
    world.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[5, 5, 0.05], material="grid",
                   contype=0, conaffinity=1, friction=[CRAWL_FRICTION, 0.005, 1e-4])
    grey, bone, limb = [0.45, 0.45, 0.5, 1], [0.93, 0.9, 0.8, 1], [0.55, 0.6, 0.75, 1]
    pelvis = world.add_body(name="pelvis", pos=[0, 0, 0.3])
    pelvis.add_freejoint(name="root")
    pelvis.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=list(CRAWL_PELVIS_HALF_M), mass=CLA.link_mass_kg[0],
                    rgba=grey, contype=1, conaffinity=0)
    pelvis.add_site(name="pelvis", size=[0.005, 0, 0])
    r = CLA.vertebra_radius_m
    link, disc = pelvis, CLA.disc
    for i in range(CLA_JOINTS):
        link = link.add_body(name=f"link{i + 1}", pos=[PELVIS_TO_BALL1 if i == 0 else CLA_SEGMENT_M, 0, 0])
        for axis_name, axis, k in (("yaw", [1, 0, 0], disc.k_twist_nm_rad), ("pitch", [0, 1, 0], disc.k_bend_nm_rad),
                                   ("roll", [0, 0, -1], disc.k_bend_nm_rad)):
            name = f"j{i + 1}_{axis_name}"
            link.add_joint(name=name, type=mujoco.mjtJoint.mjJNT_HINGE, axis=axis, stiffness=k,
                           damping=disc.damping_nms_rad, armature=1e-4, limited=True,
                           range=[-CLA_LIMIT_RAD, CLA_LIMIT_RAD])
            spec.add_equality(name=f"lock_{name}", type=mujoco.mjtEq.mjEQ_JOINT, name1=name, active=False,
                              solref=[0.004, 1.0], solimp=[0.99, 0.999, 0.001, 0.5, 2])
        link.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[r], mass=1e-3, rgba=[0.7, 0.7, 0.75, 1],
                      contype=1, conaffinity=0)
        mass = CLA.link_mass_kg[i + 1]
        if mass > 0:
            add_capsule(link, [CLA_SEGMENT_M, 0, 0], 0.6 * r, mass, bone, contype=1)
    clav = link  # the robot's (x, y, z) load offsets are the trunk's (−z, y, x)
    for load in CLA_TRUNK_LOADS:
        (lx, ly, lz), (sx, sy, sz) = load.com_m, load.size_m
        clav.add_geom(name=load.name, type=mujoco.mjtGeom.mjGEOM_BOX, size=[sz, sy, sx], pos=[lz, ly, -lx],
                      mass=load.mass_kg, rgba=grey, contype=1, conaffinity=0)
    clav.add_site(name="clavicle", size=[0.005, 0, 0])
    for side in ("r", "l"):
        s = -1 if side == "r" else 1
        upper = clav.add_body(name=f"upper_arm_{side}", pos=[SHOULDER[0], s * SHOULDER[1], SHOULDER[2]])
        upper.add_joint(name=f"shoulder_{side}", axis=[0, -1, 0], range=[-2.2, 2.2], limited=True,
                        damping=0.02, armature=1e-4)
        add_capsule(upper, [0, 0, -CRAWL_UPPER_ARM_M], 0.012, CRAWL_ARM_KG[0], limb, contype=1)
        fore = upper.add_body(name=f"forearm_{side}", pos=[0, 0, -CRAWL_UPPER_ARM_M])
        fore.add_joint(name=f"elbow_{side}", axis=[0, -1, 0], range=[0.0, 2.6], limited=True, damping=0.02,
                       armature=1e-4)
        add_capsule(fore, [0, 0, -CRAWL_FOREARM_M], 0.01, CRAWL_ARM_KG[1] * 0.5, limb, contype=1)
        fore.add_geom(name=f"palm_{side}", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[CRAWL_HAND_RADIUS_M],
                      pos=[0, 0, -CRAWL_FOREARM_M], mass=CRAWL_ARM_KG[1] * 0.5, rgba=limb, contype=1,
                      conaffinity=0)
        thigh = pelvis.add_body(name=f"thigh_{side}", pos=[HIP[0], s * HIP[1], HIP[2]])
        thigh.add_joint(name=f"hip_{side}", axis=[0, -1, 0], range=[-1.8, 1.8], limited=True, damping=0.02,
                        armature=1e-4)
        add_capsule(thigh, [0, 0, -CRAWL_THIGH_M], 0.018, CRAWL_LEG_KG[0], limb, contype=1)
        shin = thigh.add_body(name=f"shin_{side}", pos=[0, 0, -CRAWL_THIGH_M])
        shin.add_joint(name=f"knee_{side}", axis=[0, -1, 0], range=[-2.8, 0.2], limited=True, damping=0.02,
                       armature=1e-4)
        shin.add_geom(name=f"knee_{side}", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[CRAWL_KNEE_RADIUS_M], mass=0.02,
                      rgba=limb, contype=1, conaffinity=0)
        add_capsule(shin, [0, 0, -CRAWL_SHIN_M], 0.015, CRAWL_LEG_KG[1], limb, contype=1)
    for joint in LIMB_JOINTS:
        add_position_actuator(spec, joint, CRAWL_LIMB_KP, CRAWL_LIMB_KV, CRAWL_LIMB_TORQUE_NM)
    for joint in SPINE_JOINTS:
        add_position_actuator(spec, joint, CRAWL_SPINE_KP, SPINE_KV, CRAWL_SPINE_TORQUE_NM)
    for name, obj in (("pelvis_pos", "pelvis"), ("clavicle_pos", "clavicle")):
        spec.add_sensor(name=name, type=mujoco.mjtSensor.mjSENS_FRAMEPOS, objtype=mujoco.mjtObj.mjOBJ_SITE,
                        objname=obj)
    spec.add_sensor(name="pelvis_xaxis", type=mujoco.mjtSensor.mjSENS_FRAMEXAXIS, objtype=mujoco.mjtObj.mjOBJ_SITE,
                    objname="pelvis")
    for joint in ACTUATED:
        spec.add_sensor(name=f"tau_{joint}", type=mujoco.mjtSensor.mjSENS_ACTUATORFRC,
                        objtype=mujoco.mjtObj.mjOBJ_ACTUATOR, objname=joint)
    for joint in SPINE_JOINTS:
        spec.add_sensor(name=f"q_{joint}", type=mujoco.mjtSensor.mjSENS_JOINTPOS, objtype=mujoco.mjtObj.mjOBJ_JOINT,
                        objname=joint)
    return spec


# sensordata columns
S_PELVIS, S_CLAVICLE, S_XAXIS, S_TAU = slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 9 + len(ACTUATED))
S_SPINE = slice(S_TAU.stop, S_TAU.stop + len(SPINE_JOINTS))
ROLL_COLUMNS = [S_SPINE.start + SPINE_JOINTS.index(f"j{i + 1}_roll") for i in range(CLA_JOINTS)]
N_LIMB = len(LIMB_JOINTS)


def limb_targets(c: np.ndarray, lift: np.ndarray, limb: str) -> tuple[np.ndarray, np.ndarray]:
    """The two joint targets of ``limb`` for stroke ``c`` ∈ [−1, 1] (back → front) and lift ∈ [0, 1]: arms by
    planar inverse kinematics of the palm (relative to the shoulder: fore–aft ``c`` × stroke, down
    :data:`PALM_DROP_M` − lift), legs as the thigh's swing about vertical and the shin's lift about the knee;
    joint angle = the link's angle from straight down (forward positive) − the trunk's pitch β."""
    if limb.startswith("arm"):
        dx, dz = CRAWL_HAND_STROKE_M * c, -PALM_DROP_M + CRAWL_HAND_LIFT_M * lift
        L1, L2 = CRAWL_UPPER_ARM_M, CRAWL_FOREARM_M
        d2 = dx * dx + dz * dz
        flex = np.arccos(np.clip((d2 - L1 * L1 - L2 * L2) / (2 * L1 * L2), -1.0, 1.0))
        upper = np.arctan2(dx, -dz) - np.arctan2(L2 * np.sin(flex), L1 + L2 * np.cos(flex))
        return upper - BETA, flex
    thigh = math.radians(CRAWL_THIGH_STROKE_DEG) * c
    shin = -math.pi / 2 - math.radians(CRAWL_SHIN_LIFT_DEG) * lift
    return thigh - BETA, shin - thigh


def decode(genes) -> tuple[np.ndarray, np.ndarray]:
    """Genes (8 numbers in [0, 1]) → the spine's roll per joint at the end of each phase [rad] and the phases'
    durations [s]."""
    g = np.clip(np.asarray(genes, dtype=float), 0.0, 1.0)
    roll = (2.0 * g[:PHASES] - 1.0) * CLA_LIMIT_RAD
    lo, hi = CRAWL_PHASE_S
    return roll, lo + (hi - lo) * g[PHASES:]


def encode(roll_deg, durations_s) -> np.ndarray:
    """The genes of a pattern given by its per-joint roll [deg] and phase durations [s] (inverse of decode)."""
    lo, hi = CRAWL_PHASE_S
    roll = np.radians(np.asarray(roll_deg, dtype=float))
    return np.concatenate([(roll / CLA_LIMIT_RAD + 1.0) / 2.0, (np.asarray(durations_s, dtype=float) - lo) / (hi - lo)])


HAND_MADE = encode([-CRAWL_HAND_MADE_ROLL_DEG, -CRAWL_HAND_MADE_ROLL_DEG, CRAWL_HAND_MADE_ROLL_DEG,
                    CRAWL_HAND_MADE_ROLL_DEG], [CRAWL_HAND_MADE_PHASE_S] * PHASES)
"""The hand-made pattern (Fig. 5.10): the spine bends head-left (right shoulder ahead) while the right arm
swings and holds it while the left knee comes forward (the left side short), then the mirror image."""
RIGID = encode([0.0] * PHASES, [CRAWL_HAND_MADE_PHASE_S] * PHASES)
"""The rigid-spine baseline's genes: the hand-made limb timing with the spine straight (run with the lock)."""


def schedule(genes, t: np.ndarray) -> dict[str, np.ndarray]:
    """The pattern at times ``t`` [s] from its start: ``phase`` (k), ``u`` (progress in the phase), the spine
    roll per joint ``roll`` [rad] (from 0 in the first phase, then from the previous phase's roll), and each
    limb's stroke ``c_<limb>`` and lift ``lift_<limb>``."""
    roll_keys, dur = decode(genes)
    t = np.asarray(t, dtype=float)
    period = dur.sum()
    cycle, tc = np.divmod(t, period)
    starts = np.concatenate([[0.0], np.cumsum(dur)[:-1]])
    k = np.clip(np.searchsorted(starts, tc, side="right") - 1, 0, PHASES - 1)
    u = np.clip((tc - starts[k]) / dur[k], 0.0, 1.0)
    blend = 0.5 * (1.0 - np.cos(np.pi * u))
    prev = np.where((k == 0) & (cycle == 0), 0.0, roll_keys[(k - 1) % PHASES])
    out = {"phase": k, "u": u, "roll": prev + (roll_keys[k] - prev) * blend}
    for i, limb in enumerate(LIMBS):
        m = (k - i) % PHASES  # 0: swinging, 1..3: phases of stance since the swing
        swing = m == 0
        out[f"c_{limb}"] = np.where(swing, -np.cos(np.pi * u), 1.0 - 2.0 / 3.0 * (m - 1 + u))
        out[f"lift_{limb}"] = np.where(swing, np.sin(np.pi * u), 0.0)
    return out


def controls(genes, duration: float = CRAWL_EVAL_S, dt: float = CRAWL_TIMESTEP_S) -> np.ndarray:
    """The servo targets (steps × actuators, in :data:`ACTUATED` order) of the crawl ``genes`` for ``duration``."""
    t = np.arange(round(duration / dt)) * dt
    s = schedule(genes, t)
    u = np.zeros((len(t), len(ACTUATED)))
    for limb in LIMBS:
        a, b = limb_targets(s[f"c_{limb}"], s[f"lift_{limb}"], limb)
        side = "r" if limb.endswith("_r") else "l"
        first, second = ("shoulder", "elbow") if limb.startswith("arm") else ("hip", "knee")
        u[:, ACTUATED.index(f"{first}_{side}")] = a
        u[:, ACTUATED.index(f"{second}_{side}")] = b
    for i in range(CLA_JOINTS):
        u[:, ACTUATED.index(f"j{i + 1}_roll")] = s["roll"]
    return u


def start_posture() -> np.ndarray:
    """The servo targets at the pattern's first instant (the posture the body settles in)."""
    return controls(HAND_MADE, duration=CRAWL_TIMESTEP_S)[0]


@functools.lru_cache(maxsize=2)
def model(lock_spine: bool = False) -> mujoco.MjModel:
    """The compiled crawl model; ``lock_spine`` makes every spine hinge's equality lock active (the rigid
    spine: the trunk cannot bend)."""
    m = build_spec().compile()
    lock(m, lock_spine)
    return m


def lock(m: mujoco.MjModel, lock_spine: bool) -> None:
    """Lock (or free) the spine of a compiled crawl model: the equality locks on, and the spine servos
    removed (zero gain: a rigid trunk has no spine actuators, so it spends no torque holding itself)."""
    m.eq_active0[:] = 1 if lock_spine else 0
    spine = [m.actuator(j).id for j in SPINE_JOINTS]
    kp = 0.0 if lock_spine else CRAWL_SPINE_KP
    m.actuator_gainprm[spine, 0] = kp
    m.actuator_biasprm[spine, :3] = [0.0, -kp, -SPINE_KV * (kp > 0)]


def place(m: mujoco.MjModel, d: mujoco.MjData) -> None:
    """Put the body on hands and knees at the start posture (thighs vertical, knee pads 2 mm above the floor)."""
    mujoco.mj_resetData(m, d)
    target = start_posture()
    for j, name in enumerate(ACTUATED):
        d.qpos[m.jnt_qposadr[m.joint(name).id]] = target[j]
    z = CRAWL_THIGH_M + CRAWL_KNEE_RADIUS_M - HIP[2] * math.cos(BETA) + 0.002
    d.qpos[:7] = [0.0, 0.0, z, math.cos(BETA / 2), 0.0, -math.sin(BETA / 2), 0.0]
    d.ctrl[:] = target
    mujoco.mj_forward(m, d)


def kneeling_spec() -> mujoco.MjSpec:
    """:func:`build_spec` with the start posture as its keyframe ``kneel`` (the model ``shintai model`` exports)."""
    spec = build_spec()
    m = spec.compile()
    d = mujoco.MjData(m)
    place(m, d)
    spec.add_key(name="kneel", qpos=d.qpos.tolist(), ctrl=d.ctrl.tolist())
    return spec


@functools.lru_cache(maxsize=2)
def settled_state(lock_spine: bool = False) -> np.ndarray:
    """The full physics state after :data:`CRAWL_SETTLE_S` at the start posture: every crawl starts here."""
    m = model(lock_spine)
    d = mujoco.MjData(m)
    place(m, d)
    mujoco.mj_step(m, d, round(CRAWL_SETTLE_S / m.opt.timestep))
    d.time = 0.0
    state = np.empty(mujoco.mj_stateSize(m, mujoco.mjtState.mjSTATE_FULLPHYSICS))
    mujoco.mj_getState(m, d, state, mujoco.mjtState.mjSTATE_FULLPHYSICS)
    return state


_DATA: dict[bool, mujoco.MjData] = {}  # one MjData per worker process and model


def rollout_crawls(genomes: np.ndarray, lock_spine: bool = False, duration: float = CRAWL_EVAL_S) -> np.ndarray:
    """Roll out every crawl of ``genomes`` (k × 8) from the settled state: sensordata (k × steps × sensors)."""
    m = model(lock_spine)
    d = _DATA.setdefault(lock_spine, mujoco.MjData(m))
    genomes = np.atleast_2d(genomes)
    ctrl = np.stack([controls(g, duration) for g in genomes])
    _, sensors = rollout.rollout(m, d, settled_state(lock_spine)[None], ctrl)
    return sensors


def measures(sensors: np.ndarray, dt: float = CRAWL_TIMESTEP_S) -> dict[str, np.ndarray]:
    """Per rollout: forward distance [m] (the trunk's midpoint along the start heading +x), lateral drift [m],
    heading drift [deg] (the direction travelled, from +x), the pelvis's yaw at the end [deg], the torque
    integral ∫Σ|τ| dt [N m s] (all servos; also limbs and spine apart), the peak |τ| [N m], the largest spine
    joint angle and roll angle [deg], the lowest trunk height [m] and the fitness."""
    s = np.nan_to_num(np.atleast_3d(sensors), nan=np.inf)
    mid = 0.5 * (s[:, :, S_PELVIS] + s[:, :, S_CLAVICLE])
    move = mid[:, -1] - mid[:, 0]
    tau = np.abs(s[:, :, S_TAU])
    xaxis = s[:, -1, S_XAXIS]
    out = {
        "distance_m": move[:, 0], "lateral_m": move[:, 1],
        "heading_drift_deg": np.degrees(np.arctan2(move[:, 1], move[:, 0])),
        "final_yaw_deg": np.degrees(np.arctan2(xaxis[:, 1], xaxis[:, 0])),
        "torque_integral_nms": tau.sum(axis=(1, 2)) * dt,
        "limb_torque_integral_nms": tau[:, :, :N_LIMB].sum(axis=(1, 2)) * dt,
        "spine_torque_integral_nms": tau[:, :, N_LIMB:].sum(axis=(1, 2)) * dt,
        "peak_torque_nm": tau.max(axis=(1, 2)),
        "max_spine_deg": np.degrees(np.abs(s[:, :, S_SPINE]).max(axis=(1, 2))),
        "max_roll_deg": np.degrees(np.abs(s[:, :, ROLL_COLUMNS]).max(axis=(1, 2))),
        "min_trunk_height_m": np.minimum(s[:, :, S_PELVIS][:, :, 2], s[:, :, S_CLAVICLE][:, :, 2]).min(axis=1),
    }
    fitness = out["distance_m"] - W_TORQUE_INTEGRAL * out["torque_integral_nms"] - W_PEAK_TORQUE * out["peak_torque_nm"]
    # MuJoCo resets a diverging simulation to its initial pose: a jump of the pelvis by > 5 cm in one step
    jumped = np.linalg.norm(np.diff(s[:, :, S_PELVIS], axis=1), axis=2).max(axis=1) > MAX_STEP_M
    out["fitness"] = np.where(np.isfinite(fitness) & ~jumped, fitness, FAILED_FITNESS)
    return out


def evaluate(genomes, lock_spine: bool = False, duration: float = CRAWL_EVAL_S) -> dict[str, np.ndarray]:
    """:func:`measures` of the crawls ``genomes`` (k × 8, or one genome)."""
    return measures(rollout_crawls(np.atleast_2d(genomes), lock_spine, duration))


@dataclasses.dataclass(frozen=True)
class CrawlFitness:
    """The GA's batch fitness (picklable): genomes (k × 8) → fitness (k,), the spine free."""

    duration: float = CRAWL_EVAL_S

    def __call__(self, genomes: np.ndarray) -> np.ndarray:
        return evaluate(genomes, False, self.duration)["fitness"]


def crawl_body(lock_spine: bool = False):
    """A :class:`~shintai.sim.MujocoBody` of the crawl model at the settled start (for filming)."""
    from shintai.sim.body import MujocoBody

    body = MujocoBody(build_spec())
    lock(body.model, lock_spine)
    body.data.eq_active[:] = body.model.eq_active0
    mujoco.mj_setState(body.model, body.data, settled_state(lock_spine), mujoco.mjtState.mjSTATE_FULLPHYSICS)
    mujoco.mj_forward(body.model, body.data)
    return body


def play(body, genes, duration: float = CRAWL_EVAL_S) -> None:
    """Run the crawl ``genes`` on ``body`` step by step (each ``body.step()`` feeds a video recorder)."""
    for row in controls(genes, duration, body.model.opt.timestep):
        body.data.ctrl[:] = row
        body.step()
