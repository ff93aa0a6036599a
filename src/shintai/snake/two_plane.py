"""Locomotion between two non-parallel planes — seed 001 ch. 4 (§4.1–§4.4, eqs. (4.1)–(4.35)).

World (§4.1): the rear plane is the world x–y plane; the front plane is the x–y plane of Σ_f (origin p_f,
orientation θ_f, R_f = R_z R_y R_x). Both are polygons with straight edges and a gap between them; the
text gives neither the edges nor the gap (A19, A21), so :class:`TwoPlaneWorld` takes them as parameters.

Body (§4.1, Fig. 4.3), a :class:`Partition`: front-plane part (wheels 1..n_f, yaw joints φ_f), connection
part (n_c lifted wheels, joints 2n_f..2n_re, ψ_c ∈ R^{m_c}, m_c = 2(n_c+1)+1) and rear-plane part (wheels
n_re..n, n_re = n_f+n_c+1, yaw joints φ_r). Pitch joints inside the plane parts are 0 and not inputs.

Motions (§4.2, Fig. 4.4) and their laws (§4.4):

* head transition — base fixed, head part joints ψ_h drive r_1 = [d_{1,f}, κ_{1,f}, λ'_{1,f}] to
  [r_w, 0, 0] (4.1), (4.14);
* straddling propulsion — φ̇_f (4.16), ψ̇_c = u_{c1} + u_{c2} (4.17)–(4.21), φ̇_r (4.22): the head tracks its
  planar target in Σ_f while r = [d, κ, λ] of the rear-end wheel n_re on the rear plane is held at
  [r_w, 0, 0] and its no-slip row (4.6) is kept;
* connection transitions — rear shift (n_re → n_re+1 whenever n_c < n_{c_max}) and front shift (when
  d_e < ε_d, drive ψ_{c,1} → 0 with (4.27)–(4.30), then n_f → n_f+1) (§4.2.3–§4.2.4);
* null-space objective V = k_{u,1} V_1 + k_{u,2} V_2 (4.33)–(4.35) for joint limits and plane edges.

The Jacobians come from the 3D chain of model3d.py (rooted at the head, whose planar pose ^f w̃_h lies in
the front plane); the planar blocks A_f, B_f, A_r, B_r are the closed forms of model.py.

Choices where the thesis is silent (each also marked where it is made):

* r_d = [r_w, 0, 0], r'_d = [r_w, 0, 0, 0], r_{1,d} = [r_w, 0, 0] (proper contact, §2.6.1; A19).
* The head target (4.36) uses sin(2π(t − t_0)/T): the printed sin(2πt/T) jumps at t_0 (A20).
* d_e is signed: the horizontal distance (projection on the rear plane) from the connection's first wheel
  to the front edge line, positive while the wheel is behind the edge (A21), so a wheel that is already
  past the edge also triggers the front shift.
* Rear end at the tail wheel (n_re = n, not covered by the text): r = [d, κ]. λ is in r "so that the
  following rear wheels also touch" (§4.3.3, §2.6.1); the tail wheel has none, and it has no pitch joint, so
  the connection has m_c = 2(n_c+1) joints. Keeping λ there left the null space one dimension smaller, and
  the connection then cut into the front edge in condition 1.
* End of the run: the rear-end condition n_c < n_{c_max} lifts the rear-end wheel and makes the next one
  the rear end (§4.2.4). When the rear end is already the tail wheel there is no next one: the tail wheel
  is lifted all the same ("release"), the rear part is empty and the connection part becomes a free tail
  (no r, no (4.6) row; still ≤ n_{c_max} lifted wheels), whose wheels land one by one with the same
  front-shift rule. The thesis does not describe this end; without it the last wheels cannot reach the
  front plane (a front shift with the tail as rear end and one connection wheel would need H'_3 ∈ R^{5×4}).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from shintai.core.geometry import rot_z
from shintai.snake.constants import (
    CH4_ROBOT,
    TWO_PLANE,
    TWO_PLANE_SCENE,
    SnakeGeometry,
    TwoPlaneCondition,
    TwoPlaneScene,
    TwoPlaneSettings,
)
from shintai.snake.model3d import (
    PLANAR,
    Chain,
    Plane,
    anchored_twist_map,
    chain_from_wheel,
    contact_jacobian,
    contact_relation,
    forward_kinematics,
    frame_jacobian,
    planar_chain_matrices,
    planar_pose,
    point_jacobian,
    pose_jacobian,
    rot_zyx,
    tilt_rows,
    yaw_joints,
)

LIFTED, FRONT, REAR = 0, 1, 2  # contact codes of the wheels (a command to the plant, like σ in ch. 2)


# ------------------------------------------------------------------------------------------------ world

@dataclass(frozen=True, eq=False)
class TwoPlaneWorld:
    """The rear plane (world x–y), the front plane Σ_f (§4.1) and the edges the thesis leaves open (A19).

    The front plane is the rectangle ^f x ∈ [edge_x, edge_x + length], |^f y| ≤ half_width of Σ_f; its near
    edge is the line ^f x = edge_x. The rear plane ends at world x = rear_edge_x.
    """

    p_f: np.ndarray
    R_f: np.ndarray
    front: Plane
    r_w: float
    edge_x: float
    length: float
    half_width: float
    rear_edge_x: float
    rear: Plane = Plane(np.zeros(3), np.array([0.0, 0.0, 1.0]))  # the world x–y plane (§4.1)

    @staticmethod
    def build(cond: TwoPlaneCondition, scene: TwoPlaneScene, r_w: float) -> TwoPlaneWorld:
        """The world of one §4.5 condition with the edges of ``scene``."""
        R_f = rot_zyx(cond.theta_f)
        p_f = np.asarray(cond.p_f, dtype=float)
        edge_world_x = (p_f + R_f @ [scene.edge_x, 0.0, 0.0])[0]
        return TwoPlaneWorld(p_f, R_f, Plane.from_pose(p_f, cond.theta_f), float(r_w), scene.edge_x, scene.length,
                             scene.half_width, float(edge_world_x - scene.gap))

    def to_front(self, points) -> np.ndarray:
        """World points (…, 3) in Σ_f coordinates."""
        return (np.asarray(points, float) - self.p_f) @ self.R_f

    def embed(self, w_f) -> tuple[np.ndarray, np.ndarray]:
        """Head pose of the planar pose ^f w̃_h = [x, y, θ] in Σ_f: tip r_w above the plane, link 1 in it (§4.3.2)."""
        return self.p_f + self.R_f @ [w_f[0], w_f[1], self.r_w], self.R_f @ rot_z(w_f[2])

    def planar(self, p_h, R_h) -> np.ndarray:
        """^f w̃_h of a head pose (its projection onto the front plane)."""
        x, y, _ = self.to_front(p_h)
        R = self.R_f.T @ R_h
        return np.array([x, y, math.atan2(R[1, 0], R[0, 0])])

    @property
    def head_map(self) -> np.ndarray:
        """G (6×3): head twist [v_h; ω_h] = G ^f ẇ̃_h for a head moving in the front plane."""
        G = np.zeros((6, 3))
        G[:3, 0], G[:3, 1], G[3:, 2] = self.R_f[:, 0], self.R_f[:, 1], self.R_f[:, 2]
        return G

    def d_e(self, p) -> float:
        """d_e of §4.2.4 (Fig. 4.8): horizontal distance from ``p`` to the front edge line, both projected on
        the rear plane; signed, > 0 while ``p`` is behind the edge (chosen, A21)."""
        e0 = (self.p_f + self.R_f @ [self.edge_x, 0.0, 0.0])[:2]
        u = self.R_f[:2, 1] / np.linalg.norm(self.R_f[:2, 1])
        inward = np.array([u[1], -u[0]])
        if inward @ self.R_f[:2, 0] < 0:
            inward = -inward
        return float((e0 - np.asarray(p)[:2]) @ inward)

    def edge_distance(self, points) -> np.ndarray:
        """Signed distance of ``points`` to the front edge line; negative inside the front block
        (^f x ≥ edge_x, ^f z ≤ 0), where it is minus the depth."""
        q = self.to_front(points)
        dx, z = q[:, 0] - self.edge_x, q[:, 2]
        return np.where((dx >= 0) & (z <= 0), -np.minimum(dx, -z), np.hypot(dx, z))

    def on_front(self, p) -> bool:
        x, y, _ = self.to_front(p)
        return bool(self.edge_x <= x <= self.edge_x + self.length and abs(y) <= self.half_width)


def edge_clearance(world: TwoPlaneWorld, ch: Chain, first: int, last: int, link_radius: float) -> float:
    """Clearance to the front edge of the body between points P[first] and P[last] (Fig. 4.5): wheel discs of
    radius r_w at the axles P[2i], link capsules of radius ``link_radius`` along the centreline (sampled at
    12 points per link). Negative means the body cuts the edge or the front block."""
    s = np.linspace(0.0, 1.0, 12, endpoint=False)[None, :, None]
    a, b = ch.P[first:last], ch.P[first + 1:last + 1]
    centreline = np.vstack(((a[:, None, :] + s * (b - a)[:, None, :]).reshape(-1, 3), ch.P[last]))
    wheels = ch.P[max(2, first):last + 1:2]  # first and last are even: wheel axles P[2i]
    return float(min(world.edge_distance(centreline).min() - link_radius,
                     world.edge_distance(wheels).min(initial=np.inf) - world.r_w))


# -------------------------------------------------------------------------------------------- partition

@dataclass(frozen=True)
class Partition:
    """Front-plane / connection / rear-plane parts (§4.1, Fig. 4.3): wheels 1..n_f, n_f+1..n_f+n_c, n_re..n.

    ``released``: the rear end has left the tail wheel (end of the run, module docstring): no rear part,
    the connection is the free tail n_f+1..n.
    """

    n: int
    n_f: int
    n_c: int
    released: bool = False

    def __post_init__(self) -> None:
        behind = self.n - self.n_f - self.n_c
        if self.n_f < 1 or self.n_c < 0 or behind < (0 if self.released else 1):
            raise ValueError(f"bad partition n={self.n}, n_f={self.n_f}, n_c={self.n_c}, released={self.released}")
        if self.released and behind != 0:
            raise ValueError("a released partition has no rear part: n_f + n_c must equal n")

    @property
    def n_re(self) -> int | None:
        """Rear-end wheel n_re = n_f + n_c + 1 (§4.3.3); None once released."""
        return None if self.released else self.n_f + self.n_c + 1

    @property
    def n_r(self) -> int:
        return 0 if self.released else self.n - self.n_re + 1

    @property
    def front_yaw(self) -> np.ndarray:
        """0-based ψ indices of φ_f (yaw joints 1, 3, …, 2n_f−1)."""
        return yaw_joints(1, 2 * self.n_f - 1)

    @property
    def connection(self) -> np.ndarray:
        """0-based ψ indices of ψ_c: joints 2n_f..2n_re (m_c = 2(n_c+1)+1), cut at joint 2n−1 for n_re = n."""
        last = 2 * self.n - 1 if self.released else min(2 * self.n_re, 2 * self.n - 1)
        return np.arange(2 * self.n_f - 1, last)

    @property
    def rear_yaw(self) -> np.ndarray:
        """0-based ψ indices of φ_r (yaw joints 2n_re+1, …, 2n−1)."""
        return np.arange(0) if self.released else yaw_joints(2 * self.n_re + 1, 2 * self.n - 1)

    @property
    def connection_wheels(self) -> range:
        return range(self.n_f + 1, self.n_f + self.n_c + 1)

    @property
    def contact(self) -> np.ndarray:
        c = np.full(self.n, REAR)
        c[: self.n_f] = FRONT
        c[self.n_f:self.n_f + self.n_c] = LIFTED
        return c

    def rear_shift(self) -> Partition:
        """Rear-end shift (§4.2.3): the rear-end wheel is lifted and the one behind it becomes the rear end;
        at the tail wheel the rear part empties (release, module docstring)."""
        if self.released:
            raise ValueError("the rear end has already left the tail wheel")
        if self.n_re == self.n:
            return Partition(self.n, self.n_f, self.n - self.n_f, released=True)
        return replace(self, n_c=self.n_c + 1)

    def front_shift(self) -> Partition:
        """Front-end shift done (§4.2.3): the connection's first wheel n_f+1 is on the front plane."""
        return replace(self, n_f=self.n_f + 1, n_c=self.n_c - 1)

    @staticmethod
    def from_contact(contact) -> Partition:
        """The partition of a contact pattern FRONT…, LIFTED…, REAR… (REAR part optional)."""
        c = np.asarray(contact).round().astype(int)
        n_f = int(np.argmax(c != FRONT)) if (c != FRONT).any() else len(c)
        rear = np.flatnonzero(c == REAR)
        n_re = int(rear[0]) + 1 if len(rear) else None
        expected = np.full(len(c), LIFTED)
        expected[:n_f] = FRONT
        if n_re is not None:
            expected[n_re - 1:] = REAR
        if n_f < 1 or not np.array_equal(c, expected):
            raise ValueError(f"contact must read FRONT…, LIFTED…, REAR… with wheel 1 on the front, got {c.tolist()}")
        if n_re is None:
            return Partition(len(c), n_f, len(c) - n_f, released=True)
        return Partition(len(c), n_f, n_re - n_f - 1)


def head_raised_contact(n: int, n_h: int) -> np.ndarray:
    """Contact of the head-raised body (§2.5.1): wheels 1..n_h−1 lifted, n_h..n on the rear plane."""
    c = np.full(n, REAR)
    c[: n_h - 1] = LIFTED
    return c


# ------------------------------------------------------------------------------------------------ models

def head_relation(ch: Chain, world: TwoPlaneWorld) -> np.ndarray:
    """r_1 = [d_{1,f}, κ_{1,f}, λ'_{1,f}] (§4.3.1): wheel 1 against the front plane and link 1's angle to it."""
    d, kappa, _ = contact_relation(ch.wheel_position(1), ch.wheel_frame(1), world.front)
    lam = math.asin(float(np.clip(world.front.normal @ ch.R[0][:, 0], -1.0, 1.0)))
    return np.array([d, kappa, lam])


def head_part_jacobian(ch: Chain, world: TwoPlaneWorld, n_h: int) -> np.ndarray:
    """J_h ∈ R^{3×2n_h} of ṙ_1 = J_h ψ̇_h (4.1): the head part as a manipulator on the fixed wheel n_h."""
    J_t, J_psi = contact_jacobian(ch, 1, world.front)
    W_t, W_psi = frame_jacobian(ch, 0)
    g = tilt_rows(ch.R[0], world.front)[1]  # λ' row: link 1's e_x against the plane
    J_t = np.vstack((J_t[:2], g @ W_t))
    J_psi = np.vstack((J_psi[:2], g @ W_psi))
    _, T_psi = anchored_twist_map(ch, 2 * n_h, ch.wheel_link(n_h))  # head twist with wheel n_h still
    return (J_psi - J_t @ T_psi)[:, : 2 * n_h]


@dataclass(frozen=True, eq=False)
class StraddleModel:
    """Plane-part model (4.2)–(4.10) and connection-part model (4.11) at one state (all in Σ_f for the head).

    Jacobians are w.r.t. ^f ẇ̃_h (``*_h``, 3 columns) and the full joint rates ψ̇ (``*_psi``, 2n−1 columns);
    the thesis's blocks are their columns: J_{r,2} = Jr_psi[:, φ_f], J_{r,3} = Jr_psi[:, ψ_c], likewise D, J_c.
    A released partition has no rear part: D, A_r, B_r, r and J_c are empty, J_r is zero.
    """

    ch: Chain
    part: Partition
    A_f: np.ndarray  # n_f×3 (4.2)
    B_f: np.ndarray  # n_f×n_f (4.2), lower-triangular, diagonal l
    D_h: np.ndarray  # 1×3 = D_1 (4.6)
    D_psi: np.ndarray  # 1×(2n−1): D_2, D_3 by columns (4.6)
    Jr_h: np.ndarray  # 3×3 = J_{r,1} (4.5)
    Jr_psi: np.ndarray  # 3×(2n−1): J_{r,2}, J_{r,3} by columns (4.5)
    A_r: np.ndarray  # (n_r−1)×3 (4.4)
    B_r: np.ndarray  # (n_r−1)×(n_r−1) (4.4)
    r: np.ndarray  # [d_{n_re,r}, κ_{n_re,r}, λ_{n_re,r}] (§4.3.3); [d, κ] for the tail wheel
    Jc_h: np.ndarray  # 3×3 = J_{c,1} (4.11) (2×3 for the tail wheel)
    Jc_psi: np.ndarray  # 3×(2n−1): J_{c,2}, J_{c,3} by columns (4.11)

    def A_p(self) -> np.ndarray:
        """A_p = [A_f; D_1; A_r J_{r,1}] ∈ R^{(n_f+n_r)×3} (4.10)."""
        return np.vstack((self.A_f, self.D_h, self.A_r @ self.Jr_h))

    def B_p(self) -> np.ndarray:
        """B_p of (4.10) over the full joint rates (zero columns at the frozen pitch joints of the plane parts)."""
        p = self.part
        B = np.zeros((p.n_f + p.n_r, len(self.ch.psi)))
        B[: p.n_f, p.front_yaw] = self.B_f
        moved = np.concatenate((p.front_yaw, p.connection))
        B[p.n_f:, moved] = -np.vstack((self.D_psi, self.A_r @ self.Jr_psi))[:, moved]
        B[p.n_f + 1:, p.rear_yaw] = self.B_r
        return B


def straddle_model(world: TwoPlaneWorld, part: Partition, w_f, psi, l: float) -> StraddleModel:
    """Build (4.2)–(4.11) for the head at ^f w̃_h = ``w_f`` and the joints ``psi``."""
    ch = forward_kinematics(*world.embed(w_f), psi, l)
    A_f, B_f = planar_chain_matrices(w_f, ch.psi[part.front_yaw], l)
    J = len(ch.psi)
    if part.released:
        e3, e0 = np.zeros((3, 3)), np.zeros((0, 3))
        return StraddleModel(ch, part, A_f, B_f, e0, np.zeros((0, J)), e3, np.zeros((3, J)), e0, np.zeros((0, 0)),
                             np.zeros(0), e0, np.zeros((0, J)))
    G = world.head_map
    i, k = part.n_re, 2 * part.n_re
    m = ch.wheel_link(i)
    P_t, P_psi = pose_jacobian(ch, k, m)
    Jr_h, Jr_psi = P_t[PLANAR] @ G, P_psi[PLANAR]
    w_r = planar_pose(ch, k, m)
    lateral = np.array([[math.sin(w_r[2]), -math.cos(w_r[2]), 0.0]])  # (4.3)
    A_r, B_r = planar_chain_matrices(w_r, ch.psi[part.rear_yaw], l)
    C_t, Jc_psi = contact_jacobian(ch, i, world.rear)
    r = contact_relation(ch.wheel_position(i), ch.wheel_frame(i), world.rear)
    rows = slice(0, 2 if i == part.n else 3)  # a lone tail wheel: r = [d, κ] (module docstring)
    return StraddleModel(ch, part, A_f, B_f, lateral @ Jr_h, lateral @ Jr_psi, Jr_h, Jr_psi, A_r, B_r, r[rows],
                         (C_t @ G)[rows], Jc_psi[rows])


def objective(model: StraddleModel, cond: TwoPlaneCondition, psi_lim: float) -> tuple[float, np.ndarray]:
    """V = k_{u,1} V_1 + k_{u,2} V_2 (4.33)–(4.35) and η = ∂V/∂ψ_c (4.20), m_c entries (A22).

    V_1 = (1/m_c) Σ (ψ_lim² − ψ_{c,i}²)/ψ_lim²; V_2 = (1/n_c) Σ (d_r² − (d_{c,i} − d_d)²)/d_r², d_{c,i} the
    height of connection wheel i above the rear plane. Partial derivatives with ^f w̃_h and φ_f held (4.31).
    """
    part, ch = model.part, model.ch
    psi_c = ch.psi[part.connection]
    m_c = len(psi_c)
    if m_c == 0:  # nothing left to move: V is undefined
        return float("nan"), np.zeros(0)
    V = cond.k_u1 * float(np.mean((psi_lim ** 2 - psi_c ** 2) / psi_lim ** 2))
    eta = cond.k_u1 * (-2.0 * psi_c / (m_c * psi_lim ** 2))
    wheels = list(part.connection_wheels)
    if wheels:
        d = np.array([ch.wheel_position(i)[2] for i in wheels])
        dd = np.array([point_jacobian(ch, 2 * i)[1][2, part.connection] for i in wheels])
        V += cond.k_u2 * float(np.mean((cond.d_r ** 2 - (d - cond.d_d) ** 2) / cond.d_r ** 2))
        eta = eta + cond.k_u2 * (-2.0 / (len(wheels) * cond.d_r ** 2)) * ((d - cond.d_d) @ dd)
    return V, eta


def settle_connection(world: TwoPlaneWorld, part: Partition, w_f, psi, l: float, r_w: float) -> np.ndarray:
    """ψ with the connection joints moved (Newton, least change) until r = r_d ([r_w, 0, 0], or [r_w, 0] at the tail):
    a posture whose rear end properly touches the rear plane (§4.3.3), for building initial states."""
    psi = np.array(psi, dtype=float)
    for _ in range(50):
        m = straddle_model(world, part, w_f, psi, l)
        error = np.array([r_w, 0.0, 0.0])[: len(m.r)] - m.r
        if np.abs(error).max() < 1e-13:
            return psi
        psi[part.connection] += np.linalg.pinv(m.Jc_psi[:, part.connection]) @ error
    raise ValueError(f"connection did not settle on the rear plane (r error {np.abs(error).max():.2e})")


def initial_posture(world: TwoPlaneWorld, scene: TwoPlaneScene = TWO_PLANE_SCENE,
                    geometry: SnakeGeometry = CH4_ROBOT, settings: TwoPlaneSettings = TWO_PLANE):
    """Head pose and joints (p_h, R_h, ψ) to start the head transition from (see :class:`TwoPlaneScene`).

    First the posture just after the head transition: wheel 1 on the front plane ``wheel1_past_edge`` inside
    the edge (heading π, ^f y = 0), the rear yaw joints ``rear_yaw``, the connection joints 2..2n_h settled by
    Newton so that wheel n_h properly touches the rear plane. Then ``head_offset`` is added to the head part's
    joints 1..2n_h with wheel n_h (and so the whole base) fixed.
    """
    n, n_h, l = geometry.n, settings.n_h, geometry.l
    if len(scene.connection_guess) != 2 * n_h - 1 or len(scene.head_offset) != 2 * n_h \
            or len(scene.rear_yaw) != n - n_h:
        raise ValueError(f"scene posture sizes do not fit n = {n}, n_h = {n_h}")
    psi = np.zeros(geometry.joints)
    psi[1:2 * n_h] = scene.connection_guess
    psi[yaw_joints(2 * n_h + 1, 2 * n - 1)] = scene.rear_yaw
    w_f = np.array([world.edge_x + scene.wheel1_past_edge + 2 * l, 0.0, math.pi])
    psi = settle_connection(world, Partition(n, 1, n_h - 2), w_f, psi, l, world.r_w)
    landed = forward_kinematics(*world.embed(w_f), psi, l)
    psi[: 2 * n_h] += scene.head_offset
    ch = chain_from_wheel(psi, l, n_h, landed.wheel_position(n_h), landed.wheel_frame(n_h))
    return ch.P[0], ch.R[0], psi


def resolved_rate(H: np.ndarray, rhs: np.ndarray, eta: np.ndarray, k_v: float) -> np.ndarray:
    """H^† rhs + k_v (I − H^† H) η — (4.18)–(4.19), (4.28)–(4.29); with k_v = 0 also (4.14)."""
    H_pinv = np.linalg.pinv(H)
    return H_pinv @ rhs + k_v * (eta - H_pinv @ (H @ eta))


# ----------------------------------------------------------------------------------------- control laws

def head_target(t: float, t_0: float, origin, cond: TwoPlaneCondition) -> tuple[np.ndarray, np.ndarray]:
    """^f w̃_{h,d}(t) of (4.36) and its rate, from the head's position ``origin`` at the end of the head transition.

    The text's sin(2πt/T) jumps at t_0 unless t restarts there (A20); chosen sin(2π(t − t_0)/T).
    """
    s = t - t_0
    w = 2.0 * math.pi / cond.T
    return (np.array([origin[0] + cond.v_p * s, origin[1] + cond.A * math.sin(w * s), math.pi]),
            np.array([cond.v_p, cond.A * w * math.cos(w * s), 0.0]))


def heading_error(target: float, actual: float) -> float:
    return math.remainder(target - actual, 2.0 * math.pi)


@dataclass(frozen=True)
class StraddleStep:
    """One evaluation of the straddling / connection-transition law."""

    psi_dot: np.ndarray  # full joint rates (zeros at the frozen pitch joints)
    xi: np.ndarray  # ξ_h = ^f ẇ̃_{h,d} + K_p(^f w̃_{h,d} − ^f w̃_h)
    V: float
    sigma_H: float  # smallest singular value of H_3 (or H'_3)
    sigma_A: float  # smallest singular value of A_p


def connection_rows(model: StraddleModel, k_c: float, r_w: float, shifting_front: bool):
    """H_1, [H_2 H_3] over all joints and the wanted rates of (4.18)/(4.21), or of (4.28)/(4.30) while
    ``shifting_front``: rows r (ṙ_d + K_c(r_d − r), r_d = [r_w, 0, 0]), then ψ_{c,1} (K'_c(0 − ψ_{c,1}),
    K'_c = k_c), then the no-slip row (4.6) of the rear part's front-end wheel (target 0)."""
    H1, Hpsi = model.Jc_h, model.Jc_psi
    rate = k_c * (np.array([r_w, 0.0, 0.0])[: len(model.r)] - model.r)
    if shifting_front:  # J'_{c,*} of (4.13)
        first = np.zeros((1, len(model.ch.psi)))
        first[0, model.part.connection[0]] = 1.0
        H1, Hpsi = np.vstack((H1, np.zeros((1, 3)))), np.vstack((Hpsi, first))
        rate = np.r_[rate, -k_c * model.ch.psi[model.part.connection[0]]]
    return (np.vstack((H1, model.D_h)), np.vstack((Hpsi, model.D_psi)),
            np.r_[rate, np.zeros(len(model.D_h))])


def straddle_input(model: StraddleModel, w_f, w_d, w_d_dot, cond: TwoPlaneCondition, r_w: float, psi_lim: float,
                   k_v: float, shifting_front: bool) -> StraddleStep:
    """(4.16)–(4.22) and, while ``shifting_front``, (4.27)–(4.30)."""
    part = model.part
    error = np.asarray(w_d, float) - w_f
    error[2] = heading_error(w_d[2], w_f[2])
    xi = np.asarray(w_d_dot, float) + cond.k_p * error
    phi_f_dot = np.linalg.solve(model.B_f, model.A_f @ xi)  # (4.16)
    H1, Hpsi, rate = connection_rows(model, cond.k_c, r_w, shifting_front)
    H3 = Hpsi[:, part.connection]
    V, eta = objective(model, cond, psi_lim)
    psi_c_dot = resolved_rate(H3, rate - H1 @ xi - Hpsi[:, part.front_yaw] @ phi_f_dot, eta, k_v)  # (4.17)
    psi_dot = np.zeros(len(model.ch.psi))
    psi_dot[part.front_yaw] = phi_f_dot
    psi_dot[part.connection] = psi_c_dot
    if part.n_r > 1:  # (4.22)
        moved = model.Jr_h @ xi + model.Jr_psi @ psi_dot
        psi_dot[part.rear_yaw] = np.linalg.solve(model.B_r, model.A_r @ moved)
    sigma_H = float(np.linalg.svd(H3, compute_uv=False)[-1]) if H3.size else float("nan")
    sigma_A = float(np.linalg.svd(model.A_p(), compute_uv=False)[-1])
    return StraddleStep(psi_dot, xi, V, sigma_H, sigma_A)


def head_input(ch: Chain, world: TwoPlaneWorld, n_h: int, k_h: float) -> tuple[np.ndarray, np.ndarray]:
    """u_h = J_h^† {ṙ_{1,d} + K_h (r_{1,d} − r_1)} (4.14) with r_{1,d} = [r_w, 0, 0]; returns (full ψ̇, r_1)."""
    r_1 = head_relation(ch, world)
    u = np.zeros(len(ch.psi))
    target = np.array([world.r_w, 0.0, 0.0])
    u[: 2 * n_h] = resolved_rate(head_part_jacobian(ch, world, n_h), k_h * (target - r_1), np.zeros(2 * n_h), 0.0)
    return u, r_1
