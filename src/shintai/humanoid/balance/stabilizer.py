"""The LIP-tracking stabilizer HRP2-JSK stands and steps with (seed 000 §5.2.2; Kajita et al. 2010 [55]).

The thesis runs hrpsys-base's Stabilizer, "the balance stabilization of Kajita et al. [55]" (§5.2.2,
footnote 1), and names two of its foot layers, "Foot torque control" (Eqs. 5.1–5.3, the one SLC learns)
and "Foot force difference control"; the rest of the stack is [55]'s (Kajita, Morisawa, Miura, Nakaoka,
Harada, Kaneko, Kanehiro, Yokoi, "Biped walking stabilization based on linear inverted pendulum
tracking", IROS 2010). One control period (4 ms) here:

1. **LIP tracking** ([55] Eq. 26, hrpsys ``Stabilizer`` EEFM): with the CoM x, its velocity ẋ and the
   measured ZMP p against their references (per horizontal axis)::

       p_d = p_ref + k1 (x_ref − x) + k2 (ẋ_ref − ẋ) + k3 (p_ref − p)

   k1, k2, k3 (:data:`LIP_K`) are hrpsys-base's defaults for HRP-2 (pole placement in [55] on the LIP
   ẍ = ω² (x − p) with the ZMP following p_d with the delay ṗ = (p_d − p)/T_p, T_p = 0.04 s); the
   poles they give our model are :func:`closed_loop_poles` (tested stable).
2. **ZMP distributor** ([55] §IV, as hrpsys ``ZMPDistributor``'s default): the point p_α of the segment
   between the two feet's points closest to p_d gives the ratio α = |p_α − a_R| / |a_L − a_R| (clipped to
   [0, 1]); the feet take f_L = α F, f_R = (1 − α) F of the weight F = M g, and the residual p_d − p_α
   as each foot's centre-of-pressure offset from its point a_j, i.e. the ankle torques τᵈ_j; the total
   reaction then has its ZMP at p_d. In single support everything is on the stance foot (α = 1 or 0).
3. **Foot torque damping** (Eqs. 5.1–5.3): :class:`~shintai.humanoid.balance.foot_damping.FootDampingModule` turns
   τᵈ − τ into the sole attitude corrections δ (roll, pitch) per foot — as §5.2.2 defines its terms: τ
   measured by the soles' 6-axis force sensors, τᵈ "from the ZMP distributor of [55]", δ the roll/pitch
   displacement of the foot frame's attitude R_R, R_L: δ turns the sole about the reference frame's x/y
   axes (the plans of :mod:`~shintai.humanoid.balance.standing` give the soles no yaw), and τ is read about the
   *actual* foot's roll/pitch axes (the world reading turned by the sole's yaw, :func:`into_yawed`), so that
   τ and δ share axes when the feet yaw — on the V-BOARD they turn with the scooter. In world axes a foot's
   pitch torque leaks into roll by sin ψ and its roll torque into pitch (tested); measured on level 2 of
   :mod:`~shintai.humanoid.vboard.ride` that leak was half of the yaw divergence (ω doubling every ≈1.5 s, a
   fall at 12 s; read in the foot frame ≈3 s).
4. **Foot force difference control** ([55] Eq. 18): :class:`~shintai.humanoid.balance.foot_damping.ForceDifferenceControl`
   turns Δfᵈ − Δf into sole heights ∓z_ctrl/2, in double support.
5. The corrected sole poses and the waist placed under the CoM reference → :func:`~shintai.humanoid.robots.leg_ik.legs_ik`
   → the leg servos' targets (:mod:`shintai.humanoid.balance.standing` wires the modules).

**Sign convention** (chosen, so that Eq. 5.1 as written is negative feedback): τ and f are what each
foot *exerts on the floor* (the negated reaction of :func:`~shintai.humanoid.robots.hrp2.ft_reaction`),
τ about the foot's point a_j (the sole site under the ankle), world x (roll) and y (pitch) axes; δ
rotates the sole about world x and y. Tipping the toe down (δ_pitch > 0) moves the pressure forward
and raises τ_pitch = f (q_x − a_x), so ∂τ/∂δ > 0 on both axes and δ̇ = (τᵈ − τ)/D converges; likewise
Δf = f_L − f_R of the exerted forces' z components (downward, −f_z: an overloaded left foot makes Δf
more negative) makes the existing ``(z_R, z_L) = (−z/2, +z/2)`` of :class:`ForceDifferenceControl` lift
the overloaded foot (with Δf of the magnitudes it pushes it down: measured, it falls in 1.5 s).

**Measured CoM** (chosen, the simulator's stand-in for hrpsys's IMU + joint-encoder FK): MuJoCo's
whole-body CoM of the last physics step (``subtree_com`` of the root); on a flat floor with the feet
flat this is what the IMU + FK estimate gives. Its velocity is the world finite difference over the
period, low-passed like hrpsys's (ẋ ← 0.9 ẋ + 0.1 Δx/Δt). Like hrpsys (its "foot_origin" frame), the
CoM and the measured ZMP are compared with their references *relative to the stance feet*: moved by
(mean reference stance sole point − mean actual one) and turned by −ψ, ψ the stance soles' mean yaw (the
references have none); the CoM velocity is turned by −ψ too. This is the only reading (hrpsys's
foot-origin frame; §5.2.2's δ and τ are the foot frame's): on a flat floor the feet keep their yaw and it
changes little; on the V-BOARD the feet yaw with the scooter — on level 2, and up to 70° during the
self-boarding's right swing, where the world-axes reading let SLC's run fall (vboard-boarding's notes). In world
coordinates a foot that lands 13 mm off its reference left a 23 mm CoM offset the LIP feedback kept fighting
(measured, three steps).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from shintai.core.constants import GRAVITY
from shintai.core.geometry import wrap_pi
from shintai.core.runtime import SET, Module, declare
from shintai.humanoid.balance.attitude import TiltEstimate
from shintai.humanoid.balance.foot_attitude import CONTACT_FZ
from shintai.humanoid.balance.foot_damping import ForceDifferenceControl
from shintai.humanoid.balance.stabilizer_tick import (COM, OUT_SIZE, READINGS, STATE_SIZE, foot_wrench_rows,
                                                        lip_tracking)
from shintai.humanoid.constants import ATTITUDE_TAU, COM_VEL_FILTER, CONTROL_PERIOD, HRP2_LINKS, LIP_K, ZMP_DELAY_T
from shintai.sim.body import MujocoBody

# --- constants ------------------------------------------------------------------------------------
SIDES = ("l", "r")
# support code on the loop's "support" channel (a number, so it can travel on a channel)
SUPPORT_CODE = {"lr": 0.0, "l": 1.0, "r": -1.0}
SUPPORT_NAME = {v: k for k, v in SUPPORT_CODE.items()}
_EYE3 = np.eye(3)  # no attitude error: the CoM readings other than "imu"
STANCE = {name: tuple(i for i, side in enumerate(SIDES) if side in name) for name in SUPPORT_CODE}  # the feet down

CHANNELS = {
    **declare("tau_d_L", "tau_d_R", "tau_L", "tau_R", "f_Lz", "f_Rz", "zmp_d", "zmp_act", "sole_dz", kind=SET),
}


def lip_feedback(zmp_ref, com_ref, com_vel_ref, com, com_vel, zmp, k=LIP_K):
    """[55] Eq. 26 (module docstring): the modified ZMP reference p_d (x, y)."""
    k1, k2, k3 = k
    zr, cr, vr, c, v, z = (np.asarray(a, float)[:2] for a in (zmp_ref, com_ref, com_vel_ref, com, com_vel, zmp))
    return zr + k1 * (cr - c) + k2 * (vr - v) + k3 * (zr - z)


def mean_yaw(yaws: list[float]) -> float:
    """The stance feet's mean yaw, taken about the first foot's so that +179° and −179° average to 180°, not 0°
    (the rule the tick's compiled frame, :func:`~shintai.humanoid.balance.stabilizer_tick.lip_tracking`, follows)."""
    first, turn = yaws[0], 0  # the first's own term is 0 (an int, as sum's start)
    for y in yaws[1:]:
        turn += wrap_pi(y - first)
    return first + turn / len(yaws)


def into_yawed(x: float, y: float, psi: float) -> tuple[float, float]:
    """A horizontal vector (x, y) of the world in a frame yawed by ψ: Rz(−ψ) (x, y). The stabilizer's
    foot-origin frame (module docstring): world readings into the frame of feet that have turned by ψ."""
    c, s = math.cos(psi), math.sin(psi)
    return c * x + s * y, -s * x + c * y


def error_system(k=LIP_K, zc: float = 0.82, tp: float = ZMP_DELAY_T, g: float = GRAVITY) -> tuple[np.ndarray, np.ndarray]:
    """[55]'s error system under Eq. 26, ė = A e + b c: e = (x − x_ref, ẋ − ẋ_ref, p − p_ref),
    ė₁ = e₂, ė₂ = ω² (e₁ − e₃), ė₃ = (−k1 e₁ − k2 e₂ − (1 + k3) e₃ + c) / T_p, ω² = g / z_c, where c is a
    correction added to the LIP tracking's output p^{d*} (seed 000 Eq. 7.2's p^{d**} = p^{d*} + u_traj).

    Its characteristic polynomial is s³ + (1 + k3)/T_p s² − ω² (1 + k2/T_p) s − ω² (1 + k1 + k3)/T_p, so by
    Routh–Hurwitz every stabilising gain set has 1 + k1 + k3 < 0; the equilibrium under a constant c is
    e₁ = e₃ = c/(1 + k1 + k3): a forward correction after the LIP tracking moves the mass centre back, for every
    stabilising gain set, not only hrpsys's (tests/humanoid/balance/test_stabilizer.py)."""
    if not (zc > 0 and tp > 0 and g > 0):
        raise ValueError(f"error_system: zc, tp and g must be > 0, got {zc!r}, {tp!r}, {g!r}")
    k1, k2, k3 = k
    w2 = g / zc
    a = np.array([[0.0, 1.0, 0.0], [w2, 0.0, -w2], [-k1 / tp, -k2 / tp, -(1.0 + k3) / tp]])
    return a, np.array([0.0, 0.0, 1.0 / tp])


def closed_loop_poles(k=LIP_K, zc: float = 0.82, tp: float = ZMP_DELAY_T, g: float = GRAVITY) -> np.ndarray:
    """Poles of [55]'s error system under Eq. 26 (:func:`error_system`)."""
    return np.linalg.eigvals(error_system(k, zc, tp, g)[0])


def support_polygon(soles, support: str, links=HRP2_LINKS) -> np.ndarray:
    """The convex hull (counter-clockwise (x, y) vertices) of the stance soles' rectangles, each sole's centre
    ``foot_forward`` ahead of and ``foot_outward`` outside its sole point; ``soles`` (left, right) sole points of
    the reference (which have no yaw)."""
    corners = []
    for i, side in enumerate(SIDES):
        if side in support:
            cx = soles[i][0] + links.foot_forward
            cy = soles[i][1] + (1.0 if side == "l" else -1.0) * links.foot_outward
            hx, hy = links.foot_length / 2, links.foot_width / 2
            corners += [(cx - hx, cy - hy), (cx + hx, cy - hy), (cx + hx, cy + hy), (cx - hx, cy + hy)]
    pts = sorted(set(corners))
    if len(pts) < 3:
        return np.array(pts, dtype=float)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []  # Andrew's monotone chain
    for chain, seq in ((lower, pts), (upper, reversed(pts))):
        for q in seq:
            while len(chain) >= 2 and cross(chain[-2], chain[-1], q) <= 0:
                chain.pop()
            chain.append(q)
    return np.array(lower[:-1] + upper[:-1], dtype=float)


def truncate_zmp(p, polygon: np.ndarray) -> np.ndarray:
    """``p`` if it lies in the convex ``polygon`` (counter-clockwise), else the polygon's nearest point to it: the
    ZMP truncation of hrpsys's Stabilizer (``use_zmp_truncation``), which [55]'s distributor presupposes (its
    centres of pressure are only reachable inside the soles)."""
    p = np.asarray(p, dtype=float)
    edges = np.roll(polygon, -1, axis=0) - polygon
    rel = p - polygon
    if np.all(edges[:, 0] * rel[:, 1] - edges[:, 1] * rel[:, 0] >= 0.0):
        return p.copy()
    t = np.clip(np.sum(rel * edges, axis=1) / np.sum(edges * edges, axis=1), 0.0, 1.0)
    nearest = polygon + t[:, None] * edges
    return nearest[np.argmin(np.sum((nearest - p) ** 2, axis=1))]


class Distribution(NamedTuple):
    """The distributor's output: ``alpha`` (left share), per side ``fz`` (N, exerted downward on the
    floor, so positive) and ``tau_d`` (roll, pitch) N·m exerted about the foot's point."""

    alpha: float
    fz: dict
    tau_d: dict


def distribute(zmp_d, points: dict, support: str, total_fz: float) -> Distribution:
    """The ZMP distributor of [55] §IV (module docstring, step 2). ``points``: side → the foot's (x, y)
    point a_j; ``support``: "lr", "l" or "r"; ``total_fz`` the weight to share (N)."""
    if support not in SUPPORT_CODE:
        raise ValueError(f"distribute: support is 'lr', 'l' or 'r', got {support!r}")
    if not (math.isfinite(total_fz) and total_fz >= 0):
        raise ValueError(f"distribute: total_fz must be a finite force ≥ 0 N, got {total_fz!r}")
    alpha, fz_l, fz_r, dx, dy = distribution(float(zmp_d[0]), float(zmp_d[1]), float(points["l"][0]),
                                             float(points["l"][1]), float(points["r"][0]), float(points["r"][1]),
                                             SUPPORT_CODE[support], float(total_fz))
    fz = {"l": fz_l, "r": fz_r}
    # exerted torque about a_j of a downward force f at q_j: (−d_y f, d_x f) (roll, pitch)
    tau_d = {s: np.array([-dy * f, dx * f]) for s, f in fz.items()}
    return Distribution(alpha, fz, tau_d)


@njit(cache=True)
def distribution(px, py, lx, ly, rx, ry, code, total_fz):
    """:func:`distribute`'s arithmetic, compiled (p_d = (px, py), a_L, a_R; ``code`` the support's
    :data:`SUPPORT_CODE`; unchecked, the stabilizer's 4 ms tick): (α, f_L, f_R, d_x, d_y), d = p_d − p_α each foot's
    pressure-centre offset from its point. The clip of α to [0, 1] is Python's ``min(1, max(0, ·))``, NaN to 0."""
    if code == 1.0:
        alpha = 1.0
    elif code == -1.0:
        alpha = 0.0
    else:
        ux, uy = lx - rx, ly - ry
        n2 = ux * ux + uy * uy
        if n2 > 0:
            a = ((px - rx) * ux + (py - ry) * uy) / n2
            a = a if a > 0.0 else 0.0
            alpha = a if a < 1.0 else 1.0
        else:
            alpha = 0.5
    ax, ay = rx + alpha * (lx - rx), ry + alpha * (ly - ry)  # p_α
    # each foot's pressure centre q_j = a_j + (p_d − p_α)
    return alpha, alpha * total_fz, (1.0 - alpha) * total_fz, px - ax, py - ay


class FootWrench(NamedTuple):
    """What a foot exerts on the floor, about its sole point: ``fz`` (N, + pushing down), ``tau``
    (roll, pitch) N·m; ``point`` the sole site (world) the torque is about."""

    fz: float
    tau: np.ndarray
    point: np.ndarray


class FootSensors:
    """Both feet's exerted wrenches (sign convention: module docstring) from the ankle F/T sensors: the
    quasi-static reaction of :func:`~shintai.humanoid.robots.hrp2.ft_reaction` (foot weight compensated),
    moved from the sensor site to the sole point, negated. Ids and masses are looked up once, MjData's arrays
    held as live views (as :class:`~shintai.sim.body.MujocoBody` holds its own) and the arithmetic is one compiled
    kernel (:func:`~shintai.humanoid.balance.stabilizer_tick.foot_wrench_rows`; it runs every 4 ms tick,
    ``ft_reaction`` costs ≈0.15 ms a foot)."""

    def __init__(self, body: MujocoBody):
        m, d = body.model, body.data
        self.body = body
        self.rows = {}
        for s in SIDES:
            site, sole = body.id("site", f"{s}_ankle_ft"), body.id("site", f"{s}_sole")
            link = int(m.site_bodyid[site])
            weight = (m.body_subtreemass[link] * m.opt.gravity).tolist()
            f_adr = int(m.sensor_adr[body.id("sensor", f"{s}_ankle_force")])
            t_adr = int(m.sensor_adr[body.id("sensor", f"{s}_ankle_torque")])
            self.rows[s] = (site, sole, link, weight, f_adr, t_adr)
        self._index = np.array([[site, sole, link, f_adr, t_adr] for site, sole, link, _, f_adr, t_adr in self.rows.values()],
                               dtype=np.int64)
        self._weights = np.array([row[3] for row in self.rows.values()])
        self._arrays = (d.sensordata, d.site_xmat, d.site_xpos, d.subtree_com)  # live views of MjData, formed once
        self.w = np.zeros((2, 7))

    def read_rows(self) -> np.ndarray:
        """Both feet's wrenches as rows (left, right) of (f_z, τ roll, τ pitch, sole point x, y, z, sole yaw), the yaw
        the angle of the sole's x axis projected on the floor (rad, world); the array is this reader's, rewritten at
        every read."""
        foot_wrench_rows(self.w, *self._arrays, self._index, self._weights)
        return self.w

    def read_floats(self) -> dict[str, tuple[float, ...]]:
        """:meth:`read_rows` on Python floats: side → its row."""
        return {s: tuple(row) for s, row in zip(SIDES, self.read_rows().tolist(), strict=True)}

    def read(self) -> dict[str, FootWrench]:
        """Both feet's :class:`FootWrench` (side → wrench)."""
        return {s: FootWrench(fz, np.array([tx, ty]), np.array([sx, sy, sz]))
                for s, (fz, tx, ty, sx, sy, sz, _) in self.read_floats().items()}


def foot_wrenches(body: MujocoBody, snapshot=None) -> dict[str, FootWrench]:
    """Both feet's exerted wrenches, about their sole points (:class:`FootSensors`; the body's current
    data, which is what a snapshot taken now holds)."""
    return FootSensors(body).read()


class StabilizerModule(Module):
    """Steps 1, 2 and 4 of the module docstring in the control loop; step 3 is the
    :class:`~shintai.humanoid.balance.foot_damping.FootDampingModule` of the next stage, which reads what this
    writes. Reads ``com_ref`` (x, y, z), ``zmp_ref`` (x, y), ``sole_ref`` (2 × 3: left, right sole
    points) and ``support`` (:data:`SUPPORT_CODE`); writes (:data:`CHANNELS`) ``tau_d_L/R``,
    ``tau_L/R`` (roll, pitch; a swinging foot gets 0 and 0, so its δ only decays by −δ/T), ``f_Lz``,
    ``f_Rz`` (the SLC's landing guards), ``zmp_d`` (p_d), ``zmp_act`` (measured ZMP, NaN in the air) and
    ``sole_dz`` (left, right height corrections of the force difference control).

    ``lip=False`` leaves p_d = p_ref (no LIP tracking); ``force_difference=False`` keeps the heights;
    ``truncate=True`` bounds p_d to the stance soles before the distributor (:func:`truncate_zmp`; off by default,
    as in hrpsys: the thesis is silent).

    ``com_reading``: ``"world"`` (default) MuJoCo's CoM against the true vertical (module docstring);
    ``"imu"`` the CoM's offset from the stance feet read through the chest IMU's attitude estimate
    (:class:`~shintai.humanoid.balance.attitude.TiltEstimate`, time constant ``attitude_tau``), as hrpsys's
    ``act_cog`` is (forward kinematics from the KalmanFilter's attitude, in the foot-origin frame), and its velocity
    the difference of that offset (hrpsys's ``act_cogvel``); under a sustained acceleration it balances about the
    apparent vertical (issue 26); ``"feet"`` the same offset against the true vertical and its difference (hrpsys's
    act_cogvel in the foot-origin frame without the attitude filter: the Σ_vehicle-relative CoM of §6.2.2's level 2).
    ``read_com`` keeps the (x, ẋ) the LIP tracking last used, in its frame.

    ``foot_origin``: ``"sole"`` (default) the frame's origin at the stance sole points; ``"ankle"`` at the ankle
    links' origins, as hrpsys's ``calcFootOriginCoords`` (the force sensor's link, ``foot_origin_offset`` 0), the
    reference ankles above the reference soles at the commanded pitch ``foot_pitch_ref``, and the distributor over the
    actual soles in that frame (issue 26: measured, it changes level 2 and the probe by < 25 %); ``ref_ankle_pitch``
    (R, L) keeps the reference ankles at that pitch's place (the commanded pitch as an ankle joint angle,
    :mod:`~shintai.humanoid.vboard.ankle_pivot`)."""

    def __init__(self, body: MujocoBody, lip: bool = True, k=LIP_K, force_difference: bool = True,
                 name: str = "stabilizer", period: float = CONTROL_PERIOD, truncate: bool = False,
                 com_reading: str = "world", attitude_tau: float = ATTITUDE_TAU, foot_origin: str = "sole",
                 ref_ankle_pitch=None):
        super().__init__(name, period)
        if com_reading not in ("world", "imu", "feet"):
            raise ValueError(f"stabilizer: com_reading is 'world', 'imu' or 'feet', got {com_reading!r}")
        if foot_origin not in ("sole", "ankle"):
            raise ValueError(f"stabilizer: foot_origin is 'sole' or 'ankle', got {foot_origin!r}")
        self.foot_origin = foot_origin
        if ref_ankle_pitch is not None and foot_origin != "ankle":
            raise ValueError("stabilizer: ref_ankle_pitch places the reference ankles; it needs foot_origin='ankle'")
        self.ref_ankle_pitch = None if ref_ankle_pitch is None else tuple(float(p) for p in ref_ankle_pitch)
        self.com_reading = com_reading
        self.tilt = TiltEstimate(attitude_tau, period) if com_reading == "imu" else None
        self.read_com = (math.nan, math.nan)
        self.truncate = bool(truncate)
        self.body, self.k, self.lip, self.use_force_difference = body, tuple(float(v) for v in k), lip, force_difference
        if len(self.k) != 3 or not all(math.isfinite(v) for v in self.k):
            raise ValueError(f"stabilizer: k is three finite gains (k1, k2, k3), got {k!r}")
        self.weight = float(body.model.body_subtreemass[body.id("body", "waist")] * GRAVITY)
        self._root = body.id("body", "waist")
        self.force_difference = ForceDifferenceControl(dt=period)
        self.sensors = FootSensors(body)
        self._com_now = body.data.subtree_com[self._root]  # the whole-body CoM, a live view of MjData
        # the LIP tracking's state between ticks (stabilizer_tick's slots: CoM, its velocity, the last reference, the
        # feet/imu reading's) and its outputs, both rewritten in place every tick
        self._state, self._out = np.zeros(STATE_SIZE), np.zeros(OUT_SIZE)
        self._reading = READINGS[com_reading]
        self._ankle_links = [self.sensors.rows[s][2] for s in SIDES]
        self._no_ankles = np.zeros((2, 2))

    def reset(self, snapshot) -> None:
        self._state[:] = 0.0
        self._state[COM:COM + 3] = self._com_now
        self.force_difference.z_ctrl = 0.0
        if self.tilt is not None:
            self.tilt.reset(snapshot)

    def _ref_ankle_dx(self, snapshot, stance) -> float:
        """The reference ankles' mean x offset from the reference sole points: h_a sin φ_ref, φ_ref the soles' pitch
        the leg IK is commanded without the damping's δ (``foot_pitch_ref``: R, L; 0 without it), or the fixed
        ``ref_ankle_pitch`` (R, L) when the commanded pitch turns the feet about their ankles
        (:mod:`~shintai.humanoid.vboard.ankle_pivot`)."""
        ref = self.ref_ankle_pitch or snapshot.get("foot_pitch_ref")
        if ref is None:
            return 0.0
        pitch = {"r": float(ref[0]), "l": float(ref[1])}
        h = HRP2_LINKS.ankle_height
        return sum(h * math.sin(pitch[SIDES[i]]) for i in stance) / len(stance)

    def update(self, snapshot):
        code = float(snapshot["support"])
        support = SUPPORT_NAME[code]
        err = self.tilt.update(snapshot) if self.tilt is not None else _EYE3
        w = self.sensors.read_rows()  # left, right: (f_z, τ roll, τ pitch, sole point x, y, z, sole yaw)
        ankle = self.foot_origin == "ankle"
        ankles, ankle_dx = self._no_ankles, 0.0
        if ankle:  # hrpsys's foot origin: the ankle links' origins (module docstring)
            ankles = self.body.data.xpos[self._ankle_links, :2]
            ankle_dx = self._ref_ankle_dx(snapshot, STANCE[support])
        # the CoM filter, the foot-origin frame (the actual CoM, ZMP and torques relative to the actual stance feet,
        # their mean point and mean yaw, re-expressed on the reference stance feet, which have no yaw: module
        # docstring), the measured ZMP and [55] Eq. 26, compiled (stabilizer_tick.lip_tracking)
        k1, k2, k3 = self.k
        soles = snapshot["sole_ref"]
        lip_tracking(self._out, self._state, w, self._com_now, snapshot["com_ref"], snapshot["zmp_ref"], soles, code,
                     k1, k2, k3, self.period, COM_VEL_FILTER, CONTACT_FZ, self.lip, self._reading, err, ankle, ankles, ankle_dx)
        pd_x, pd_y, act_x, act_y, cx, vx, c, s, ax, ay, rx, ry, tracked = self._out.tolist()
        if tracked:
            self.read_com = (cx, vx)
        if self.truncate:
            pd_x, pd_y = truncate_zmp(np.array([pd_x, pd_y]), support_polygon(soles, support)).tolist()
        rows = w.tolist()
        (lx, ly, _), (rx_, ry_, _) = soles.tolist()
        if ankle:  # hrpsys distributes over the actual soles, in the foot-origin frame
            (lx, ly), (rx_, ry_) = ((c * x + s * y + rx, -s * x + c * y + ry)  # Rz(−ψ)(p − a) + r
                                    for x, y in ((row[3] - ax, row[4] - ay) for row in rows))
        alpha, fz_l, fz_r, dx, dy = distribution(pd_x, pd_y, lx, ly, rx_, ry_, code, self.weight)
        feet = []  # per foot: τᵈ (roll, pitch), τ (roll, pitch); a swinging foot gets 0 and 0
        for side, fd, row in (("l", fz_l, rows[0]), ("r", fz_r, rows[1])):
            if side in support:
                # the distributor's τᵈ: a downward force f at q_j exerts (−d_y f, d_x f) (roll, pitch) about a_j; τ
                # about the foot's own roll and pitch axes, the axes δ turns it about
                feet += [-dy * fd, dx * fd, *into_yawed(row[1], row[2], row[6])]
            else:
                feet += [0.0, 0.0, 0.0, 0.0]
        dz_l = dz_r = 0.0
        if self.use_force_difference:
            # Δf of the exerted vertical forces (downward: −f_z), see the sign convention
            dz_r, dz_l = self.force_difference.step(fz_r - fz_l, rows[1][0] - rows[0][0], support == "lr")
        # the tick's outputs in one array, each channel a view of it (the Loop copies what it keeps)
        res = np.array([pd_x, pd_y, act_x, act_y, *feet, dz_l, dz_r])
        zmp_d, act = res[0:2], res[2:4]
        out = {"zmp_d": zmp_d, "zmp_act": act, "tau_d_L": res[4:6], "tau_L": res[6:8], "tau_d_R": res[8:10],
               "tau_R": res[10:12], "f_Lz": rows[0][0], "f_Rz": rows[1][0], "sole_dz": res[12:14]}
        if self.recorder is not None:
            self.log(snapshot["t"], **{f"{self.name}.zmp_d": zmp_d.copy(), f"{self.name}.zmp_act": act.copy(),
                                       f"{self.name}.com": self._state[COM:COM + 3].copy(), f"{self.name}.alpha": alpha})
        return out
