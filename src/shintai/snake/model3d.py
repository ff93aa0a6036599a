"""3D kinematics of the wheeled snake — seed 001 §2.1, §2.5 (head raised, double arm) and §2.6 (wheel–plane).

Chain (§2.1, spec §1.1, §5.1 item 2; 1-based thesis numbers, 0-based arrays):

* 2n links of length l, 2n−1 joints; odd joints yaw (about the link's z), even joints pitch (about its y).
* ``R[m]`` is the frame of link m+1, ``R[0] = R_h`` (2.1); joint j turns link j into link j+1:
  ``R[j] = R[j−1] R_z(ψ_j)`` (j odd) or ``R[j−1] R_y(ψ_j)`` (j even). Positive pitch turns the tail-ward
  direction down (R_y(ψ) e_x = [cos ψ, 0, −sin ψ]); the thesis fixes no sign.
* ``P[0]`` is the head tip, ``P[k] = P[k−1] + l R[k−1] e_x`` is joint k (k ≤ 2n−1) and ``P[2n]`` the tail
  tip. e_x points tail-ward (§2.1, A3). Wheel i sits at ``P[2i]`` (joint 2i, or the tail tip for i = n, A2).
* Wheel frame Σ_{w,i} (2.2): e_x along the link *behind* wheel i, e_z along the yaw joint behind it, i.e.
  the frame of link 2i+1 (``R[2i]``); the tail wheel n has no link behind, it takes link 2n (``R[2n−1]``).
  The pitch joint at a wheel turns about that wheel's axle, so e_y (the axle) is the same on both links.
* Poses are w = [p; θ] with θ = [roll, pitch, yaw] and R = R_z(yaw) R_y(pitch) R_x(roll) (2.1)–(2.2).
  With all pitch joints 0 and a level head this chain is the planar model of model.py.

Velocities: a *twist* is [v_h; ω_h], the head tip's velocity and the head frame's angular velocity in the
world. Every Jacobian below is a pair (J_twist, J_psi) with velocity = J_twist twist + J_psi ψ̇ over all
2n−1 joints; :func:`head_euler_map` turns Euler rates ẇ_h into the twist.

Models built on the chain: the head-raised model (2.16)–(2.26), the double-arm model (2.27)–(2.35) used by
the handcart experiment (§3.4.2), and the wheel–plane relation d, κ, λ (2.36)–(2.38).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core.geometry import cross3, rot_x, rot_y, rot_z, skew
from shintai.snake.model import configuration, constraint_matrices

E_X, E_Y, E_Z = np.eye(3)
I3 = np.eye(3)


def rot_zyx(theta) -> np.ndarray:
    """R = R_z(θ_y) R_y(θ_p) R_x(θ_r) of θ = [roll, pitch, yaw], eqs. (2.1)–(2.2)."""
    roll, pitch, yaw = theta
    return rot_z(yaw) @ rot_y(pitch) @ rot_x(roll)


def euler_zyx(R: np.ndarray) -> np.ndarray:
    """[roll, pitch, yaw] of R = R_z R_y R_x (2.1), pitch in [−π/2, π/2]."""
    pitch = math.asin(max(-1.0, min(1.0, -R[2, 0])))
    return np.array([math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])])


def euler_rate_matrix(theta) -> np.ndarray:
    """E with ω = E θ̇ for θ = [roll, pitch, yaw] of (2.1): columns R_z R_y e_x, R_z e_y, e_z."""
    _, pitch, yaw = theta
    cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)
    return np.array([[cy * cp, -sy, 0.0], [sy * cp, cy, 0.0], [-sp, 0.0, 1.0]])


def head_euler_map(theta_h) -> np.ndarray:
    """6×6 map from ẇ_h = [ṗ_h; θ̇_h] to the head twist [v_h; ω_h]: blockdiag(I_3, E(θ_h))."""
    M = np.eye(6)
    M[3:, 3:] = euler_rate_matrix(theta_h)
    return M


@dataclass(frozen=True, eq=False)
class Chain:
    """Forward kinematics of one state: link frames ``R`` (2n, 3, 3), points ``P`` (2n+1, 3), joint axes."""

    l: float
    psi: np.ndarray  # (2n−1,) joint angles
    R: np.ndarray
    P: np.ndarray
    axis: np.ndarray  # (2n−1, 3): world axis of joint j at row j−1

    @property
    def n(self) -> int:
        return len(self.R) // 2

    def wheel_link(self, i: int) -> int:
        """Index into ``R`` of wheel i's frame Σ_{w,i} (2.2): link 2i+1, or link 2n for the tail wheel."""
        if not 1 <= i <= self.n:
            raise ValueError(f"wheel index must be 1..{self.n}, got {i}")
        return 2 * i if i < self.n else 2 * self.n - 1

    def wheel_position(self, i: int) -> np.ndarray:
        """Axle centre p_i = P[2i] (i = n: the tail tip)."""
        return self.P[2 * i]

    def wheel_frame(self, i: int) -> np.ndarray:
        return self.R[self.wheel_link(i)]

    def wheel_pose(self, i: int) -> np.ndarray:
        """w_i = [p_i; θ_i] (2.2)."""
        return np.concatenate((self.wheel_position(i), euler_zyx(self.wheel_frame(i))))

    def head_pose(self) -> np.ndarray:
        """w_h = [p_h; θ_h] (2.1)."""
        return np.concatenate((self.P[0], euler_zyx(self.R[0])))


def forward_kinematics(p_h, R_h, psi, l: float) -> Chain:
    """The chain of head tip ``p_h``, head frame ``R_h`` and joint angles ψ ∈ R^{2n−1} (§2.1)."""
    psi = np.asarray(psi, dtype=float)
    if psi.ndim != 1 or psi.shape[0] < 3 or psi.shape[0] % 2 == 0:
        raise ValueError(f"psi must hold 2n−1 >= 3 joint angles (odd count), got shape {psi.shape}")
    R = np.empty((psi.shape[0] + 1, 3, 3))
    R[0] = R_h
    axis = np.empty((psi.shape[0], 3))
    for j, angle in enumerate(psi.tolist(), start=1):
        yaw = j % 2 == 1
        axis[j - 1] = R[j - 1][:, 2 if yaw else 1]
        R[j] = R[j - 1] @ (rot_z(angle) if yaw else rot_y(angle))
    P = np.vstack((p_h, np.asarray(p_h, float) + l * np.cumsum(R[:, :, 0], axis=0)))
    return Chain(float(l), psi, R, P, axis)


def chain_from_pose(w_h, psi, l: float) -> Chain:
    """The chain of head pose w_h = [p_h; θ_h] (2.1)."""
    w_h = np.asarray(w_h, dtype=float)
    if w_h.shape != (6,):
        raise ValueError(f"w_h must be [x, y, z, roll, pitch, yaw], got shape {w_h.shape}")
    return forward_kinematics(w_h[:3], rot_zyx(w_h[3:]), psi, l)


def chain_from_wheel(psi, l: float, i: int, p_i, R_i) -> Chain:
    """The chain whose wheel i has axle centre ``p_i`` and frame ``R_i`` (place a body by one wheel)."""
    local = forward_kinematics(np.zeros(3), I3, psi, l)
    R_h = np.asarray(R_i, float) @ local.wheel_frame(i).T
    return forward_kinematics(np.asarray(p_i, float) - R_h @ local.wheel_position(i), R_h, psi, l)


# ----------------------------------------------------------------------------------------------- Jacobians

def point_jacobian(ch: Chain, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Velocity of point P[k]: (3×6 w.r.t. the head twist, 3×(2n−1) w.r.t. ψ̇).

    ṗ_k = v_h + ω_h × (P_k − P_0) + Σ_{j<k} ω_j × (P_k − P_j), ω_j the world axis of joint j.
    """
    J_psi = np.zeros((3, len(ch.axis)))
    J_psi[:, : k - 1] = cross3(ch.axis[: k - 1], ch.P[k] - ch.P[1:k]).T
    return np.hstack((I3, -skew(ch.P[k] - ch.P[0]))), J_psi


def frame_jacobian(ch: Chain, m: int) -> tuple[np.ndarray, np.ndarray]:
    """Angular velocity of link frame R[m]: (3×6, 3×(2n−1)); ω = ω_h + Σ_{j≤m} ω_j."""
    J_psi = np.zeros((3, len(ch.axis)))
    J_psi[:, :m] = ch.axis[:m].T
    return np.hstack((np.zeros((3, 3)), I3)), J_psi


def pose_jacobian(ch: Chain, k: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """Rates of the pose [P[k]; θ(R[m])] (Euler rates, (2.1)): (6×6 w.r.t. the twist, 6×(2n−1))."""
    Jp_t, Jp_psi = point_jacobian(ch, k)
    Jw_t, Jw_psi = frame_jacobian(ch, m)
    E_inv = np.linalg.inv(euler_rate_matrix(euler_zyx(ch.R[m])))
    return np.vstack((Jp_t, E_inv @ Jw_t)), np.vstack((Jp_psi, E_inv @ Jw_psi))


def wheel_pose_jacobian(ch: Chain, i: int) -> tuple[np.ndarray, np.ndarray]:
    """Rates of w_i = [p_i; θ_i] (2.2): (6×6 w.r.t. the twist, 6×(2n−1))."""
    return pose_jacobian(ch, 2 * i, ch.wheel_link(i))


PLANAR = [0, 1, 5]  # rows x, y, yaw of a pose: the planar pose w̃ (2.22)
OFF_PLANE = [2, 3, 4]  # rows z, roll, pitch: the base front wheel's contact rows (2.16)


def anchored_twist_map(ch: Chain, k: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """Head twist of a motion that gives the frame (P[k], R[m]) the twist τ_a: twist = T_a τ_a − T_ψ ψ̇.

    The frame's twist is [[I, −[r]×], [0, I]] twist + J_ψ ψ̇ with r = P[k] − P[0]; T_a is that 6×6
    block's inverse [[I, [r]×], [0, I]] and T_ψ = T_a J_ψ. Used for bodies resting on a wheel: the head part
    of §4.3.1 (anchor fixed, τ_a = 0) and the base of the head-raised model (§2.5.1).
    """
    _, Jp_psi = point_jacobian(ch, k)
    _, Jw_psi = frame_jacobian(ch, m)
    T_a = np.eye(6)
    T_a[:3, 3:] = skew(ch.P[k] - ch.P[0])
    return T_a, T_a @ np.vstack((Jp_psi, Jw_psi))


# ------------------------------------------------------------------------------------ wheel–plane relation

@dataclass(frozen=True, eq=False)
class Plane:
    """Plane j of §2.6.1: a point p_{e,j} and a unit normal n_j."""

    point: np.ndarray
    normal: np.ndarray

    @staticmethod
    def from_pose(p, theta) -> Plane:
        """The x–y plane of the frame at ``p`` with orientation θ = [roll, pitch, yaw] (z up), as Σ_f of §4.1."""
        return Plane(np.asarray(p, float), rot_zyx(theta)[:, 2])


def contact_relation(p_i, R_i, plane: Plane) -> np.ndarray:
    """r = [d, κ, λ] of a wheel at ``p_i`` with frame ``R_i`` and ``plane`` (2.36)–(2.38).

    d = n^T (p_i − p_e); κ = asin(n · e_y) (axle tilt); λ = asin(n · e_x) (tilt of the link behind).
    Proper contact is d = r_w, κ = 0; λ = 0 extends it to the following wheels (§2.6.1).
    """
    n = plane.normal
    return np.array([n @ (np.asarray(p_i) - plane.point), math.asin(np.clip(n @ R_i[:, 1], -1, 1)),
                     math.asin(np.clip(n @ R_i[:, 0], -1, 1))])


def tilt_rows(R: np.ndarray, plane: Plane) -> np.ndarray:
    """G (2×3) with [κ̇, λ̇] = G ω for a frame R turning at ω: d/dt asin(n·e) = ω·(e × n) / cos(asin(n·e))."""
    n = plane.normal
    rows = [cross3(R[:, c], n) / math.sqrt(max(1e-300, 1.0 - (n @ R[:, c]) ** 2)) for c in (1, 0)]
    return np.array(rows)


def contact_jacobian(ch: Chain, i: int, plane: Plane) -> tuple[np.ndarray, np.ndarray]:
    """Rates of r_i = [d, κ, λ] of wheel i and ``plane`` (2.36)–(2.38): (3×6 twist, 3×(2n−1))."""
    Jp_t, Jp_psi = point_jacobian(ch, 2 * i)
    Jw_t, Jw_psi = frame_jacobian(ch, ch.wheel_link(i))
    G = tilt_rows(ch.wheel_frame(i), plane)
    n = plane.normal
    return np.vstack((n @ Jp_t, G @ Jw_t)), np.vstack((n @ Jp_psi, G @ Jw_psi))


# ------------------------------------------------------------------------------- planar parts on a plane

def planar_chain_matrices(w_anchor, phi, l: float) -> tuple[np.ndarray, np.ndarray]:
    """A ∈ R^{k×3}, B ∈ R^{k×k} of (2.8) for the k = len(φ) wheels behind an anchor w̃ (head or wheel).

    The anchor is the head for (2.8) and a wheel for the base part (2.21) and the rear part (4.4): the
    geometry is the same, spacing l + l to the first wheel (spec §2.3). Any k ≥ 0: row i of A and B only
    involves wheels up to i, so a short chain is padded to model.py's minimum of two wheels and cut.
    """
    phi = np.asarray(phi, dtype=float)
    k = phi.shape[0]
    A, B = constraint_matrices(configuration(w_anchor, np.concatenate((phi, np.zeros(max(0, 2 - k)))), l))
    return A[:k], B[:k, :k]


def base_matrices(w_anchor, phi_b, l: float) -> tuple[np.ndarray, np.ndarray]:
    """A_b ∈ R^{n_b×3}, B_b ∈ R^{n_b×(n_b−1)} of the base part, A_b ẇ̃_{n_h} = B_b φ̇_b (2.17)–(2.22).

    Row 1 is the anchor wheel's own constraint [sin θ, −cos θ, 0] ẇ̃ = 0 (2.20) for b_1; the others are
    :func:`planar_chain_matrices` of the wheels behind it.
    """
    A, B = planar_chain_matrices(w_anchor, phi_b, l)
    theta = w_anchor[2]
    A_b = np.vstack(([math.sin(theta), -math.cos(theta), 0.0], A))
    return A_b, np.vstack((np.zeros((1, B.shape[1])), B))


def planar_pose(ch: Chain, k: int, m: int) -> np.ndarray:
    """w̃ = [x, y, yaw] of the point P[k] with the frame R[m] (a wheel on the rear plane, (2.22))."""
    return np.array([ch.P[k][0], ch.P[k][1], math.atan2(ch.R[m][1, 0], ch.R[m][0, 0])])


# ------------------------------------------------------------------------------------- head-raised model

def yaw_joints(first: int, last: int) -> np.ndarray:
    """0-based ψ indices of the yaw joints first, first+2, …, last (1-based, both odd)."""
    return np.arange(first - 1, last, 2)


@dataclass(frozen=True, eq=False)
class HeadRaised:
    """Matrices of the head-raised model (2.25)–(2.26) over the base wheels n_h..n_last.

    ``A_h`` (n_b+3)×6, ``B_h`` (n_b+3)×(2n_h + n_last − n_h) with ψ̄ = [ψ_h; φ_b] (2.26); n_last = n gives
    §2.5.1 (B_h is (n_b+3)×(n+n_h)), n_last = n_t gives A'_h, B'_h of the double arm (2.27)–(2.28).
    Rows 1..n_b: base wheels' no-side-slip (2.24), sign of (2.6); rows n_b+1..n_b+3: the base front wheel
    keeps z, roll and pitch (2.16).
    """

    A_h: np.ndarray
    B_h: np.ndarray
    J_b1: np.ndarray  # 3×6   (2.16), w.r.t. ẇ_h
    J_b2: np.ndarray  # 3×2n_h (2.16), w.r.t. ψ̇_h
    J_b3: np.ndarray  # 3×6   (2.23); the text's 3×3 is a misprint (A4)
    J_b4: np.ndarray  # 3×2n_h (2.23)
    A_b: np.ndarray  # n_b×3 (2.21)
    B_b: np.ndarray  # n_b×(n_b−1) (2.21)


def head_raised(ch: Chain, n_h: int, n_last: int | None = None) -> HeadRaised:
    """(2.16)–(2.26) at the chain ``ch`` (base wheels n_h..n_last, default n, flat with zero pitch joints)."""
    n = ch.n
    n_last = n if n_last is None else n_last
    if not 2 <= n_h < n_last <= n:
        raise ValueError(f"need 2 <= n_h < n_last <= n = {n} (n_h >= 2 for solvability, §2.5.1), got "
                         f"n_h={n_h}, n_last={n_last}")
    M = head_euler_map(euler_zyx(ch.R[0]))
    J_t, J_psi = wheel_pose_jacobian(ch, n_h)
    head = slice(0, 2 * n_h)
    J_b1, J_b2 = J_t[OFF_PLANE] @ M, J_psi[OFF_PLANE, head]
    J_b3, J_b4 = J_t[PLANAR] @ M, J_psi[PLANAR, head]
    phi_b = ch.psi[yaw_joints(2 * n_h + 1, 2 * n_last - 1)]
    A_b, B_b = base_matrices(planar_pose(ch, 2 * n_h, ch.wheel_link(n_h)), phi_b, ch.l)
    A_h = np.vstack((A_b @ J_b3, J_b1))
    B_h = np.block([[-A_b @ J_b4, B_b], [-J_b2, np.zeros((3, B_b.shape[1]))]])
    return HeadRaised(A_h, B_h, J_b1, J_b2, J_b3, J_b4, A_b, B_b)


# -------------------------------------------------------------------------------------- double-arm model

@dataclass(frozen=True, eq=False)
class DoubleArmMatrices:
    """A_{d,σ} ċ_d = B_{d,σ} ψ̇_d (2.32)–(2.35) at one state, with its blocks.

    Shapes (n'_b = n_t − n_h + 1 base wheels, n'_{b,σ} of them grounded):
    ``A_d`` (n'_{b,σ}+9)×12, ``B_d`` (n'_{b,σ}+9)×(2n−n'_b+1) — the column count does not change with σ;
    ``J_t1`` 6×3 and ``J_t2`` 6×(2n−2n_t) of ẇ_t = J_{t,1} ẇ̃_{n_t} + J_{t,2} ψ̇_t (2.29) (the text's 3×3,
    3×(2n−2n_t) are misprints, A4); ``J_nt1`` 3×6 and ``J_nt2`` 3×(n_t+n_h) of ẇ̃_{n_t} = J_{n_t,1} ẇ_h +
    J_{n_t,2} ψ̄̇' (2.30); ``A_h``, ``B_h`` = A'_h, B'_h (2.27) before the mode selection; ``c_d`` = [w_h; w_t].
    """

    A_d: np.ndarray
    B_d: np.ndarray
    J_t1: np.ndarray
    J_t2: np.ndarray
    J_nt1: np.ndarray
    J_nt2: np.ndarray
    A_h: np.ndarray
    B_h: np.ndarray
    c_d: np.ndarray


@dataclass(frozen=True)
class DoubleArm:
    """The double-arm model of §2.5.2 (head and tail raised), used by the handcart experiment (§3.4.2, n = 15).

    Base wheels n_h..n_t are on the plane (flat, base pitch joints 0); head part joints 1..2n_h (ψ_h), base
    joints 2n_h+1..2n_t−1 (yaw ones φ'_b, n_t − n_h of them), tail part joints 2n_t..2n−1 (ψ_t).
    Controlled c_d = [w_h; w_t] (2.34), w_t the pose of the tail tip (= wheel n, frame of link 2n).
    Input ψ_d = [ψ_h; φ'_b; ψ_t] ∈ R^{2n−n'_b+1}; :attr:`input_joints` maps it into the full ψ.
    The planar pose w̃_{n_t} is [x, y] of wheel n_t and the yaw of link 2n_t (equal to its wheel frame's yaw
    while the base is flat).
    """

    n: int
    l: float
    n_h: int
    n_t: int

    def __post_init__(self) -> None:
        if not 2 <= self.n_h < self.n_t < self.n:
            raise ValueError(f"need 2 <= n_h < n_t < n = {self.n} (head and tail parts raised), got "
                             f"n_h={self.n_h}, n_t={self.n_t}")

    @property
    def base_wheels(self) -> int:
        """n'_b = n_t − n_h + 1 (§2.5.2)."""
        return self.n_t - self.n_h + 1

    @property
    def input_joints(self) -> np.ndarray:
        """0-based ψ indices of ψ_d = [ψ_h; φ'_b; ψ_t] (2.34)."""
        return np.concatenate((np.arange(2 * self.n_h), yaw_joints(2 * self.n_h + 1, 2 * self.n_t - 1),
                               np.arange(2 * self.n_t - 1, 2 * self.n - 1)))

    def chain(self, w_h, psi) -> Chain:
        psi = np.asarray(psi, dtype=float)
        if psi.shape != (2 * self.n - 1,):
            raise ValueError(f"psi must hold 2n−1 = {2 * self.n - 1} joint angles, got shape {psi.shape}")
        return chain_from_pose(w_h, psi, self.l)

    def controlled(self, ch: Chain) -> np.ndarray:
        """c_d = [w_h; w_t] (2.34)."""
        return np.concatenate((ch.head_pose(), ch.wheel_pose(self.n)))

    def matrices(self, w_h, psi, grounded=None) -> DoubleArmMatrices:
        """(2.27)–(2.35) at head pose ``w_h`` and joints ``psi``; ``grounded`` (n'_b booleans for wheels
        n_h..n_t, default all) deletes the lifted base wheels' rows (2.35), as T_σ does in (2.11)."""
        ch = self.chain(w_h, psi)
        g = np.ones(self.base_wheels, bool) if grounded is None else np.asarray(grounded, dtype=bool)
        if g.shape != (self.base_wheels,):
            raise ValueError(f"grounded must give n'_b = {self.base_wheels} base wheels, got shape {g.shape}")
        hr = head_raised(ch, self.n_h, self.n_t)
        M = head_euler_map(euler_zyx(ch.R[0]))
        k_nt, m_nt = 2 * self.n_t, 2 * self.n_t - 1  # wheel n_t and the flat base link in front of it
        J_t, J_psi = pose_jacobian(ch, k_nt, m_nt)
        bar = self.input_joints[: 2 * self.n_h + self.n_t - self.n_h]  # ψ̄' = [ψ_h; φ'_b] (2.28)
        J_nt1, J_nt2 = J_t[PLANAR] @ M, J_psi[PLANAR][:, bar]
        J_t1, J_t2 = self._tail_jacobians(ch)
        rows = np.concatenate((np.flatnonzero(g), self.base_wheels + np.arange(3)))
        A_h, B_h = hr.A_h[rows], hr.B_h[rows]
        tail_cols = 2 * self.n - 2 * self.n_t
        A_d = np.block([[A_h, np.zeros((len(rows), 6))], [J_t1 @ J_nt1, -np.eye(6)]])
        B_d = np.block([[B_h, np.zeros((len(rows), tail_cols))], [-J_t1 @ J_nt2, -J_t2]])
        return DoubleArmMatrices(A_d, B_d, J_t1, J_t2, J_nt1, J_nt2, hr.A_h, hr.B_h, self.controlled(ch))

    def _tail_jacobians(self, ch: Chain) -> tuple[np.ndarray, np.ndarray]:
        """J_{t,1} (6×3), J_{t,2} (6×(2n−2n_t)) of (2.29): the tail tip's pose rates from the planar motion
        [ẋ, ẏ, θ̇] of the flat base end (wheel n_t) and from the tail joints, with the base end fixed."""
        r = ch.P[2 * self.n] - ch.P[2 * self.n_t]
        E_inv = np.linalg.inv(euler_rate_matrix(euler_zyx(ch.R[2 * self.n - 1])))
        J_t1 = np.zeros((6, 3))
        J_t1[:3, 0], J_t1[:3, 1], J_t1[:3, 2] = E_X, E_Y, cross3(E_Z, r)
        J_t1[3:, 2] = E_inv @ E_Z
        _, J_psi = wheel_pose_jacobian(ch, self.n)
        return J_t1, J_psi[:, 2 * self.n_t - 1:]
