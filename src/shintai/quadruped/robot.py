"""TITAN-VIII: leg kinematics (eqs. 1-2), static stability (§1.5) and the static crawl gait (§1.6, §4).

Frames (§1.2): body x to the right, y forward, z up; a body pose is ``(x, y, θ)`` in the world with
θ counter-clockwise and θ = 0 facing world +y, so a body-frame vector ``v`` is ``R(θ) v`` in the world
(the composition that reproduces the paper's tables, §5.7). Legs are indexed 0..3 for the paper's
legs 1..4 (LF, RF, LR, RR); swing orders are given with the paper's leg numbers 1..4.

One walking cycle (:func:`crawl_cycle`) executes the command (ΔXr, ΔYr, Δθr) at body height Zr with
a swing order:

1. the target pose is the current pose composed with the command; each leg's foothold is the target
   pose applied to its initial stance offset (§7.9), moved off the forbidden edge bands (§2.4);
2. for each leg in the order: in four-leg support the body translates by the shortest path that
   puts the CoG inside the other three feet's triangle with a margin of ``STABILITY_MARGIN``; then
   the leg swings while the body stands still (§1.6): it lifts to ``SWING_CLEARANCE`` above the
   highest surface under its straight path, moves, and lands;
3. in four-leg support the body moves to the target pose.

The body turns evenly over its five moves (Δθr/5 each; chosen, the paper does not say when it
turns), so the stability shifts are translations plus a fifth of the turn.

The body movement Br is the length of the body path in the cycle (§7.8). Key poses are checked for
joint limits (IK of every leg in contact or in the air, both knee branches) and collisions (trunk
against obstacles taller than its underside, swing paths across walls, no admissible foothold; the
leg links are not tested against obstacles, chosen, as the paper does not define a collision, §7.7).
All functions are batched over a leading axis of E episodes so that a GA generation is a few array
operations per swing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import world as W

SHOULDER_XY = np.array(C.SHOULDER_XY)
NOMINAL_FEET = np.array(C.INITIAL_FEET)
THETA0_LIMITS = np.radians(np.array(C.THETA0_LIMITS_DEG))
THETA1_LIMITS = np.radians(C.THETA1_LIMITS_DEG)
THETA2_LIMITS = np.radians(np.array(C.THETA2_LIMITS_DEG) + C.THETA2_ZERO_DEG)
KNEE_UP, KNEE_DOWN = 1, -1


# --- Kinematics (seed §2.1) -----------------------------------------------------------------------

def fk(theta: np.ndarray, shoulder: np.ndarray) -> np.ndarray:
    """Eq. (1): foot position ``(..., 3)`` from joint angles ``(θ0, θ1, θ2)`` [rad] and the shoulder.

    θ2 is absolute (measured from horizontal), not relative to θ1.
    """
    t0, t1, t2 = np.moveaxis(np.asarray(theta, dtype=float), -1, 0)
    reach = C.L0 + C.L1 * np.cos(t1) + C.L2 * np.cos(t2)
    return np.asarray(shoulder, dtype=float) + np.stack(
        [reach * np.cos(t0), reach * np.sin(t0), C.L1 * np.sin(t1) + C.L2 * np.sin(t2) - C.L3], axis=-1)


def ik(foot: np.ndarray, shoulder: np.ndarray, branch: int = KNEE_UP) -> tuple[np.ndarray, np.ndarray]:
    """Eq. (2): joint angles ``(..., 3)`` [rad] and a reachability mask for one knee branch.

    Uses the l3-consistent vertical offset z_i = z_fi - z_si + l3 (§1.3 consistency note) and atan2.
    With ρ_i the horizontal reach beyond l0, r_i = |(ρ_i, z_i)|, d1i = (r² + l1² - l2²) / (2 l1) and
    d2i = (r² - l1² + l2²) / (2 l2): θ1 = α + branch·acos(d1/r), θ2 = α - branch·acos(d2/r) with α the
    direction of (ρ, z). Unreachable (|d| > r, i.e. r > l1 + l2 or r < |l1 - l2|) gives NaN angles.
    As in eq. (2) the leg points at the foot (θ0 = atan2), so ρ = horizontal distance - l0.
    """
    if branch not in (KNEE_UP, KNEE_DOWN):
        raise ValueError(f"ik: branch must be +1 (knee up) or -1 (knee down), got {branch}")
    theta, reachable = ik_both(foot, shoulder)
    return theta[0 if branch == KNEE_UP else 1], reachable


def ik_both(foot: np.ndarray, shoulder: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`ik` for both branches at once: angles ``(2, ..., 3)`` (knee up, knee down) and reachability."""
    rel = np.asarray(foot, dtype=float) - np.asarray(shoulder, dtype=float)
    theta0 = np.arctan2(rel[..., 1], rel[..., 0])
    rho = np.hypot(rel[..., 0], rel[..., 1]) - C.L0
    z = rel[..., 2] + C.L3
    r = np.hypot(rho, z)
    d1 = (r**2 + C.L1**2 - C.L2**2) / (2 * C.L1)
    d2 = (r**2 - C.L1**2 + C.L2**2) / (2 * C.L2)
    reachable = (np.abs(d1) <= r) & (np.abs(d2) <= r) & (r > 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha = np.arctan2(z, rho)
        beta1, beta2 = np.arccos(d1 / r), np.arccos(d2 / r)
    up = np.stack([theta0, alpha + beta1, alpha - beta2], axis=-1)
    down = np.stack([theta0, alpha - beta1, alpha + beta2], axis=-1)
    return np.where(reachable[..., None], np.stack([up, down]), np.nan), reachable


def wrap_theta0(theta0: np.ndarray, leg: np.ndarray) -> np.ndarray:
    """θ0 shifted by whole turns into ``[lo, lo + 2π)`` of its leg's range (LF and LR cross ±180°)."""
    lo = THETA0_LIMITS[leg, 0]
    return lo + np.mod(theta0 - lo, 2 * np.pi)


def within_limits(theta: np.ndarray, leg) -> np.ndarray:
    """Whether joint angles ``(..., 3)`` [rad] of legs ``leg`` (0..3, broadcast) are inside §1.3's ranges."""
    leg = np.asarray(leg)
    t0 = wrap_theta0(theta[..., 0], leg)
    eps = 1e-9
    return ((t0 <= THETA0_LIMITS[leg, 1] + eps)
            & (theta[..., 1] >= THETA1_LIMITS[0] - eps) & (theta[..., 1] <= THETA1_LIMITS[1] + eps)
            & (theta[..., 2] >= THETA2_LIMITS[0] - eps) & (theta[..., 2] <= THETA2_LIMITS[1] + eps))


def leg_angles(foot: np.ndarray, shoulder: np.ndarray, leg) -> tuple[np.ndarray, np.ndarray]:
    """Joint angles that put the foot at ``foot``: the knee-up branch if it is within the limits,
    else the knee-down branch; and whether either is (both in the body frame)."""
    (up, down), _ = ik_both(foot, shoulder)
    ok_up, ok_down = within_limits(np.stack([up, down]), leg)
    theta = np.where(ok_up[..., None] | ~ok_down[..., None], up, down)
    return theta, ok_up | ok_down


# --- Frames ----------------------------------------------------------------------------------------

def rotate(theta: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``R(θ) v`` for body-frame vectors ``v (..., 2)`` and headings ``θ`` broadcast against ``v[..., 0]``."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def to_world(pose: np.ndarray, local: np.ndarray) -> np.ndarray:
    """Body-frame points ``(E, ..., 2)`` to the world for poses ``(E, 3)``."""
    extra = (None,) * (local.ndim - 2)
    return pose[(slice(None), *extra, slice(0, 2))] + rotate(pose[(slice(None), *extra, 2)], local)


def to_body(pose: np.ndarray, world: np.ndarray) -> np.ndarray:
    """World points ``(E, ..., 2)`` to the body frame of poses ``(E, 3)``."""
    extra = (None,) * (world.ndim - 2)
    return rotate(-pose[(slice(None), *extra, 2)], world - pose[(slice(None), *extra, slice(0, 2))])


def compose(pose: np.ndarray, command: np.ndarray) -> np.ndarray:
    """Pose after a body-frame displacement (ΔXr, ΔYr, Δθr): p + R(θ)(ΔX, ΔY), θ + Δθ (§5.7)."""
    return np.concatenate([pose[:, :2] + rotate(pose[:, 2], command[:, :2]), pose[:, 2:] + command[:, 2:]], axis=1)


def legs_within_limits(pose: np.ndarray, zr: np.ndarray, feet: np.ndarray, legs) -> np.ndarray:
    """Whether feet ``(E, n, 3)`` (world) of legs ``legs`` (``(E, n)`` or broadcast to it, e.g. ``(4,)``)
    are reachable within the joint limits from the body at ``pose (E, 3)``, height ``zr (E,)``; ``(E,)``.

    :func:`leg_angles`' test (eq. 2's two knee branches, §1.3's ranges) reduced to its mask: the same
    floating-point operations on the x, y, z components, without the angles' stacks (the hot loop of a
    GA generation; bit-identical to ``np.all(leg_angles(...)[1], -1)``, tested)."""
    legs = np.asarray(legs)
    c, s = np.cos(-pose[:, 2:3]), np.sin(-pose[:, 2:3])  # to_body: R(-θ) (world - p)
    vx, vy = feet[..., 0] - pose[:, 0:1], feet[..., 1] - pose[:, 1:2]
    rx = (c * vx - s * vy) - SHOULDER_XY[legs, 0]
    ry = (s * vx + c * vy) - SHOULDER_XY[legs, 1]
    z = ((feet[..., 2] - zr[:, None]) - C.SHOULDER_DZ) + C.L3  # ik_both's z_i = z_fi - z_si + l3
    rho = np.hypot(rx, ry) - C.L0
    r = np.hypot(rho, z)
    r2 = r**2
    d1 = (r2 + C.L1**2 - C.L2**2) / (2 * C.L1)
    d2 = (r2 - C.L1**2 + C.L2**2) / (2 * C.L2)
    ok = (np.abs(d1) <= r) & (np.abs(d2) <= r) & (r > 0)
    lo0 = THETA0_LIMITS[legs, 0]
    wrapped = np.arctan2(ry, rx) - lo0  # wrap_theta0's np.mod(., 2π) as it computes it for |.| < 2π: + 2π below 0
    ok &= lo0 + (wrapped + (wrapped < 0) * (2 * np.pi)) <= THETA0_LIMITS[legs, 1] + _EPS
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha = np.arctan2(z, rho)
        beta1, beta2 = np.arccos(d1 / r), np.arccos(d2 / r)
    ok &= ((_in_theta1(alpha + beta1) & _in_theta2(alpha - beta2))  # knee up
           | (_in_theta1(alpha - beta1) & _in_theta2(alpha + beta2)))  # knee down
    return _all_last(ok)


_EPS = 1e-9  # within_limits' tolerance
assert np.all(np.abs(THETA0_LIMITS[:, 0]) < np.pi)  # so that θ0 - lo is within (-2π, 2π) in legs_within_limits


def _all_last(ok: np.ndarray) -> np.ndarray:
    """``np.all(ok, axis=-1)`` as a chain of ``&`` over the (few) columns (faster on a short last axis)."""
    out = ok[..., 0].copy()
    for i in range(1, ok.shape[-1]):
        out &= ok[..., i]
    return out


def _in_theta1(t: np.ndarray) -> np.ndarray:
    return (t >= THETA1_LIMITS[0] - _EPS) & (t <= THETA1_LIMITS[1] + _EPS)


def _in_theta2(t: np.ndarray) -> np.ndarray:
    return (t >= THETA2_LIMITS[0] - _EPS) & (t <= THETA2_LIMITS[1] + _EPS)


# --- Static stability (seed §2.2) ---------------------------------------------------------------

def stability_margin(cog: np.ndarray, feet: np.ndarray) -> np.ndarray:
    """McGhee-Frank stability margin: the distance from the CoG projection ``(..., 2)`` to the nearest
    edge of the support polygon, the convex hull of the supporting feet ``(..., n, 2)`` (any order);
    negative when the CoG is outside.

    An edge of the hull is a pair of feet with every other foot on one side of its line.
    """
    n = feet.shape[-2]
    i, j = np.triu_indices(n, 1)
    fx, fy = feet[..., 0], feet[..., 1]  # the x and y components apart
    ax, ay = fx[..., i], fy[..., i]  # (..., P)
    abx, aby = fx[..., j] - ax, fy[..., j] - ay
    side = abx[..., None] * (fy[..., None, :] - ay[..., None]) - aby[..., None] * (fx[..., None, :] - ax[..., None])
    columns = [side[..., k] for k in range(n)]  # side: (..., P, n); short reductions as chains over its columns
    scale = _chain(np.maximum, [np.abs(c) for c in columns]) * 1e-9
    hull_edge = (_chain(np.logical_and, [c >= -scale for c in columns])
                 | _chain(np.logical_and, [c <= scale for c in columns]))
    inward = np.sign(np.sum(side, axis=-1))
    dist = inward * (abx * (cog[..., 1, None] - ay) - aby * (cog[..., 0, None] - ax)) / np.hypot(abx, aby)
    dist = np.where(hull_edge, dist, np.inf)
    return _chain(np.minimum, [dist[..., k] for k in range(dist.shape[-1])])


def _chain(op, arrays: list) -> np.ndarray:
    """``op`` folded over ``arrays`` (a reduction over a short axis written out)."""
    out = arrays[0]
    for a in arrays[1:]:
        out = op(out, a)
    return out


def longitudinal_margin(cog: np.ndarray, polygon: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """Longitudinal stability margin (Fig. 4): the shorter distance from the CoG projection along the
    direction of travel (θ = 0 is +y), forwards and backwards, to the support polygon's boundary;
    negative when the CoG is outside."""
    poly = W.ccw(polygon)
    direction = rotate(heading, np.array([0.0, 1.0]) * np.ones_like(cog))
    a, n = W.edges(poly)
    den = W.dot(n, direction[..., None, :])
    num = W.dot(n, a - cog[..., None, :])  # distance to each edge line along the direction
    with np.errstate(divide="ignore", invalid="ignore"):
        t = num / den
    forward = np.min(np.where(den > 0, t, np.inf), axis=-1)
    backward = np.min(np.where(den < 0, -t, np.inf), axis=-1)
    return np.minimum(forward, backward)


def _support_step(cog: np.ndarray, triangle: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The shortest body translation target putting the CoG inside ``triangle`` with the margin,
    and whether such a target exists (the triangle's inradius exceeds the margin)."""
    tri = W.ccw(triangle)
    x, y = tri[..., 0], tri[..., 1]  # the x and y components apart
    ax, bx, cx, ay, by, cy = x[..., 0], x[..., 1], x[..., 2], y[..., 0], y[..., 1], y[..., 2]
    la, lb, lc = np.hypot(bx - cx, by - cy), np.hypot(cx - ax, cy - ay), np.hypot(ax - bx, ay - by)
    perimeter = la + lb + lc
    area = 0.5 * np.abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))
    inradius = 2 * area / np.maximum(perimeter, 1e-12)
    feasible = inradius > C.STABILITY_MARGIN + 1e-9
    p = np.maximum(perimeter, 1e-12)
    ix, iy = (la * ax + lb * bx + lc * cx) / p, (la * ay + lb * by + lc * cy) / p  # the incentre
    scale = np.where(feasible, (inradius - C.STABILITY_MARGIN) / np.maximum(inradius, 1e-12), 1.0)[..., None]
    shrunk = np.stack([ix[..., None] + scale * (x - ix[..., None]), iy[..., None] + scale * (y - iy[..., None])], -1)
    return np.where(feasible[..., None], W.nearest_inside(cog, shrunk), cog), feasible


# --- Environment interaction --------------------------------------------------------------------

def _near(points: np.ndarray, centre: np.ndarray, radius: np.ndarray, reach) -> np.ndarray:
    """Whether points ``(..., 2)`` may be within ``reach`` of the obstacles in circles ``centre (..., 2)``,
    ``radius``: false only when they are farther than ``reach`` + 1 µm from the circle (a margin far
    above rounding), so a test skipped where it is false gives what it would have given."""
    dx, dy = points[..., 0] - centre[..., 0], points[..., 1] - centre[..., 1]
    return ~(dx * dx + dy * dy > (radius + reach + 1e-6) ** 2)


def _stand(points: np.ndarray, poly: np.ndarray, surmountable: np.ndarray, normals: np.ndarray,
           circles: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Whether points ``(..., K, 2)`` are admissible footholds among obstacles ``poly (..., 1, M, 4, 2)``
    (with their ``normals`` and bounding ``circles``, broadcast alike) and the obstacle each stands on
    ``(..., K)`` (-1 = floor). The signed distance is computed for the point-obstacle pairs within
    ``GROUND_BAND`` of the obstacle's circle only: farther, the point is off the obstacle and its band."""
    near = _near(points[..., None, :], circles[0], circles[1], C.GROUND_BAND)  # (..., K, M)
    sd = np.full(near.shape, np.inf)
    idx = np.nonzero(near)
    if len(idx[0]):
        sd[idx] = W.signed_distance(np.broadcast_to(points[..., None, :], near.shape + (2,))[idx],
                                    np.broadcast_to(poly, near.shape + poly.shape[-2:])[idx],
                                    np.broadcast_to(normals, near.shape + normals.shape[-2:])[idx])
    top = (sd <= -C.TOP_BAND + 1e-9) & surmountable
    admissible = np.all((sd >= C.GROUND_BAND - 1e-9) | top, axis=-1)
    return admissible, np.max(np.where(top, np.arange(top.shape[-1]), -1), axis=-1, initial=-1)


def crossings(a: np.ndarray, b: np.ndarray, envs: W.EnvBatch) -> np.ndarray:
    """Whether segments ``a -> b (E, S, 2)`` meet the obstacles of their environment ``(E, S, M)``
    (``world.segment_hits``), tested exactly only where the segment reaches the obstacle's bounding circle."""
    centre, radius = envs.circles
    mid = (a + b) / 2
    half = W.length(b - a) / 2
    near = _near(mid[:, :, None], centre[:, None], radius[:, None] + half[..., None], 0.0)
    hit = np.zeros(near.shape, dtype=bool)
    e, k, m = np.nonzero(near)
    if len(e):
        hit[e, k, m] = W.segment_hits(a[e, k], b[e, k], envs.polygons[e, m], envs.normals[e, m])
    return hit


def snap_footholds(p: np.ndarray, envs: W.EnvBatch) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """§2.4: move planned footholds ``p (E, n, 2)`` off the forbidden bands (±50 mm of an edge on the
    ground, 30 mm inside the edge on a top) to the nearest admissible point; walls have no admissible
    top. Returns the foothold ``(E, n, 3)`` (z = surface height), the obstacle it stands on ``(E, n)``
    (-1 = floor), and whether an admissible point was found ``(E, n)``.

    Candidates for a point in a band: per obstacle, the nearest point 50 mm outside it and the nearest
    point of its top 30 mm inside the edge; the nearest admissible candidate wins.
    """
    circles = envs.circles
    ok, stand = _stand(p, envs.polygons[:, None], envs.surmountable[:, None], envs.normals[:, None],
                       (circles[0][:, None], circles[1][:, None]))
    best = p.copy()
    e, f = np.nonzero(~ok)
    if len(e):
        poly, surm, q = envs.polygons[e], envs.surmountable[e], p[e, f]  # (B, M, 4, 2), (B, M), (B, 2)
        _, near, out = W.closest_boundary(q[:, None], poly)
        tops = W.nearest_inside(q[:, None], W.inset(poly, C.TOP_BAND))
        candidates = np.concatenate([near + C.GROUND_BAND * out, tops], axis=1)  # (B, 2M, 2)
        admissible, on = _stand(candidates, poly[:, None], surm[:, None], envs.normals[e][:, None],
                                (circles[0][e][:, None], circles[1][e][:, None]))
        dist = np.where(admissible, W.length(candidates - q[:, None]), np.inf)
        k = np.argmin(dist, axis=1)
        best[e, f] = candidates[np.arange(len(e)), k]
        stand[e, f] = on[np.arange(len(e)), k]
        ok[e, f] = np.isfinite(dist.min(axis=1, initial=np.inf))
    on_top = stand[..., None] == np.arange(envs.heights.shape[1])
    z = np.max(np.where(on_top, envs.heights[:, None, :], 0.0), axis=-1, initial=0.0)
    return np.concatenate([best, z[..., None]], axis=-1), stand, ok


def trunk_polygon(pose: np.ndarray) -> np.ndarray:
    """Footprint of the trunk ``(E, ..., 4, 2)`` (counter-clockwise) for poses ``(E, ..., 3)``."""
    hw, hl = C.TRUNK_WIDTH / 2, C.BODY_LENGTH / 2
    local = np.array([[-hw, -hl], [hw, -hl], [hw, hl], [-hw, hl]])
    return pose[..., None, :2] + rotate(pose[..., None, 2], local * np.ones(pose.shape[:-1] + (4, 2)))


def trunk_collides(start: np.ndarray, end: np.ndarray, zr: np.ndarray, envs: W.EnvBatch,
                   samples: int = C.SHIFT_SAMPLES) -> np.ndarray:
    """Whether the trunk, moving from pose ``start`` to ``end`` (E, 3), overlaps an obstacle taller
    than its underside, sampled at ``samples`` poses along the move (one for a body standing still).
    Only obstacles within reach of the move (bounding circles) are tested exactly."""
    centre, radius = envs.circles
    mid = (start[:, :2] + end[:, :2]) / 2
    reach = np.hypot(C.TRUNK_WIDTH, C.BODY_LENGTH) / 2 + W.length(end[:, :2] - start[:, :2]) / 2
    near = W.length(centre - mid[:, None]) < radius + reach[:, None]
    e, m = np.nonzero(near & (envs.heights > zr[:, None] - C.TRUNK_THICKNESS / 2))
    s = np.linspace(0.0, 1.0, samples)[None, :, None]
    poses = start[e, None] + s * (end[e] - start[e])[:, None]  # (P, S, 3)
    hit = np.any(W.polygons_overlap(trunk_polygon(poses), envs.polygons[e, m][:, None]), axis=1)
    collided = np.zeros(len(zr), dtype=bool)
    collided[e[hit]] = True
    return collided


def swing_height(a: np.ndarray, b: np.ndarray, envs: W.EnvBatch) -> tuple[np.ndarray, np.ndarray]:
    """Apex height of a swing from foothold ``a`` to ``b`` (E, 3): ``SWING_CLEARANCE`` above the
    highest of both surfaces and every surmountable obstacle under the straight path; and whether the
    path crosses a wall (a collision)."""
    crossed = crossings(a[:, None, :2], b[:, None, :2], envs)[:, 0]  # (E, M)
    over = np.max(np.where(crossed & envs.surmountable, envs.heights, 0.0), axis=-1, initial=0.0)
    apex = np.maximum(np.maximum(a[:, 2], b[:, 2]), over) + C.SWING_CLEARANCE
    return apex, np.any(crossed & ~envs.surmountable, axis=-1)


def body_height(pose: np.ndarray, feet: np.ndarray, envs: W.EnvBatch) -> np.ndarray:
    """Body-raise rule (seed §3.2, §4.1): Zr = ZR_NOMINAL + RAISE_GAIN·h for the tallest surmountable
    obstacle on the stretch of either side's feet, from the rear foot to ``RAISE_LOOKAHEAD`` ahead of
    the front foot (left: leg 3 to leg 1, right: leg 4 to leg 2); ZR_NOMINAL when there is none.

    Decided from the feet before the cycle's action (the network gets Zr as an input). Chosen: the
    paper raises the body "when a landing point is within 300 mm in front of an obstacle" and lowers
    it after; this reading gives the printed Zr of 30 of the 31 cycles of Tables 3, 6 and 7 (not
    Table 3 cycle 7, which Tables 6 and 7 contradict for any rule on positions).
    """
    ahead = rotate(pose[:, None, 2], np.array([0.0, C.RAISE_LOOKAHEAD]) * np.ones((len(pose), 2, 2)))
    rear, front = feet[:, [2, 3], :2], feet[:, [0, 1], :2] + ahead
    near = crossings(rear, front, envs)  # (E, 2, M)
    relevant = np.any(near, axis=1) & envs.surmountable
    return C.ZR_NOMINAL + C.RAISE_GAIN * np.max(np.where(relevant, envs.heights, 0.0), axis=-1, initial=0.0)


# --- The crawl cycle ------------------------------------------------------------------------------

@dataclass
class CrawlState:
    """Batched robot state: ``pose (E, 3)`` world (x, y, θ), ``zr (E,)`` body height, ``feet (E, 4, 3)``."""

    pose: np.ndarray
    zr: np.ndarray
    feet: np.ndarray

    @classmethod
    def initial(cls, n: int) -> CrawlState:
        """The start of seed §4.1.1: CoG (0, 0, 0.3), heading +y, feet at the initial stance on the floor."""
        feet = np.concatenate([NOMINAL_FEET, np.zeros((4, 1))], axis=1)
        return cls(np.zeros((n, 3)), np.full(n, C.ZR_NOMINAL), np.tile(feet, (n, 1, 1)))

    def take(self, idx) -> CrawlState:
        return CrawlState(self.pose[idx], self.zr[idx], self.feet[idx])

    def put(self, idx, other: CrawlState) -> None:
        self.pose[idx], self.zr[idx], self.feet[idx] = other.pose, other.zr, other.feet


@dataclass
class CycleOutcome:
    """Result of one batched walking cycle.

    ``state`` is the state at the end of the cycle; ``br`` the body movement [m]; ``footholds
    (E, 4, 3)`` and ``stands_on (E, 4)`` the landing points; the failure masks say why a cycle could
    not be executed. ``poses (E, 6, 3)``: the body at the start, after each of the four stability
    shifts (held while that swing leg is in the air), at the end. Per swing s (in order):
    ``triangles (E, 4, 3, 2)`` the support triangle and :attr:`margins` ``(E, 4)`` the CoG's stability margin
    (computed when asked for: the crawl itself does not need it).
    """

    state: CrawlState
    br: np.ndarray
    footholds: np.ndarray
    stands_on: np.ndarray
    collided: np.ndarray
    limit: np.ndarray
    unstable: np.ndarray
    triangles: np.ndarray
    poses: np.ndarray

    @property
    def margins(self) -> np.ndarray:
        """The CoG's stability margin in each swing's support triangle ``(E, 4)``."""
        return stability_margin(self.poses[:, 1:5, :2], self.triangles)

    @property
    def failed(self) -> np.ndarray:
        return self.collided | self.limit | self.unstable

    def record(self, e: int, k: int, command: np.ndarray, order) -> CycleRecord:
        """The cycle of episode ``e`` as a :class:`CycleRecord`."""
        return CycleRecord(k, tuple(np.asarray(command, dtype=float)), float(self.state.zr[e]), tuple(order),
                           self.footholds[e].copy(), self.stands_on[e].copy(), self.poses[e].copy(),
                           self.triangles[e].copy(), self.poses[e, 1:5, :2].copy(),
                           stability_margin(self.poses[e, 1:5, :2], self.triangles[e]),
                           float(1000 * self.br[e]), bool(self.collided[e]), bool(self.limit[e]),
                           bool(self.unstable[e]))


@dataclass(frozen=True)
class CycleRecord:
    """One executed walking cycle of one episode (lengths in m unless named ``_mm``).

    ``footholds (4, 3)`` per leg (0..3 = LF, RF, LR, RR), ``stands_on (4,)`` the obstacle each foot
    lands on (0 right, 1 left, -1 floor), ``body_poses (6, 3)`` start / after each of the four
    stability shifts / end, ``support_triangles (4, 3, 2)`` and ``cog (4, 2)`` and ``margins (4,)`` at
    each swing (in swing order), ``br_mm`` the body movement.
    """

    k: int
    command: tuple
    zr: float
    order: tuple
    footholds: np.ndarray
    stands_on: np.ndarray
    body_poses: np.ndarray
    support_triangles: np.ndarray
    cog: np.ndarray
    margins: np.ndarray
    br_mm: float
    collided: bool
    limit: bool
    unstable: bool


def _order_legs(order: np.ndarray) -> np.ndarray:
    order = np.asarray(order)
    if order.ndim != 2 or order.shape[1] != 4 or not np.all(np.sort(order, axis=1) == np.arange(1, 5)):
        raise ValueError(f"swing orders must be permutations of the legs 1..4, shape (E, 4); got {order.tolist()}")
    return order - 1


def crawl_cycle(state: CrawlState, command: np.ndarray, order: np.ndarray, zr: np.ndarray,
                envs: W.EnvBatch) -> CycleOutcome:
    """Execute one walking cycle per episode (module docstring). ``command (E, 3)`` is (ΔXr [m],
    ΔYr [m], Δθr [rad]) in the body frame, ``order (E, 4)`` the swing order in leg numbers 1..4,
    ``zr (E,)`` the body height for this cycle."""
    command = np.asarray(command, dtype=float)
    if command.shape != (len(state.zr), 3) or not np.all(np.isfinite(command)):
        raise ValueError(f"crawl_cycle: command must be finite with shape ({len(state.zr)}, 3), got {command.shape}")
    legs = _order_legs(order)
    n = len(legs)
    rows = np.arange(n)
    target = compose(state.pose, command)
    footholds, stands_on, admissible = snap_footholds(to_world(target, NOMINAL_FEET[None].repeat(n, 0)), envs)
    feet = state.feet.copy()
    body = state.pose.copy()
    limit = ~legs_within_limits(body, zr, feet, ALL_LEGS)
    collided = ~np.all(admissible, axis=1) | trunk_collides(body, body, zr, envs, samples=1)
    unstable = np.zeros(n, dtype=bool)
    br = np.zeros(n)
    poses = [body.copy()]
    triangles = []
    for s in range(4):
        leg = legs[:, s]
        triangle = feet[rows[:, None], SUPPORT[leg], :2]
        goal, feasible = _support_step(body[:, :2], triangle)
        moved = np.concatenate([goal, state.pose[:, 2:] + command[:, 2:] * (s + 1) / 5], axis=1)  # turn evenly
        collided |= trunk_collides(body, moved, zr, envs)
        br += W.length(goal - body[:, :2])
        body = moved
        unstable |= ~feasible
        triangles.append(triangle)
        poses.append(body.copy())
        a, b = feet[rows, leg], footholds[rows, leg]
        apex, crosses_wall = swing_height(a, b, envs)
        collided |= crosses_wall
        # with the body held after the shift: the four feet, then the swing foot's key poses (one IK call)
        points = np.concatenate([feet, _swing_key_points(a, b, apex, body, leg)], axis=1)
        limit |= ~legs_within_limits(body, zr, points, np.concatenate([np.broadcast_to(ALL_LEGS, (n, 4)),
                                                                     np.repeat(leg[:, None], 4, 1)], axis=1))
        feet[rows, leg] = b
    collided |= trunk_collides(body, target, zr, envs)
    br += W.length(target[:, :2] - body[:, :2])
    limit |= ~legs_within_limits(target, zr, feet, ALL_LEGS)
    unstable |= stability_margin(target[:, :2], feet[..., :2]) <= 0.0
    poses.append(target.copy())
    return CycleOutcome(CrawlState(target, zr.copy(), feet), br, footholds, stands_on, collided, limit, unstable,
                        np.stack(triangles, 1), np.stack(poses, 1))


ALL_LEGS = np.arange(4)
SUPPORT = np.array([[other for other in range(4) if other != leg] for leg in range(4)])  # (4, 3): the stance legs


def _swing_key_points(a: np.ndarray, b: np.ndarray, apex: np.ndarray, body: np.ndarray, leg: np.ndarray) -> np.ndarray:
    """Key poses of a swing foot ``(E, 4, 3)``: lifted above ``a``, at the point of the straight path
    nearest its shoulder, above ``b``, and landed on ``b``."""
    shoulder = to_world(body, SHOULDER_XY[leg][:, None])[:, 0]
    ab = b[:, :2] - a[:, :2]
    t = np.clip(W.dot(shoulder - a[:, :2], ab) / np.maximum(W.dot(ab, ab), 1e-12), 0.0, 1.0)
    mid = a[:, :2] + t[:, None] * ab
    air = np.stack([a[:, :2], mid, b[:, :2]], axis=1)
    air = np.concatenate([air, np.repeat(apex[:, None, None], 3, axis=1)], axis=-1)
    return np.concatenate([air, b[:, None]], axis=1)
