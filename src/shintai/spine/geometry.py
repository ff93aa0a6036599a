"""Geometric model of a muscle-driven spine (seed 003 §4.3–4.5): posture, muscle lengths, J_m, statics.

Units: SI throughout — metres, radians, newtons. The thesis works in mm and degrees at its
interfaces (Tables 4.2–4.3); convert at the edge (``np.degrees``, ``* 1000``).

Posture (§4.3.1, eq. 4.1). Joint i of n (i = 1 … n, from the base up) has roll φ_i, pitch θ_i,
yaw ψ_i; the posture vector is θ = (φ1, θ1, ψ1, …, φn, θn, ψn) ∈ R^{3n}. Arrays of postures have
shape ``(..., 3n)``; every function here broadcasts over the leading dimensions.

Frames. Link 0 is the base (pelvis / hip block), link n the top (clavicle / shoulder block);
joint i joins link i−1 to link i. Link i's frame has its origin at the centre of ball i:

    p_i = p_{i−1} + R_{i−1} (o_i + g_i e_z),     R_i = R_{i−1} W_i Rz(ψ_i) Ry(θ_i) Rx(φ_i)

with o_i the fixed offset of ball i in link i−1's frame, W_i a fixed rest rotation (Kenta's 10°
wedge vertebrae; identity elsewhere) and g_i an optional axial gap change (Rabbit's §3.5.3: muscle
lengths "computed for a larger or smaller joint gap"; zero in the thesis's model). The rotation
order Rz·Ry·Rx is EusLisp's ``:rpy (yaw pitch roll)`` that the thesis's ``qjoint :joint-angle``
applies (§6.5.2 code; spec 003 §2.3).

Muscles (§4.4.2, eq. 4.25). A muscle is an ordered list of points, each fixed in one link's frame
(pull point, via holes, attachment point); its length is the sum of the straight segments,

    l_j = Σ_k | ⁰p_jk − ⁰q_jk |                                            (4.25)

so muscle–muscle and muscle–body interference is ignored, as in the thesis.

Jacobian (§4.3.4, eqs. 4.13–4.15): J_m = ∂q/∂θ is m × 3n (the text's "3n rows, m columns" is a
typo, spec §6.4). :meth:`SpineModel.jacobian` is analytic: for a segment with unit direction u
(from its start point to its end point) the derivative of its length with respect to a joint
axis a through the joint centre c is a · ((x_end − c) × u) minus the same for the start point,
each term present only if the point lies above the joint. :meth:`SpineModel.jacobian_fd` is the
thesis's numerical differentiation (eq. 4.15), kept to check it.

Statics (§4.3.4, eqs. 4.17–4.24; §4.5.1, eqs. 4.32–4.35): τ = −J_mᵀ T (4.22), the tension
distribution T = −(J_mᵀ)⁺ τ + Z ζ, Z = I − (J_mᵀ)⁺ J_mᵀ (4.23, 4.24) with the non-negativity of
T, and the joint stiffness K_j = J_mᵀ K_m J_m (4.35) — with K_m = diag(k_s) the stiffness the
software spring of eq. 4.36 gives the joints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic
from scipy.optimize import linprog, nnls

from shintai.core.geometry import cross3

E = np.eye(3)


def rpy_matrix(rpy) -> np.ndarray:
    """R = Rz(ψ) Ry(θ) Rx(φ) for ``rpy = (..., [φ roll, θ pitch, ψ yaw])`` in radians → (..., 3, 3).

    Written out element by element, vectorised over any batch of postures (the chain's forward
    kinematics evaluates thousands at once); :mod:`shintai.core.geometry`'s ``rot_x/y/z`` are single
    scalar rotations, and their product would round differently (and change every result)."""
    rpy = np.asarray(rpy, dtype=float)
    cr, sr = np.cos(rpy[..., 0]), np.sin(rpy[..., 0])
    cp, sp = np.cos(rpy[..., 1]), np.sin(rpy[..., 1])
    cy, sy = np.cos(rpy[..., 2]), np.sin(rpy[..., 2])
    R = np.empty(rpy.shape[:-1] + (3, 3))
    R[..., 0, 0] = cy * cp
    R[..., 0, 1] = cy * sp * sr - sy * cr
    R[..., 0, 2] = cy * sp * cr + sy * sr
    R[..., 1, 0] = sy * cp
    R[..., 1, 1] = sy * sp * sr + cy * cr
    R[..., 1, 2] = sy * sp * cr - cy * sr
    R[..., 2, 0] = -sp
    R[..., 2, 1] = cp * sr
    R[..., 2, 2] = cp * cr
    return R


def matrix_rpy(R) -> np.ndarray:
    """Inverse of :func:`rpy_matrix` (for |θ| < 90°): (..., 3, 3) → (..., [φ, θ, ψ])."""
    R = np.asarray(R, dtype=float)
    phi = np.arctan2(R[..., 2, 1], R[..., 2, 2])
    theta = np.arcsin(np.clip(-R[..., 2, 0], -1.0, 1.0))
    psi = np.arctan2(R[..., 1, 0], R[..., 0, 0])
    return np.stack([phi, theta, psi], axis=-1)


def uniform_posture(whole, n: int) -> np.ndarray:
    """Uniform bending (eq. 4.29): the whole-spine angles Θ = (φ_s, θ_s, ψ_s) shared equally by the
    n joints (Appendix A.1.3: "pitch −30" on Cla's 5 joints is −6° each). (..., 3) → (..., 3n)."""
    whole = np.asarray(whole, dtype=float)
    if whole.ndim == 1:  # one posture (the 1 ms players): the same values without np.tile's overhead
        return np.concatenate((whole / n,) * n)
    return np.tile(whole / n, n)


def whole_spine(theta) -> np.ndarray:
    """Sum of the per-joint (φ, θ, ψ) — the whole-spine angle of a uniform bend. (..., 3n) → (..., 3)."""
    theta = np.asarray(theta, dtype=float)
    return theta.reshape(theta.shape[:-1] + (-1, 3)).sum(axis=-2)


@dataclass(frozen=True)
class Chain:
    """The vertebra chain: ``offsets[i]`` is ball i+1's centre in link i's frame, ``rest[i]`` its
    fixed rest rotation W, ``lower``/``upper`` the joint limits (3n,) in radians."""

    offsets: np.ndarray  # (n, 3)
    rest: np.ndarray  # (n, 3, 3)
    lower: np.ndarray  # (3n,)
    upper: np.ndarray  # (3n,)

    @classmethod
    def straight(cls, heights, limit_rad, rest_pitch_rad=None) -> Chain:
        """Balls stacked along z at ``heights`` (n,) apart, per-axis limits ±``limit_rad`` (scalar or
        (3n,)), optional fixed rest pitch per joint (Kenta's wedges)."""
        heights = np.asarray(heights, dtype=float)
        n = heights.size
        offsets = np.zeros((n, 3))
        offsets[:, 2] = heights
        rest = np.broadcast_to(E, (n, 3, 3)).copy()
        if rest_pitch_rad is not None:
            rest = rpy_matrix(np.stack([np.zeros(n), np.asarray(rest_pitch_rad, float), np.zeros(n)], axis=-1))
        limit = np.broadcast_to(np.asarray(limit_rad, dtype=float), (3 * n,)).copy()
        return cls(offsets, rest, -limit, limit)

    @property
    def n(self) -> int:
        return len(self.offsets)

    def frames(self, theta, gap=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Forward kinematics: (R (..., n+1, 3, 3), p (..., n+1, 3), Q (..., n, 3, 3)) where R, p are
        the link frames (link 0 = base at the origin) and Q_i = R_{i−1} W_i the frame each joint's
        rotation starts from (for the joint axes)."""
        theta = np.asarray(theta, dtype=float)
        n = self.n
        if theta.shape[-1] != 3 * n:
            raise ValueError(f"posture has {theta.shape[-1]} values, the chain has 3n = {3 * n}")
        batch = theta.shape[:-1]
        if not batch and gap is None:
            return self._frames_one(theta)
        joint_R = rpy_matrix(theta.reshape(batch + (n, 3)))
        offsets = np.broadcast_to(self.offsets, batch + (n, 3)).copy()
        if gap is not None:
            offsets[..., 2] += np.asarray(gap, dtype=float)
        R = np.empty(batch + (n + 1, 3, 3))
        p = np.empty(batch + (n + 1, 3))
        Q = np.empty(batch + (n, 3, 3))
        R[..., 0, :, :] = E
        p[..., 0, :] = 0.0
        for i in range(n):
            p[..., i + 1, :] = p[..., i, :] + np.einsum("...ab,...b->...a", R[..., i, :, :], offsets[..., i, :])
            Q[..., i, :, :] = R[..., i, :, :] @ self.rest[i]
            R[..., i + 1, :, :] = Q[..., i, :, :] @ joint_R[..., i, :, :]
        return R, p, Q

    def _frames_one(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`frames` of one posture without a gap change: the same products, on 2-D arrays (the
        player's 1 ms path; the batched indexing costs more than the arithmetic there)."""
        n = self.n
        joint_R = rpy_matrix(theta.reshape(n, 3))
        R = np.empty((n + 1, 3, 3))
        p = np.empty((n + 1, 3))
        Q = np.empty((n, 3, 3))
        R[0] = E
        p[0] = 0.0
        for i in range(n):
            np.add(p[i], np.einsum("ab,b->a", R[i], self.offsets[i]), out=p[i + 1])
            np.matmul(R[i], self.rest[i], out=Q[i])
            np.matmul(Q[i], joint_R[i], out=R[i + 1])
        return R, p, Q

    def joint_axes(self, theta, Q) -> np.ndarray:
        """World axes of the 3n joint coordinates, (..., 3n, 3), in the order (φ_i, θ_i, ψ_i):
        a_ψ = Q e_z, a_θ = Q Rz(ψ) e_y, a_φ = Q Rz(ψ) Ry(θ) e_x."""
        theta = np.asarray(theta, dtype=float)
        batch = theta.shape[:-1]
        t = theta.reshape(batch + (self.n, 3))
        zero = np.zeros_like(t[..., 0])
        Rz = rpy_matrix(np.stack([zero, zero, t[..., 2]], axis=-1))
        Rzy = rpy_matrix(np.stack([zero, t[..., 1], t[..., 2]], axis=-1))
        a_phi = (Q @ Rzy)[..., :, 0]
        a_theta = (Q @ Rz)[..., :, 1]
        a_psi = Q[..., :, 2]
        return np.stack([a_phi, a_theta, a_psi], axis=-2).reshape(batch + (3 * self.n, 3))


@dataclass(frozen=True)
class MuscleSet:
    """Muscles (or any point-to-point elastic paths: Kenta's ligaments, disc ring springs) as
    via-point paths. ``paths[j]`` is a list of ``(link, (x, y, z))`` points of muscle j, each fixed
    in its link's frame, from the pull point to the attachment point."""

    names: tuple[str, ...]
    point_link: np.ndarray  # (P,) int
    point_xyz: np.ndarray  # (P, 3)
    seg_start: np.ndarray  # (S,) point index
    seg_end: np.ndarray  # (S,) point index
    seg_muscle: np.ndarray  # (S,) muscle index
    incidence: np.ndarray = field(repr=False)  # (S, m): 1 where segment s belongs to muscle j
    paths: tuple = field(repr=False, default=())

    @classmethod
    def from_paths(cls, names, paths) -> MuscleSet:
        names = tuple(names)
        if len(names) != len(paths) or len(set(names)) != len(names):
            raise ValueError("muscle names must be unique, one per path")
        links, xyz, start, end, owner = [], [], [], [], []
        for j, path in enumerate(paths):
            if len(path) < 2:
                raise ValueError(f"muscle {names[j]!r} needs at least two points, got {len(path)}")
            base = len(links)
            for link, point in path:
                links.append(int(link))
                xyz.append(np.asarray(point, dtype=float))
            for k in range(len(path) - 1):
                start.append(base + k)
                end.append(base + k + 1)
                owner.append(j)
        owner = np.array(owner)
        incidence = (owner[:, None] == np.arange(len(names))[None, :]).astype(float)
        return cls(names, np.array(links), np.array(xyz), np.array(start), np.array(end), owner, incidence,
                   tuple(tuple((int(lk), tuple(map(float, pt))) for lk, pt in path) for path in paths))

    @property
    def m(self) -> int:
        return len(self.names)

    def index(self, name: str) -> int:
        if name not in self.names:
            raise KeyError(f"unknown muscle {name!r}; valid: {', '.join(self.names)}")
        return self.names.index(name)

    def world_points(self, R, p) -> np.ndarray:
        """All path points in the base frame, (..., P, 3), from the link frames of :meth:`Chain.frames`."""
        Rl = R[..., self.point_link, :, :]
        return np.einsum("...pab,pb->...pa", Rl, self.point_xyz) + p[..., self.point_link, :]

    def segments(self, points) -> tuple[np.ndarray, np.ndarray]:
        """Segment vectors (end − start) and their lengths, (..., S, 3) and (..., S)."""
        d = points[..., self.seg_end, :] - points[..., self.seg_start, :]
        return d, np.linalg.norm(d, axis=-1)

    def sum_per_muscle(self, per_segment) -> np.ndarray:
        """Σ over each muscle's segments of a (..., S) array → (..., m)."""
        return per_segment @ self.incidence


@dataclass(frozen=True)
class SpineModel:
    """The thesis's geometric model (§4.4): a :class:`Chain` and its :class:`MuscleSet`."""

    chain: Chain
    muscles: MuscleSet

    @property
    def n(self) -> int:
        return self.chain.n

    @property
    def m(self) -> int:
        return self.muscles.m

    def points(self, theta, gap=None) -> np.ndarray:
        """Muscle path points in the base frame, (..., P, 3)."""
        R, p, _ = self.chain.frames(theta, gap)
        return self.muscles.world_points(R, p)

    def lengths(self, theta, gap=None) -> np.ndarray:
        """q = f⁻¹(θ): muscle lengths by eq. 4.25, (..., m) metres. One posture without a gap change (the
        players' 1 ms path) goes through :func:`_segment_lengths`, the same numbers in one compiled loop."""
        if gap is None and np.ndim(theta) == 1:
            chain, mus = self.chain, self.muscles
            theta = np.asarray(theta, dtype=float)
            if theta.shape[-1] != 3 * chain.n:
                raise ValueError(f"posture has {theta.shape[-1]} values, the chain has 3n = {3 * chain.n}")
            seg_len = np.empty(len(mus.seg_start))
            _segment_lengths(theta, chain.offsets, chain.rest, mus.point_link, mus.point_xyz, mus.seg_start,
                             mus.seg_end, np.empty((chain.n + 1, 3, 3)), np.empty((chain.n + 1, 3)),
                             np.empty((len(mus.point_link), 3)), seg_len)
            return mus.sum_per_muscle(seg_len)
        _, seg_len = self.muscles.segments(self.points(theta, gap))
        return self.muscles.sum_per_muscle(seg_len)

    def jacobian(self, theta, gap=None) -> np.ndarray:
        """J_m = ∂q/∂θ (eq. 4.14), analytic, (..., m, 3n) in m/rad."""
        return self.derivatives(theta, gap)[1]

    def gap_jacobian(self, theta, gap=None) -> np.ndarray:
        """∂q/∂g: muscle lengths against the axial joint gaps, (..., m, n) (Rabbit's §3.5.3)."""
        return self.derivatives(theta, gap)[2]

    @cached_property
    def _segment_ends(self) -> tuple:
        """For the segments' end and start points (sign +1, −1): their point indices, whether each lies above each
        joint coordinate (S, 3n) and above each joint's gap (S, n) — the model's constants :meth:`derivatives`
        uses, formed once."""
        n, link = self.chain.n, self.muscles.point_link
        joint_of = np.repeat(np.arange(1, n + 1), 3)  # coordinate k belongs to joint joint_of[k]
        joint = np.arange(1, n + 1)
        return tuple((sign, pts, joint_of[None, :] <= link[pts][:, None], joint[None, :] <= link[pts][:, None])
                     for sign, pts in ((1.0, self.muscles.seg_end), (-1.0, self.muscles.seg_start)))

    def derivatives(self, theta, gap=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Lengths q (..., m), J_m (..., m, 3n) and ∂q/∂g (..., m, n) from one forward kinematics."""
        chain, mus = self.chain, self.muscles
        R, p, Q = chain.frames(theta, gap)
        x = mus.world_points(R, p)
        d, seg_len = mus.segments(x)
        u = d / np.maximum(seg_len, 1e-12)[..., None]
        axes = chain.joint_axes(theta, Q)  # (..., 3n, 3)
        centres = np.repeat(p[..., 1:, :], 3, axis=-2)  # joint i's centre for its 3 coordinates
        dtheta = np.zeros(x.shape[:-2] + (3 * chain.n, mus.m))
        dgap = np.zeros(x.shape[:-2] + (chain.n, mus.m))
        gap_dirs = R[..., :-1, :, 2]  # ∂p_i/∂g_i = R_{i−1} e_z
        for sign, pts, above, above_gap in self._segment_ends:
            xs = x[..., pts, :]  # (..., S, 3)
            r = xs[..., :, None, :] - centres[..., None, :, :]  # (..., S, 3n, 3)
            moment = np.einsum("...ska,...ka->...sk", cross3(r, u[..., :, None, :]), axes)
            dtheta += sign * np.einsum("...sk,sm->...km", moment * above, mus.incidence)
            along = np.einsum("...sa,...ia->...si", u, gap_dirs) * above_gap
            dgap += sign * np.einsum("...si,sm->...im", along, mus.incidence)
        return mus.sum_per_muscle(seg_len), np.swapaxes(dtheta, -1, -2), np.swapaxes(dgap, -1, -2)

    def jacobian_fd(self, theta, step: float = 1e-6) -> np.ndarray:
        """J_m by central differences of eq. 4.25 — the thesis's eq. 4.15. (m, 3n) for one posture."""
        theta = np.asarray(theta, dtype=float)
        k = theta.size
        probes = theta + step * np.concatenate([np.eye(k), -np.eye(k)])
        q = self.lengths(probes)
        return ((q[:k] - q[k:]) / (2 * step)).T

    def tension_to_torque(self, theta, tension) -> np.ndarray:
        """τ = −J_mᵀ T (eq. 4.22): joint torques (3n,) [N m] from muscle tensions (m,) [N]."""
        return -self.jacobian(theta).T @ np.asarray(tension, dtype=float)

    def joint_stiffness(self, theta, k_m) -> np.ndarray:
        """K_j = J_mᵀ K_m J_m (eq. 4.35) for muscle stiffnesses ``k_m`` (m,) [N/m] → (3n, 3n) [N m/rad]."""
        return joint_stiffness(self.jacobian(theta), k_m)

    def distribute_tension(self, theta, tau, t_min: float = 0.0) -> TensionDistribution:
        """Tensions that produce the joint torques ``tau`` (eqs. 4.23, 4.24); see :func:`distribute_tension`."""
        return distribute_tension(self.jacobian(theta), tau, t_min)


def joint_stiffness(J, k_m) -> np.ndarray:
    """K_j = J_mᵀ diag(k_m) J_m (eq. 4.35): symmetric positive semi-definite, rank ≤ min(m, 3n)."""
    J = np.asarray(J, dtype=float)
    return J.T @ (np.asarray(k_m, dtype=float)[:, None] * J)


@dataclass(frozen=True)
class TensionDistribution:
    """Result of eq. 4.23 with non-negative tensions.

    ``tension`` — the chosen T; ``min_norm`` — the first term −(J_mᵀ)⁺τ; ``null_dim`` — dim of the
    range of Z (eq. 4.24) = m − rank J_m, the co-contraction freedom; ``residual`` —
    ‖−J_mᵀT − τ‖; ``exact`` — whether T ≥ t_min reproduces τ (to 1e-9 relative).
    """

    tension: np.ndarray
    min_norm: np.ndarray
    null_dim: int
    residual: float
    exact: bool

    def report(self) -> str:
        """One line on what the distribution could do: the co-contraction freedom and whether τ is met."""
        if self.null_dim == 0:
            freedom = "Z = 0 (rank J_m = m): the min-norm tension is the only exact one"
        else:
            freedom = f"Z has {self.null_dim} dims of co-contraction"
        if self.exact:
            return f"{freedom}; T ≥ t_min reproduces τ"
        return f"{freedom}; no T ≥ t_min reproduces τ: least squares, residual {self.residual:.3g} N m"


def distribute_tension(J, tau, t_min: float = 0.0) -> TensionDistribution:
    """Muscle tensions T ≥ t_min with −J_mᵀ T = τ (eqs. 4.23, 4.24).

    The thesis adds a null-space term Zζ, "ζ the smallest such that no element of T is negative";
    for a vector ζ that is not defined (spec §6.5). We take the smallest total tension: minimise
    Σ T_j subject to −J_mᵀT = τ, T ≥ t_min (a linear programme; chosen, because it is the
    least co-contraction that satisfies the thesis's condition). When Z = 0 (rank J_m = m, e.g.
    Rabbit's 6 × 15 J_m; not Cla's, whose 8 block-to-block muscles give rank 6, robots.CLA) the
    min-norm term is the only exact solution; it is returned if it is non-negative. When no
    non-negative exact solution exists the least-squares T ≥ t_min is returned with
    ``exact=False``; :meth:`TensionDistribution.report` says which case it was.
    """
    J = np.asarray(J, dtype=float)
    tau = np.asarray(tau, dtype=float)
    m = J.shape[0]
    JT = J.T
    pinv = np.linalg.pinv(JT)
    t0 = -pinv @ tau
    null_dim = m - int(np.linalg.matrix_rank(J))
    scale = max(1.0, float(np.abs(tau).max(initial=0.0)))
    if t0.min() >= t_min - 1e-12:
        candidate = t0
    elif null_dim > 0:
        lp = linprog(np.ones(m), A_eq=-JT, b_eq=tau, bounds=[(t_min, None)] * m, method="highs")
        candidate = lp.x if lp.status == 0 else None
    else:
        candidate = None
    if candidate is None:  # no exact non-negative solution: least squares on T − t_min ≥ 0
        shift, _ = nnls(-JT, tau + JT @ np.full(m, t_min))
        candidate = shift + t_min
    residual = float(np.linalg.norm(-JT @ candidate - tau))
    return TensionDistribution(candidate, t0, null_dim, residual, residual <= 1e-9 * scale)


@intrinsic
def fma(typingctx, a, b, c):
    """a·b + c rounded once (LLVM's fma), for compiled loops: how OpenBLAS's dgemm forms each element of a small
    matrix product (NumPy's ``@`` on 3 × 3 blocks), so a loop that uses it gives NumPy's bits."""
    sig = types.float64(types.float64, types.float64, types.float64)

    def codegen(context, builder, signature, args):
        double = ir.DoubleType()
        fused = builder.module.declare_intrinsic("llvm.fma", [double], ir.FunctionType(double, [double] * 3))
        return builder.call(fused, args)

    return sig, codegen


@njit(cache=True)
def _segment_lengths(theta, offsets, rest, point_link, point_xyz, seg_start, seg_end, R, p, x, out):
    """Eq. 4.25's segment lengths |⁰p − ⁰q| (S,) at one posture θ (3n,), into ``out``: the link frames
    p_i = p_{i−1} + R_{i−1} o_i, R_i = R_{i−1} W_i Rz(ψ_i) Ry(θ_i) Rx(φ_i) (module docstring; ``R``, ``p``
    (n+1, …) are scratch), the path points in the base frame (``x``, P × 3), the segments between them. The
    arithmetic of :meth:`Chain._frames_one`, :meth:`MuscleSet.world_points` and :meth:`MuscleSet.segments`
    (NumPy's 3-term einsums sum terms 0, 2, then 1; its 3 × 3 ``@`` is an fma chain), so the same bits."""
    for a in range(3):
        p[0, a] = 0.0
        for b in range(3):
            R[0, a, b] = 1.0 if a == b else 0.0
    W, J = np.empty((3, 3)), np.empty((3, 3))
    for i in range(offsets.shape[0]):
        cr, sr = math.cos(theta[3 * i]), math.sin(theta[3 * i])
        cp, sp = math.cos(theta[3 * i + 1]), math.sin(theta[3 * i + 1])
        cy, sy = math.cos(theta[3 * i + 2]), math.sin(theta[3 * i + 2])
        J[0, 0], J[0, 1], J[0, 2] = cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr  # rpy_matrix
        J[1, 0], J[1, 1], J[1, 2] = sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr
        J[2, 0], J[2, 1], J[2, 2] = -sp, cp * sr, cp * cr
        o = offsets[i]
        for a in range(3):
            p[i + 1, a] = p[i, a] + ((R[i, a, 0] * o[0] + R[i, a, 2] * o[2]) + R[i, a, 1] * o[1])
            for c in range(3):
                W[a, c] = fma(R[i, a, 2], rest[i, 2, c], fma(R[i, a, 1], rest[i, 1, c], R[i, a, 0] * rest[i, 0, c]))
        for a in range(3):
            for c in range(3):
                R[i + 1, a, c] = fma(W[a, 2], J[2, c], fma(W[a, 1], J[1, c], W[a, 0] * J[0, c]))
    for k in range(point_link.shape[0]):
        link, v = point_link[k], point_xyz[k]
        for a in range(3):
            x[k, a] = ((R[link, a, 0] * v[0] + R[link, a, 2] * v[2]) + R[link, a, 1] * v[1]) + p[link, a]
    for s in range(seg_start.shape[0]):
        end, start = seg_end[s], seg_start[s]
        d0, d1, d2 = x[end, 0] - x[start, 0], x[end, 1] - x[start, 1], x[end, 2] - x[start, 2]
        out[s] = math.sqrt((d0 * d0 + d1 * d1) + d2 * d2)
