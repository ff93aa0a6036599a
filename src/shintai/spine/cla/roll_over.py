"""Cla rolls over on the floor, from lying on its back to lying on its front, yawing its spine together with the
shoulders and hips (seed 003 §5.2.8, Fig. 5.9), on the whole-body Cla of :mod:`~shintai.spine.cla.body`, with
the spine or with it locked.

§5.2.8: "股関節や肩のアクチュエータのパワーが不足しているため、股関節の力・肩の力だけでは体を捻って半身を起こすことが
できない。脊椎を yaw 軸回りに回転させる動きと肩・股関節の動きを同時に行うことで、肩・股のアクチュエータのパワーと
脊椎の回転力を合わせて、半身を起こすことができる。これにより、仰向けからうつぶせ、うつぶせから仰向けと、両方向の寝返り
ができるようになった".

**The model** (:func:`lying_spec`): cla_body's standing Cla (free pelvis), with every part of the trunk, head and
limbs made to touch the floor (cla_body lets only the hands and soles touch anything). It is calibrated upright
(§4.6.4, as the robot would be), then laid on its back (:func:`lay`).

**The behaviour** (:func:`keys`, hand-made as the thesis's were): the right arm goes overhead (out of the way of
the roll), the left arm points up and the left knee rises; the spine twists the shoulders toward the right ("半身
を起こす") while the left arm reaches across; then the spine twists back the other way with the left hip flexed
further so that the pelvis follows; the limbs return to their rest.
Locked, the same keys run with the spine held straight. The turn of a part is the angle between its front (x
axis) and the world's up: 0° on the back, 90° on a side, 180° on the front.

**The search** (:data:`GENES`, :class:`RollFitness`; issue 28): the same five keys with their angles and durations
as genes, evolved by seed 003's GA (:mod:`shintai.spine.ga_run`) from the back (supine → prone) and from the front
(:func:`lay` ``prone``, prone → supine); the hand-made keys are the genome :data:`HAND_MADE`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.scenarios.experiment import Rig, run_rig
from shintai.spine.cla.body import LIMB_JOINTS, ClaBody, build_spec, start_targets
from shintai.spine.cla.constants import CONTACT_MIN_SIZE_M, LIE_HEIGHT_M, REST_S, ROLL_OVER_YAW_DEG, ROLLED_DEG
from shintai.spine.cla.control import spine_control
from shintai.spine.cla.keyframes import Key, WholeBodyKeys
from shintai.spine.control import SETPOINTS
from shintai.spine.geometry import whole_spine
from shintai.spine.robots import CLA

VARIANTS = ("spine", "locked")


def lying_spec() -> mujoco.MjSpec:
    """The standing Cla's spec with the trunk, head and limbs colliding with the floor (module docstring)."""
    spec = build_spec("standing")
    for geom in spec.geoms:
        body = geom.parent
        if body.name == "world" or geom.contype or geom.name == "wrap" or body.name.endswith(":reel"):
            continue
        if geom.size[0] >= CONTACT_MIN_SIZE_M:
            geom.contype = 1
    return spec


def lay(body: ClaBody, prone: bool = False) -> None:
    """Put the calibrated Cla on its back (on its front if ``prone``) on the floor, head toward −x, at rest."""
    m, d = body.model, body.data
    adr = m.jnt_qposadr[body.id("joint", "root")]
    quat = np.array([math.cos(-math.pi / 4), 0.0, math.sin(-math.pi / 4), 0.0])  # the front up
    if prone:  # turned half about the long (world x) axis: the front down
        mujoco.mju_mulQuat(quat, np.array([0.0, 1.0, 0.0, 0.0]), quat.copy())
    d.qpos[adr:adr + 3] = [0.0, 0.0, LIE_HEIGHT_M]
    d.qpos[adr + 3:adr + 7] = quat
    d.qvel[:] = 0.0
    mujoco.mj_forward(m, d)


# The genes: (key, what it sets, range) — durations [s], limb servo targets [rad] (their joint ranges), whole-spine
# roll and yaw [deg] (yaw ±90° = 5 × ±18°, roll ±72° = cla ROLL_DEG). Chosen; the thesis gives no sequence.
GENES = (("raise", "duration", 0.5, 2.0), ("twist", "duration", 0.5, 2.0), ("follow", "duration", 0.5, 2.0),
         ("raise", "shoulder_pitch_r", -1.0, 3.1), ("raise", "shoulder_pitch_l", -1.0, 3.1),
         ("raise", "hip_l", -1.0, 2.2), ("raise", "knee_l", 0.0, 2.6),
         ("twist", "spine_yaw", -90.0, 90.0), ("twist", "spine_roll", -72.0, 72.0),
         ("twist", "shoulder_pitch_l", -1.0, 3.1), ("twist", "shoulder_roll_l", -0.3, 2.6),
         ("follow", "spine_yaw", -90.0, 90.0), ("follow", "spine_roll", -72.0, 72.0),
         ("follow", "hip_l", -1.0, 2.2), ("follow", "hip_r", -1.0, 2.2),
         # the posture the sequence ends in ("lie"; hand-made: every joint back to 0). Added after the first search
         # failed: its best reached the side (92°) once "lie" had straightened every joint, and fell back from there
         ("lie", "spine_yaw", -90.0, 90.0), ("lie", "spine_roll", -72.0, 72.0),
         ("lie", "shoulder_pitch_l", -1.0, 3.1), ("lie", "shoulder_roll_l", -0.3, 2.6),
         ("lie", "shoulder_pitch_r", -1.0, 3.1), ("lie", "hip_l", -1.0, 2.2), ("lie", "hip_r", -1.0, 2.2),
         ("lie", "knee_l", 0.0, 2.6))
N_GENES = len(GENES)


def encode(values: dict) -> np.ndarray:
    """A genome in [0, 1]^N from ``{(key, what): value}`` (the units of :data:`GENES`)."""
    return np.array([(values[(k, w)] - lo) / (hi - lo) for k, w, lo, hi in GENES])


def hand_made(yaw_deg: float = ROLL_OVER_YAW_DEG) -> np.ndarray:
    """The hand-made keys (module docstring) as a genome: yaw − twists the shoulders to the right."""
    return encode({("raise", "duration"): 1.5, ("twist", "duration"): 1.5, ("follow", "duration"): 1.5,
                   ("raise", "shoulder_pitch_r"): 2.8, ("raise", "shoulder_pitch_l"): 1.57, ("raise", "hip_l"): 1.0,
                   ("raise", "knee_l"): 1.2, ("twist", "spine_yaw"): -yaw_deg, ("twist", "spine_roll"): 0.0,
                   ("twist", "shoulder_pitch_l"): 2.0, ("twist", "shoulder_roll_l"): -0.3,
                   ("follow", "spine_yaw"): 2.0 * yaw_deg / 3.0, ("follow", "spine_roll"): 0.0,
                   ("follow", "hip_l"): 1.8, ("follow", "hip_r"): 0.0,
                   **{(key, what): 0.0 for key, what, _, _ in GENES if key == "lie"}})


HAND_MADE = hand_made()


def keys(genes=None, yaw_deg: float = ROLL_OVER_YAW_DEG) -> list[Key]:
    """Rest, raise, twist, follow, lie (the end posture; hand-made: every joint the keys moved back to 0), hold;
    ``genes`` in [0, 1]^N (default: the hand-made keys with the twist ``yaw_deg``)."""
    genes = hand_made(yaw_deg) if genes is None else np.clip(np.asarray(genes, dtype=float), 0.0, 1.0)
    parts = {"raise": {}, "twist": {}, "follow": {}, "lie": {}}
    for g, (key, what, lo, hi) in zip(genes, GENES):
        v = lo + g * (hi - lo)
        parts[key][what] = math.radians(v) if what.startswith("spine_") else v
    moves = [Key(parts[k].pop("duration"), parts[k], k) for k in ("raise", "twist", "follow")]
    return [Key(REST_S, {}, "rest"), *moves, Key(1.5, parts["lie"], "lie"), Key(1.0, {}, "hold")]


def sequence_s(genes=None) -> float:
    """The keys' length [s] (the run's duration at fraction 1)."""
    return float(sum(k.duration_s for k in keys(genes)))


def turn_deg(body: ClaBody, part: str) -> float:
    """The angle between ``part``'s front (x axis) and the world's up [deg]: 0 supine, 180 prone."""
    R = body.data.xmat[body.id("body", part)].reshape(3, 3)
    return math.degrees(math.acos(float(np.clip(R[2, 0], -1.0, 1.0))))


def build(spine: bool, yaw_deg: float = ROLL_OVER_YAW_DEG, calibration_s: float = 1.0, genes=None,
          prone: bool = False):
    """A lying Cla (on its front if ``prone``), calibrated upright then laid down, its spine locked unless
    ``spine``; the keys' player (``genes``, default the hand-made keys) and the muscle controller."""
    body = ClaBody("standing", spec=lying_spec())
    control, zero = spine_control(body, calibration_s=calibration_s)
    lay(body, prone)
    if not spine:
        body.lock_spine(True)
    start = {**start_targets("standing"), "spine_roll": 0.0, "spine_pitch": 0.0, "spine_yaw": 0.0}
    player = WholeBodyKeys(CLA.model, zero, LIMB_JOINTS, start, keys(genes, yaw_deg))
    return body, player, control


def signals(body: ClaBody) -> dict:
    return {"pelvis_turn_deg": turn_deg(body, "link0"), "shoulder_turn_deg": turn_deg(body, f"link{CLA.n}"),
            "whole_deg": np.degrees(whole_spine(body.theta())),
            "pelvis": body.body_pos("link0").copy()}


def roll_rig(spine: bool, genes=None, prone: bool = False, fraction: float = 1.0, calibration_s: float = 1.0,
             yaw_deg: float = ROLL_OVER_YAW_DEG, view=None) -> Rig:
    """The keys ``genes`` from lying on the back (front if ``prone``), recording :func:`signals` every 10 steps."""
    body, player, control = build(spine, yaw_deg, calibration_s, genes, prone)
    return Rig(body, stages=[[player], [control]], channels=SETPOINTS, duration=float(player.times[-1]) * fraction,
               record={10: lambda snap: signals(body)}, view=view or {})


def outcome(log, prone: bool = False) -> dict:
    """Each half's turn toward the goal (from 0 lying at the start to 180 rolled over): the largest and the last
    [deg], ``rolled`` (both halves past cla ``ROLLED_DEG`` at the end), the spine's largest yaw and change [deg]."""
    turns = {h: log.values(f"{h}_turn_deg") for h in ("pelvis", "shoulder")}
    turns = {h: 180.0 - v if prone else v for h, v in turns.items()}
    whole = log.values("whole_deg")
    return {"max_shoulder_turn_deg": float(turns["shoulder"].max()), "max_pelvis_turn_deg": float(turns["pelvis"].max()),
            "final_shoulder_turn_deg": float(turns["shoulder"][-1]), "final_pelvis_turn_deg": float(turns["pelvis"][-1]),
            "rolled": int(min(turns["pelvis"][-1], turns["shoulder"][-1]) > ROLLED_DEG),
            "max_yaw_deg": float(np.abs(whole[:, 2]).max()),
            "max_spine_change_deg": float(np.abs(whole - whole[0]).max())}


def roll_fitness(o: dict) -> float:
    """The search's fitness [deg] (maximised; chosen before any search): the mean of the two halves' last turn
    toward the goal, plus half the pelvis's largest turn — the heavier half is the one that does not follow, and
    its peak gives the search a slope before any sequence rolls."""
    return 0.5 * (o["final_pelvis_turn_deg"] + o["final_shoulder_turn_deg"]) + 0.5 * o["max_pelvis_turn_deg"]


@dataclass(frozen=True)
class RollFitness:
    """Picklable fitness of one genome: the keys run with the spine from the back (front if ``prone``)."""

    prone: bool = False
    fraction: float = 1.0
    calibration_s: float = 1.0

    def __call__(self, genes) -> float:
        rig = roll_rig(True, genes, self.prone, self.fraction, self.calibration_s)
        return roll_fitness(outcome(run_rig(rig).log, self.prone))
