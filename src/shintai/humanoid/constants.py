"""Constants of seed 000 (Kimura 2018): the humanoid HRP2-JSK, the tricycle, Kenshiro's leg, the
pedalling/steering laws. One place for every number; each has its source.

Sources: the thesis ``/work/shared/seeds/000_875fac3b182a28c6.txt`` (cited by section, table,
figure or equation) and its English extractions ``/work/shared/spec/000-part1-ch1-3.md`` ("spec
§x") and ``000-part3-ch7-8-appendix.md`` ("spec-A §x"). A value the thesis does not give is marked
*chosen* with the reason. Angles are radians, lengths metres, masses kg, unless a name says otherwise.

Frames (chosen, used by every model of :mod:`shintai.humanoid`): x forward, y left, z up. Pitch
joints turn about +y, roll about +x, yaw about +z (right-hand rule), so a *forward* pitch of hip,
shoulder, elbow and ankle is negative and a forward pitch of waist and neck positive (§A.2.1 names
ranges "forward/backward", not signs).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core.constants import GRAVITY  # noqa: F401  (9.81 m/s², shared by every body)

DEG = math.pi / 180.0

# ------------------------------------------------------------------------------------------------
# Timing
# ------------------------------------------------------------------------------------------------

CONTROL_PERIOD = 0.004  # s, hrpsys real-time period "約 4 ms" (§A.2.1, Fig. A.14; spec-A §4.4)
# not a thesis number: issue 30's aim for the standing stack's and the tricycle's 4 ms tick, as a multiple of bare mj_step
# for the same physics steps (shintai bench reports each against it)
TICK_OVERHEAD_TARGET = 1.5
# F_thre: a foot is on the board/floor when it pushes more than this — the SLC's start/stop test on
# f_Lz, f_Rz (§5.4.1, Fig. 5.5) and the feet counted in the measured ZMP.
F_THRE = 25.0  # N
# Chosen: 1 ms physics keeps the closed loops (grips, pedals, saddle weld) stiff and stable; four
# physics steps make one 4 ms control step.
PHYSICS_TIMESTEP = 0.001
SUBSTEPS = round(CONTROL_PERIOD / PHYSICS_TIMESTEP)

# Collision bits (chosen, Table 3.1's contacts). Only these pairs collide: floor–sole, floor–tyre and
# sole–pedal (the unilateral foot–pedal contact); hands hold grips by equality constraints, the hip is
# welded to the saddle (§3.3.2), links do not self-collide. A sole has contype SOLE (conaffinity 0), a pedal
# conaffinity SOLE (contype 0), a tyre contype WHEEL (conaffinity 0); the floor accepts all.
FLOOR = 1
SOLE = 2
WHEEL = 4
# The scene every humanoid model starts from (:func:`shintai.sim.spec.scene_spec`'s timestep and floor bits).
SCENE = (PHYSICS_TIMESTEP, FLOOR, FLOOR | SOLE | WHEEL)

# ------------------------------------------------------------------------------------------------
# Steering / pedalling laws (Ch. 3)
# ------------------------------------------------------------------------------------------------

DELTA_C = 20 * DEG  # δ_c, switching offset of the stepping leg from TDC (Eq. 3.6, §3.3.3, §3.5.2)
THETA_H_INIT = 0.0  # θ_h^init, handle switching angle (Eq. 3.19)
THETA_C_INIT = math.pi / 2 + DELTA_C  # θ_c^init, crank switching angle (Eq. 3.19)
THETA_H_MAX = 25 * DEG  # Θ_H used in the experiments (Table 3.4)
THETA_H0 = 90 * DEG  # Θ_H0, the tricycle's physical steering limit "約 90 deg" (§A.1.1)
D_THETA_H = 5 * DEG  # Δθ_h, handle command sampling interval (§3.5.1)
D_THETA_C = 10 * DEG  # Δθ_c, crank command sampling interval (§3.5.1)
DELTA_T = 0.8  # s, motion transition time per function (§3.5.2, Eq. 3.20)
T_2PI = 2 * math.pi * 2 * DELTA_T / D_THETA_C  # 57.6 s per crank revolution (Eq. 3.20)
F_TRG_PASSIVE_LEG_IMPROVED = 50.0  # N, passive-leg f^trg_z of the improved outdoor run (§3.5.4)


@dataclass(frozen=True)
class Impedance:
    """Position-based impedance parameters of one limb role (Eq. 3.13, Table 3.4).

    Scalars: isotropic diagonal M_v, D_v, K_v (spec §6 item 3). ``f_trg`` is the target contact
    force (x, y, z) in N; ``theta_h_max`` is Θ_H for the arms, None for the legs.
    """

    m: float  # N s²/m
    d: float  # N s/m
    k: float  # N/m
    f_trg: tuple[float, float, float]
    theta_h_max: float | None = None


IMPEDANCE = {  # Table 3.4
    "active_arm": Impedance(10.0, 600.0, 3000.0, (0.0, 0.0, 0.0), THETA_H_MAX),
    "passive_arm": Impedance(10.0, 500.0, 300.0, (0.0, 0.0, 0.0), THETA_H_MAX),
    "active_leg": Impedance(10.0, 600.0, 3000.0, (0.0, 0.0, 150.0)),
    "passive_leg": Impedance(10.0, 500.0, 300.0, (0.0, 0.0, 150.0)),
}

# ------------------------------------------------------------------------------------------------
# HRP2-JSK (App. A.2.1, Tables A.1 and A.2)
# ------------------------------------------------------------------------------------------------

HRP2_HEIGHT = 1.607  # m, Table A.1 (from CAD)
HRP2_WIDTH = 0.627  # m, Table A.1
HRP2_DEPTH = 0.324  # m, Table A.1
HRP2_MASS = 56.5  # kg, Table A.1 (measured on a scale)
HRP2_DOF = 32  # Table A.1: arms 2×(7+1), legs 2×6, waist 2, neck 2


@dataclass(frozen=True)
class JointSpec:
    """One row of Table A.2: the range as printed (two magnitudes, deg), max torque, max speed.

    ``neg_deg``/``pos_deg`` are the printed magnitudes mapped to the negative/positive side of the
    joint axis for the **right** limb (or the centre joints); the left limb mirrors roll and yaw
    (see :func:`joint_range`). Which printed word ("forward", "out", …) maps to which side follows the
    module's sign convention and is noted per row.
    """

    name: str
    axis: str  # "x" roll, "y" pitch, "z" yaw
    neg_deg: float
    pos_deg: float
    torque: float  # N m, maximum output torque
    speed_rpm: float  # maximum speed

    @property
    def speed(self) -> float:
        """Maximum speed in rad/s."""
        return self.speed_rpm * 2 * math.pi / 60


# Table A.2 (spec-A §4.4). Order within each limb = order along the kinematic chain (HRP-2
# convention: yaw–roll–pitch at the hip, pitch–roll–yaw at the shoulder).
NECK_JOINTS = (
    JointSpec("neck_yaw", "z", 45, 45, 9.6, 64.0),  # "左右方向 45"
    JointSpec("neck_pitch", "y", 30, 45, 9.6, 64.0),  # forward (down, +) 45 / back 30
)
WAIST_JOINTS = (
    JointSpec("waist_yaw", "z", 45, 45, 151.8, 41.9),  # "左右方向 45"
    JointSpec("waist_pitch", "y", 5, 60, 278.9, 22.8),  # forward (+) 60 / back 5
)
ARM_JOINTS = (  # right arm; 7 DoF + the 1-DoF hand
    JointSpec("shoulder_pitch", "y", 180, 60, 160.3, 39.2),  # forward (−) 180 / back 60
    JointSpec("shoulder_roll", "x", 95, 10, 100.4, 22.9),  # out (−y for the right arm) 95 / in 10
    JointSpec("shoulder_yaw", "z", 92, 92, 48.7, 39.4),  # out 92 / in 92
    JointSpec("elbow_pitch", "y", 137, 2, 108.5, 21.2),  # forward (−) 137 / back 2
    JointSpec("wrist_yaw", "z", 92, 92, 13.9, 44.0),  # out 92 / in 92
    JointSpec("wrist_roll", "x", 90, 90, 18.7, 63.4),  # "forward 90 / back 90"
    JointSpec("wrist_pitch", "y", 90, 90, 16.0, 26.5),  # forward 90 / back 90
    # hand thumb roll, open 60 / close 16: chosen + opens, − closes
    JointSpec("gripper", "x", 16, 60, 13.9, 44.0),
)
LEG_JOINTS = (  # right leg
    JointSpec("hip_yaw", "z", 45, 30, 86.2, 33.8),  # out (toe to −y for the right leg) 45 / in 30
    JointSpec("hip_roll", "x", 35, 20, 175.4, 36.2),  # out (−y) 35 / in 20
    JointSpec("hip_pitch", "y", 125, 42, 151.4, 42.1),  # forward (−) 125 / back 42
    JointSpec("knee_pitch", "y", 2, 150, 168.3, 37.9),  # "forward 2 / back 150": flexion +
    JointSpec("ankle_pitch", "y", 75, 42, 131.6, 48.3),  # forward (toe up, −) 75 / back 42
    # Printed "前方 20, 後方 35" (forward/back) for a roll joint, probably out/in (spec-A §9 item
    # 14): chosen out (−y for the right leg) 20 / in 35.
    JointSpec("ankle_roll", "x", 20, 35, 73.1, 87.0),
)


def joint_range(spec: JointSpec, side: str = "") -> tuple[float, float]:
    """(lower, upper) in rad of a Table A.2 joint on side ``"r"``, ``"l"`` or ``""`` (centre).

    Roll and yaw joints of the left limb are the mirror image of the right: (−pos, neg).
    """
    lo, hi = -spec.neg_deg * DEG, spec.pos_deg * DEG
    if side == "l" and spec.axis in ("x", "z"):
        lo, hi = -hi, -lo
    return lo, hi


# Link lengths: not in the thesis (spec §5.1 item 3). Chosen from the height 1607 mm (Table A.1)
# and commonly published, approximate HRP-2 dimensions (marked "HRP-2": thigh and shank 0.30 m,
# hip joints 0.06 m off the centre line, upper arm and forearm about 0.25 m), the rest filled in so
# the standing model is 1.607 m tall with the neck 30 mm longer than HRP-2's (§A.2.1 item 2).
@dataclass(frozen=True)
class Hrp2Links:
    """HRP2-JSK-like link dimensions (m), in the waist (pelvis) frame at the zero posture.

    Standing at zero posture: sole 0, ankle 0.105, knee 0.405, hip 0.705, waist origin 0.780,
    waist joints 0.880, shoulders 1.300, neck 1.430, head top 1.607 (= Table A.1 height).
    """

    hip_y: float = 0.06  # hip joint off the centre line (HRP-2)
    hip_z: float = -0.075  # hip yaw/roll/pitch axes meet below the waist origin (chosen)
    thigh: float = 0.30  # HRP-2
    shank: float = 0.30  # HRP-2
    ankle_height: float = 0.105  # ankle axis above the sole (HRP-2)
    foot_length: float = 0.24  # sole 240 × 136 mm (HRP-2)
    foot_width: float = 0.136
    foot_forward: float = 0.015  # sole centre ahead of the ankle axis (chosen)
    foot_outward: float = 0.010  # sole centre outside the ankle axis (chosen: soles 4 mm apart)
    waist_z: float = 0.10  # waist yaw/pitch joints above the waist origin (chosen)
    shoulder_y: float = 0.25  # half the shoulder span; ±0.25 + arm radius ≈ width 627 mm
    shoulder_z: float = 0.42  # shoulders above the waist joints (chosen: height budget)
    neck_z: float = 0.55  # neck joints above the waist joints (HRP-2 + 30 mm, §A.2.1)
    head_top: float = 0.177  # head top above the neck joints → total height 1.607
    upper_arm: float = 0.25  # HRP-2
    forearm: float = 0.25  # elbow to wrist, HRP-2
    hand: float = 0.10  # wrist to grasp centre (chosen, HRP-2 1-DoF gripper)
    chest_depth: float = 0.30  # Table A.1 depth 324 mm incl. the back-mounted ZBOX (§A.2.1)
    hip_cover: float = 0.10  # waist origin above the hip cover's underside, which sits on the saddle (chosen)
    ankle_ft: float = 0.07  # ankle F/T sensor below the ankle axis, between ankle and sole (chosen)
    wrist_ft: float = 0.02  # wrist F/T sensor beyond the wrist axes, between wrist and hand (chosen)
    imu_z: float = 0.20  # chest IMU above the waist joints (chosen; the IMU is in the chest, §6.2.1)


HRP2_LINKS = Hrp2Links()

# Link masses: not in the thesis beyond the 56.5 kg total (Table A.1). Chosen after HRP-2's
# layout: heavy chest (two PCs, batteries, ZBOX), waist with the hip cover (§A.2.1 item 11),
# 9.5 kg legs and 5.5 kg arms. Keys are body names of robots/hrp2.py; "l_"/"r_" parts apply to both.
HRP2_MASSES = {
    "waist": 10.0,
    "chest_yaw_link": 1.0,
    "chest": 12.5,
    "neck_yaw_link": 0.3,
    "head": 2.7,
    # per arm: 5.5 kg
    "shoulder_pitch_link": 0.8, "shoulder_roll_link": 0.7, "upper_arm": 1.8, "forearm": 0.9,
    "wrist_yaw_link": 0.3, "wrist_roll_link": 0.3, "hand": 0.6, "thumb": 0.1,
    # per leg: 9.5 kg
    "hip_yaw_link": 0.8, "hip_roll_link": 1.2, "thigh": 3.5, "shank": 2.0, "ankle_link": 0.5, "foot": 1.5,
}

# Postures (chosen), per limb with the left limb's signs (roll, yaw and the gripper mirror for the
# right). Standing: knees bent with the ankles under the hips, arms slightly out. Riding: what the IK
# pursues in the null space of the hand/foot targets — waist leaning forward to the low handle
# (Fig. 3.15), arms reaching forward, knees up; the grippers closed on the bars.
STANDING_POSTURE = {"hip_pitch": -0.25, "knee_pitch": 0.5, "ankle_pitch": -0.25, "shoulder_roll": 0.15,
                    "elbow_pitch": -0.3}
RIDING_WAIST_PITCH = 0.35
RIDING_POSTURE = {"shoulder_pitch": -0.7, "elbow_pitch": -0.9, "hip_pitch": -1.2, "knee_pitch": 1.6,
                  "ankle_pitch": -0.3}
GRIPPER_CLOSED = 0.2  # rad toward "close" (the left gripper closes toward +; Table A.2: 16° range)
# The "grip" grasp of riding.build_riding (chosen, used by E1): a hand closed round a cylindrical
# grip holds its position and the bar's direction but can turn about the bar (the grip rotates in
# the palm), so the grasp is two point holds (equality "connect") on the bar, at the grasp centre
# and this far along the hand's x axis (= the bar; ~ half the 6 cm grip length of the model). The
# 6-DoF weld of Table 3.1 also locks that roll, so it turns every roll mismatch between the IK's
# hand orientation and the true handle into wrist loads, which a position-only impedance
# (Table 3.4, Eq. 3.13) cannot relieve.
GRIP_BAR_OFFSET = (0.04, 0.0, 0.0)  # m, site frame of s_grasp

# Joint servos (hrpsys joint PD): not in the thesis. Chosen stiffness so that the maximum torque
# of Table A.2 is reached at a 0.05 rad (2.9°) error — stiff enough to hold the riding posture,
# and the actuator force is clipped to ±max torque (forcerange). Critically damped (dampratio 1).
SERVO_SATURATION_ERROR = 0.05  # rad
SERVO_DAMPRATIO = 1.0
# Reflected rotor inertia (armature), chosen: HRP-2 class harmonic drives (rotor ~1e-5 kg m²,
# ratios ~100–160) give 0.1–0.3 kg m² at the big joints; small joints 0.02.
ARMATURE_BIG = 0.2  # kg m², joints whose max torque (Table A.2) is at least ARMATURE_SPLIT
ARMATURE_SMALL = 0.02  # kg m², wrists, grippers, neck
ARMATURE_SPLIT = 40.0  # N m

# ------------------------------------------------------------------------------------------------
# Tricycle (App. A.1.1, Figs. A.1, A.2)
# ------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class TricycleSpec:
    """Tricycle geometry (m) in the vehicle frame: origin on the ground under the crank shaft.

    Thesis values (Figs. A.1/A.2) and chosen ones (marked). The steering axis passes through the
    front axle; the grips hang ``grip_sweep`` behind the point where it crosses the grip height.
    """

    crank_to_front: float = 0.600  # crank shaft → front shaft, horizontal (Fig. A.1)
    crank_to_back: float = 0.600  # crank shaft → back shaft, horizontal (Fig. A.1)
    # Fig. A.1 "Crank Diameter: 250 mm" vs Kenshiro's r = 100 mm (Fig. 3.31), spec §6 item 7.
    # Chosen r = 125 mm: App. A.1.1 is the tricycle's own specification and "diameter" read as the
    # pedal circle; Kenshiro's model keeps its own r (KENSHIRO below).
    crank_radius: float = 0.125
    front_tire_radius: float = 0.250  # Fig. A.1
    back_tire_radius: float = 0.200  # Fig. A.1
    saddle_above_crank: float = 0.450  # saddle height from crank shaft (Fig. A.1)
    grip_height: float = 0.900  # handle grip height from the ground (Fig. A.1)
    saddle_to_grip: float = 0.350  # horizontal saddle → handle grip (Fig. A.1)
    pedal_width: float = 0.270  # Fig. A.2; chosen to mean pedal centre to pedal centre
    handle_width: float = 0.480  # Fig. A.2 → grips at ±0.24 from the steering axis
    tread: float = 0.400  # back-wheel tread width (Fig. A.2)
    travel_per_rev: float = 2.45  # D_c, m per crank revolution (§A.1.1)
    # Chosen: the crank shaft height (not given) puts the pedal 0.125 m above the ground at BDC.
    crank_height: float = 0.250
    # Chosen: steering axis raked back 20° (city-cycle head angle 70°; spec §6 item 6: unknown).
    steer_rake: float = 20 * DEG
    # Chosen: grips 0.10 m behind the steering axis (swept-back bar). With the rake this puts the
    # saddle 0.087 m behind the crank shaft, close to Kenshiro's D_cx = 80 mm (Fig. 3.31).
    grip_sweep: float = 0.100
    pedal_size: tuple[float, float, float] = (0.100, 0.090, 0.020)  # chosen city-cycle pedal (x, y, z)
    # Masses: not in the thesis (spec §6 item 14). Chosen for a steel adult tricycle, 21 kg in all.
    frame_mass: float = 14.0
    handle_mass: float = 2.0  # bar, stem and fork
    front_wheel_mass: float = 1.5
    back_wheel_mass: float = 1.5  # each
    crank_mass: float = 0.5  # with the chainring
    pedal_mass: float = 0.25  # each
    # Crank load: not in the thesis (spec §6 item 14), so a parameter of the builder; these are
    # the defaults. Viscous load plus a dry friction that keeps the parked crank still.
    crank_damping: float = 1.0  # N m s/rad
    crank_friction: float = 1.0  # N m
    pedal_damping: float = 0.01  # N m s/rad, chosen: bearings of the free pedal
    pedal_com_drop: float = 0.005  # m, chosen: pedal mass below its axle, so an unloaded pedal hangs level
    wheel_damping: float = 0.01  # N m s/rad, chosen: wheel bearings
    steer_damping: float = 0.5  # N m s/rad, chosen: headset bearing
    wheel_friction: float = 1.2  # tyre–floor friction coefficient, chosen: "no slip" (§3.5.1)

    @property
    def gear_ratio(self) -> float:
        """Drive-wheel turns per crank turn: D_c / (2π r_back) ≈ 1.95 (spec-A §4.1, derived)."""
        return self.travel_per_rev / (2 * math.pi * self.back_tire_radius)

    @property
    def front_axle(self) -> tuple[float, float]:
        """(x, z) of the front shaft."""
        return self.crank_to_front, self.front_tire_radius

    @property
    def steer_top(self) -> tuple[float, float]:
        """(x, z) where the raked steering axis crosses the grip height."""
        x0, z0 = self.front_axle
        return x0 - (self.grip_height - z0) * math.tan(self.steer_rake), self.grip_height

    @property
    def grip_x(self) -> float:
        """x of both grips at θ_h = 0."""
        return self.steer_top[0] - self.grip_sweep

    @property
    def saddle(self) -> tuple[float, float]:
        """(x, z) of the saddle top: 0.35 m behind the grips, 0.45 m above the crank shaft."""
        return self.grip_x - self.saddle_to_grip, self.crank_height + self.saddle_above_crank


TRICYCLE = TricycleSpec()

# Position servos on handle and crank, only to drive the tricycle without a rider (tests, demos);
# chosen stiff, and damped for the inertia they move (the crank carries the vehicle's mass through
# the gear, ≈ 3.5 kg m²): joint → (kp N m/rad, kv N m s/rad).
TRICYCLE_DRIVE_SERVOS = {"handle": (2000.0, 100.0), "crank": (5000.0, 300.0)}

# ------------------------------------------------------------------------------------------------
# V-BOARD, the parallel two-wheeled electric scooter (App. A.1.2, Eqs. A.1–A.4, Figs. A.4–A.7)
# ------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class VboardSpec:
    """The V-BOARD [58] (Vivo Market; a 6.5-inch "hoverboard") as :mod:`~shintai.humanoid.vboard.vehicle`
    builds it. Thesis values: Eq. A.1 (K, θ_O), Fig. A.4 (r, W). Everything else is *chosen* for a
    commercial 6.5-inch hoverboard, as marked; the thesis gives no mass, size or dynamics.

    Sides are ``"r"`` and ``"l"``. θ (board pitch) is a rotation about the scooter's +y (left) axis:
    positive tips the toes down, and θ > θ_O drives the wheel forward (§6.2.1: θ_R > θ_RO "右車輪は前進").
    """

    # Eq. A.1 (the linear regression of Fig. A.6): Ω [rad/s] = K [rad/s per deg] · (θ − θ_O) [deg].
    k: tuple[tuple[str, float], ...] = (("r", 4.6203), ("l", 4.3356))  # K_R, K_L
    theta_o_deg: tuple[tuple[str, float], ...] = (("r", -1.7871), ("l", -1.9972))  # θ_RO, θ_LO
    wheel_radius: float = 0.080  # r, "Wheel radius: 80[mm]" (Fig. A.4), Eq. A.2
    # W, "515[mm]" (Fig. A.4), the 車体幅 of Eq. A.3. Chosen to be the wheel track (tyre centre to
    # tyre centre), so that Eq. A.3 is the exact rolling kinematics of the model; a 6.5-inch board is
    # about 0.58 m long over the tyres, ≈ 0.52 m between tyre centres.
    track: float = 0.515
    # Chosen sizes of a 6.5-inch board: 55 mm tyre; each half's housing 0.18 m deep (x), from the
    # centre pivot to 10 mm short of its tyre (y), its underside 35 mm above the ground; the rubber
    # foot pad's top (where a sole stands) 0.12 m above the ground; pads 0.16 × 0.15 m.
    tyre_width: float = 0.055
    housing_depth: float = 0.18
    housing_gap: float = 0.015  # m, housing edge from the centre pivot (y)
    housing_bottom: float = 0.035
    deck_height: float = 0.12
    pad_size: tuple[float, float] = (0.16, 0.15)  # x, y
    pad_thickness: float = 0.005
    # Chosen masses, 10.5 kg in all (6.5-inch boards weigh 10–12 kg): each half 3.0 kg (housing, hub
    # motor stator, battery or mainboard), each wheel 2.0 kg (tyre and the motor's outer rotor), the
    # centre pivot tube 0.5 kg. A half's mass centre sits 10 mm below the axle (battery and boards
    # low in the housing), so an unloaded half whose drive is off hangs level.
    half_mass: float = 3.0
    wheel_mass: float = 2.0
    pivot_mass: float = 0.5
    half_com_drop: float = 0.010
    # The drive (chosen; the thesis measured only the steady law Eq. A.1): the hub motor is speed
    # servoed, τ = k_v (Ω_ref − Ω) with Ω_ref from Eq. A.1; k_v stiff enough that a 28 kg half-load
    # reaches its speed in ≈ 0.1 s, τ limited to 15 N m (a 350 W, 36 V hub motor, ≈ 15 A peak).
    speed_gain: float = 2.0  # k_v, N m s/rad
    max_torque: float = 15.0  # N m
    # Contact switch (§A.1.2: a binary contact sensor per board turns its wheel's drive on/off).
    # Chosen: on above 20 N of normal force on the foot pad (a foot, not a dropped glove).
    switch_force: float = 20.0  # N
    tyre_friction: float = 1.2  # chosen like the tricycle's: rolling without slip (Eq. A.2)
    wheel_damping: float = 0.01  # N m s/rad, chosen: wheel bearings (drive off: the wheel coasts)
    pivot_damping: float = 0.2  # N m s/rad, chosen: friction of the centre pivot between the halves

    def __post_init__(self):
        for name, value in (("k", dict(self.k)), ("theta_o_deg", dict(self.theta_o_deg))):
            if sorted(value) != ["l", "r"]:
                raise ValueError(f"VboardSpec.{name} must give sides 'r' and 'l', got {sorted(value)}")
            for side, x in value.items():
                if not math.isfinite(x) or (name == "k" and x <= 0):
                    raise ValueError(f"VboardSpec.{name}[{side!r}] must be a finite"
                                     f"{' positive' if name == 'k' else ''} number, got {x!r}")
        for name in ("wheel_radius", "track", "tyre_width", "housing_depth", "deck_height", "pad_thickness",
                     "half_mass", "wheel_mass", "pivot_mass", "speed_gain", "max_torque", "switch_force",
                     "tyre_friction"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"VboardSpec.{name} must be a finite positive number, got {value!r}")
        if self.deck_height <= self.wheel_radius or self.housing_bottom >= self.wheel_radius:
            raise ValueError(f"VboardSpec: the housing must span the axle height {self.wheel_radius} m "
                             f"(housing_bottom {self.housing_bottom} < r < deck_height {self.deck_height})")

    def gain(self, side: str) -> float:
        """K of ``side`` in rad/s per rad (Eq. A.1's rad/s per degree × 180/π)."""
        return dict(self.k)[side] / DEG

    def theta_o(self, side: str) -> float:
        """θ_O of ``side`` in rad (Eq. A.1)."""
        return dict(self.theta_o_deg)[side] * DEG

    @property
    def housing_outer(self) -> float:
        """|y| of a housing's outer edge: 10 mm inside its tyre."""
        return self.track / 2 - self.tyre_width / 2 - 0.010

    @property
    def pad_y(self) -> float:
        """|y| of a foot pad's centre: the middle of its housing."""
        return (self.housing_gap + self.housing_outer) / 2


VBOARD = VboardSpec()

# Position servos holding each board's pitch against the level frame: only a fixture for tests and
# demos (Fig. A.5's hand and protractor), never part of the scooter. (kp N m/rad, kv N m s/rad).
# Use it on unloaded boards: with a heavy box on a held board and the drive on, the stiff fixture,
# the box's contact and the firmware ring at the 1 ms physics step (gone at 0.25 ms).
VBOARD_HOLD_SERVO = (3000.0, 60.0)

# ------------------------------------------------------------------------------------------------
# Kenshiro (App. A.2.2, §3.5.5, Fig. 3.31)
# ------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class KenshiroSpec:
    """Kenshiro's sagittal leg and crank (Fig. 3.31) and the §3.5.5 parameters."""

    l1: float = 0.348  # thigh L1 (Fig. 3.31)
    l2: float = 0.343  # shank L2
    l3: float = 0.260  # foot L3
    d_ap: float = 0.075  # ankle joint → pedal contact point D_ap
    d_cx: float = 0.080  # hip (fixed point) → crank centre, x: chosen forward (Fig. 3.31 not in text)
    d_cz: float = 0.605  # hip → crank centre, z (crank below the hip)
    crank_radius: float = 0.100  # r (Fig. 3.31, Eq. 3.23)
    samples: int = 18  # T per active half revolution (Eq. 3.23)
    phi_min: float = 5 * math.pi / 6  # Φ > 5π/6 (Eq. 3.23)
    k_n: float = 0.002  # K_n = 2 mm/N, passive update gain (Eq. 3.24–3.25)
    control_period: float = 0.016  # s (§3.5.5)
    ft_resolution: float = 0.25  # N, foot F/T sensor resolution, translational (§3.5.5)
    mass: float = 51.9  # kg, whole robot (Table A.3)
    # Chosen (not in the thesis): the contact point lies on the sole D_ap below the ankle, and
    # the foot reaches 0.06 m behind / 0.20 m ahead of the ankle (L3 = 0.26 m in all).
    heel: float = 0.060
    # Chosen leg masses (Kenshiro's 51.9 kg body, human-like proportions) and pedal spacing.
    thigh_mass: float = 4.0
    shank_mass: float = 2.5
    foot_mass: float = 1.0
    pedal_spacing: float = 0.270  # same tricycle as HRP2-JSK (Fig. A.2)
    # Chosen joint ranges (human-like) and servo torque limits (muscle-driven, no table given).
    hip_range: tuple[float, float] = (-120 * DEG, 30 * DEG)
    knee_range: tuple[float, float] = (0.0, 150 * DEG)
    ankle_range: tuple[float, float] = (-45 * DEG, 45 * DEG)
    hip_torque: float = 200.0  # N m
    knee_torque: float = 200.0
    ankle_torque: float = 100.0
    armature: float = 0.05  # kg m², chosen: reflected inertia of the tendon drives

    @property
    def d_th(self) -> float:
        """D_th of Eq. 3.22–3.23: r √(2(1 − cos(π/T))) |cos Φ| ≈ 0.0151 m."""
        return self.crank_radius * math.sqrt(2 * (1 - math.cos(math.pi / self.samples))) * abs(math.cos(self.phi_min))


KENSHIRO = KenshiroSpec()

# ------------------------------------------------------------------------------------------------
# Laws and scenarios of Ch. 3 (active/passive functions, switching, Kenshiro pedalling) — added by
# the laws' author (humanoid/active.py, passive.py, switching.py, operation.py, kenshiro.py)
# ------------------------------------------------------------------------------------------------

# Chosen: a measured handle/crank angle must pass a switching angle (Eq. 3.19) by this much before
# the roles swap, so that estimation noise at the switching angle cannot make them chatter.
SWITCH_HYSTERESIS = 0.5 * DEG
# Chosen: Kenshiro's active leg ends its plan exactly at the switching angle (Eq. 3.7 with
# i = T), which a position-controlled crank reaches only asymptotically; its roles swap once the
# measured crank angle is within half a sample (Δθ_c/2 = 5°) of it, with a hysteresis of half that.
KENSHIRO_SWITCH_LEAD = 5 * DEG
# Chosen: time per brain sample i of Kenshiro's plan (Eqs. 3.7, 3.24), interpolated by the middle
# layer (App. A.2.2). The thesis's first half revolution (18 samples) took about 5 s (§3.5.5,
# "0 [s] ~ 約 5 [s]") → 0.28 s, rounded to 17 control periods of 16 ms.
KENSHIRO_SAMPLE_PERIOD = 17 * 0.016
# Chosen: Kenshiro sits still this long (servos holding the riding posture) before pedalling.
KENSHIRO_SETTLE_S = 0.5
# Chosen: the passive leg's tendons are relaxed to this fraction of the servo stiffness (hip and
# knee 8 N m/rad). Its foot's vertical stiffness is then 150–410 N/m over the passive half
# revolution (level foot), below 1/K_n = 500 N/m. [DERIVED] Eq. 3.24 with Δf_i = f_i − f_{i−1} sums to
# q = q_0 + K_n (f − f_0); against a foot stiffness k that fixed point is reached only if K_n k < 1,
# so a stiff position-servoed leg (k ≈ 10⁵ N/m here) makes the update diverge, and K_n = 2 mm/N
# presupposes a compliant passive leg — the thesis calls K_n the passive foot's "stiffness"
# (§3.5.5) and gives the HRP2 passive limbs a tenth of the active stiffness (Table 3.4).
KENSHIRO_RELAXED_TENDON = 0.002
# Eq. 3.24's Δf_i, "足が運動中のペダルから受ける外力変化" (§3.5.5), has no stated reference. "previous" (default): the
# change over one control period, which telescopes to q = q_0 + K_n (f − f_0), a 500 N/m spring — what the thesis
# calls K_n: "受動機能側の脚の足先エンドエフェクタの位置における剛性パラメータ" (a stiffness). "start": the deviation of
# f_i from the force at the passive phase's start, so q moves at a rate ∝ the force built since (an integral
# admittance). Issue 26 item 7 asked for "start" for Fig. 3.35, declared before the run (commit 'Kenshiro: Eq. 3.24's
# Δf_i read as ...'); run at the defaults it let the passive foot leave the pedal (contact 88 % of the time, peak
# 72.5 N) but the feet's crank estimate then went wrong at the swap (176° error, a second swap 0.13 s after the
# first, 177° of crank): the default went back to the stiffness reading for the thesis's word, after that run.
KENSHIRO_DELTA_F = "previous"
KENSHIRO_DELTA_F_READINGS = ("start", "previous")
# Chosen: Kenshiro's crank angle is estimated (method (a)) from the feet pressing their pedals with
# at least this vertical force (8 steps of the 0.25 N sensor resolution); a lifted foot is ignored.
KENSHIRO_CONTACT_N = 2.0
# Chosen: … and whose pedal-axle point (from the leg's forward kinematics) lies within this distance
# of the crank circle (a fifth of r); a foot fallen off its pedal can still press something.
KENSHIRO_ON_PEDAL_M = 0.02

# Chosen (spec §6 item 15: the thesis does not give HRP2's foot orientation on the pedal; the pedal
# turns freely, Table 3.1): the IK keeps each sole level in the vehicle frame, as in the riding
# posture (ankle pitch −63° … −14° over the whole circle, inside Table A.2's 75° forward). With the
# pitch left free the DLS IK let it drift by up to ±30°, the free pedal tilted with the sole, the
# vertical f^trg = (0, 0, 150) N (Table 3.4) then had a 40 % component along the tilted pedal,
# and the sole crept down the pedal (≈6 mm/s) until the passive foot fell off at θ_c ≈ 200°.
PEDAL_SOLE_PITCH = 0.0  # rad, sole pitch about the crank axis relative to the vehicle frame
# Chosen (evaluation only, E4 §3.5.3): the active foot's force is summarised "near the crank
# horizontal" (|cos θ_c| ≥ cos 30°) and "near the dead centres" (|cos θ_c| ≤ sin 30°), a third of
# the circle each, so that both bands hold several 10° command samples (the ±20 N per-sample ripple
# averages out) — the bands in which §3.5.3 measured the rise near TDC/BDC and ≈150 N at the
# horizontal (1/|cos θ_c|, the thesis's conjectured order, is ≤ 1.15 and ≥ 2 there).
PEDAL_FORCE_BAND = 30 * DEG

# ------------------------------------------------------------------------------------------------
# Ch. 4 corrections (§4.3–4.4, §7.3.1, §7.3.2, §7.4.1) — humanoid/corrections.py, navigation.py,
# ch4_riding.py, ch4_drive.py, experiments/. The thesis gives none of these numbers unless marked.
# ------------------------------------------------------------------------------------------------

WHEELBASE = TRICYCLE.crank_to_front + TRICYCLE.crank_to_back  # L of Eqs. 4.15–4.22: front to back shaft (Fig. A.1)


@dataclass(frozen=True)
class NavigationSpec:
    """Depth sensor, costmap and dynamic-window planner (§4.4.2; ours: the thesis used ROS move_base/DWA)."""

    # Depth sensor: MultiSense S7 field of view 80° × 49° (vendor data sheet; the thesis names the
    # sensor, §A.2.1). Chosen ray grid and range.
    fov_h: float = 80 * DEG
    fov_v: float = 49 * DEG
    rays_h: int = 48
    rays_v: int = 12
    max_range: float = 5.0  # m
    min_obstacle_height: float = 0.05  # m, points lower than this are floor (ground filter)
    # Costmap (ROS costmap_2d-like): chosen cell size and extent; inflation by the vehicle's
    # half width plus a margin.
    resolution: float = 0.05  # m per cell
    size: tuple[float, float] = (11.0, 6.0)  # m (x, y) extent
    origin: tuple[float, float] = (-2.0, -3.0)  # m, world position of cell (0, 0)'s corner
    # Footprint: circles of this radius along the vehicle centreline (vehicle frame x, crank origin);
    # covers wheels (tread 0.40 m → half 0.2 + tyre) and the rider's knees.
    footprint_x: tuple[float, ...] = (-0.55, -0.2, 0.15, 0.5)
    footprint_r: float = 0.32
    # DWA (Fox et al. 1997): chosen limits of a slowly pedalled tricycle.
    v_max: float = 0.4  # m/s
    a_max: float = 0.4  # m/s²
    yaw_acc_max: float = 1.0  # rad/s²
    horizon: float = 3.0  # s of forward simulation per sample
    samples_v: int = 7
    samples_w: int = 15
    w_path: float = 2.0  # per m of the trajectory end's distance from the global path
    w_goal: float = 1.0  # per m still to go along the path
    w_clearance: float = 0.4
    clearance_cap: float = 0.3  # m: clearance beyond this earns nothing (else stopping scores best)
    w_speed: float = 0.4
    path_margin: float = 0.35  # m, chosen: the global path pays to come closer than this beyond the footprint
    goal_tolerance: float = 0.3  # m: stop within this of the goal (the thesis: (ẋ, θ̇) → 0 at the goal)
    period: float = 0.1  # s, planner period (move_base's controller_frequency 10 Hz)


NAVIGATION = NavigationSpec()

# Interrupt-type sitting recovery (§4.3.2, Table 7.6). Chosen: trigger when |θ_roll| exceeds 1°
# (the thesis gives no threshold) at a crank angle within 5° of kπ; STAND pushes both feet with
# Table 7.6's 320 N; L_hip→COG from the model's seated CoM (computed in the scenario). Why 1°: in
# our model a creeping seat slip tilts the trunk by only a degree or two while the hip slides many
# centimetres across the saddle (measured with an earlier 30 N foot contact: ≈1.5° at 9 cm, tipping
# within ≈1 s past ≈3.5°), so a larger threshold would leave no θ_c = kπ window (every 4.1 s at
# 0.3 m/s) before the fall. Chosen before the final runs; not changed since.
RECOVERY_ROLL_THRESHOLD = 1 * DEG
RECOVERY_CRANK_TOLERANCE = 5 * DEG
RECOVERY_PUSH_N = 320.0  # N per foot, Table 7.6 (f_trg = (0, 0, 320)^T)
RECOVERY_LIFT_M = 0.02  # m, chosen: the hip rises this much above the saddle during STAND
RECOVERY_PHASE_S = 1.0  # s, chosen duration of each of STAND, SHIFT, RESEAT (T1–T3 not given)

# Hip–saddle contact geometry (§4.3.1, Fig. 4.4; the thesis gives no shape or size). Chosen: the hip
# sits on two sit bones (capsules along x, radius 3 cm, 12 cm long) 5 cm either side of the hip's
# mid-plane (human ischial spacing ≈ 10–13 cm), on a saddle whose top is crowned across y with a
# 15 cm radius over its 0.20 m width, as bicycle saddles are. Why: a pelvis sliding sideways on a
# crowned saddle drops its outer sit bone, i.e. the y translation shows as an x rotation, as §4.3.2
# assumes for the detection (Fig. 4.4: y translation and x rotation dominate). With the earlier flat
# saddle and one central hip line the slip was a pure translation (≤ 1.3° of trunk roll up to 10 cm).
# Values picked before any run with them. Sensitivity (sitting-recovery, drive=motor, measured on a
# first version whose crown was an unbounded cylinder): R = 0.10, 0.20 m and spacing ±6 cm pass
# alike; spacing ±4 cm overturns with recovery too (at 41.9 s, after 4 recoveries).
SIT_BONE_Y = 0.05  # m, half the sit-bone spacing
SIT_BONE_RADIUS = 0.03  # m
SIT_BONE_HALF_LENGTH = 0.06  # m, along x
SADDLE_CROWN_RADIUS = 0.15  # m, radius of the saddle top across y
SADDLE_HALF_WIDTH = 0.10  # m, the saddle's half width (its visual box, vehicles/tricycle.py)

# Real-time chest posture control (§4.3.3, Eq. 4.8): k_C, T_C not given. Chosen k_C = 4 1/s,
# T_C = 1 s: a 0.25 s response and a slow return of the correction.
POSTURE_K_C = 4.0
POSTURE_T_C = 1.0

# Pedalling power detection (§4.4.3): no rule given. Chosen: a rise of the summed vertical ankle
# force by more than 40 % above its running mean (2 s window) while the crank stalls.
PPDM_RISE = 0.4
PPDM_WINDOW_S = 2.0
PPDM_PUSH_FACTOR = 2.0  # "push harder": f_trg doubled (150 → 300 N, near Table 7.6's 320 N)

# The legs turning the crank at a commanded rate (drive=legs, ch4_drive.LeadPedal): Eq. 4.22's Δt for
# the crank target is the thesis's transition time Δt = 0.8 s (§3.5.1); both soles press with Table
# 3.4's active-leg target f^trg_z = 150 N.
LEAD_DT = DELTA_T
LEGS_FZ = 150.0  # N
# Chosen cruising speeds ẋ^ref over the 10 mm steps (§7.3.1) and toward the 14 mm board (§4.4.3); the
# thesis gives none (its ch. 3 pedalling was far slower, T_2π = 57.6 s).
STEPS_SPEED = 0.3  # m/s
SMALL_SPEED = 0.3  # m/s
STEP_HEIGHT = 0.010  # m, "≈10 mm" steps (§7.3.1)
BOARD_THICKNESS = 0.014  # m, the 14 mm wooden board (Fig. 4.22)
MODEL_ERROR_MM = 10.0  # mm, chosen: the true crank centre / steering axis ahead of the controllers' nominal
# tricycle model in the ch. 3 rides (E1, E4); the thesis names no model error
SLIP_START_S = 2.0  # s, chosen: the seat slip of humanoid.sitting-recovery grows from this time on
RECOVERY_PEDAL_REVOLUTIONS = 6.0  # chosen: the ch. 3 crank schedule of sitting-recovery, longer than any ride
OVERTURN_ROLL = 45 * DEG  # chosen: the ch. 4 rig counts a fall when the tricycle's frame rolls beyond this

# Chosen: saddle friction 0.5 (vinyl on the robot's plastic cover); studded pedals under a rubber sole
# (soles hold on them while pushing hard: PPDM, STAND).
SADDLE_FRICTION = 0.5
PEDAL_FRICTION = 1.5
# Chosen: the ch. 4 rider's whole-body IK runs at 50 Hz (every 5th control period); the servos hold
# its output between solves. Steering rate limit 15°/s (the thesis: 5° per 1.6 s sample, E7 faster).
RIDER_PERIOD = 5 * CONTROL_PERIOD
STEER_RATE = 15 * DEG

# Crank motor standing in for the legs (drive=motor, NOT the thesis's method): velocity servo.
CRANK_MOTOR_KV = 200.0  # N m s/rad
CRANK_MOTOR_TORQUE = 60.0  # N m, ≈ a 480 N push at r = 0.125 m
# Feet riding the motor-driven pedals press with Table 3.4's leg target f^trg_z = 150 N (both feet:
# the two pedal torques cancel, the motor turns the crank), the contact state of the thesis's driving.
FOOT_FOLLOW_F_TRG = IMPEDANCE["passive_leg"].f_trg[2]
# Chosen: a ride counts as a fall once the tricycle frame tilts this far from upright (its z axis
# against the vertical); the thesis reports falls only qualitatively (§3.5.4: fall risk, safety lift).
FALL_TILT = 30 * DEG
# §3.5.4 (E7): the wait for a commanded motion to complete was cut to 80 % of the original's.
WAIT_FRACTION_IMPROVED = 0.8

# --- the numbers of balance/foot_damping.py -----------------------------------------------------------------------
DAMPING_T = 1.5  # s, T of Eq. 5.1 (Table 5.2; also hrpsys-base's eefm_rot_time_const default)
DAMPING_D_FLAT = 22.0  # N·m·s/rad, D "adaptive on a flat floor" and the SLC start value D₀ (§5.4.1)
# hrpsys-base's default rotation damping gain is 100 (20·5); the thesis's robot ran with 22.0 on the floor.
DELTA_LIMIT = 10 * math.pi / 180  # rad; chosen: hrpsys-base eefm_rot_compensation_limit (thesis: no value)
# Force difference control: no value in the thesis; hrpsys-base defaults (eefm_pos_damping_gain z,
# eefm_pos_time_const_support z, 2 × eefm_pos_compensation_limit).
FORCE_DIFF_D = 3500.0  # N·s/m
FORCE_DIFF_T = 1.5  # s
FORCE_DIFF_LIMIT = 0.05  # m

# --- the numbers of balance/preview.py ----------------------------------------------------------------------------
# Preview control parameters. The thesis gives none (§5.4 only cites [84][85]).
PREVIEW_TIME = 1.6  # s, N_L·T: hrpsys-base AutoBalancer's default (PreviewController.h, d = 1.6), also
# the preview used with Kajita 2003's example parameters (T = 5 ms, z_c = 0.814 m, Q_e = 1, R = 1e-6) in
# its common reproductions; the gains G_p have decayed below 1 % of their peak by then (tested)
PREVIEW_QE = 1.0  # Q_e, ZMP error weight: Kajita 2003's example and hrpsys-base's default q = 1
PREVIEW_R = 1e-6  # R, jerk increment weight: Kajita 2003's example and hrpsys-base's default r = 1e-6
# Q_x = 0 (Kajita 2003's example): the state increments are not penalised.
# Footstep timing: chosen, because not in the thesis (Fig. 5.6 shows the boarding but no timing):
# hrpsys-base's GaitGenerator defaults, default_step_time 1.0 s with double-support ratios 0.1 before
# + 0.1 after (GaitGenerator.h): 0.2 s double support and 0.8 s single support per step.
STEP_DOUBLE_S = 0.2
STEP_SINGLE_S = 0.8
# s, chosen: the ZMP rests this long at the start and the end; > 3/ω = 0.87 s of the LIP (ω = √(g/z_c)).
# Starting at rest 1 s before the first shift costs a 2.8 mm transient of the cart-table ZMP.
PLAN_HOLD_S = 1.0

# --- the numbers of balance/scooter.py ----------------------------------------------------------------------------
LIFT_GAP = 0.02  # m, chosen: the soles hang this far above the pads when the lowering starts
LIFT_SPEED = 0.05  # m/s, chosen: a hand-cranked care lift (§6.4.1 '介護用リフト') lowers at a few cm/s
V_PERIOD = 0.024  # s, v's sampling period and latency (Table 6.1, '*': latency = period)
VO_LATENCY = 0.010  # s, chosen: the thesis gives x_VO's period (10 ms) only; one period, like the '*' rows
VO_NOISE = 1.0e-3  # m, chosen: ZED visual odometry's position jitter, white, per sample
ACC_NOISE = 0.05  # m/s², chosen: a MEMS accelerometer's white noise at 250 Hz
LIFT_K, LIFT_C = 2.0e4, 2.0e3  # N/m, N·s/m, chosen: the harness's stiffness and damping (each axis)
LIFT_KR, LIFT_CR = 2.0e3, 2.0e2  # N·m/rad, N·m·s/rad, chosen: its hold of the waist's attitude
GYRO_NOISE = 0.005  # rad/s, chosen: a MEMS gyro's white noise at 250 Hz

COM_ITERATIONS = 3  # waist moves then IK; the mass centre settles over the axle to < 1 mm in 2–3

# --- the numbers of balance/stabilizer.py -------------------------------------------------------------------------
# LIP feedback gains of [55] Eq. 26 (k1 on the CoM, k2 on its velocity, k3 on the ZMP): hrpsys-base
# Stabilizer's defaults, −1.41429, −0.404082, −0.18, each × its k_ratio 0.9 (the thesis gives none).
LIP_K = (-1.41429 * 0.9, -0.404082 * 0.9, -0.18 * 0.9)
ZMP_DELAY_T = 0.04  # s, T_p of the ZMP's first-order response in [55] (hrpsys eefm_zmp_delay_time_const)
COM_VEL_FILTER = 0.9  # hrpsys's act_cogvel ← 0.9 act_cogvel + 0.1 (finite difference)
# s, the chest-attitude estimate's time constant for the CoM read through the IMU (balance/attitude.py): hrpsys's
# KalmanFilter defaults (Q_angle 0.001, Q_rate 0.003, R_angle 1000) at our 4 ms give a steady-state angle gain of
# 9.4e-4 per sample, an initial rate 0.23 1/s (issue 26)
ATTITUDE_TAU = 4.3

# --- the numbers of balance/standing.py ---------------------------------------------------------------------------
SWING_HEIGHT = 0.05  # m, chosen: hrpsys GaitGenerator's default_step_height
# chosen: the swing moves horizontally only for s ∈ [0.35, 0.65]; at s = 0.35 (and 0.65) the sole is
# 0.85 of the way up to (down from) its apex: 25 mm above the V-BOARD deck's 0.12 m with SWING_HEIGHT (tested)
SWING_DELAY = 0.35

# m, chosen: the CoM lowered for the 0.30 m step up (at the stand height the trailing leg is out of
# reach once the CoM is ≈0.15 m ahead of it, before it lifts: measured, 58 ticks out of reach)
BOARDING_CROUCH = 0.05
BOARDING_STEP_X = 0.30  # m, chosen: the landing's sole point; its heel 15 mm past platform_body's near edge

SETTLE_S = 0.1  # s, chosen: the keyframe's soles touch the floor at zero penetration (≈15 N a foot)

# --- the numbers of learning/mlc.py -------------------------------------------------------------------------------
T_L = 2.0  # s, mini-batch length (§6.3.2: 2/0.004 = 500 samples)
ETA_V = (1e-7, 1e-7, 1e-7)  # (η_P, η_I, η_D) for v (Table 6.6)
ETA_OMEGA = (1e-9, 1e-9, 1e-9)  # for ω (Table 6.6)
TERMINATION_K = 3  # consecutive mini-batches (Eq. 6.32, "k = 3")
# Chosen (Eq. 6.32 gives no numbers): σ — an RMS error of 1 cm/s for v and 0.01 rad/s for ω over a batch;
# ε — a gradient whose step η‖∇J‖ moves the gains by less than 1e-6 (the thesis's gains are O(1e-3), Fig. 6.15).
SIGMA_V, SIGMA_OMEGA = 1e-4, 1e-4
EPS_V, EPS_OMEGA = 1e-6 / ETA_V[0], 1e-6 / ETA_OMEGA[0]

MLC_ETA_MAX = 1.0  # chosen upper end of the learning-rate range; A must be positive definite (Table 6.4)

# --- the numbers of learning/prior_value_integrator.py ------------------------------------------------------------
R_SAT_V = 1.5  # r_sat^v of the comparison in §6.4.2 (Fig. 6.17)

# --- the numbers of learning/slc.py -------------------------------------------------------------------------------
SLC_Q = 0.1  # weight of e_τ² (Table 5.2)
SLC_R = 1.0e5  # weight of δ² (Table 5.2)
SLC_ETA = 0.01  # learning rate η (Table 5.2) → Q′ = 1e-3, R′ = 1e3
SLC_D0 = 22.0  # D at the start, the flat-floor value (§5.4.1)
SLC_D_MIN = 1.0  # chosen: floor under D (not in the text; D divides Eqs. 5.1 and 5.17)
# s, chosen: how long f_z must stay ≤ F_thre for the foot to count as in the air, which arms its landing
# guard (§5.4.1 guards foot *placements*; the thesis gives no hysteresis). Longer than the lift-off
# jitter and chatter (one to two 4 ms ticks, measured on the boarding), far shorter than a swing (0.8 s).
SLC_AIR_TIME = 0.1
SLC_ETA_MAX = 1.0  # chosen: η ∈ (0, 1]; Table 5.1 needs A = η > 0, the thesis runs 0.01

# --- the numbers of learning/speed_governing.py -------------------------------------------------------------------
VO_PERIOD = 0.010  # s, x_VO sampling (Table 6.1)
T_V, T_OMEGA = 1.1, 0.6  # s, identified lags (Table 6.2)
K_V, K_OMEGA = 5.88e2, 1.39e4  # identified gains (Table 6.2); units of u as the thesis's (see module doc)
T_F = 0.5  # s, chosen: Eq. 6.3's T_f is not given; 0.5 s keeps a 0.05 m/s² accelerometer bias to 2.5 cm/s
MIX = np.array([[1.0, 1.0], [1.0, -1.0]])  # Eq. 6.5

# --- the numbers of robots/hrp2.py --------------------------------------------------------------------------------
WHITE = [0.92, 0.92, 0.94, 1]
BLUE = [0.22, 0.36, 0.72, 1]
GREY = [0.35, 0.35, 0.38, 1]

# --- the numbers of robots/kenshiro.py ----------------------------------------------------------------------------
SKIN = [0.85, 0.75, 0.55, 1]
