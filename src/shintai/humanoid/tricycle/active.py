"""The active function: trajectories from the offline search index (seed 000 §3.4.2, Eqs. 3.2–3.12).

The active manipulator is given the input trajectory X_active^ref(t) that the object's desired motion
needs (§3.4.1): here the pedal contact point for a target crank angle and the grip points for a
target handle angle, both from the vehicle's kinematic model.

Crank angles (spec 000-part1 §6 item 5 — the thesis mixes two conventions; we keep both and tie them):

* φ, the *pedal angle* of Eqs. 3.6–3.8: in the crank-centred frame (x forward, y the crank axis,
  z up) a pedal at angle φ sits at r (sin φ, 0, cos φ) — φ = 0 is top dead centre (TDC) and φ grows
  toward the front (positive rotation about +y, R_y of Eq. 3.8), which is forward pedalling.
* θ_c, the *general crank angle* of Eqs. 3.3, 3.19 and the role table of §3.5.2. Fig. 3.11 (which
  fixes its zero) is not in the text; the role table and Eq. 3.6 fix it: the right leg takes over at
  θ_c = π/2 + δ_c exactly when its pedal enters the active region φ = δ_c, so
  **φ_right = θ_c − π/2 and φ_left = θ_c + π/2** — θ_c = 0 is the crank horizontal with the left
  pedal forward, which also matches the ~1/|cos θ_c| force argument of §3.5.3 (smallest at θ_c = 0, π).
"""

from __future__ import annotations

import numpy as np

from shintai.humanoid.constants import THETA_H_MAX, TRICYCLE, TricycleSpec
from shintai.humanoid.tricycle.vehicle import grip_position

PEDAL_PHASE_OFFSET = {"left": np.pi / 2, "right": -np.pi / 2}  # φ_leg = θ_c + offset (module docstring)


def R_y(theta: float) -> np.ndarray:
    """Rotation by θ about the crank axis y (Eq. 3.8)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def v(delta_c: float) -> np.ndarray:
    """v(δ_c) = (sin δ_c, 0, cos δ_c)ᵀ, the unit vector δ_c past TDC (Eq. 3.8)."""
    return np.array([np.sin(delta_c), 0.0, np.cos(delta_c)])


def pedal_phase(theta_c: float, leg: str) -> float:
    """The pedal angle φ of ``leg`` (from TDC, Eq. 3.8 frame) at general crank angle θ_c, in [0, 2π)."""
    return float(np.mod(theta_c + PEDAL_PHASE_OFFSET[leg], 2 * np.pi))


def crank_angle_of_phase(phi: float, leg: str) -> float:
    """The general crank angle θ_c ∈ [0, 2π) at which ``leg``'s pedal is at pedal angle φ."""
    return float(np.mod(phi - PEDAL_PHASE_OFFSET[leg], 2 * np.pi))


def pedal_point(crank_centre, r: float, phi: float) -> np.ndarray:
    """The pedal point at pedal angle φ on the crank circle: c + r (sin φ, 0, cos φ)."""
    return np.asarray(crank_centre, dtype=float) + r * v(phi)


def in_active_region(point, crank_centre, delta_c: float, tol: float = 1e-12) -> bool:
    """Eq. 3.6: x_c ≥ z_c tan δ_c in the crank-centred frame — the pedal is between δ_c past TDC and
    δ_c past BDC, where the stepping leg acts (the human hamstring phase 20°–200° of [125], §3.3.3)."""
    x_c, _, z_c = np.asarray(point, dtype=float) - np.asarray(crank_centre, dtype=float)
    return bool(x_c >= z_c * np.tan(delta_c) - tol)


def pedal_trajectory(p0, r: float, delta_c: float, T: int) -> np.ndarray:
    """Eq. 3.7: p_i = p_0 + r (R_y(π i/T) − I₃) v(δ_c), i = 0 … T — the active half revolution.

    p_0 is the foot at the start of the active phase, δ_c past TDC (spec §6 item 5b); the crank centre
    is p_0 − r v(δ_c). Returns a (T+1)×3 array.
    """
    if T < 1 or r <= 0:
        raise ValueError(f"pedal trajectory needs T >= 1 and r > 0, got T={T}, r={r}")
    p0 = np.asarray(p0, dtype=float)
    return np.array([p0 + r * (R_y(np.pi * i / T) - np.eye(3)) @ v(delta_c) for i in range(T + 1)])


def pedal_offline_index(i: int, r: float, delta_c: float, T: int) -> np.ndarray:
    """The offline search index of Eq. 3.9 with its weight (Table 3.2: A ↔ r, v(δ_c)) applied:
    r (R_y(π i/T) − R_y(π (i+1)/T)) v(δ_c) — current state minus target state."""
    return r * (R_y(np.pi * i / T) - R_y(np.pi * (i + 1) / T)) @ v(delta_c)


def pedal_update(p_i, i: int, r: float, delta_c: float, T: int) -> np.ndarray:
    """Eq. 3.9: p_{i+1} := p_i − r (R_y(π i/T) − R_y(π (i+1)/T)) v(δ_c) (the rule ρ ← ρ − A f, Eq. 2.13)."""
    return np.asarray(p_i, dtype=float) - pedal_offline_index(i, r, delta_c, T)


def grip_plan(theta_h: float, arm: str, Theta_H: float = THETA_H_MAX, t: TricycleSpec = TRICYCLE) -> np.ndarray:
    """X_active^ref of an arm (§3.4.2): its grip at the target handle angle, kept within Eq. 3.2, from
    the tricycle's nominal kinematic model — :func:`~shintai.humanoid.tricycle.vehicle.grip_position`,
    the θ_h = 0 grip (±0.24 m from the steering axis, App. A.1.1; spec §6 item 6) turned about the
    raked steering axis. The thesis gives no formula beyond "from the handle's kinematic parameters".
    ``arm`` is "left" or "right"; vehicle frame."""
    return grip_position(clamp_handle(theta_h, Theta_H), arm[0], t)


def clamp_handle(theta_h: float, Theta_H: float) -> float:
    """Eq. 3.2: −Θ_H ≤ θ_h ≤ Θ_H (Θ_H of Eq. 3.4 = 25° in Table 3.4)."""
    return float(np.clip(theta_h, -Theta_H, Theta_H))
