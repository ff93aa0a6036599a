"""Self-localisation of the tricycle (seed 000 §7.3.2, Figs. 7.3–7.4): wheel odometry, visual odometry,
and a localisation against the map from the head's depth rays that fuses the two.

The thesis compares four odometries (§7.3.2): 'Wheel Odometry: 搭乗型機器(本実験では三輪車)の移動モデル
(ハンドル角度や車輪の回転数から推定)', 'Visual Odometry: ヒューマノイド頭部に搭載されたステレオカメラおよび
LRF によるビジョン情報・距離情報に基づく移動量' and 'SLAM Odometry: Wheel Odometry と Visual Odometry を相補する
SLAM システム [64][190] から推定された Odometry', against the ground truth. Ours:

* :class:`WheelOdometry` — Eq. 4.15 (the tricycle model of §4.4.2) driven by the crank and handle
  angles the robot measures with its own FK (method (a), §3.4.4: ``CrankEstimate`` from the feet,
  :func:`~shintai.humanoid.tricycle.switching.estimate_handle_angle` from the hands), v_b = D_c Δθ_c / 2π at the
  rear axle; the pose reported is the vehicle frame's (the crank origin, ``crank_to_back`` ahead).
* :class:`VisualOdometry` — the head camera's true planar motion between two samples, corrupted by a
  scale error, a yaw drift per metre and a random walk per √m (:data:`LOCALISATION`, ours: the thesis
  gives no VO error), composed onto its own estimate; the vehicle pose follows from the camera's pose
  in the vehicle frame (the robot's FK).
* :class:`ParticleFilter` — Monte Carlo localisation (Thrun, Burgard, Fox, *Probabilistic Robotics*,
  2005: the odometry motion model, Table 5.6; the likelihood-field range model, Table 6.3; the
  low-variance resampler, Table 4.4) on a known occupancy map (:func:`box_map`), its motion the mean
  of the wheel and visual increments ("相補する", equal trust: ours) and its measurement the head's
  depth rays (:class:`~shintai.humanoid.tricycle.navigation.DepthSensor`) in the vehicle frame. The thesis's
  SLAM [64][190] also builds the map; ours localises against a given map (the obstacles' footprints).
  No maintained Python package fitted (PyPI's ``pfilter`` and ``particles`` are generic SMC without a
  map model, ``amcl`` 0.1.2 young bindings), so this is a short implementation of the textbook filter.
* :class:`Localiser` — the three together, updated at the planner period from one snapshot.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from shintai.core.geometry import wrap, wrap_pi
from shintai.humanoid.constants import NAVIGATION, TRICYCLE, WHEELBASE
from shintai.humanoid.tricycle.hrp2_limbs import riding_limbs
from shintai.humanoid.tricycle.navigation import Costmap, DepthSensor, integrate_pose
from shintai.humanoid.tricycle.rig import CrankEstimate
from shintai.humanoid.tricycle.switching import estimate_handle_angle


@dataclass(frozen=True)
class LocalisationSpec:
    """Chosen, because not in text (the thesis names the methods [64][190], not their errors)."""

    # visual odometry: ZED stereo (§6.2, Table 6.1: x_VO every 10 ms); sampled here at the localiser's
    # period, its error specified per metre travelled so that the rate does not change its size
    vo_scale: float = 0.06  # relative scale error of the translation (a stereo baseline/calibration error)
    vo_yaw_drift: float = 0.04  # rad of heading drift per metre travelled (one direction: a biased drift)
    vo_walk_m: float = 0.01  # m per √m: random walk of the translation
    vo_walk_rad: float = 0.01  # rad per √m: random walk of the heading
    # the known map: obstacle outlines on a grid finer than the navigation costmap's 5 cm
    map_resolution: float = 0.02  # m
    # particle filter (Thrun et al. 2005; AMCL's defaults where they exist)
    particles: int = 300
    alpha: tuple[float, float, float, float] = (0.05, 0.05, 0.1, 0.05)  # odometry motion noise, Table 5.6
    sigma_hit: float = 0.1  # m, likelihood field's Gaussian (AMCL: 0.2; our map is exact)
    z_rand: float = 0.05  # weight of a random reading against z_hit = 1 (unnormalised)
    max_beams: int = 60  # beams used per update (AMCL's laser_max_beams)
    min_points: int = 10  # fewer sensed points: prediction only
    init_sigma: tuple[float, float, float] = (0.05, 0.05, 0.03)  # m, m, rad around the given start
    roughen: tuple[float, float, float] = (0.005, 0.005, 0.003)  # jitter after resampling (Gordon et al. 1993)
    period: float = NAVIGATION.period  # s, one update per planner step (0.1 s)


LOCALISATION = LocalisationSpec()


def relative(a, b) -> np.ndarray:
    """Pose ``b`` in the frame of pose ``a`` (x, y, θ each)."""
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    return np.array([c * dx + s * dy, -s * dx + c * dy, wrap_pi(b[2] - a[2])])


def compose(a, d) -> np.ndarray:
    """Pose ``a`` moved by ``d`` given in its own frame."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return np.array([a[0] + c * d[0] - s * d[1], a[1] + s * d[0] + c * d[1], wrap_pi(a[2] + d[2])])


# --- the map --------------------------------------------------------------------------------------


def box_map(obstacles, spec=NAVIGATION, resolution: float | None = None) -> Costmap:
    """The known map: a :class:`Costmap` (``spec``'s extent, cells of ``resolution``, default
    :attr:`LocalisationSpec.map_resolution`) with the outline of every obstacle box
    (:class:`~shintai.humanoid.tricycle.ch4_riding.Obstacle`) tall enough to be seen marked occupied — the
    surfaces a range sensor meets, as a map built from range scans holds them (a filled footprint would
    let a wall's thickness absorb a position error)."""
    res = LOCALISATION.map_resolution if resolution is None else resolution
    cmap = Costmap(dataclasses.replace(spec, resolution=res))
    for ob in obstacles:
        if ob.pos[2] + ob.half[2] < spec.min_obstacle_height:
            continue
        hx, hy = ob.half[0], ob.half[1]
        u, v = np.arange(-hx, hx + 1e-9, res / 2), np.arange(-hy, hy + 1e-9, res / 2)
        edge = np.concatenate([np.stack([u, np.full_like(u, s)], 1) for s in (-hy, hy)]
                              + [np.stack([np.full_like(v, s), v], 1) for s in (-hx, hx)])
        c, s = math.cos(ob.yaw), math.sin(ob.yaw)
        cmap.mark(np.stack([ob.pos[0] + c * edge[:, 0] - s * edge[:, 1], ob.pos[1] + s * edge[:, 0] + c * edge[:, 1]],
                           axis=-1))
    return cmap


def map_distance(cmap: Costmap, xy: np.ndarray, outside: float) -> np.ndarray:
    """Distance [m] from world points (…, 2) to the nearest occupied cell; ``outside`` off the map."""
    ij = np.floor((xy - cmap.origin) / cmap.res).astype(int)
    i, j = ij[..., 0], ij[..., 1]
    inside = (i >= 0) & (i < cmap.shape[0]) & (j >= 0) & (j < cmap.shape[1])
    out = np.full(i.shape, outside)
    out[inside] = np.minimum(cmap.distance[i[inside], j[inside]], outside)
    return out


# --- the odometries -------------------------------------------------------------------------------


class WheelOdometry:
    """Eq. 4.15 from the measured crank and handle angles: the rear axle moves by v_b Δt = D_c Δθ_c / 2π
    and turns by v_b Δt tan φ / L (exact arc); ``pose`` is the vehicle frame (crank origin)."""

    def __init__(self, start, d_c: float = TRICYCLE.travel_per_rev, wheelbase: float = WHEELBASE,
                 back: float = TRICYCLE.crank_to_back):
        self.d_c, self.wheelbase, self.back = d_c, wheelbase, back
        self.axle = compose(np.asarray(start, dtype=float), (-back, 0.0, 0.0))
        self.crank = None

    @property
    def pose(self) -> np.ndarray:
        return compose(self.axle, (self.back, 0.0, 0.0))

    def step(self, crank: float, handle: float) -> np.ndarray:
        if self.crank is not None:
            ds = self.d_c * (crank - self.crank) / (2 * math.pi)
            self.axle = integrate_pose(self.axle, ds, ds * math.tan(handle) / self.wheelbase, 1.0)
            self.axle[2] = wrap_pi(self.axle[2])
        self.crank = crank
        return self.pose


class VisualOdometry:
    """The head camera's planar motion with a scale error, a yaw drift and a random walk (per metre,
    :class:`LocalisationSpec`); ``step(camera, camera_in_vehicle)`` takes the camera's true planar pose
    and its pose in the vehicle frame (FK) and returns the estimated vehicle pose."""

    def __init__(self, start, spec: LocalisationSpec = LOCALISATION, rng=None):
        self.spec, self.rng = spec, rng or np.random.default_rng(0)
        self.start = np.asarray(start, dtype=float)
        self.camera = self.true_prev = None
        self.pose = self.start.copy()

    def step(self, camera, camera_in_vehicle) -> np.ndarray:
        camera = np.asarray(camera, dtype=float)
        if self.true_prev is None:  # the camera starts where the vehicle's known start puts it
            self.camera = compose(self.start, camera_in_vehicle)
        else:
            d = relative(self.true_prev, camera)
            dist = math.hypot(d[0], d[1])
            s, n = self.spec, self.rng.standard_normal(3)
            d[:2] = (1 + s.vo_scale) * d[:2] + s.vo_walk_m * math.sqrt(dist) * n[:2]
            d[2] += s.vo_yaw_drift * dist + s.vo_walk_rad * math.sqrt(dist) * n[2]
            self.camera = compose(self.camera, d)
        self.true_prev = camera
        self.pose = compose(self.camera, relative(camera_in_vehicle, (0.0, 0.0, 0.0)))
        return self.pose


# --- Monte Carlo localisation ---------------------------------------------------------------------


class ParticleFilter:
    """MCL on a known :class:`Costmap` (Thrun et al. 2005): :meth:`predict` (odometry motion model),
    :meth:`correct` (likelihood field of sensed points in the vehicle frame), :attr:`pose` (mean)."""

    def __init__(self, cmap: Costmap, start, spec: LocalisationSpec = LOCALISATION, rng=None,
                 sigma=None, max_range: float = NAVIGATION.max_range):
        self.map, self.spec, self.max_range = cmap, spec, max_range
        self.rng = rng or np.random.default_rng(0)
        n = spec.particles
        self.p = np.asarray(start, dtype=float) + self.rng.standard_normal((n, 3)) * np.asarray(
            sigma if sigma is not None else spec.init_sigma)
        self.w = np.full(n, 1.0 / n)
        self.resamples = 0

    def predict(self, d) -> None:
        """Table 5.6: the increment ``d`` (in the previous frame) as rot1, trans, rot2, each sampled with
        variance α₁rot² + α₂trans² (rotations) or α₃trans² + α₄(rot1² + rot2²) (translation). As in ROS
        AMCL's odometry model: rot1 = 0 below 1 cm of travel (a jitter's direction is meaningless), and the
        noise of a backward step is that of the same step forward."""
        trans = math.hypot(d[0], d[1])
        rot1 = math.atan2(d[1], d[0]) if trans > 0.01 else 0.0
        rot2 = wrap_pi(d[2] - rot1)
        n1 = min(abs(rot1), abs(wrap_pi(rot1 - math.pi)))
        n2 = min(abs(rot2), abs(wrap_pi(rot2 - math.pi)))
        a1, a2, a3, a4 = self.spec.alpha
        n = len(self.p)
        r1 = rot1 - self.rng.standard_normal(n) * math.sqrt(a1 * n1 ** 2 + a2 * trans ** 2)
        tr = trans - self.rng.standard_normal(n) * math.sqrt(a3 * trans ** 2 + a4 * (n1 ** 2 + n2 ** 2))
        r2 = rot2 - self.rng.standard_normal(n) * math.sqrt(a1 * n2 ** 2 + a2 * trans ** 2)
        th = self.p[:, 2]
        self.p[:, 0] += tr * np.cos(th + r1)
        self.p[:, 1] += tr * np.sin(th + r1)
        self.p[:, 2] = wrap(th + r1 + r2)

    def correct(self, points) -> bool:
        """Weight each particle by Π_k (exp(−d_k²/2σ²) + z_rand), d_k the map distance of sensed point k
        placed by the particle (Table 6.3), over at most ``max_beams`` points; resample (Table 4.4) when
        the effective sample size falls under half. False if too few points were sensed."""
        pts = np.asarray(points, dtype=float)[:, :2]
        if len(pts) < self.spec.min_points:
            return False
        if len(pts) > self.spec.max_beams:
            pts = pts[np.linspace(0, len(pts) - 1, self.spec.max_beams).astype(int)]
        c, s = np.cos(self.p[:, 2:3]), np.sin(self.p[:, 2:3])
        world = np.stack([self.p[:, :1] + c * pts[:, 0] - s * pts[:, 1],
                          self.p[:, 1:2] + s * pts[:, 0] + c * pts[:, 1]], axis=-1)
        d = map_distance(self.map, world, self.max_range)
        logw = np.log(self.w) + np.sum(np.log(np.exp(-0.5 * (d / self.spec.sigma_hit) ** 2) + self.spec.z_rand), axis=1)
        w = np.exp(logw - logw.max())
        self.w = w / w.sum()
        if 1.0 / np.sum(self.w ** 2) < 0.5 * len(self.w):
            self.resample()
        return True

    def resample(self) -> None:
        """Low-variance resampling (Table 4.4), then a small roughening jitter."""
        n = len(self.w)
        u = (self.rng.uniform(0, 1.0 / n) + np.arange(n) / n)
        idx = np.minimum(np.searchsorted(np.cumsum(self.w), u), n - 1)
        self.p = self.p[idx] + self.rng.standard_normal((n, 3)) * np.asarray(self.spec.roughen)
        self.w = np.full(n, 1.0 / n)
        self.resamples += 1

    @property
    def pose(self) -> np.ndarray:
        w = self.w
        th = math.atan2(float(w @ np.sin(self.p[:, 2])), float(w @ np.cos(self.p[:, 2])))
        return np.array([float(w @ self.p[:, 0]), float(w @ self.p[:, 1]), th])


# --- all three on the seated robot ---------------------------------------------------------------


def planar(pos, xmat) -> np.ndarray:
    """(x, y, yaw) of a frame: its position and the heading of its x axis."""
    r = np.asarray(xmat).reshape(3, 3)
    return np.array([pos[0], pos[1], math.atan2(r[1, 0], r[0, 0])])


class Localiser:
    """Wheel odometry, visual odometry and MCL on ``body`` against ``cmap``, from the known ``start``.
    :meth:`update` (once per planner step) reads the crank and handle by FK, the camera, and the head's
    depth rays, and returns the MCL pose; ``history`` keeps (t, truth, wheel, visual, mcl) per call.
    ``truth`` (the simulator's vehicle pose) is for evaluation only."""

    def __init__(self, body, cmap: Costmap, start, spec: LocalisationSpec = LOCALISATION, seed: int = 0,
                 sensor: DepthSensor | None = None):
        rng = np.random.default_rng(seed)
        self.body, self.spec = body, spec
        self.crank, self.hands = CrankEstimate(body), riding_limbs(body, "hand")
        self.wheel = WheelOdometry(start)
        self.visual = VisualOdometry(start, spec, rng)
        self.pf = ParticleFilter(cmap, start, spec, rng)
        self.sensor = sensor or DepthSensor()
        self.fused = np.asarray(start, dtype=float)
        self.pose = self.pf.pose
        self.corrections = 0
        self.history: list[tuple] = []

    def vehicle(self) -> np.ndarray:
        d = self.body.data.body("tricycle")
        return planar(d.xpos, d.xmat)

    def scan_vehicle(self) -> np.ndarray:
        """The head's depth points (above the ground filter) in the vehicle frame (N, 3): the ranges
        placed by the camera's pose in the vehicle frame (FK)."""
        d = self.body.data.body("tricycle")
        return (self.body_points() - d.xpos) @ d.xmat.reshape(3, 3)

    def body_points(self) -> np.ndarray:
        return self.sensor.scan(self.body.model, self.body.data)

    def update(self, snapshot, points=None) -> np.ndarray:
        """One step: odometries, MCL prediction by their mean increment, correction by ``points`` (vehicle
        frame; scanned here when None)."""
        truth = self.vehicle()
        before = (self.wheel.pose, self.visual.pose)
        handle = estimate_handle_angle({k: h.point(snapshot) for k, h in self.hands.items()})
        wheel = self.wheel.step(self.crank(snapshot), handle)
        cam = self.body.data.site("head_camera")
        camera = planar(cam.xpos, cam.xmat)
        visual = self.visual.step(camera, relative(truth, camera))
        if len(self.history):
            d = (relative(before[0], wheel) + relative(before[1], visual)) / 2
            self.fused = compose(self.fused, d)
            self.pf.predict(d)
        self.corrections += self.pf.correct(self.scan_vehicle() if points is None else points)
        self.pose = self.pf.pose
        self.history.append((float(snapshot["t"]), truth, wheel.copy(), visual.copy(), self.pose.copy(),
                             self.fused.copy()))
        return self.pose
