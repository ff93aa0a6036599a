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
CAGING = CagingExperiment()
PLANT = PlantSettings()
