"""Small geometry every body uses, in one place: elementary rotations, the cross-product matrix and a
broadcasting cross product, angle wrapping and unwrapping, roll of a rotation matrix."""

from __future__ import annotations

import math

import numpy as np


def rot_x(a: float) -> np.ndarray:
    """Rotation by ``a`` about x."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a: float) -> np.ndarray:
    """Rotation by ``a`` about y."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a: float) -> np.ndarray:
    """Rotation by ``a`` about z."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rot_xy(roll: float, pitch: float) -> np.ndarray:
    """Ry(pitch) Rx(roll): ``roll`` about world x, then ``pitch`` about world y."""
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    return np.array([[cp, sp * sr, sp * cr], [0.0, cr, -sr], [-sp, cp * sr, cp * cr]])


def roll_of(rot: np.ndarray) -> float:
    """Roll (about the body's x, ZYX Euler) of a rotation matrix: the tilt of its y axis out of the
    horizontal; positive when the body's left side rises (top leans to −y)."""
    return float(np.arctan2(rot[2, 1], rot[2, 2]))


def skew(r) -> np.ndarray:
    """[r]_× with [r]_× a = r × a."""
    x, y, z = r
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a × b over the last axis (length 3) of two broadcast arrays: ``np.cross``'s own products and differences
    (a₁b₂ − a₂b₁, a₂b₀ − a₀b₂, a₀b₁ − a₁b₀, each product rounded before the difference), so the same bits, without
    its per-call axis handling (≈60 µs on a spine's (54, 15, 3) arrays, most of the cost)."""
    a, b = np.asarray(a), np.asarray(b)
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), np.result_type(a, b))
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    np.subtract(a1 * b2, a2 * b1, out=out[..., 0])
    np.subtract(a2 * b0, a0 * b2, out=out[..., 1])
    np.subtract(a0 * b1, a1 * b0, out=out[..., 2])
    return out


def wrap(a):
    """Angle(s) wrapped to [−π, π) (a float for a scalar, an array otherwise)."""
    out = (np.asarray(a, dtype=float) + math.pi) % (2 * math.pi) - math.pi
    return float(out) if out.ndim == 0 else out


def wrap_pi(angle: float) -> float:
    """An angle (a scalar) in (−π, π] (the other half-open convention, where +π stays +π): π − ((π − a) mod 2π).

    Python's float ``%`` is np.mod's floored modulo (fmod, then the divisor's sign), so this is the NumPy form's
    result bit for bit (tests/core/test_geometry.py), at a fraction of its per-call cost (the tricycle's switching
    diagnostics unwrap with it every control tick)."""
    return math.pi - (math.pi - float(angle)) % (2 * math.pi)


def unwrap_from(angle, start: float) -> np.ndarray:
    """A series of wrapped angles made continuous and shifted to begin at ``start``."""
    u = np.unwrap(np.asarray(angle, dtype=float))
    return u - u[0] + start
