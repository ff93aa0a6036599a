"""The ultrasonic sensing of the real TITAN-VIII (§1.4; seed §3.1-3.3, eqs. 3-6, Figs. 6-9), for a
sensor-in-the-loop ablation: the paper's simulation gives the network the *known* obstacle corners
(seed §4, §2.2 of the spec); here its 12 obstacle features (§2.3) can come from simulated sensors.

**Eqs. (3)-(6), corrected** (seed §3.3 "障害物認識"): a reading L_so of the forward or side sensor on
the foot tip of front leg i (i = 1, 2) gives the obstacle point, body frame, as

    x_ob = x_si + (l0 + l1 cos θ1i + l2 cos θ2i) cos θ0i + L_so u_x
    y_ob = y_si + (l0 + l1 cos θ1i + l2 cos θ2i) sin θ0i + L_so u_y

with the beam direction u = (-sin θ0i, cos θ0i) for the forward sensor (eqs. 3-4) and
u = (cos θ0i, sin θ0i) for the side sensor (eqs. 5-6). Two corrections (spec §1.4 notes, §7.2):

* the paper prints ``l2 sin θ2i``; the foot's horizontal reach in the kinematics, eq. (1), is
  ``l2 cos θ2i`` (θ2 absolute from horizontal), so the printed term is a typo: with it, L_so = 0
  would not give the foot tip (:func:`obstacle_point` with L_so = 0 *is* eq. (1)'s foot);
* for the left front leg (θ01 ≈ 180°) the printed forward direction (-sin θ0, cos θ0) points
  backwards; it is mirrored, u = (sin θ0, -cos θ0), for leg 1. The side direction already points
  outwards for both legs.

**Beams** (:func:`cast`): each front foot's forward and side beams are rays in the ground plane from
the foot tip, ``BEAM_HEIGHT`` above the surface the foot stands on; only obstacles taller than the
beam stop it. The nearest obstacle surface along the ray is what the beam meets; it echoes if that
surface is within ``SENSOR_RANGE`` (0.5 m, seed §3.3) and the angle between the beam and the
surface normal is below the incidence limit (the paper only says "nearly perpendicular", §1.4;
``INCIDENCE_LIMIT_DEG`` is chosen). A beam meeting a surface too obliquely gives no echo and does
not see what lies behind it. Optional Gaussian range noise (seeded) is added to the reading.

**When** (:class:`SensedObstacles`): at the start of every walking cycle, when the robot stands on
four legs with the body still (§1.6: readings need the body still and level), each front leg
sweeps its shoulder yaw θ0 over ±``SWEEP_HALF_DEG`` about its stance value (Fig. 7), the foot on its
arc about the shoulder at its stance reach and just off its surface, and returns to its foothold.
Chosen simplifications: the sweep does not change the stance, the body is not shifted for it and the
three-leg stability of that moment is not checked (on the real robot it would fit into the leg's
swing). At every sweep step both beams are read; the joint angles are those of the swept foot (IK,
as the robot reads its potentiometers) and every echo becomes a point by eqs. (3)-(6).

**Height** (Fig. 8, :func:`height_estimate`): for every echo the leg is raised until the echo stops:
the beam is raised in steps of ``HEIGHT_STEP`` up to ``RAISE_MAX`` of foot lift, and the first beam
height without the echo (the first at or above the obstacle's top) is the height estimate; an echo
that persists to the top of the raise means "cannot be climbed" and the estimate is ``WALL_HEIGHT``
(constants). Chosen simplifications: the raise is evaluated for the obstacle that gave the echo (a
farther obstacle appearing over it is not mistaken for it), and it applies to either beam's echo.
The downward sensor (Fig. 9) is not modelled: footholds, swing heights and the body-raise rule stay
the executor's (robot.py), which uses the true geometry, as the real robot's downward sensor and
foot switches would.

**Features** (§2.3): detected points are kept per side in the world frame over the cycles, the
right obstacle's from leg 2's sensors and the left one's from leg 1's (seed §3.3, as the paper
assigns them; a beam of one leg meeting the other side's obstacle is not corrected). In the body
frame the features are the points' bounding box (x_max, x_min, y_max, y_min), z_max the largest
height estimate and z_min = 0, the floor (as ``episode.obstacle_features``). A side with no point
yet, or whose points are all behind the body centre (y_max < 0, the "passed" rule of
``obstacle_features``), gives the sentinels. Without noise every point lies on the boundary of an
obstacle of that side's leg's view, so the sensed box is inside the true one whenever the leg only
sees its own side's obstacle; the forward beams see the front edge (o2-o3, Fig. 14), so y_max in
particular stays short of the true back edge until a side beam sees an inner edge.

Everything is batched over a leading axis of E environments, like the rest of the package.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import world as W
from shintai.quadruped.episode import SENTINELS, obstacle_features

FORWARD, SIDE = 0, 1  # beams
FRONT_LEGS = np.array([0, 1])  # package indices of the paper's legs 1 (LF) and 2 (RF)
SIDE_OF_LEG = np.array([1, 0])  # leg 1 (index 0) sees the left obstacle (feature side 1), leg 2 the right (0)
SWEEP = np.radians(np.arange(-C.SWEEP_HALF_DEG, C.SWEEP_HALF_DEG + 1e-9, C.SWEEP_STEP_DEG))  # yaw offsets δ


# --- Eqs. (3)-(6) -------------------------------------------------------------------------------------

def beam_direction(theta0: np.ndarray, leg, beam) -> np.ndarray:
    """Unit beam directions ``(..., 2)`` in the body frame of front leg ``leg`` (0 = leg 1 LF, 1 = leg 2
    RF) at shoulder yaw θ0 [rad]: forward (-sin θ0, cos θ0) of eqs. (3)-(4), mirrored for leg 1
    (module docstring); side (cos θ0, sin θ0) of eqs. (5)-(6). ``leg`` and ``beam`` broadcast."""
    leg, beam = np.asarray(leg), np.asarray(beam)
    if not np.all(np.isin(leg, FRONT_LEGS)):
        raise ValueError(f"ultrasonic sensors are on the front legs only (indices 0, 1), got {leg.tolist()}")
    theta0 = np.asarray(theta0, dtype=float)
    c, s = np.cos(theta0), np.sin(theta0)
    mirror = np.where(leg == 0, -1.0, 1.0)
    forward = np.stack([-mirror * s, mirror * c], axis=-1)
    side = np.stack([c, s], axis=-1)
    return np.where((beam == FORWARD)[..., None], forward, side)


def obstacle_point(theta: np.ndarray, l_so: np.ndarray, leg, beam) -> np.ndarray:
    """Eqs. (3)-(6) corrected: the obstacle point ``(..., 2)`` (body frame, origin at the body centre)
    of a reading ``l_so`` [m] of the forward or side sensor of front leg ``leg`` with joint angles
    ``theta (..., 3)`` = (θ0, θ1, θ2) [rad] (θ2 absolute, as robot.fk). With ``l_so = 0`` it is the
    foot tip's (x, y) of eq. (1)."""
    t0, t1, t2 = np.moveaxis(np.asarray(theta, dtype=float), -1, 0)
    leg = np.asarray(leg)
    reach = C.L0 + C.L1 * np.cos(t1) + C.L2 * np.cos(t2)  # the paper prints l2 sin θ2 (typo)
    radial = np.stack([np.cos(t0), np.sin(t0)], axis=-1)
    return (R.SHOULDER_XY[leg] + reach[..., None] * radial
            + np.asarray(l_so, dtype=float)[..., None] * beam_direction(t0, leg, beam))


# --- Beams ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Echoes:
    """What a batch of beams returns: ``distance`` [m] (NaN: no echo), ``obstacle`` the index of the
    obstacle that echoed (-1: none), ``incidence`` [rad] the angle between the beam and the normal of
    the nearest surface it meets (NaN: it meets none)."""

    distance: np.ndarray
    obstacle: np.ndarray
    incidence: np.ndarray


def cast(origin: np.ndarray, direction: np.ndarray, beam_z: np.ndarray, polygons: np.ndarray,
         heights: np.ndarray, incidence_limit: float = np.radians(C.INCIDENCE_LIMIT_DEG),
         max_range: float = C.SENSOR_RANGE) -> Echoes:
    """Horizontal beams from ``origin (..., 2)`` along unit ``direction (..., 2)`` at height ``beam_z
    (...)`` against obstacles ``polygons (..., M, V, 2)`` (counter-clockwise) of ``heights (..., M)``;
    the leading axes broadcast. The entry point into a convex polygon is found by Cyrus-Beck clipping
    (as ``world.segment_hits``, with the entering edge kept for its normal); obstacles not taller than
    the beam and those containing the origin do not stop it."""
    if polygons.shape[-3] == 0:  # no obstacles: no echo
        shape = np.broadcast_shapes(origin.shape[:-1], direction.shape[:-1], np.shape(beam_z))
        return Echoes(np.full(shape, np.nan), np.full(shape, -1), np.full(shape, np.nan))
    v, n = W.edges(polygons)
    o, d = origin[..., None, None, :], direction[..., None, None, :]
    num = W.dot(n, v - o)  # >= 0: origin inside the edge's half-plane
    den = W.dot(n, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = num / den
    entering = np.where(den < 0, ratio, -np.inf)
    edge = np.argmax(entering, axis=-1)
    t_in = np.max(entering, axis=-1)
    t_out = np.min(np.where(den > 0, ratio, np.inf), axis=-1)
    outside = np.any(num < 0, axis=-1)
    parallel_out = np.any((den == 0) & (num < 0), axis=-1)
    blocks = heights > np.asarray(beam_z)[..., None]
    met = outside & ~parallel_out & (t_in >= 0) & (t_in <= t_out) & blocks  # (..., M)
    t = np.where(met, t_in, np.inf)
    nearest = np.argmin(t, axis=-1)[..., None]
    dist = np.take_along_axis(t, nearest, axis=-1)[..., 0]
    cos_in = -np.take_along_axis(np.take_along_axis(den, edge[..., None], axis=-1)[..., 0], nearest, axis=-1)[..., 0]
    incidence = np.where(np.isfinite(dist), np.arccos(np.clip(cos_in, -1.0, 1.0)), np.nan)
    echo = np.isfinite(dist) & (dist <= max_range) & (incidence <= incidence_limit)
    return Echoes(np.where(echo, dist, np.nan), np.where(echo, nearest[..., 0], -1), incidence)


def height_estimate(top: np.ndarray, surface: np.ndarray) -> np.ndarray:
    """Fig. 8: the height estimate [m] of an echoing obstacle with top ``top`` [m] seen from a foot on
    a surface at ``surface`` [m]: the beam rises from ``surface + BEAM_HEIGHT`` in steps of
    ``HEIGHT_STEP``; the first beam height at or above the top (no echo) is the estimate (error in
    [0, HEIGHT_STEP)); ``WALL_HEIGHT`` if the beam still echoes after ``RAISE_MAX`` of lift."""
    base = np.asarray(surface, dtype=float) + C.BEAM_HEIGHT
    steps = np.maximum(np.ceil((np.asarray(top, dtype=float) - base) / C.HEIGHT_STEP - 1e-9), 0.0)
    estimate = base + steps * C.HEIGHT_STEP
    return np.where(steps * C.HEIGHT_STEP <= C.RAISE_MAX + 1e-9, estimate, C.WALL_HEIGHT)


# --- One sensing phase ----------------------------------------------------------------------------------

@dataclass(frozen=True)
class Readings:
    """One sensing phase of E robots, ``(E, 2 sides, S sweep steps, 2 beams)`` per reading (side 0 =
    right = leg 2's sensors, 1 = left = leg 1's): ``points (..., 2)`` world [m] (NaN: no echo),
    ``tops`` the height estimates [m], ``obstacle`` the obstacle that echoed (-1: none), ``origins
    (..., 2)`` the sensor positions (world)."""

    points: np.ndarray
    tops: np.ndarray
    obstacle: np.ndarray
    origins: np.ndarray


def sense(state: R.CrawlState, envs: W.EnvBatch, incidence_limit: float = np.radians(C.INCIDENCE_LIMIT_DEG),
          noise_std: float = 0.0, rng: np.random.Generator | None = None) -> Readings:
    """The sweep of both front legs at a four-leg-support phase (module docstring) in every
    environment: ``state`` holds the feet (world) and the body pose and height."""
    n = len(state.pose)
    legs = FRONT_LEGS[:, None]  # (2, 1) against the sweep axis
    shoulder = R.SHOULDER_XY[FRONT_LEGS]
    foot = R.to_body(state.pose, state.feet[:, FRONT_LEGS, :2])  # (E, 2, 2)
    surface = state.feet[:, FRONT_LEGS, 2]
    foot3 = np.concatenate([foot, (surface - state.zr[:, None])[..., None]], axis=-1)
    theta, _ = R.leg_angles(foot3, np.concatenate([shoulder, np.full((2, 1), C.SHOULDER_DZ)], axis=1), FRONT_LEGS)
    theta0 = R.wrap_theta0(theta[..., None, 0] + SWEEP, legs)  # (E, 2, S)
    theta0 = np.clip(theta0, R.THETA0_LIMITS[legs, 0], R.THETA0_LIMITS[legs, 1])
    swept = np.concatenate([theta0[..., None], np.broadcast_to(theta[:, :, None, 1:], theta0.shape + (2,))], -1)
    swept = np.repeat(swept[..., None, :], 2, axis=-2)  # (E, 2, S, 2 beams, 3)
    leg, beam = FRONT_LEGS[:, None, None], np.array([FORWARD, SIDE])
    origin = obstacle_point(swept, 0.0, leg, beam)
    direction = beam_direction(swept[..., 0], leg, beam)
    pose = state.pose[:, None, None, None]
    origin_world = R.to_world(state.pose, origin)
    echo = cast(origin_world, R.rotate(pose[..., 2], direction),
                (surface + C.BEAM_HEIGHT)[:, :, None, None], envs.polygons[:, None, None, None],
                envs.heights[:, None, None, None], incidence_limit)
    reading = echo.distance
    if noise_std > 0:
        rng = np.random.default_rng() if rng is None else rng
        reading = np.maximum(reading + rng.normal(0.0, noise_std, reading.shape), 0.0)
    points = R.to_world(state.pose, obstacle_point(swept, np.nan_to_num(reading), leg, beam))
    hit = echo.obstacle >= 0
    heights = np.concatenate([envs.heights, np.zeros((n, 1))], axis=1)  # index -1: no obstacle
    top = np.take_along_axis(heights, echo.obstacle.reshape(n, -1), axis=1).reshape(hit.shape)
    tops = np.where(hit, height_estimate(top, surface[:, :, None, None]), np.nan)
    side = SIDE_OF_LEG.argsort()  # reorder the leg axis into the side axis
    return Readings(np.where(hit[..., None], points, np.nan)[:, side], tops[:, side], echo.obstacle[:, side],
                    origin_world[:, side])


def box_features(pose: np.ndarray, points: np.ndarray, tops: np.ndarray) -> np.ndarray:
    """§2.3 features ``(E, 2, 6)`` from detected points ``(E, 2 sides, P, 2)`` (world, NaN = none) and
    their height estimates ``(E, 2, P)``: the points' bounding box in the body frame of ``pose``,
    z_max the largest estimate, z_min = 0; the sentinels for a side without points or whose points
    are all behind the body centre (as ``episode.obstacle_features``)."""
    if points.shape[2] == 0:
        return np.broadcast_to(SENTINELS, (len(pose), 2, 6)).copy()
    body = R.to_body(pose, points.reshape(len(pose), -1, 2)).reshape(points.shape)
    x, y = body[..., 0], body[..., 1]
    hi, lo = np.fmax.reduce, np.fmin.reduce
    feats = np.stack([hi(x, axis=-1), lo(x, axis=-1), hi(y, axis=-1), lo(y, axis=-1), hi(tops, axis=-1),
                      np.zeros(x.shape[:2])], axis=-1)
    seen = np.any(np.isfinite(x), axis=-1)
    return np.where((~seen | ~(feats[..., 2] >= 0))[..., None], SENTINELS, feats)


# --- The perception state of a rollout ---------------------------------------------------------------------

@dataclass
class SensedObstacles:
    """Sensor-in-the-loop perception for ``episode.rollout(..., perception=...)``: at every cycle
    it senses (:func:`sense`) in the active environments, adds the points to each environment's
    history and returns the features of the points gathered so far (:func:`box_features`).

    After a rollout, ``points``/``tops``/``obstacle``/``cycle`` hold every reading ``(E, 2, P)`` (P =
    calls x sweep steps x 2 beams; NaN / -1 where there was no echo or the environment was not active)
    and ``known``/``sensed`` ``(E, K, 2, 6)`` the known (``episode.obstacle_features``) and sensed
    features each cycle k = 0..K-1 was given (NaN after the walk stopped)."""

    noise_std: float = 0.0
    incidence_deg: float = C.INCIDENCE_LIMIT_DEG
    seed: int | None = 0
    rng: np.random.Generator = field(init=False, repr=False)
    points: np.ndarray = field(init=False, repr=False)
    tops: np.ndarray = field(init=False, repr=False)
    obstacle: np.ndarray = field(init=False, repr=False)
    cycle: np.ndarray = field(init=False, repr=False)
    _calls: int = field(default=0, init=False, repr=False)
    _log: list = field(default_factory=list, init=False, repr=False)
    _n: int = field(default=0, init=False, repr=False)

    def __post_init__(self):
        if self.noise_std < 0 or not 0 <= self.incidence_deg <= 90:
            raise ValueError(f"SensedObstacles: noise_std >= 0 and incidence_deg in [0, 90], got "
                             f"{self.noise_std}, {self.incidence_deg}")
        self.reset(W.EnvBatch.flat(0))

    def reset(self, envs: W.EnvBatch) -> None:
        """Forget every reading; a rollout over ``envs`` starts (and the noise restarts from the seed)."""
        n = len(envs)
        self.rng = np.random.default_rng(self.seed)
        self.points, self.tops = np.zeros((n, 2, 0, 2)), np.zeros((n, 2, 0))
        self.obstacle, self.cycle = np.zeros((n, 2, 0), dtype=int), np.zeros((n, 2, 0), dtype=int)
        self._calls, self._log, self._n = 0, [], n

    def __call__(self, k: int, rows: np.ndarray, state: R.CrawlState, envs: W.EnvBatch) -> np.ndarray:
        r = sense(state, envs, np.radians(self.incidence_deg), self.noise_std, self.rng)
        s = r.tops.shape[2] * r.tops.shape[3]
        block = {"points": np.full((self._n, 2, s, 2), np.nan), "tops": np.full((self._n, 2, s), np.nan),
                 "obstacle": np.full((self._n, 2, s), -1), "cycle": np.full((self._n, 2, s), -1)}
        block["points"][rows] = r.points.reshape(len(rows), 2, s, 2)
        block["tops"][rows] = r.tops.reshape(len(rows), 2, s)
        block["obstacle"][rows] = r.obstacle.reshape(len(rows), 2, s)
        block["cycle"][rows] = k
        for key, values in block.items():  # every reading so far, (E, 2, P)
            setattr(self, key, np.concatenate([getattr(self, key), values], axis=2))
        self._calls += 1
        sensed = box_features(state.pose, self.points[rows], self.tops[rows])
        self._log.append((k, rows, obstacle_features(state.pose, envs), sensed))
        return sensed

    @property
    def beam(self) -> np.ndarray:
        """Beam of every reading ``(E, 2, P)`` (FORWARD / SIDE), in the order of ``points``."""
        per_call = np.tile([FORWARD, SIDE], len(SWEEP))
        return np.broadcast_to(np.tile(per_call, self._calls), (self._n, 2, len(per_call) * self._calls))

    def _history(self, index: int) -> np.ndarray:
        out = np.full((self._n, max((k for k, *_ in self._log), default=-1) + 1, 2, 6), np.nan)
        for k, rows, *features in self._log:
            out[rows, k] = features[index]
        return out

    known = property(lambda self: self._history(0))
    sensed = property(lambda self: self._history(1))
