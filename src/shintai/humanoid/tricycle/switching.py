"""Switching the search indices between two manipulators (seed 000 §3.4.4, Eq. 3.19, Fig. 3.14; role
tables of §3.5.2).

Motion measurement, method (a) of §3.4.4 (there is no sensor on the tricycle): the handle and crank
angles come from the robot's own forward kinematics of its hand and foot points. The thesis gives no
algorithm (spec §6 item 10); ours is the least-squares angle of one rotation about the known axis
that carries the points' θ = 0 directions onto the measured points (:func:`fit_angle`).

Switching rule, Eq. 3.19: θ_*^SW = θ_*^init + kπ, θ_h^init = 0, θ_c^init = π/2 + δ_c. When the
measured angle passes a switching angle the two limbs exchange the offline (active) and online
(passive) index. Roles (§3.5.2): arms — left active on −Θ_H ≤ θ_h ≤ 0, right on 0 ≤ θ_h ≤ Θ_H; legs —
right active on π/2 + δ_c ≤ θ_c < 3π/2 + δ_c (mod 2π), left otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from numba import njit

from shintai.core.geometry import wrap_pi
from shintai.humanoid.constants import TRICYCLE, TricycleSpec
from shintai.humanoid.tricycle.active import PEDAL_PHASE_OFFSET, v
from shintai.humanoid.tricycle.vehicle import grip_position, steer_axis, steer_point

Y_AXIS = np.array([0.0, 1.0, 0.0])
Y_AXIS.setflags(write=False)  # read-only: crank_zero caches it by identity


def fit_angle(points: Sequence, zero_dirs: Sequence, axis_point, axis_dir) -> float:
    """Method (a): the rotation angle θ about the axis (``axis_point``, ``axis_dir``) that best maps the
    θ = 0 directions ``zero_dirs`` onto the measured ``points`` (least squares, in (−π, π]).

    With w_k the measured point and z_k the θ = 0 direction, both projected on the plane normal to the
    unit axis a, Σ‖w_k − R(θ) z_k‖² is smallest at θ = atan2(Σ a·(z_k × w_k), Σ z_k·w_k). The radius
    drops out, so a contact point off the pedal axle along the crank arm does not bias θ.
    """
    a = np.asarray(axis_dir, dtype=float)
    a = a / np.linalg.norm(a)
    zs = [_on_plane(np.asarray(z, dtype=float), a) for z in zero_dirs]
    if len(zs) != len(points):
        raise ValueError(f"fit_angle: {len(points)} points but {len(zs)} zero directions")
    return _fit(points, zs, np.asarray(axis_point, dtype=float), a)


def _on_plane(z: np.ndarray, a: np.ndarray) -> np.ndarray:
    return z - a * (a @ z)


def _fit(points: Sequence, zs: Sequence, axis_point: np.ndarray, a: np.ndarray) -> float:
    """:func:`fit_angle` with the unit axis ``a`` and the projected θ = 0 directions ``zs`` given
    (constant per model: the per-tick estimates take them from a cache).

    On Python floats: the NumPy form it replaced bit for bit where the BLAS sums a 3-vector ``ddot`` left to right
    (OpenBLAS's Haswell and Zen kernels; its SkylakeX ones, an AVX-512 machine's default, differ in the last bit:
    tests/blas.py, ``test_laws``), and the same on every BLAS; the angle stays ``np.arctan2``, whose last bits differ
    from ``math.atan2``'s."""
    num = den = 0.0
    a0, a1, a2 = a.tolist()
    c0, c1, c2 = axis_point.tolist()
    for p, z in zip(points, zs):
        p0, p1, p2 = p.tolist() if isinstance(p, np.ndarray) else (float(x) for x in p)
        w0, w1, w2 = p0 - c0, p1 - c1, p2 - c2
        s = a0 * w0 + a1 * w1 + a2 * w2
        w0, w1, w2 = w0 - a0 * s, w1 - a1 * s, w2 - a2 * s  # on the plane normal to the axis: w − a (a·w)
        z0, z1, z2 = z.tolist()
        num += a0 * (z1 * w2 - z2 * w1) + a1 * (z2 * w0 - z0 * w2) + a2 * (z0 * w1 - z1 * w0)  # a·(z × w)
        den += z0 * w0 + z1 * w1 + z2 * w2
    return fit_angle_of(num, den)


def fit_angle_of(num: float, den: float) -> float:
    """The fit's angle atan2(Σ a·(z × w), Σ z·w) from its two sums (:func:`_fit`, :func:`axle_fit_terms`)."""
    if num == 0.0 and den == 0.0:
        raise ValueError("fit_angle: the points lie on the axis; the angle is undefined")
    return float(np.arctan2(num, den))


@njit(cache=True)
def axle_fit_terms(p, r, site_xpos, site_xmat, sites, h, centre, a, zs):
    """:func:`_fit`'s two sums (Σ a·(z × w), Σ z·w) for the pedal-axle points of the sole sites ``sites``, compiled:
    each site's point in the vehicle frame (p, r: its pose in the world) less ``h`` along the sole normal (the site's
    z axis, turned into the vehicle frame), then the fit about the unit axis ``a`` through ``centre`` with the θ = 0
    directions ``zs`` (one row per site) — the per-tick crank estimate of
    :class:`~shintai.humanoid.tricycle.rig.FeetCrankAngle`. The same IEEE operations in the same order as
    ``rig.pedal_axles`` then :func:`_fit` on Python floats (no fused multiply-adds): their bits where the BLAS sums
    ``r.T.dot(v)`` and a 3-vector ``ddot`` left to right, as :func:`_fit` says (``test_rig``)."""
    num = 0.0
    den = 0.0
    a0, a1, a2 = a[0], a[1], a[2]
    for k in range(len(sites)):
        s = sites[k]
        w0, w1, w2 = site_xpos[s, 0] - p[0], site_xpos[s, 1] - p[1], site_xpos[s, 2] - p[2]
        m0, m1, m2 = site_xmat[s, 2], site_xmat[s, 5], site_xmat[s, 8]  # the sole normal, world
        x0 = (r[0, 0] * w0 + r[1, 0] * w1 + r[2, 0] * w2) - h * (r[0, 0] * m0 + r[1, 0] * m1 + r[2, 0] * m2)
        x1 = (r[0, 1] * w0 + r[1, 1] * w1 + r[2, 1] * w2) - h * (r[0, 1] * m0 + r[1, 1] * m1 + r[2, 1] * m2)
        x2 = (r[0, 2] * w0 + r[1, 2] * w1 + r[2, 2] * w2) - h * (r[0, 2] * m0 + r[1, 2] * m1 + r[2, 2] * m2)
        w0, w1, w2 = x0 - centre[0], x1 - centre[1], x2 - centre[2]
        sa = a0 * w0 + a1 * w1 + a2 * w2
        w0, w1, w2 = w0 - a0 * sa, w1 - a1 * sa, w2 - a2 * sa
        z0, z1, z2 = zs[k, 0], zs[k, 1], zs[k, 2]
        num += a0 * (z1 * w2 - z2 * w1) + a1 * (z2 * w0 - z0 * w2) + a2 * (z0 * w1 - z1 * w0)
        den += z0 * w0 + z1 * w1 + z2 * w2
    return num, den


_CRANK_ZERO: dict = {}  # (leg, axis bytes) -> (unit axis, projected θ_c = 0 direction)


def crank_zero(leg: str, axis_dir) -> tuple[np.ndarray, np.ndarray]:
    # the default axis (every per-tick estimate) by identity, any other by its bits
    key = (leg, None if axis_dir is Y_AXIS else np.asarray(axis_dir, dtype=float).tobytes())
    hit = _CRANK_ZERO.get(key)
    if hit is None:
        a = np.asarray(axis_dir, dtype=float)
        a = a / np.linalg.norm(a)
        hit = _CRANK_ZERO[key] = (a, _on_plane(v(PEDAL_PHASE_OFFSET[leg]), a))
    return hit


def estimate_crank_angle(feet: dict, crank_centre, axis_dir=Y_AXIS) -> float:
    """θ_c ∈ [0, 2π) from the foot points on the pedals (``{"left": p, "right": p}`` or one of them).

    At θ_c = 0 the left pedal points forward (φ = π/2) and the right one backward (module
    :mod:`shintai.humanoid.tricycle.active`); θ_c turns about +y.
    """
    zero = [crank_zero(leg, axis_dir) for leg in feet]
    if not zero:
        raise ValueError("estimate_crank_angle: no foot points")
    angle = _fit(list(feet.values()), [z for _, z in zero], np.asarray(crank_centre, dtype=float), zero[0][0])
    return angle % (2 * math.pi)  # = float(np.mod(angle, 2π)): Python's float % is NumPy's floored modulo


def estimate_handle_angle(hands: dict, t: TricycleSpec = TRICYCLE) -> float:
    """θ_h from the hand points on the grips (``{"left": p, "right": p}`` or one of them), in the
    vehicle frame, about the steering axis of the tricycle's nominal model."""
    axis_point, zero, axis = _handle_model(t)
    return _fit(list(hands.values()), [zero[side[0]] for side in hands], axis_point, axis)


_HANDLE_MODELS: dict = {}  # id(spec) -> (spec, its handle model), the last 8 specs (as the lru_cache was)


def _handle_model(t: TricycleSpec) -> tuple[np.ndarray, dict, np.ndarray]:
    """The nominal steering axis point, each grip's θ_h = 0 direction from it projected on the plane
    normal to the axis, and the unit axis (constant: computed once per tricycle model, found by the spec's
    identity — :func:`estimate_handle_angle` runs several times a control tick, and hashing the spec cost more)."""
    hit = _HANDLE_MODELS.get(id(t))
    if hit is None or hit[0] is not t:
        if len(_HANDLE_MODELS) >= 8:
            _HANDLE_MODELS.pop(next(iter(_HANDLE_MODELS)))
        axis_point = steer_point(t)
        a = steer_axis(t)
        a = a / np.linalg.norm(a)
        hit = _HANDLE_MODELS[id(t)] = (t, (axis_point, {s: _on_plane(grip_position(0.0, s, t) - axis_point, a)
                                                        for s in ("l", "r")}, a))
    return hit[1]


def switching_angles(theta_init: float, lo: float, hi: float) -> np.ndarray:
    """Eq. 3.19: the switching angles θ^init + kπ, k ∈ Z, that lie in [lo, hi)."""
    k = np.arange(np.ceil((lo - theta_init) / np.pi), np.ceil((hi - theta_init) / np.pi))
    return theta_init + k * np.pi


def active_leg(theta_c: float, delta_c: float) -> str:
    """The stepping (active) leg at general crank angle θ_c (§3.5.2 role table)."""
    phase = float(theta_c) % (2 * math.pi)  # = np.mod(θ_c, 2π) (the floored modulo), on a Python float
    return "right" if np.pi / 2 + delta_c <= phase < 3 * np.pi / 2 + delta_c else "left"


def active_arm(theta_h: float, heading: float = 0.0) -> str:
    """The active arm at handle angle θ_h (§3.5.2): left on −Θ_H ≤ θ_h < 0, right on 0 < θ_h ≤ Θ_H.
    At θ_h = θ_h^init = 0, where the table gives both, the arm of the side the handle is heading to
    (the sign of ``heading``; left if it is 0 too — our choice)."""
    side = theta_h if theta_h != 0 else heading
    return "right" if side > 0 else "left"


class SwitchingDiagnostic:
    """Fig. 3.14 for one limb pair: measure the angle by method (a) and tell when the roles swap.

    ``estimate(snapshot) -> angle`` is the method-(a) estimate, unwrapped here (θ_c is unbounded,
    Eq. 3.3) into ``angle``. ``role_of(angle) -> side`` is the role table, whose changes are the
    switching angles of Eq. 3.19. :meth:`guard_to` makes the guard of a role
    :class:`~shintai.core.runtime.Switcher` transition: it holds once the table gives the new side
    on both sides of a band of ±``hysteresis`` around the measured angle — a band we add so that
    estimation noise at a switching angle cannot make the roles chatter (the thesis is silent on it).
    Switches are kept in ``log`` as (t, unwrapped angle, new active side).
    """

    def __init__(self, estimate: Callable[[dict], float], role_of: Callable[[float], str], hysteresis: float):
        self.estimate = estimate
        self.role_of = role_of
        self.hysteresis = hysteresis
        self.angle: float | None = None
        self.log: list[tuple[float, float, str]] = []

    def measure(self, snapshot) -> float:
        measured = self.estimate(snapshot)
        self.angle = measured if self.angle is None else self.angle + wrap_pi(measured - self.angle)
        return self.angle

    def guard_to(self, side: str) -> Callable[[dict], bool]:
        def guard(snapshot) -> bool:
            angle = self.measure(snapshot)
            h = self.hysteresis
            swap = self.role_of(angle - h) == side == self.role_of(angle + h)
            if swap:
                self.log.append((float(snapshot["t"]), angle, side))
            return swap

        return guard
