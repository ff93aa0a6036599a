"""Constants of the wheeled snake robot of seed 001 (Nakajima 2020), one place, each with its source.

Every value is either a thesis number (section / table cited) or marked *chosen* with the reason.
Seed 001 is the source of truth; the English extraction is ``/work/shared/spec/001-snake.md``
(cited as "spec §x", errata as "A<n>").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

PI = math.pi


@dataclass(frozen=True)
class SnakeGeometry:
    """Body of the wheeled snake (§2.1): 2n links of length ``l``, 2n−1 joints, n wheel pairs.

    Odd joints (1, 3, …, 2n−1) are yaw, even joints (2, …, 2n−2) pitch. Wheel i < n is coaxial with
    pitch joint 2i; wheel n is at the tail tip (eqs. (2.3)–(2.4) only fit this layout, spec §1.1, A2).
    """

    n: int = 9  # wheels; §3.3 "車輪数 n = 9" (also the caging experiment, §3.4.1)
    l: float = 0.0685  # m, link length; §3.3 "リンク長 l = 0.0685 m"
    # Joint limit of the Ch. 3 robot: drawn in Fig. 3.7 only, no value in the text (A12).
    # Chosen π/2 because the Ch. 4 robot of the same lab and servo family states ψ_lim = π/2 (§4.5).
    joint_limit: float = PI / 2

    def __post_init__(self) -> None:
        if not (isinstance(self.n, int) and self.n >= 2):
            raise ValueError(f"n (wheels) must be an integer >= 2, got {self.n!r}")
        if not self.l > 0:
            raise ValueError(f"l (link length) must be > 0 m, got {self.l!r}")

    @property
    def joints(self) -> int:
        """2n − 1 joints (§2.1)."""
        return 2 * self.n - 1

    @property
    def length(self) -> float:
        """Total length 2n·l (§2.1)."""
        return 2 * self.n * self.l

    @property
    def wheel_offsets(self) -> tuple[float, ...]:
        """Arc length from the head tip to each wheel axle: 2l·i, i = 1..n (from (2.3)–(2.4)).

        Head tip –l– yaw joint 1 –l– wheel 1 –l– yaw joint 3 –l– wheel 2 … –l– wheel n (tail tip).
        """
        return tuple(2 * self.l * i for i in range(1, self.n + 1))

    @staticmethod
    def yaw_joint(i: int) -> int:
        """Joint number (1-based) of the i-th yaw joint φ_i: 2i − 1 (§2.2)."""
        return 2 * i - 1

    @staticmethod
    def pitch_joint(i: int) -> int:
        """Joint number (1-based) of the pitch joint carrying wheel i < n: 2i (§2.1)."""
        return 2 * i


@dataclass(frozen=True)
class TwoPointGains:
    """Two-point controller of Ch. 3, the parameter list of §3.3 (the caging run §3.4.1 uses the same)."""

    dt: float = 0.05  # s, control period δt; §3.3
    t_sigma: float = 2.0  # mode-selection period t_σ; §3.3 prints "t_σ = 2" without unit: chosen seconds (A9)
    phi_th: float = PI / 4  # rad, threshold φ_th of V_{u,1} (3.13); §3.3
    n_l: int = 4  # (ii') n_g ≤ n_σ ≤ n − n_l; §3.3
    n_g: int = 4  # §3.3
    n_c: int = 2  # (iii) at most n_c adjacent wheels lifted; §3.3
    # ‖u_σ‖ threshold of (3.20); §3.3 "u_lim = 4", unit and norm not printed (A10):
    # chosen the Euclidean norm of the joint rates in rad/s.
    u_lim: float = 4.0
    # K_p = k_p·I_6. §3.3 prints "K_p = 4 I_4", but K_p multiplies the 6-vector c_c (3.4): read 4·I_6 (A5).
    k_p: float = 4.0
    k_v: float = 2.0  # redundancy gain of (3.5); §3.3
    k_u: tuple[float, float, float] = (0.6, 0.8, 0.0)  # k_{u,1..3} of (3.12); §3.3
    k_m: tuple[float, float] = (0.0, 1.0)  # k_{m,1}, k_{m,2} of (3.19); §3.3
    # Run-counting rule for (iii). §3.3 states 66 candidates; the literal rules give 80 (spec §3.1, A8).
    # Chosen: the wheel-less head end counts as one more lifted element, which gives exactly 66.
    # Reason: the head tip is 2l ahead of wheel 1, the tail wheel is the tail tip, so with this rule the
    # unsupported overhang is at most 4l at both ends (wheels 1 | 8, 9 lifted); without it the head end
    # could overhang 6l (wheels 1, 2 lifted) while the tail end never can.
    head_end_lifted: bool = True
    candidate_count: int = 66  # §3.3 "選択対象のモード数は66"; the enumeration is tested against it

    def __post_init__(self) -> None:
        for name in ("dt", "t_sigma", "u_lim", "k_p", "phi_th"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be > 0, got {getattr(self, name)!r}")
        if not (self.n_l >= 3 and self.n_g >= 3):
            raise ValueError(f"n_l and n_g must be >= 3 (§3.2.4), got n_l={self.n_l}, n_g={self.n_g}")


@dataclass(frozen=True)
class TrackingExperiment:
    """Two-point trajectory tracking, §3.3 (real robot): ramp (3.21) from c_c(0) to c_{c,e}."""

    t_end: float = 120.0  # s; §3.3
    phi0: tuple[float, ...] = (PI / 6, -PI / 6, -PI / 6, 0.0, PI / 6, 0.0, 0.0, PI / 6, PI / 6)  # §3.3
    w_h0: tuple[float, float, float] = (0.0, 0.0, PI)  # [x_h, y_h, θ_{y,h}](0); §3.3 (printed p̃_h(0))
    # c_{c,e} = [head x, y, θ; tail x, y, θ]; §3.3. The tail's −π/2 is only right modulo 2π; the ramp
    # must use the branch nearest c_c(0) (3π/2), see targets.unwrap_targets (A6).
    c_e: tuple[float, ...] = (-0.4, -0.4, PI / 2, -0.8, -0.4, -PI / 2)


@dataclass(frozen=True)
class CagingExperiment:
    """Caging transport, §3.4.1: same gains and head pose as §3.3; two-stage ramp (3.22)–(3.23)."""

    t_end: float = 120.0  # s; "same as the tracking experiment", §3.4.1
    t_s1: float = 30.0  # s; §3.4.1
    phi0: tuple[float, ...] = (0.0, PI / 9, PI / 9, PI / 6, PI / 9, PI / 6, PI / 6, PI / 6, 0.0)  # §3.4.1
    w_h0: tuple[float, float, float] = (0.0, 0.0, PI)  # §3.4.1 (same as §3.3)
    c_e1: tuple[float, ...] = (0.1, 0.0, PI, 0.1, -0.5, 0.0)  # §3.4.1; tail heading 0 ≡ 2π (A6)
    c_e2: tuple[float, ...] = (0.55, 0.0, PI, 0.55, -0.5, 0.0)  # §3.4.1


@dataclass(frozen=True)
class PlantSettings:
    """Integration of the kinematic plant (the thesis's own model, spec §5.2). All chosen."""

    # RK4 steps per control period δt. Chosen 2 (25 ms): within a period u and σ are constant, so the
    # ODE is smooth; tests/snake/test_plant.py checks 2 against 200 steps to < 1e−5 m at ‖u‖ = u_lim.
    rk4_steps: int = 2

    def __post_init__(self) -> None:
        if not (isinstance(self.rk4_steps, int) and self.rk4_steps >= 1):
            raise ValueError(f"rk4_steps must be an integer >= 1, got {self.rk4_steps!r}")


CH3_ROBOT = SnakeGeometry()
CH3_GAINS = TwoPointGains()
TRACKING = TrackingExperiment()
# not a thesis number: issue 30's aim for snake.tracking on the kinematic plant, simulated seconds per wall second
# (shintai bench reports against it)
REALTIME_TARGET = 300.0
CAGING = CagingExperiment()
PLANT = PlantSettings()


@dataclass(frozen=True)
class MujocoSnakeSettings:
    """Physical build of the MuJoCo snake (mujoco_plant.py). The thesis gives none of these for the Ch. 3
    robot (A12: masses, torques, tread, wheel radius and the lift are never given); each is *chosen*, reason
    next to it. Link length and wheel layout come from :class:`SnakeGeometry`.
    """

    # r_w: the Ch. 4 robot of the same lab and servo family states r_w = 0.029 m (§4.5). It must exceed the
    # link's half-height (link_radius) by more than lift_height, or a pitched link would scrape the floor.
    wheel_radius: float = 0.029
    wheel_half_width: float = 0.005  # m; a thin rubber tyre (thickness is ignored by the model, §2.6.1)
    # d_tr, distance between the left and right wheels: not given (§2.6.1). XH430 body 28.5 mm wide plus a
    # bracket and a tyre on each side; 0.08 m also keeps the body well inside the 0.5 m caging U.
    tread: float = 0.08
    # Link collision capsule radius: the XH430-V350-R case is 28.5 × 34 mm, so about 17 mm half-size; the
    # 12 mm floor clearance (r_w − 0.017) exceeds lift_height, so only wheels touch the floor.
    link_radius: float = 0.017
    link_mass: float = 0.1  # kg; one XH430-V350-R (82 g) plus bracket per link
    wheel_mass: float = 0.01  # kg; one wheel with hub
    # Lift of a lifted wheel (§2.3: "slightly", no value, A14). 8 mm: clear of the floor with the servo sag
    # under the lifted part's weight (≈ 0.3 N·m / kp ≈ 15 mrad ≈ 2 mm at 2l), yet the largest pitch angle
    # (2·asin(8 mm / 2l) ≈ 0.12 rad) keeps the 2D model's zero-pitch approximation (§2.3).
    lift_height: float = 0.008
    # Least-squares weight of a grounded wheel's height and axle-tilt rows in mujoco_plant.lift_profile
    # (a lifted wheel's: 1). Chosen 10: with equal weights the support kept ~2 mm residuals, the rigid
    # body rocked onto other wheels and its long lifted tail touched down 30 % of the time; with 10, < 5 %.
    lift_ground_weight: float = 10.0
    # Largest pitch-joint rate while lifting or lowering wheels (rad/s). How fast the robot lifts is not
    # given (A14). Reaching the new pitch targets within one δt (2α ≈ 0.12 rad in 50 ms, wheels dropped and
    # lifted at ≈ 0.16 m/s) made impacts with the stiff servos below: on MuJoCo 3/4 of the sideways slip of
    # caging fell within 0.15 s of a mode switch, and tracking (§3.3) jumped 9 mm off its targets right
    # after one. 0.5 rad/s lifts a wheel in about 0.25 s (servo no-load speed ≈ 4.8 rad/s): tracking 2.9 mm,
    # caging slip 5.4 → 3.5 %, at the price of a lifted wheel still touching for those 0.25 s
    # (contact_mismatch_fraction 0.6 → 3.8 % in caging).
    lift_rate: float = 0.5
    # For the slip statistics only: a control period counts as "steady" (no lift transient) from this long
    # after a mode switch; twice the time lift_rate needs for a full lift.
    switch_settle: float = 0.5
    # Position servo (XH430-V350-R, commanded by angle and angular velocity, §3.3): PD with velocity
    # feed-forward, torque = kp (ψ_cmd − ψ) + kv (ψ̇_cmd − ψ̇), clamped at the stall torque. At the factory
    # P gain the XH430 reaches its stall torque at about 0.2 rad of error (kp ≈ 20 N·m/rad); its P gain goes
    # 20× higher. kp 200 N·m/rad: the pitch joints then sag < 0.01 rad under the lifted parts' weight. At
    # 60 N·m/rad they sagged 12–25 mrad (2–3 mm at 2l, a third of lift_height): in caging on MuJoCo a
    # grounded wheel hung or a lifted one touched in 12 % of the control periods, all through each t_σ
    # window, and the body then moved by another mode's constraints (38 mm off the targets at t ≈ 83 s);
    # at 200 the mismatches are confined to the lift transients. (400 N·m/rad chattered at the 2 ms step.)
    # kv 2 N·m·s/rad: ζ = kv / (2 √(kp J)) ≈ 0.7 with J ≈ the armature.
    servo_kp: float = 200.0
    servo_kv: float = 2.0
    servo_torque: float = 4.1  # N·m; XH430-V350-R stall torque at 12 V (datasheet)
    # Reflected rotor inertia of a 353.5:1 gear head, about 1e−7 kg·m² × 353.5² ≈ 0.01 kg·m².
    servo_armature: float = 0.01
    wheel_damping: float = 1e-5  # N·m·s/rad; ball-bearing hub, "rolls almost freely" (§2.1)
    # Tyre friction (slide, torsion, roll). §2.1 assumes no slip along the axle: rubber μ = 1 on the floor.
    wheel_friction: tuple[float, float, float] = (1.0, 0.005, 0.0001)
    body_friction: float = 0.3  # μ of links, box, door and cart (plastic / cardboard on the floor)
    # Contact model for the passive wheels (STACK.md): condim 6 with elliptic cones and impratio ≈ 10
    # made side slip about 0.1 % of the forward speed. MuJoCo uses the larger condim of a pair.
    wheel_condim: int = 6
    impratio: float = 10.0
    timestep: float = 0.002  # s, physics step
    servo_period: float = 0.01  # s; servo targets are ramped in these steps within one control period δt
    # Mocap (OptiTrack V120:Trio, §3.3): markers on a rigid body about 5 cm across, so a position noise σ
    # gives a heading noise of about σ / 0.05 m.
    marker_span: float = 0.05

    def __post_init__(self) -> None:
        if not self.wheel_radius > self.link_radius + self.lift_height:
            raise ValueError(f"wheel_radius {self.wheel_radius} must exceed link_radius + lift_height = "
                             f"{self.link_radius + self.lift_height} m (links would touch the floor)")
        ratio = self.servo_period / self.timestep
        if round(ratio) < 1 or abs(ratio - round(ratio)) > 1e-9:
            raise ValueError(f"servo_period {self.servo_period} s must be a whole multiple of timestep {self.timestep} s")


MUJOCO_SNAKE = MujocoSnakeSettings()


# ------------------------------------------------------------------------------- Ch. 4: two planes (§4.5)

CH4_ROBOT = SnakeGeometry(n=9, l=0.0905, joint_limit=PI / 2)  # §4.5: n = 9, l = 0.0905 m, ψ_lim = π/2 rad


@dataclass(frozen=True)
class TwoPlaneSettings:
    """Two-plane locomotion, §4.5: values common to both conditions, then the ones the text leaves open (A19)."""

    r_w: float = 0.029  # m, wheel radius; §4.5
    dt: float = 0.2  # s, control period; §4.5
    n_h: int = 3  # head part of the head adaptation (= head transition); §4.5
    n_c_max: int = 2  # rear-end condition n_c < n_{c_max}; §4.5
    eps_d: float = 0.029  # m, front-end condition d_e < ε_d; §4.5 (trial and error, §4.2.4)
    # K_h of (4.14): not given (A19). Chosen k_h·I_3 with k_h = 1, the value of k_c and k_p in Table 4.1.
    k_h: float = 1.0
    # ε_1 of §4.4.1 (head transition done when r_{1,d} − r_1 < ε_1): not given (A19). Chosen as a bound on
    # max|r_{1,d} − r_1| (m and rad) small enough that laying the front part exactly on the front plane at
    # the switch (the plane-part model assumes it, §4.3.2) moves the tail, 1.5 m away, by ≤ 0.15 mm.
    eps_1: float = 1e-4
    # "Front shift complete": no test in the text (A19). Chosen |ψ_{c,1}| < 1e−4 rad. The landed pitch joint
    # keeps that residual (it is no input in the front part), and the residuals of the 8 landings add up
    # along the body: 1e−3 rad left 2 mm at the tail; 1e−4 rad keeps it near 0.2 mm, for ~2.3 s more per
    # landing at K'_c = 1. K'_c of (4.28) is not given: chosen K_c, padded to 4×4.
    front_shift_tol: float = 1e-4
    # Plant: RK4 steps per control period (0.05 s); tests/snake/test_two_plane.py checks them against 40.
    rk4_steps: int = 4


@dataclass(frozen=True)
class TwoPlaneCondition:
    """One condition of §4.5: the front-plane pose and its row of Table 4.1 (K_c = k_c I_3, K_p = k_p I_3)."""

    name: str
    p_f: tuple[float, float, float]  # m, origin of Σ_f (mocap marker on the front plane); §4.5
    theta_f: tuple[float, float, float]  # rad, [roll, pitch, yaw] of Σ_f; §4.5
    d_d: float  # m, desired height of the lifted connection wheels in V_2 (4.35); Table 4.1
    d_r: float  # m, normalising range of V_2 (4.35); Table 4.1
    k_c: float  # K_c = k_c I_3 (4.18); Table 4.1 (lower-case: read as a scalar gain, spec §3.2)
    k_p: float  # K_p = k_p I_3 (4.16); Table 4.1
    k_v: float  # redundancy gain (4.19); Table 4.1
    k_u1: float  # weight of V_1 (joint limits) (4.33); Table 4.1
    k_u2: float  # weight of V_2 (plane edges) (4.33); Table 4.1
    v_p: float  # m/s, head speed of (4.36); Table 4.1
    A: float  # m, amplitude of (4.36); Table 4.1
    T: float  # s, period of (4.36); Table 4.1


CONDITION_1 = TwoPlaneCondition("condition 1 (front plane rolled)", (0.595, 0.146, 0.0970), (-0.107, 0.0, 0.0),
                                0.272, 0.272, 1.0, 1.0, 3.0, 0.7, 0.3, 0.01, 0.25, 90.0)
CONDITION_2 = TwoPlaneCondition("condition 2 (front plane pitched)", (0.593, 0.140, 0.0673), (0.0, -0.0609, 0.0),
                                0.181, 0.181, 1.0, 1.0, 2.0, 0.7, 0.3, 0.01, 0.3, 90.0)
TWO_PLANE = TwoPlaneSettings()


@dataclass(frozen=True)
class TwoPlaneScene:
    """What §4.5 leaves open but a simulation needs (A19, A21): plane edges, body thickness, initial posture.

    All chosen. The front plane is the rectangle ^f x ∈ [edge_x, edge_x + length], |^f y| ≤ half_width of Σ_f.
    """

    # Near edge of the front plane, in Σ_f. p_f is the mocap marker *on* the plane (§4.5): taken 10 cm in.
    edge_x: float = -0.10
    gap: float = 0.05  # m, horizontal gap from the rear plane's end to the front edge ("a gap", §4.1)
    length: float = 4.0  # m; with half_width, larger than anything the run reaches
    half_width: float = 1.0
    # Body thickness for the edge clearance: the wheels are discs of radius r_w at the axles (§2.6.1); the
    # links between them are capsules of radius 0.017 m, half the 34 mm of an XH430 servo case (the Ch. 3
    # robot's servo, §3.3; Ch. 4 names none).
    link_radius: float = 0.017
    # Initial posture: §4.5 reads ψ_0 from the robot, the text gives none. Built as the posture just after
    # the head transition (n_f = 1, rear end n_h), then the head part is turned away from it with wheel n_h
    # fixed, so that the head transition has work to do:
    wheel1_past_edge: float = 0.10  # m; wheel 1 lands 10 cm inside the front plane, at ^f y = 0, heading π
    # Start of the Newton settle of joints 2..2n_h (an arch over the edge, ψ > 0 turns the tail-ward link down).
    connection_guess: tuple[float, ...] = (-0.15, 0.0, 0.8, 0.0, -0.5)
    # Yaw joints 2n_h+1, …, 2n−1 on the rear plane: a gentle S, so that no plane part starts at singular
    # configuration I (parallel or concurrent axles, §2.3.4).
    rear_yaw: tuple[float, ...] = (0.3, 0.3, 0.0, -0.3, -0.3, 0.0)
    # Added to joints 1..2n_h (wheel n_h fixed): wheel 1 starts 7 mm high, tilted κ ≈ 0.04, λ' ≈ −0.13 rad.
    head_offset: tuple[float, ...] = (0.1, -0.12, 0.05, 0.05, -0.05, -0.05)


TWO_PLANE_SCENE = TwoPlaneScene()
# A wheel is "on a plane" when |d − r_w| and |κ| of (2.36)–(2.37) are below these (spec §5.4 #15's tolerances).
ON_PLANE_D_TOL = 1e-3  # m
ON_PLANE_TILT_TOL = 0.01  # rad


@dataclass(frozen=True)
class CagingBox:
    """The object of the caging transport, §3.4.1 ("the white box in the middle of Fig. 3.9"); the thesis
    gives no size, mass or friction (A12), all chosen."""

    # Half sizes (m): a 12 × 12 × 10 cm cardboard box. The U of φ(0) leaves about 0.44 × 0.49 m clear
    # inside (body width 2·(tread/2 + tyre) ≈ 0.09 m), so the box fits with several cm all round.
    half: tuple[float, float, float] = (0.06, 0.06, 0.05)
    mass: float = 0.15  # kg; an empty cardboard box (μ = body_friction = 0.3: 0.44 N to push it)
    # Initial centre (m): inside the U of φ(0) at w̃_h(0) (spec §4.2), 5 cm clear of the U's bottom
    # (its inner wheels at x ≈ −0.44), midway between the sides (y ≈ 0 and −0.59).
    xy: tuple[float, float] = (-0.33, -0.30)


CAGING_BOX = CagingBox()
# The box on the kinematic plant (caging.KinematicBox) is pushed clear of the body in at most this many passes
# per δt (chosen: one push can move it into another part of the body; the U's corners need two or three).
BOX_PUSH_PASSES = 8


@dataclass(frozen=True)
class DoorSetup:
    """The spring-hinged door of §3.4.3 and the motion designed for it. The thesis gives no door geometry,
    spring, hook or trajectory numbers (A18: an operator chose targets and phases with a gamepad); every
    value here is chosen, reason next to it. Frame: the wall is x ∈ [0, thickness], the robot starts
    outside (x < 0); the hinge is at the origin and the leaf, closed, spans y ∈ [0, width]; it opens
    toward the robot (the knob is pulled, §3.4.3), turning counter-clockwise seen from above.
    """

    n: int = 15  # wheels: "30 links" (§3.4.3); link length etc. "as the tracking robot" (CH3_ROBOT)
    # Mode constants: §3.3's (n_c = 2, n_g = 4, t_σ = 2 s; the door text gives none), on the base of the
    # head-raised model with its two front wheels kept down (spatial.base_candidates, fixed = 2).
    width: float = 0.40  # m; a small door: twice the ≈ 0.2 m the body needs to pass (U-turn of two arms)
    thickness: float = 0.02  # m; leaf and wall
    height: float = 0.25  # m
    floor_gap: float = 0.005  # m; the leaf clears the floor but not the snake's 58 mm tall wheels
    leaf_mass: float = 0.3  # kg; a light panel (foam board)
    # Hinge spring (N·m/rad) and damping (N·m·s/rad). Held open at 90° the spring pulls the knob with
    # k·(π/2)/0.37 m ≈ 1 N, well below the lateral grip of the hooked body's grounded wheels (μN ≈ 1 N per
    # wheel pair on 4–5 pairs); damping 0.05 gives ζ ≈ 0.4 with the leaf's 0.016 kg·m² (no slamming).
    spring: float = 0.25
    damping: float = 0.05
    open_limit: float = 1.75  # rad; door stop at 100°; the frame stops it at 0 (closed)
    # Knob: on the outside face, knob_from_edge from the free edge, standing knob_offset off the face: the
    # hooked head then lies 7 cm off the leaf, so the body (±0.045 m) clears it when the door is open.
    knob_from_edge: float = 0.03
    knob_offset: float = 0.07
    knob_radius: float = 0.012  # m; a 24 mm ball (visual; the hook is an equality, not a contact)
    knob_stem_radius: float = 0.006  # m; the knob's stem (visual)
    knob_mass: float = 0.01  # kg, ball and stem each
    # The knob slides vertically on the leaf (m, down and up), so that the hook holds it only in the plane:
    # the planar head cannot follow its height exactly (the thesis's hook is "simple", §3.4.3).
    knob_slide: tuple[float, float] = (-0.03, 0.05)
    leaf_clearance: float = 0.005  # m between the leaf's edges and the door frame
    wall_length: float = 1.5  # m of wall on each side of the doorway (further than the body reaches)
    hook_capture: float = 0.006  # m; the hook engages when the head tip is this close to the knob
    # Motion (operator's targets, A18). Initial U around where the leaf will swing (head arm along the
    # closed knob's line, U-turn of 4 × −π/4, tail arm at y ≈ 0.7, outside the leaf's 0.4 m sweep); small
    # alternating angles keep the arms off singular configuration I (parallel axles, §2.3.4).
    approach_gap: float = 0.03  # m; the head starts this far short of the knob
    phi0: tuple[float, ...] = (0.1, -0.1, 0.1, -0.1, 0.1, 0.05, -PI / 4, -PI / 4, -PI / 4, -PI / 4,
                               0.05, -0.1, 0.1, -0.1, 0.0)
    open_angle: float = PI / 2  # rad; phase 1 pulls the door to 90°
    pull_waypoints: int = 19  # the knob's arc about the hinge as waypoints 5° apart (the pull is linear between)
    # Head raising for phases 1–2 as the thesis does it ([12], §3.4.3): wheels 1..raise_n_h − 1 lifted as an
    # arm of 2·raise_n_h links (0.55 m, more than the knob's 0.37 m radius about the hinge), raised at
    # raise_pitch from wheel raise_n_h and levelled at joint 2 (as the handcart's arms), the hook at its tip.
    raise_n_h: int = 4
    raise_pitch: float = 0.3
    # The knob is this far below the raised head tip's unloaded height: the arm sags ≈ 12 mm under its weight
    # when the body settles (MujocoSnake.settle, settle s), and the knob slides ±(knob_slide) on the leaf.
    knob_drop: float = 0.01
    settle: float = 1.0  # s at rest before the run starts
    t_approach: float = 5.0  # s; phase 1a, head to the knob
    # Target durations (s, on the operator's clock). Speeds as in §3.3 (0.57 m in 120 s ≈ 5 mm/s): the
    # knob's 0.58 m arc in 120 s; the tail's 0.62 m to the doorway in 120 s and 0.38 m inside in 80 s.
    t_pull: float = 120.0
    t_tail: tuple[float, float] = (120.0, 80.0)
    # Phase 2 tail waypoints (m): in front of the doorway, then inside; close to the leaf (§3.4.3: "as close
    # to the door as possible" so that the released door lands softly on the body).
    tail_doorway: tuple[float, float] = (-0.08, 0.17)
    tail_inside: tuple[float, float] = (0.30, 0.15)
    t_settle: float = 3.0  # s; after the hook is released, the door closes onto the body
    # Phase 3, shift control [8]: the shape moves one yaw-joint spacing (2l) toward the head every
    # shift_period s, so the body crawls tail-first at 2l / 2 s ≈ 7 cm/s; beyond the tail the curve is
    # continued by a serpenoid of amplitude shift_amplitude and shift_wave joints per wave (the thesis's
    # tail "snakes" through, Fig. 3.14c).
    shift_period: float = 2.0
    shift_amplitude: float = PI / 6
    shift_wave: int = 8
    t_shift: float = 60.0  # s; time allowed for phase 3
    # Simulated time allowed for a whole run (the operator's clock stops while the robot is stopped).
    t_budget: float = 480.0
    # The operator gives up when the robot has not followed for this long (10 mode selections of t_σ).
    give_up: float = 20.0
    pass_margin: float = 0.03  # m; passed = every link origin this far beyond the wall's inner face
    # Perturbed runs (two runs of an operator differ): the body starts up to ±1 cm in x, y and ±0.03 rad in
    # heading off, the hinge spring up to ±20 % off (uniform draws). Chosen: a few times the operator's
    # placement error, and a spring the thesis does not give.
    perturb_pose: tuple[float, float, float] = (0.01, 0.01, 0.03)
    perturb_spring: float = 0.2


DOOR = DoorSetup()


@dataclass(frozen=True)
class HandcartSetup:
    """Handcart steering, §3.4.2: the double-arm model (2.35) with n = 15, head and tail raised, pushing a
    cart's handle. n_h, n_t, the modes, gains, t_end and the cart are not given (A17); all chosen here."""

    n: int = 15  # §3.4.2 "n = 15"
    # Base wheels n_h..n_t on the floor. n_h = 3 and n_t = 12 give two equal arms of 6 links (0.41 m):
    # the head part (joints 1–6, wheels 1–2 raised) and the tail part (joints 24–29, wheels 13–15 raised;
    # wheel n is the tail tip); B_d then has 2n − n'_b + 1 = 21 columns for 19 rows with all 10 base wheels
    # grounded (n_h >= 2 and the 6 tail rows need it, §2.5).
    n_h: int = 3
    n_t: int = 12
    # Initial base: a U of 10 wheels (yaw joints 7–23) with arms 0.42 m apart, opening toward +x; the arms
    # rise at γ from wheels n_h and n_t (pitch joints 2n_h and 2n_t) and level off two wheels on (joints 2 and
    # 28), so both tips point +x, level, 0.11 m up, side by side (FK: head (0.40, 0), tail (0.40, 0.42)).
    base_yaw: tuple[float, ...] = (0.1, -0.1, -PI / 5, -PI / 5, -PI / 5, -PI / 5, -PI / 5, 0.1, -0.1)
    arm_pitch: float = 0.3
    advance: float = 0.5  # m; c_{d,e}: both ends +0.5 m in x, the rest held (§3.4.2, read as in A17)
    # s the MuJoCo body rests under gravity before the run (MujocoSnake.settle): placed unloaded, the raised
    # arms sagged 2–3 cm within 0.1 s, which the run counted as 33 mm of tracking error and 12 mm of drift;
    # by 1 s the errors were < 1 mm.
    settle: float = 1.0
    t_end: float = 120.0  # s; as §3.3
    # Base modes: wheels n_h and n_t always grounded (the model assumes them on the plane, (2.16), (2.29)),
    # at most n_c lifted in a row, at least n_g grounded: §3.3's n_c = 2, n_g = 4 and t_σ = 2 s (the handcart
    # text restates no constants, A17; caging keeps §3.3's). An earlier choice n_c = 1 (the door's reason)
    # left too few base modes: within any one mode σ_min(B_{d,σ}) fell from 0.02 to < 1e−3 in ≈ 1.3 s,
    # before the next selection, so (3.20) stopped the robot at ≈ 3 s even on the kinematic plant.
    n_c: int = 2
    n_g: int = 4
    # Grounded wheels kept at each end of the base in every mode: 2, wheels n_h, n_h + 1 and n_t − 1, n_t
    # (spatial.base_candidates: lifting n_h + 1 tips the frame of wheel n_h that (2.16) holds level).
    fixed_end_wheels: int = 2
    # Cart: a 0.40 × 0.62 m board on four fixed-axle wheels (it rolls along x only, like a cart pushed
    # straight) with a handle pad in front of each tip. Light (0.5 kg) so that the pushing force (rolling
    # resistance and acceleration) stays far below the tips' servo torques.
    cart_half: tuple[float, float, float] = (0.20, 0.31, 0.01)
    cart_mass: float = 0.5
    cart_wheel_radius: float = 0.03
    cart_wheel_half_width: float = 0.01
    cart_wheel_inset: float = 0.02  # m, wheels this far in from the board's sides
    cart_wheel_mass: float = 0.02
    cart_wheel_friction: tuple[float, float, float] = (1.0, 0.005, 0.0001)  # rubber, as the snake's tyres
    cart_wheel_damping: float = 1e-4  # N·m·s/rad; a cheap caster bearing, 10× the snake's hub
    # Handle pads (half sizes: thickness along x, width, height; m): 12 × 6 cm faces, wide enough that the
    # tips stay on them with a few cm of sideways error, on light struts (visual only, no contact).
    pad_half: tuple[float, float, float] = (0.01, 0.06, 0.03)
    pad_mass: float = 0.01
    strut_radius: float = 0.005
    strut_mass: float = 0.001
    bar_gap: float = 0.01  # m between the head tip's capsule end (tail wheel's rim) and its pad at the start


HANDCART = HandcartSetup()
