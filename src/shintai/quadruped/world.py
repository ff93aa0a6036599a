"""The continuous 2.5-D world: a flat floor with quadrilateral prism obstacles (§2, seed §4.1.1).

An obstacle is four ground-plane corners o1..o4 plus a height (§2.1); below 0.2 m high it is
surmountable (climbed over or stepped over), the 0.3 m wall is not. Every environment has exactly
one obstacle on the right (index 0) and one on the left (index 1) and a destination; the robot
starts at the origin heading +y, so the destination equals the initial destination error.

Geometry is vectorised: polygons are ``(..., 4, 2)`` arrays with counter-clockwise corners and every
function broadcasts over the leading axes, so that a whole batch of environments (and of feet) is
handled in one call. :class:`EnvBatch` stacks environments for the batched crawl executor.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from shintai.quadruped import constants as C


# --- Convex polygon geometry ---------------------------------------------------------------------

def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Dot product over the last axis of planar vectors (faster than a size-2 reduction)."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def length(v: np.ndarray) -> np.ndarray:
    """Length of planar vectors ``(..., 2)``."""
    return np.hypot(v[..., 0], v[..., 1])


def edges(poly: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Edge start points and outward unit normals of counter-clockwise polygons ``(..., V, 2)``."""
    e = np.roll(poly, -1, axis=-2) - poly
    n = np.stack([e[..., 1], -e[..., 0]], axis=-1)
    return poly, n / length(n)[..., None]


def ccw(poly: np.ndarray) -> np.ndarray:
    """The polygons with their corners reordered counter-clockwise where they were clockwise."""
    poly = np.asarray(poly, dtype=float)
    x, y = poly[..., 0], poly[..., 1]
    area2 = np.sum(x * np.roll(y, -1, axis=-1) - np.roll(x, -1, axis=-1) * y, axis=-1)
    return np.where((area2 < 0)[..., None, None], poly[..., ::-1, :], poly)


def closest_boundary(p: np.ndarray, poly: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Signed distance of points to convex polygons (negative inside), nearest boundary point, and
    the unit direction pointing out of the polygon there.

    ``p`` is ``(..., 2)``, ``poly`` ``(..., V, 2)``; the leading axes broadcast.
    """
    a, n = edges(poly)
    ab = np.roll(poly, -1, axis=-2) - a
    ap = p[..., None, :] - a
    t = np.clip(dot(ap, ab) / dot(ab, ab), 0.0, 1.0)
    foot = a + t[..., None] * ab
    dist = length(p[..., None, :] - foot)
    k = np.argmin(dist, axis=-1)[..., None]
    near = np.take_along_axis(foot, k[..., None], axis=-2)[..., 0, :]
    d = np.take_along_axis(dist, k, axis=-1)[..., 0]
    inside = np.all(dot(n, ap) <= 0.0, axis=-1)
    away = p - near
    gap = length(away)[..., None]
    normal = np.take_along_axis(np.broadcast_to(n, foot.shape), k[..., None], axis=-2)[..., 0, :]
    out = np.where(inside[..., None] | (gap < 1e-12), normal, away / np.maximum(gap, 1e-12))
    return np.where(inside, -d, d), near, out


def signed_distance(p: np.ndarray, poly: np.ndarray, normals: np.ndarray | None = None) -> np.ndarray:
    """Distance of points to convex polygons, negative inside: :func:`closest_boundary`'s first value
    from the same operations, edge by edge on the x and y components, without the nearest point and
    direction (the foothold test of every crawl cycle; bit-identical, tested). ``normals``:
    :func:`edges`' normals of ``poly`` when known."""
    n = edges(poly)[1] if normals is None else normals
    px, py = p[..., 0], p[..., 1]
    d = inside = None
    for v in range(poly.shape[-2]):
        ax, ay = poly[..., v, 0], poly[..., v, 1]
        w = (v + 1) % poly.shape[-2]
        abx, aby = poly[..., w, 0] - ax, poly[..., w, 1] - ay
        apx, apy = px - ax, py - ay
        t = np.clip((apx * abx + apy * aby) / (abx * abx + aby * aby), 0.0, 1.0)
        dist = np.hypot(px - (ax + t * abx), py - (ay + t * aby))
        out = n[..., v, 0] * apx + n[..., v, 1] * apy <= 0.0
        d, inside = (dist, out) if d is None else (np.minimum(d, dist), inside & out)
    return np.where(inside, -d, d)


def inset(poly: np.ndarray, depth: float) -> np.ndarray:
    """Convex polygons shrunk by ``depth`` (each edge moved inwards; corners re-intersected)."""
    a, n = edges(poly)
    c = dot(n, a) - depth  # inset edge lines n . x = c
    n_prev, c_prev = np.roll(n, 1, axis=-2), np.roll(c, 1, axis=-1)
    det = n_prev[..., 0] * n[..., 1] - n_prev[..., 1] * n[..., 0]
    x = (c_prev * n[..., 1] - n_prev[..., 1] * c) / det
    y = (n_prev[..., 0] * c - c_prev * n[..., 0]) / det
    return np.stack([x, y], axis=-1)


def nearest_inside(p: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """The point of each convex polygon nearest to ``p`` (``p`` itself when inside): :func:`closest_boundary`
    edge by edge on the x and y components, without the direction (bit-identical for polygons with no
    zero-length edge, tested)."""
    n = edges(poly)[1]
    px, py = p[..., 0], p[..., 1]
    for v in range(poly.shape[-2]):
        ax, ay = poly[..., v, 0], poly[..., v, 1]
        w = (v + 1) % poly.shape[-2]
        abx, aby = poly[..., w, 0] - ax, poly[..., w, 1] - ay
        apx, apy = px - ax, py - ay
        t = np.clip((apx * abx + apy * aby) / (abx * abx + aby * aby), 0.0, 1.0)
        fx, fy = ax + t * abx, ay + t * aby
        dist = np.hypot(px - fx, py - fy)
        out = n[..., v, 0] * apx + n[..., v, 1] * apy <= 0.0
        if v == 0:
            d, near_x, near_y, inside = dist, fx, fy, out
        else:  # the first nearest edge, as np.argmin
            closer = dist < d
            d, near_x, near_y, inside = (np.where(closer, dist, d), np.where(closer, fx, near_x),
                                         np.where(closer, fy, near_y), inside & out)
    keep = (np.where(inside, -d, d) <= 0.0)[..., None]
    return np.where(keep, p, np.stack([near_x, near_y], axis=-1))


def segment_hits(a: np.ndarray, b: np.ndarray, poly: np.ndarray, normals: np.ndarray | None = None) -> np.ndarray:
    """Whether segments ``a -> b`` meet convex polygons (Cyrus-Beck clipping; touching counts), edge by
    edge on the x and y components. ``normals``: :func:`edges`' normals of ``poly`` when known."""
    n = edges(poly)[1] if normals is None else normals
    dx, dy = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    t_in, t_out, parallel_out = 0.0, 1.0, False
    for v in range(poly.shape[-2]):
        nx, ny = n[..., v, 0], n[..., v, 1]
        num = nx * (poly[..., v, 0] - a[..., 0]) + ny * (poly[..., v, 1] - a[..., 1])  # inside: t * den <= num
        den = nx * dx + ny * dy
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = num / den
        t_in = np.maximum(t_in, np.where(den < 0, ratio, -np.inf))
        t_out = np.minimum(t_out, np.where(den > 0, ratio, np.inf))
        parallel_out = parallel_out | ((den == 0) & (num < 0))
    return (t_in <= t_out) & ~parallel_out


def polygons_overlap(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Whether convex polygons ``p (..., V, 2)`` and ``q (..., W, 2)`` overlap (separating axes;
    touching does not count). The leading axes broadcast. The projections' extremes are taken vertex
    by vertex on the x and y components (short reductions are slow in NumPy)."""
    axes = np.concatenate(_broadcast_lead(edges(p)[1], edges(q)[1]), axis=-2)  # (..., A, 2)
    ax, ay = axes[..., 0], axes[..., 1]
    (p_lo, p_hi), (q_lo, q_hi) = _extent(ax, ay, p), _extent(ax, ay, q)
    separated = (p_hi <= q_lo) | (q_hi <= p_lo)
    return ~np.any(separated, axis=-1)


def _extent(ax: np.ndarray, ay: np.ndarray, poly: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The least and greatest projection of the corners of ``poly (..., V, 2)`` on axes ``(ax, ay) (..., A)``."""
    lo = hi = None
    for v in range(poly.shape[-2]):
        d = ax * poly[..., v, None, 0] + ay * poly[..., v, None, 1]
        lo, hi = (d, d) if lo is None else (np.minimum(lo, d), np.maximum(hi, d))
    return lo, hi


def _broadcast_lead(p: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    lead = np.broadcast_shapes(p.shape[:-2], q.shape[:-2])
    return np.broadcast_to(p, lead + p.shape[-2:]), np.broadcast_to(q, lead + q.shape[-2:])


# --- Obstacles and environments ------------------------------------------------------------------

@dataclass(frozen=True)
class Obstacle:
    """A quadrilateral prism: corners o1..o4 in the ground plane [m] (as printed) and a height [m]."""

    corners: tuple
    height: float

    def __post_init__(self):
        c = np.asarray(self.corners, dtype=float)
        if c.shape != (4, 2) or not np.all(np.isfinite(c)):
            raise ValueError(f"obstacle corners must be 4 finite (x, y) points, got {self.corners!r}")
        if not (0.0 < self.height):
            raise ValueError(f"obstacle height must be positive, got {self.height}")
        poly = ccw(c)
        a, n = edges(poly)
        turn = dot(n, np.roll(poly, -2, axis=0) - a)
        if np.any(turn >= 0):
            raise ValueError(f"obstacle corners {self.corners!r} do not form a convex quadrilateral")
        if np.any(signed_distance(inset(poly, C.TOP_BAND).mean(0), poly) > -C.TOP_BAND):
            raise ValueError(f"obstacle {self.corners!r} is too thin for the {C.TOP_BAND} m top band")

    @property
    def polygon(self) -> np.ndarray:
        """Corners counter-clockwise, ``(4, 2)``."""
        return ccw(np.asarray(self.corners, dtype=float))

    @property
    def surmountable(self) -> bool:
        return self.height < C.SURMOUNTABLE_BELOW


@dataclass(frozen=True)
class Environment:
    """One right and one left obstacle and the destination (= initial destination error) [m]."""

    name: str
    right: Obstacle
    left: Obstacle
    destination: tuple

    @property
    def obstacles(self) -> tuple[Obstacle, Obstacle]:
        return self.right, self.left


@dataclass(frozen=True)
class EnvBatch:
    """Environments stacked for the batched executor: ``polygons (E, 2, 4, 2)`` counter-clockwise,
    ``heights (E, 2)`` and ``destination (E, 2)``; obstacle 0 is the right one, 1 the left one."""

    polygons: np.ndarray
    heights: np.ndarray
    destination: np.ndarray

    @classmethod
    def of(cls, envs) -> EnvBatch:
        envs = list(envs)
        if not envs:
            raise ValueError("EnvBatch.of: no environments given")
        return cls(np.array([[o.polygon for o in e.obstacles] for e in envs]),
                   np.array([[o.height for o in e.obstacles] for e in envs], dtype=float),
                   np.array([e.destination for e in envs], dtype=float))

    @classmethod
    def flat(cls, n: int) -> EnvBatch:
        """``n`` obstacle-free floors (destination at the origin), e.g. for the swing-order teacher."""
        return cls(np.zeros((n, 0, 4, 2)), np.zeros((n, 0)), np.zeros((n, 2)))

    def __len__(self) -> int:
        return len(self.heights)

    @property
    def surmountable(self) -> np.ndarray:
        return self.heights < C.SURMOUNTABLE_BELOW

    @cached_property
    def circles(self) -> tuple[np.ndarray, np.ndarray]:
        """Bounding circles of the obstacles, computed once: centres ``(E, M, 2)`` (corner means), radii ``(E, M)``."""
        centre = self.polygons.mean(axis=-2)
        return centre, length(self.polygons - centre[..., None, :]).max(axis=-1, initial=0.0)

    @cached_property
    def normals(self) -> np.ndarray:
        """The obstacles' outward unit edge normals ``(E, M, 4, 2)`` (:func:`edges`), computed once."""
        return edges(self.polygons)[1]

    def take(self, idx) -> EnvBatch:
        """The rows ``idx``, with the normals and circles taken along when they are computed already."""
        batch = EnvBatch(self.polygons[idx], self.heights[idx], self.destination[idx])
        for name in ("normals", "circles"):
            if name in self.__dict__:  # functools.cached_property's store
                value = self.__dict__[name]
                batch.__dict__[name] = value[idx] if name == "normals" else (value[0][idx], value[1][idx])
        return batch

    def tile(self, k: int) -> EnvBatch:
        """The batch repeated ``k`` times (row ``i * E + e`` is environment ``e``)."""
        return EnvBatch(np.tile(self.polygons, (k, 1, 1, 1)), np.tile(self.heights, (k, 1)),
                        np.tile(self.destination, (k, 1)))


def _environment(name: str, spec: dict) -> Environment:
    return Environment(name, Obstacle(spec["right"], spec["z_right"]), Obstacle(spec["left"], spec["z_left"]),
                       tuple(spec["destination"]))


def table1_obstacles(x_row: int, y_row: int, heights: tuple[float, float]) -> tuple[Obstacle, Obstacle]:
    """Right and left obstacle of Table 1 rows (1-based), with the corner assignment of §2.6:
    right ``(x_in, y1), (x_in, y2), (0.5, y3), (0.5, y4)``, left ``(-0.5, y1), (-0.5, y2), (x_in, y3),
    (x_in, y4)``."""
    if not (1 <= x_row <= len(C.TABLE1_X_ROWS) and 1 <= y_row <= len(C.TABLE1_Y_ROWS)):
        raise ValueError(f"Table 1 has x-rows 1..4 and y-rows 1..2, got ({x_row}, {y_row})")
    xin_r, xin_l = C.TABLE1_X_ROWS[x_row - 1]
    yr, yl = C.TABLE1_Y_ROWS[y_row - 1]
    xr = (xin_r, xin_r, C.OUTER_X, C.OUTER_X)
    xl = (-C.OUTER_X, -C.OUTER_X, xin_l, xin_l)
    return (Obstacle(tuple(zip(xr, yr)), heights[0]), Obstacle(tuple(zip(xl, yl)), heights[1]))


def training_set() -> tuple[Environment, ...]:
    """The 96 training environments of seed §4.1.1: 4 x-rows x 2 y-rows x 4 height pairs x 3
    destinations (§2.6). Named ``x<i>y<j>-r<z_or>-l<z_ol>-d<k>``."""
    envs = []
    for (xi, yi), heights, (di, dest) in itertools.product(
            itertools.product(range(1, 5), range(1, 3)), C.HEIGHT_PAIRS, enumerate(C.DESTINATIONS, 1)):
        right, left = table1_obstacles(xi, yi, heights)
        envs.append(Environment(f"x{xi}y{yi}-r{heights[0]:g}-l{heights[1]:g}-d{di}", right, left, dest))
    return tuple(envs)


def scenario_421() -> Environment:
    """Seed §4.2.1 (also §6.2.1): right wall, left 0.12 m obstacle, destination (-0.15, 2.2)."""
    return _environment("s4.2.1", C.SCENARIO_421)


def scenario_422() -> Environment:
    """Seed §4.2.2: left wall, right 0.07 m obstacle, unseen destination (0.35, 2.1)."""
    return _environment("s4.2.2", C.SCENARIO_422)


def scenario_52() -> Environment:
    """Seed §5.2 (also §6.2.2, Tables 3-5 and 7): right 0.12 m obstacle, left wall, (-0.15, 2.2).
    It is training environment x-row 2, y-row 2, heights (0.12, 0.3), destination 3."""
    return _environment("s5.2", C.SCENARIO_52)


def scenario_43() -> Environment:
    """A stand-in for seed §4.3's real-robot experiment (coordinates not printed): §5.2's layout (left wall),
    destination (0.0, 1.9) (constants ``SCENARIO_43``)."""
    return _environment("s4.3 stand-in", C.SCENARIO_43)


def scenario_621() -> Environment:
    """Seed §6.2.1: the environment of §4.2.1."""
    return _environment("s6.2.1", C.SCENARIO_421)


def scenario_622() -> Environment:
    """Seed §6.2.2: the environment of §5.2."""
    return _environment("s6.2.2", C.SCENARIO_52)


def unseen_environments(n: int, seed: int) -> tuple[Environment, ...]:
    """``n`` perturbed held-out environments (§6.5 check 8), reproducible from ``seed``.

    Each draws a Table 1 layout (x-row, y-row) and a wall side, jitters every corner by up to
    ±``JITTER`` in x and y (redrawn until the quadrilaterals stay convex and thick enough), takes the
    surmountable height uniformly in ``UNSEEN_HEIGHTS`` and the destination uniformly in
    ``UNSEEN_DEST_X`` x ``UNSEEN_DEST_Y``.
    """
    if n < 0:
        raise ValueError(f"unseen_environments: n must be >= 0, got {n}")
    rng = np.random.default_rng(seed)
    envs = []
    while len(envs) < n:
        x_row, y_row = rng.integers(1, 5), rng.integers(1, 3)
        h = rng.uniform(*C.UNSEEN_HEIGHTS)
        heights = (C.WALL_HEIGHT, h) if rng.random() < 0.5 else (h, C.WALL_HEIGHT)
        base = table1_obstacles(int(x_row), int(y_row), heights)
        jitter = rng.uniform(-C.JITTER, C.JITTER, size=(2, 4, 2))
        dest = (rng.uniform(*C.UNSEEN_DEST_X), rng.uniform(*C.UNSEEN_DEST_Y))
        try:
            right, left = (Obstacle(tuple(map(tuple, np.asarray(o.corners) + j)), o.height)
                           for o, j in zip(base, jitter))
        except ValueError:
            continue
        envs.append(Environment(f"unseen{seed}-{len(envs)}", right, left, dest))
    return tuple(envs)
