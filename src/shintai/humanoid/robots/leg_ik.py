"""Analytic 6-DoF inverse kinematics of the HRP2-JSK model's legs (issue 13 item 2).

The thesis uses HRP2's leg IK (the stabilizer of §5.2 / Kajita 2010 [55] and the AutoBalancer of
§5.4 [85] command sole poses every 4 ms) but gives no formula; this is the closed form for the
hip yaw–roll–pitch / knee pitch / ankle pitch–roll leg (Kajita et al., "Humanoid Robots", ch. 2,
analytic leg IK), written for the axes and offsets of :mod:`shintai.humanoid.robots.hrp2`:

* hip: yaw (z), roll (x), pitch (y) axes meet in one point, ``(0, ±hip_y, hip_z)`` in the waist
  frame (``Hrp2Links``; the model has no hip offset beyond this point, so the closed form is exact);
* thigh ``L1`` along −z of the hip-pitch body to the knee (pitch y), shank ``L2`` along −z to the
  ankle, whose pitch (y) and roll (x) axes meet; the sole site is ``ankle_height`` below the ankle
  along the foot's −z. Every body frame is unrotated at zero posture.

With ``R_f``, ``p_a`` the foot orientation and ankle point, ``H`` the hip point and
``r = R_fᵀ (H − p_a)`` (the hip seen from the ankle, foot frame)::

    knee        q4 = acos((|r|² − L1² − L2²) / (2 L1 L2))        ≥ 0 (flexion +, Table A.2 branch)
    ankle roll  q6 = atan2(r_y, r_z)                               (r_z < 0: the |q6| ≤ π/2 branch)
    ankle pitch q5 = atan2(−r_x, ±√(r_y² + r_z²)) − atan2(L1 sin q4, L2 + L1 cos q4)
    hip         R_wᵀ R_f Rx(−q6) Ry(−q4 − q5) = Rz(q1) Rx(q2) Ry(q3)  → q1, q2, q3 by atan2

A target beyond ``L1 + L2`` gets the stretched knee (q4 = 0) pointing at it: ``reachable`` False,
``reach_error`` the distance the ankle misses by. Joint limits (Table A.2, mirrored for the left
leg) are reported, not enforced: ``within_limits`` and ``violated``.

Used by the tricycle's feet (:meth:`shintai.humanoid.tricycle.hrp2_limbs.Hrp2Limb.solve`, ``kind == "foot"``,
which :mod:`~shintai.humanoid.tricycle.rig` and :mod:`~shintai.humanoid.tricycle.ride` reach through
``riding_limbs(body, "foot")``): the sole at ξ with ``SOLE_IN_VEHICLE``, solved in the waist frame; the
DLS IK only where :attr:`LegIKResult.ok` is False. Not by ch. 4's ``Rider`` (one whole-body DLS solve
with the sole's pitch free about the pedal axle: five constraints per foot, no unique closed form).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from shintai.core.geometry import rot_x, rot_y, rot_z
from shintai.humanoid.constants import HRP2_LINKS, LEG_JOINTS, Hrp2Links, joint_range

SIDES = {"l": 1.0, "r": -1.0}  # y sign of each leg (as robots.hrp2.SIDES)
JOINT_NAMES = tuple(j.name for j in LEG_JOINTS)  # hip_yaw, hip_roll, hip_pitch, knee_pitch, ankle_pitch, ankle_roll
LIMITS = {s: np.array([joint_range(j, s) for j in LEG_JOINTS]) for s in SIDES}  # (6, 2) rad per side
_LIMITS = {s: [tuple(row) for row in lim.tolist()] for s, lim in LIMITS.items()}


class LegIKResult(NamedTuple):
    """``q``: the six joint angles (hip yaw, roll, pitch, knee, ankle pitch, roll), rad.
    ``reachable``: the ankle target is within the leg's length (else the knee is clamped straight and
    ``reach_error`` > 0 m is how far the ankle misses). ``within_limits``: every joint inside Table
    A.2's range; ``violated`` names those outside (e.g. ``"r_knee_pitch"``)."""

    q: np.ndarray
    reachable: bool
    reach_error: float
    within_limits: bool
    violated: tuple[str, ...]

    @property
    def ok(self) -> bool:
        """Reachable and inside the joint limits (what :func:`shintai.sim.ik.solve`'s ``ok`` means)."""
        return self.reachable and self.within_limits

    def joints(self, side: str) -> dict[str, float]:
        """The angles by model joint name (``"l_hip_yaw"`` …)."""
        return {f"{side}_{n}": float(v) for n, v in zip(JOINT_NAMES, self.q)}


def hip_point(side: str, waist_pos, waist_rot, links: Hrp2Links = HRP2_LINKS) -> np.ndarray:
    """World position of the point where the hip yaw, roll and pitch axes meet."""
    return np.asarray(waist_pos, float) + np.asarray(waist_rot, float) @ (0.0, SIDES[side] * links.hip_y, links.hip_z)


def _mat(rot, name: str) -> list[float]:
    """A rotation (3×3 or flat 9, row-major) as 9 Python floats."""
    flat = np.asarray(rot, float).ravel()
    if flat.shape != (9,):
        raise ValueError(f"leg_ik: {name} is a 3×3 rotation, got {np.shape(rot)}")
    return flat.tolist()


def leg_ik(side: str, waist_pos, waist_rot, sole_pos, sole_rot, links: Hrp2Links = HRP2_LINKS,
           sole: bool = True) -> LegIKResult:
    """Joint angles of leg ``side`` ("l"/"r") putting its sole site (``sole=False``: the ankle point)
    at ``sole_pos`` with orientation ``sole_rot`` (3×3, world), the waist at ``waist_pos``/``waist_rot``.
    See the module docstring for the closed form, compiled as :func:`closed_form` on scalars: a few NumPy
    calls on 3-vectors cost more than the whole solution (the tricycle's feet, the stabilizer: every
    4 ms tick, both legs)."""
    if side not in SIDES:
        raise ValueError(f"leg_ik: side is 'l' or 'r', got {side!r}")
    return leg_ik_floats(side, np.asarray(waist_pos, float).tolist(), _mat(waist_rot, "waist_rot"),
                         np.asarray(sole_pos, float).tolist(), _mat(sole_rot, "sole_rot"), links, sole)


def leg_ik_floats(side: str, waist_pos, waist_rot, sole_pos, sole_rot, links: Hrp2Links = HRP2_LINKS,
                  sole: bool = True) -> LegIKResult:
    """:func:`leg_ik` on Python floats: the positions as 3 floats, the rotations as 9 (row-major), e.g.
    tuples formed once (the tricycle's feet in the waist frame); nothing is converted."""
    q, reach_error = leg_angles(side, waist_pos, waist_rot, sole_pos, sole_rot, links, sole)
    violated = ()
    for name, v, (lo, hi) in zip(JOINT_NAMES, q, _LIMITS[side]):
        if not lo <= v <= hi:
            violated += (f"{side}_{name}",)
    return LegIKResult(np.array(q), reach_error == 0.0, reach_error, not violated, violated)


def inside_limits(side: str, q) -> bool:
    """Every angle of ``q`` inside Table A.2's range of leg ``side`` (:attr:`LegIKResult.within_limits`, without
    naming the joints outside it; a NaN is outside): with :func:`leg_angles`' ``reach_error == 0`` it is
    :attr:`LegIKResult.ok`, for a caller that needs only that (the tricycle's feet, every tick)."""
    for v, (lo, hi) in zip(q, _LIMITS[side]):
        if not lo <= v <= hi:
            return False
    return True


def leg_angles(side: str, waist_pos, waist_rot, sole_pos, sole_rot, links: Hrp2Links = HRP2_LINKS,
               sole: bool = True) -> tuple[list[float], float]:
    """The closed form of the module docstring on Python floats (:func:`leg_ik_floats`' arguments): the six
    angles as a list and ``reach_error`` (0 when reachable), without the limit check (the stabilizer's leg IK:
    every 4 ms tick, both legs). The arithmetic is :func:`closed_form`'s."""
    *q, reach_error, dist = closed_form(SIDES[side] * links.hip_y, links.hip_z, links.ankle_height, links.thigh,
                                        links.shank, sole, *waist_pos, *waist_rot, *sole_pos, *sole_rot)
    if not math.isfinite(dist):
        raise ValueError(f"leg_ik: target or waist pose is not finite (hip from ankle at distance {dist})")
    return q, reach_error


@njit(cache=True)
def closed_form(hy, hz, h, l1, l2, sole, wx, wy, wz, w0, w1, w2, w3, w4, w5, w6, w7, w8,
                px, py, pz, f0, f1, f2, f3, f4, f5, f6, f7, f8):
    """The closed form of the module docstring, compiled (the same IEEE double operations, in the same order, as on
    Python floats: no fused multiply-adds, the C library's sin, cos, atan2 and acos; tested bit for bit against
    its own source run by Python): the hip at ``(0, hy, hz)`` in the waist frame, ``h`` the ankle height, ``l1``,
    ``l2`` thigh and shank; the waist at (wx, wy, wz) turned by w (row-major), the sole (``sole``; else the ankle)
    at (px, py, pz) turned by f. Returns (q1 … q6, reach_error, |r|), |r| not finite for a non-finite pose."""
    if sole:  # ankle = sole + R_f (0, 0, ankle_height)
        px, py, pz = px + f2 * h, py + f5 * h, pz + f8 * h
    dx = wx + w1 * hy + w2 * hz - px  # hip point H = p_w + R_w (0, hy, hz)
    dy = wy + w4 * hy + w5 * hz - py
    dz = wz + w7 * hy + w8 * hz - pz
    rx = f0 * dx + f3 * dy + f6 * dz  # r = R_fᵀ (H − p_a)
    ry = f1 * dx + f4 * dy + f7 * dz
    rz = f2 * dx + f5 * dy + f8 * dz
    dist = math.sqrt(rx * rx + ry * ry + rz * rz)
    reach_error = max(0.0, dist - (l1 + l2), abs(l1 - l2) - dist)
    c4 = (dist * dist - l1 * l1 - l2 * l2) / (2 * l1 * l2)
    q4 = math.acos(min(1.0, max(-1.0, c4)))
    if rz >= 0:
        q6, yz = math.atan2(ry, rz), math.sqrt(ry * ry + rz * rz)
    else:  # the ankle-roll branch with |q6| ≤ π/2 (the hip below the ankle: far outside the limits)
        q6, yz = math.atan2(-ry, -rz), -math.sqrt(ry * ry + rz * rz)
    q5 = math.atan2(-rx, yz) - math.atan2(l1 * math.sin(q4), l2 + l1 * math.cos(q4))
    # M = N Rx(−q6) Ry(−q4 − q5) = Rz(q1) Rx(q2) Ry(q3), N = R_wᵀ R_f (n_ij); only five entries of M are needed
    n01, n02 = w0 * f1 + w3 * f4 + w6 * f7, w0 * f2 + w3 * f5 + w6 * f8
    n11, n12 = w1 * f1 + w4 * f4 + w7 * f7, w1 * f2 + w4 * f5 + w7 * f8
    n20, n21, n22 = w2 * f0 + w5 * f3 + w8 * f6, w2 * f1 + w5 * f4 + w8 * f7, w2 * f2 + w5 * f5 + w8 * f8
    c6, s6 = math.cos(q6), math.sin(q6)
    cb, sb = math.cos(q4 + q5), -math.sin(q4 + q5)
    m01 = c6 * n01 - s6 * n02
    m11 = c6 * n11 - s6 * n12
    m21 = c6 * n21 - s6 * n22
    col2 = s6 * n21 + c6 * n22  # (N Rx(−q6))[2, 2]
    m20 = cb * n20 - sb * col2
    m22 = sb * n20 + cb * col2
    return (math.atan2(-m01, m11), math.atan2(m21, math.sqrt(m01 * m01 + m11 * m11)), math.atan2(-m20, m22),
            q4, q5, q6, reach_error, dist)


@njit(cache=True)
def rot_xy_flat(roll, pitch):
    """:func:`~shintai.core.geometry.rot_xy` (Ry(pitch) Rx(roll)) as its 9 floats, row-major, without the array:
    the sole attitude δ gives the leg IK each tick (compiled, for :func:`legs_upright`; callable from Python)."""
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    return cp, sp * sr, sp * cr, 0.0, cr, -sr, -sp, cp * sr, cp * cr


@njit(cache=True)
def legs_upright(waist, soles, delta, dz, hip_y, hip_z, h, l1, l2, ctrl, legs):
    """Both legs' :func:`closed_form` under an upright waist at ``waist`` (3,), in one call (the stabilizer's leg
    IK, :class:`~shintai.humanoid.balance.standing.LegIKModule`): the left and right soles ``soles`` (2, 3) turned
    by ``delta`` (L roll, L pitch, R roll, R pitch; empty: level) and raised by ``dz`` (L, R; empty: none). The
    twelve angles (left leg, then right, hip yaw first) are written into ``ctrl`` at ``legs``; returns (the legs
    that could not reach, whether the pose was finite)."""
    missed, finite, k = 0, True, 0
    for i in range(2):
        x, y, z = soles[i, 0], soles[i, 1], soles[i, 2]
        f0, f1, f2, f3, f4, f5, f6, f7, f8 = 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0
        if delta.shape[0]:
            f0, f1, f2, f3, f4, f5, f6, f7, f8 = rot_xy_flat(delta[2 * i], delta[2 * i + 1])
        if dz.shape[0]:
            z += dz[i]
        q1, q2, q3, q4, q5, q6, reach_error, dist = closed_form(
            hip_y if i == 0 else -hip_y, hip_z, h, l1, l2, True, waist[0], waist[1], waist[2],
            1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, x, y, z, f0, f1, f2, f3, f4, f5, f6, f7, f8)
        finite = finite and math.isfinite(dist)
        missed += reach_error != 0.0
        for q in (q1, q2, q3, q4, q5, q6):
            ctrl[legs[k]] = q
            k += 1
    return missed, finite


def legs_ik(waist_pos, waist_rot, soles: dict, links: Hrp2Links = HRP2_LINKS, sole: bool = True) -> dict[str, LegIKResult]:
    """:func:`leg_ik` for each side in ``soles`` (``{"l": (pos, rot), "r": (pos, rot)}``)."""
    return {s: leg_ik(s, waist_pos, waist_rot, pos, rot, links, sole) for s, (pos, rot) in soles.items()}


def leg_fk(side: str, q, waist_pos, waist_rot, links: Hrp2Links = HRP2_LINKS) -> tuple[np.ndarray, np.ndarray]:
    """(sole position, sole orientation) in the world for leg angles ``q`` (the model's chain, in
    NumPy; the tests check it and :func:`leg_ik` against MuJoCo's ``mj_kinematics``)."""
    q1, q2, q3, q4, q5, q6 = (float(v) for v in q)
    rw = np.asarray(waist_rot, float)
    r_hip = rw @ rot_z(q1) @ rot_x(q2) @ rot_y(q3)
    r_shank = r_hip @ rot_y(q4)
    r_foot = r_shank @ rot_y(q5) @ rot_x(q6)
    ankle = hip_point(side, waist_pos, rw, links) - r_hip[:, 2] * links.thigh - r_shank[:, 2] * links.shank
    return ankle - r_foot[:, 2] * links.ankle_height, r_foot
