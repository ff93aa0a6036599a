"""Large obstacles (seed 000 §4.4.2, §7.3.2, Figs. 4.13–4.17): depth sensor → costmap → dynamic-window
planner → (ẋ^ref, θ̇^ref) → handle and crank targets by the tricycle model (Eqs. 4.15–4.22, 4.25–4.28).

* :class:`DepthSensor` — the head stereo camera as MuJoCo ray casts (``mj_multiRay``) from the
  ``head_camera`` site; it sees the environment's obstacle geoms (group :data:`OBSTACLE_GROUP`), the
  floor being removed as a ground filter would (points below ``min_obstacle_height`` are dropped).
* :class:`Costmap` — a 2-D occupancy grid in the world frame with a distance field (the thesis's
  ROS local costmap [156][157]).
* :func:`global_path` — Dijkstra on the inflated costmap (move_base's global planner, navfn-like).
* :class:`DynamicWindow` — our DWA (Fox, Burgard, Thrun 1997; the thesis used ROS move_base/DWA
  [158]): samples (v, ω) in the dynamic window, limited by the tricycle's steering limit
  |ω| ≤ v tan Θ_H / L, simulates Eq. 4.15 over a horizon, rejects footprints that touch an
  obstacle, scores the end pose's distance to the global path and to the goal along it (ROS DWA's
  path/goal distance biases), clearance and speed.
* :func:`tricycle_rates` (Eqs. 4.15–4.16), :func:`crank_rate` (4.18), :func:`handle_reference`
  (4.20–4.21), :func:`crank_reference` (4.22) and :func:`osi_references` (4.25/4.28, the linearised
  online-search-index form).

Self-localisation (the thesis fused wheel and visual odometry by SLAM, §7.3.2) is the vehicle pose
the robot derives from its waist (:class:`~shintai.humanoid.tricycle.hrp2_limbs.VehicleFrame`), i.e. ground
truth up to the seat — a stand-in, stated as such.
"""

from __future__ import annotations

import heapq
import math

import mujoco
import numpy as np
from scipy.ndimage import distance_transform_edt

from shintai.humanoid.constants import NAVIGATION, THETA_H_MAX, TRICYCLE, WHEELBASE, NavigationSpec
from shintai.humanoid.tricycle.constants import OBSTACLE_GROUP


# --- the tricycle model, Eqs. 4.15–4.28 ------------------------------------------------------------


def tricycle_rates(theta: float, phi: float, omega_c: float, omega_h: float, d_c: float = TRICYCLE.travel_per_rev,
                   wheelbase: float = WHEELBASE) -> np.ndarray:
    """Eq. 4.16 (Eq. 4.15 with v_b = D_c ω_c / 2π): (ẋ, ẏ, θ̇, φ̇) of the pose (x, y, θ) and handle φ."""
    v_b = d_c * omega_c / (2 * math.pi)
    return np.array([v_b * math.cos(theta), v_b * math.sin(theta), v_b * math.tan(phi) / wheelbase, omega_h])


def crank_rate(xdot_ref: float, d_c: float = TRICYCLE.travel_per_rev) -> float:
    """Eq. 4.18: ω_c^ref = 2π ẋ^ref / D_c."""
    return 2 * math.pi * xdot_ref / d_c


def handle_reference(xdot_ref: float, yaw_rate_ref: float, wheelbase: float = WHEELBASE,
                     limit: float = THETA_H_MAX) -> float:
    """Eqs. 4.20–4.21: θ_h^ref = arctan(L θ̇^ref / ẋ^ref), clipped to Θ_H (Table 3.4).

    At ẋ^ref = 0 (the singular origin of Eq. 4.23) the handle goes straight (0), as at the goal.
    """
    if xdot_ref <= 0.0:
        return 0.0
    return float(np.clip(math.atan(wheelbase * yaw_rate_ref / xdot_ref), -limit, limit))


def crank_reference(theta_c: float, xdot_ref: float, dt: float, d_c: float = TRICYCLE.travel_per_rev) -> float:
    """Eq. 4.22: θ_c^ref(t+Δt) = θ_c(t) + (2π Δt / D_c) ẋ^ref(t), from the **measured** crank angle."""
    return theta_c + 2 * math.pi * dt * xdot_ref / d_c


def osi_references(theta_c: float, yaw_rate_error: float, xdot_ref: float, dt: float, dx_star: float,
                   d_c: float = TRICYCLE.travel_per_rev, wheelbase: float = WHEELBASE) -> np.ndarray:
    """Eq. 4.28: (θ_h^ref, θ_c^ref) := (0, θ_c) − diag(L/δẋ*, 2πΔt/D_c) · sgn · (x − 0), sgn = −E (4.27),
    x = (θ̇^ref, ẋ^ref) with θ̇^ref = θ̇_nav^ref − θ̇ (4.26). Equals Eq. 4.25, the linearisation of
    4.21–4.22 about (0, δẋ*)."""
    A = np.diag([wheelbase / dx_star, 2 * math.pi * dt / d_c])
    sgn = -np.eye(2)
    return np.array([0.0, theta_c]) - A @ sgn @ np.array([yaw_rate_error, xdot_ref])


def integrate_pose(pose, v: float, w: float, dt: float) -> np.ndarray:
    """One step of Eq. 4.15 with v_b = v and θ̇ = w (exact arc)."""
    x, y, th = pose
    return np.array(_arc(float(x), float(y), float(th), float(v), float(w), dt))


def _arc(x: float, y: float, th: float, v: float, w: float, dt: float) -> tuple[float, float, float]:
    """:func:`integrate_pose` on floats (the rollouts' inner step): the same IEEE operations as on NumPy's
    scalars, without an array per step."""
    if abs(w) < 1e-9:
        return x + v * dt * math.cos(th), y + v * dt * math.sin(th), th
    r = v / w
    return x + r * (math.sin(th + w * dt) - math.sin(th)), y - r * (math.cos(th + w * dt) - math.cos(th)), th + w * dt


# --- depth sensor -------------------------------------------------------------------------------


class DepthSensor:
    """The head stereo camera (§4.4.2; MultiSense S7, §A.2.1) as a grid of ray casts.

    ``scan(model, data)`` returns the world points hit (N, 3) within ``max_range``. Rays leave the
    site ``head_camera`` spread over the field of view in its frame (x forward, y left, z up).
    """

    def __init__(self, spec: NavigationSpec = NAVIGATION, site: str = "head_camera"):
        self.spec, self.site = spec, site
        az = np.linspace(-spec.fov_h / 2, spec.fov_h / 2, spec.rays_h)
        el = np.linspace(-spec.fov_v / 2, spec.fov_v / 2, spec.rays_v)
        A, E = np.meshgrid(az, el)
        self.local = np.stack([np.cos(E) * np.cos(A), np.cos(E) * np.sin(A), np.sin(E)], axis=-1).reshape(-1, 3)
        self.groups = np.zeros(6, dtype=np.uint8)
        self.groups[OBSTACLE_GROUP] = 1
        n = len(self.local)
        self._geom = np.zeros(n, dtype=np.int32)
        self._dist = np.zeros(n)

    def ranges(self, model: mujoco.MjModel, data: mujoco.MjData) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(origin, world ray directions (N, 3), distances (N,); −1 where nothing within range)."""
        sid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, self.site)
        origin = data.site_xpos[sid].copy()
        rot = data.site_xmat[sid].reshape(3, 3)
        dirs = self.local @ rot.T
        mujoco.mj_multiRay(model, data, origin, dirs.reshape(-1), self.groups, 1, -1, self._geom, self._dist, None,
                           len(dirs), self.spec.max_range)
        dist = self._dist.copy()
        dist[(self._geom < 0) | (dist > self.spec.max_range)] = -1.0
        return origin, dirs, dist

    def scan(self, model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
        origin, dirs, dist = self.ranges(model, data)
        hit = dist >= 0
        points = origin + dirs[hit] * dist[hit, None]
        return points[points[:, 2] >= self.spec.min_obstacle_height]


# --- costmap -----------------------------------------------------------------------------------


class Costmap:
    """World-frame occupancy grid (cells marked by sensed points) with a distance field [m]."""

    def __init__(self, spec: NavigationSpec = NAVIGATION):
        self.spec = spec
        self.res = spec.resolution
        self.origin = np.asarray(spec.origin, dtype=float)
        self.shape = (int(round(spec.size[0] / self.res)), int(round(spec.size[1] / self.res)))
        self.occupied = np.zeros(self.shape, dtype=bool)
        self.distance = np.full(self.shape, np.inf)

    def cell(self, xy) -> tuple[np.ndarray, np.ndarray]:
        ij = np.floor((np.atleast_2d(xy)[:, :2] - self.origin) / self.res).astype(int)
        return ij[:, 0], ij[:, 1]

    def centre(self, i, j) -> np.ndarray:
        return self.origin + (np.stack([i, j], axis=-1) + 0.5) * self.res

    def mark(self, points) -> int:
        """Mark the cells of ``points`` (N, ≥2) occupied; returns how many were new. Updates the field."""
        if len(points) == 0:
            return 0
        i, j = self.cell(points)
        ok = (i >= 0) & (i < self.shape[0]) & (j >= 0) & (j < self.shape[1])
        before = int(self.occupied.sum())
        self.occupied[i[ok], j[ok]] = True
        new = int(self.occupied.sum()) - before
        if new:
            self.distance = distance_transform_edt(~self.occupied) * self.res if self.occupied.any() else \
                np.full(self.shape, np.inf)
        return new

    def clearance(self, xy) -> np.ndarray:
        """Distance [m] from each point to the nearest occupied cell (inf if none; 0 outside the map)."""
        i, j = self.cell(xy)
        inside = (i >= 0) & (i < self.shape[0]) & (j >= 0) & (j < self.shape[1])
        out = np.zeros(len(i))
        out[inside] = self.distance[i[inside], j[inside]]
        return out


def footprint_points(pose, spec: NavigationSpec = NAVIGATION) -> np.ndarray:
    """Centres (K, 2) of the footprint circles of a vehicle at ``pose`` = (x, y, θ) (crank origin)."""
    x, y, th = pose
    fx = np.asarray(spec.footprint_x)
    return np.stack([x + fx * math.cos(th), y + fx * math.sin(th)], axis=-1)


def trajectory_footprints(traj, spec: NavigationSpec = NAVIGATION) -> np.ndarray:
    """:func:`footprint_points` of every pose of ``traj`` (N, 3), stacked (N K, 2) pose by pose: the same
    products, one array operation for the whole trajectory (the cosines and sines still ``math``'s)."""
    fx = np.asarray(spec.footprint_x, dtype=float)
    th = traj[:, 2].tolist()
    cos = np.array([math.cos(t) for t in th])
    sin = np.array([math.sin(t) for t in th])
    out = np.empty((len(th), len(fx), 2))
    out[..., 0] = traj[:, :1] + fx * cos[:, None]
    out[..., 1] = traj[:, 1:2] + fx * sin[:, None]
    return out.reshape(-1, 2)


def global_path(costmap: Costmap, start, goal, radius: float, margin: float = 0.0,
                penalty: float = 10.0) -> np.ndarray | None:
    """Cheapest 8-connected grid path (Dijkstra) from ``start`` to ``goal`` through cells farther than
    ``radius`` from every obstacle (lethal, the inflated costmap); a cell within ``radius + margin``
    costs up to 1 + ``penalty`` times more, growing toward the obstacle (costmap_2d's inflation
    decay, navfn's cost). (K, 2) world points, or None."""
    free = costmap.distance > radius
    weight = 1.0 + penalty * np.clip((radius + margin - costmap.distance) / max(margin, 1e-9), 0.0, 1.0) \
        if margin > 0 else np.ones(costmap.shape)
    si, sj = (int(v[0]) for v in costmap.cell(start))
    gi, gj = (int(v[0]) for v in costmap.cell(goal))
    n0, n1 = costmap.shape
    if not (0 <= gi < n0 and 0 <= gj < n1 and 0 <= si < n0 and 0 <= sj < n1):
        return None
    free[si, sj] = True  # the vehicle is where it is
    # the search walks Python lists (cell k = i n1 + j): NumPy's element indexing costs more than the arithmetic;
    # the same float operations and the same heap order, so the same path
    free, weight = free.ravel().tolist(), weight.ravel().tolist()
    inf = math.inf
    dist = [inf] * (n0 * n1)
    prev = [-1] * (n0 * n1)
    start, target = si * n1 + sj, gi * n1 + gj
    dist[start] = 0.0
    heap = [(0.0, si, sj)]
    steps = [(di, dj, math.hypot(di, dj)) for di in (-1, 0, 1) for dj in (-1, 0, 1) if di or dj]
    pop, push = heapq.heappop, heapq.heappush
    while heap:
        d, i, j = pop(heap)
        k = i * n1 + j
        if k == target:
            break
        if d > dist[k]:
            continue
        for di, dj, c in steps:
            a, b = i + di, j + dj
            if 0 <= a < n0 and 0 <= b < n1:
                n = a * n1 + b
                if free[n]:
                    nd = d + c * weight[n]
                    if nd < dist[n]:
                        dist[n] = nd
                        prev[n] = k
                        push(heap, (nd, a, b))
    if dist[target] == inf:
        return None
    cells = [target]
    while cells[-1] != start:
        cells.append(prev[cells[-1]])
    cells.reverse()
    ij = np.array([divmod(k, n1) for k in cells])
    return costmap.centre(ij[:, 0], ij[:, 1])


class DynamicWindow:
    """Our dynamic-window local planner (Fox et al. 1997) for the tricycle (Eq. 4.15).

    :meth:`plan` returns (ẋ^ref, θ̇^ref) and the chosen trajectory; (0, 0) at the goal or when no
    admissible sample exists (the vehicle then stops, as move_base does).
    """

    def __init__(self, spec: NavigationSpec = NAVIGATION, wheelbase: float = WHEELBASE,
                 steer_limit: float = THETA_H_MAX):
        self.spec, self.wheelbase, self.steer_limit = spec, wheelbase, steer_limit

    def rollout(self, pose, v: float, w: float, steps: int = 10) -> np.ndarray:
        dt = self.spec.horizon / steps
        v, w = float(v), float(w)
        out = [tuple(float(q) for q in pose)]
        for _ in range(steps):
            out.append(_arc(*out[-1], v, w, dt))
        return np.array(out)

    def plan(self, costmap: Costmap, pose, velocity: tuple[float, float], goal, path=None):
        """Best admissible (v, ω, trajectory). Score (ROS DWA's, Fox et al.'s terms): the trajectory
        end's distance to the global path and its remaining distance to the goal along the path
        (path/goal distance biases), its clearance (capped) and its speed."""
        s = self.spec
        pose = np.asarray(pose, dtype=float)
        goal = np.asarray(goal[:2], dtype=float)
        if np.hypot(*(goal - pose[:2])) <= s.goal_tolerance:
            return 0.0, 0.0, None
        if path is None or len(path) < 2:
            path = np.array([pose[:2], goal])
        seg = np.hypot(*np.diff(path, axis=0).T)
        remaining = np.concatenate([np.cumsum(seg[::-1])[::-1], [0.0]])
        v0, w0 = velocity
        dt = s.period
        vs = np.linspace(max(0.0, v0 - s.a_max * dt), min(s.v_max, v0 + s.a_max * dt), s.samples_v)
        best, choice = -np.inf, (0.0, 0.0, None)
        for v in vs:
            w_lim = v * math.tan(self.steer_limit) / self.wheelbase
            ws = np.linspace(max(-w_lim, w0 - s.yaw_acc_max * dt), min(w_lim, w0 + s.yaw_acc_max * dt), s.samples_w) \
                if w_lim > 0 else np.zeros(1)
            for w in ws:
                traj = self.rollout(pose, v, w)
                clear = costmap.clearance(trajectory_footprints(traj, s)).min() - s.footprint_r
                if clear <= 0.0:
                    continue
                end = traj[-1, :2]
                d = np.hypot(*(path - end).T)
                k = int(np.argmin(d))
                to_go = remaining[k] + d[k]
                score = (-s.w_path * d[k] - s.w_goal * to_go
                         + s.w_clearance * min(clear, s.clearance_cap) / s.clearance_cap + s.w_speed * v / s.v_max)
                if score > best:
                    best, choice = score, (float(v), float(w), traj)
        return choice
