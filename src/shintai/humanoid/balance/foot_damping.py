"""Foot torque damping control (seed 000 §5.2.2, Eqs. 5.1–5.3) and foot force difference control.

Kajita et al.'s "Foot torque control" (the thesis's [55], run by hrpsys-base's Stabilizer) turns each
foot's roll and pitch by δ so that the sensed ankle torque τ follows the reference τᵈ of the ZMP distributor:

    δ̇ = D⁻¹ (τᵈ − τ) − δ / T                                   (Eq. 5.1)
    e_τ = τᵈ − τ                                                (Eq. 5.2)
    δ = C_τ(s) e_τ,   C_τ(s) = T / (D (1 + T s))                (Eq. 5.3, the "damping controller")

D is the damping gain that SLC learns (§5.3, :mod:`shintai.humanoid.learning.slc`), T the time constant. On the
computer Eq. 5.1 runs in forward Euler at the control period (hrpsys-base ``calcDampingControl``:
δ ← δ + Δt (e_τ / D − δ / T)), and δ is clipped to a compensation limit afterwards. The thesis mentions that
limit ("設定した入力制限", §5.4.2) without a value.

"Foot force difference control" is named in §5.2.2 only in words: a distributor of the difference of the
two feet's vertical reactions, effective in double support, and therefore not learned. The thesis gives
no equation; the law here is Kajita et al. [55] Eq. 18 as hrpsys-base runs it — the same damping law on
the force difference Δf = f_Lz − f_Rz, moving the feet by ∓z_ctrl/2 — and it only decays in single support
(hrpsys ramps it over a transition time; chosen: off at once, see :class:`ForceDifferenceControl`).

Units: τ in N·m, δ in rad, D in N·m·s/rad (the thesis gives D without units; hrpsys-base uses these).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from shintai.core.runtime import SET, Channel, Module, Snapshot, declare
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    DAMPING_D_FLAT,
    DAMPING_T,
    DELTA_LIMIT,
    FORCE_DIFF_D,
    FORCE_DIFF_LIMIT,
    FORCE_DIFF_T,
)
from shintai.humanoid.law_params import check_real

# --- constants ------------------------------------------------------------------------------------
AXES = ("roll", "pitch")
GAIN = "damping_gain"
# δ and e_τ of this tick, and D from one tick earlier (SLC writes D(t+Δt) after this tick's damping step, Fig. 5.4)
CHANNELS = {**declare("damping_delta", "e_tau", kind=SET), GAIN: Channel(GAIN, SET, delay=1)}


@njit(cache=True)
def damping_step(delta, e_tau, D, T, dt):
    """One forward-Euler step of Eq. 5.1 with e_τ = τᵈ − τ (Eq. 5.2): δ + Δt (e_τ/D − δ/T), on floats or arrays
    (compiled without fast-math: the same IEEE operations as NumPy's or Python's)."""
    return delta + dt * (e_tau / D - delta / T)


@njit(cache=True)
def _foot_step(out, col, delta, e_tau, saturated, D, tau_d, tau, T, dt, limit):
    """One foot's Eq. 5.2 and 5.1 (roll, pitch), each δ clipped to ±``limit`` as Python's ``min(max(raw, −limit),
    limit)`` does; the foot's δ, e_τ, saturated updated in place and δ, e_τ written to ``out``'s columns ``col``,
    ``col + 1`` (rows δ, e_τ)."""
    for axis in range(2):
        e = tau_d[axis] - tau[axis]  # Eq. 5.2
        raw = damping_step(delta[axis], e, D[axis], T, dt)  # Eq. 5.1
        x = -limit if -limit > raw else raw
        d = limit if limit < x else x
        delta[axis], e_tau[axis], saturated[axis] = d, e, abs(raw) >= limit
        out[0, col + axis], out[1, col + axis] = d, e


@njit(cache=True)
def _feet_step(out, dl, el, sl, Dl, dr, er, sr, Dr, tau_d_l, tau_d_r, tau_l, tau_r, laws):
    """:class:`FootDampingModule`'s tick compiled: :func:`_foot_step` for the left foot (δ ``dl``, e_τ ``el``,
    saturated ``sl``, gains ``Dl``; T, Δt, limit ``laws[0:3]``) and the right (``laws[3:6]``); ``out`` rows δ, e_τ as
    [L roll, L pitch, R roll, R pitch]."""
    _foot_step(out, 0, dl, el, sl, Dl, tau_d_l, tau_l, laws[0], laws[1], laws[2])
    _foot_step(out, 2, dr, er, sr, Dr, tau_d_r, tau_r, laws[3], laws[4], laws[5])


def damping_controller_gain(D: float, T: float) -> float:
    """The static gain of C_τ(s) = T / (D (1 + T s)) (Eq. 5.3): δ → T e_τ / D under a constant error."""
    return T / D


class FootDamping:
    """Eq. 5.1 on one foot's roll and pitch (in that order), clipped to ±``limit``.

    ``D`` holds one damping gain per axis and may be rewritten between steps (SLC writes the pitch one).
    ``step(tau_d, tau)`` returns the new δ; ``e_tau`` keeps the error of that step.
    """

    def __init__(self, D=DAMPING_D_FLAT, T: float = DAMPING_T, dt: float = CONTROL_PERIOD, limit: float = DELTA_LIMIT):
        D = np.broadcast_to(np.asarray(D, dtype=float), (2,)).copy()
        for axis, d in zip(AXES, D, strict=True):
            check_real(f"D ({axis})", d, 0.0, low_open=True)
        self.D = D
        self.T = check_real("T", T, 0.0, low_open=True)
        self.dt = check_real("dt", dt, 0.0, low_open=True)
        self.limit = check_real("limit", limit, 0.0, low_open=True)
        self.delta = np.zeros(2)
        self.e_tau = np.zeros(2)
        self.saturated = np.zeros(2, dtype=bool)

    def step(self, tau_d, tau) -> np.ndarray:
        self.e_tau = np.asarray(tau_d, dtype=float) - np.asarray(tau, dtype=float)
        raw = damping_step(self.delta, self.e_tau, self.D, self.T, self.dt)
        self.delta = np.minimum(np.maximum(raw, -self.limit), self.limit)  # = np.clip, without its dispatch
        self.saturated = np.abs(raw) >= self.limit
        return self.delta.copy()

    def reset(self) -> None:
        self.delta[:] = 0.0
        self.e_tau[:] = 0.0


class ForceDifferenceControl:
    """Foot force difference control (§5.2.2 by name; law of [55] Eq. 18 as in hrpsys-base):

        ż_ctrl = D_z⁻¹ (Δfᵈ − Δf) − z_ctrl / T_z,   Δf = f_Lz − f_Rz,   z_R = −z_ctrl/2,  z_L = +z_ctrl/2

    in double support; in single support z_ctrl only decays (ż = −z/T_z). Returns (z_R, z_L) in m.
    """

    def __init__(self, D=FORCE_DIFF_D, T: float = FORCE_DIFF_T, dt: float = CONTROL_PERIOD, limit: float = FORCE_DIFF_LIMIT):
        self.D = check_real("D_z", D, 0.0, low_open=True)
        self.T = check_real("T_z", T, 0.0, low_open=True)
        self.dt = check_real("dt", dt, 0.0, low_open=True)
        self.limit = check_real("limit", limit, 0.0, low_open=True)
        self.z_ctrl = 0.0

    def step(self, f_d_diff: float, f_diff: float, double_support: bool) -> tuple[float, float]:
        e = (f_d_diff - f_diff) if double_support else 0.0
        z = damping_step.py_func(self.z_ctrl, e, self.D, self.T, self.dt)  # its source: on one float, cheaper than a call
        self.z_ctrl = min(max(z, -self.limit), self.limit)  # = np.clip of a float, without its dispatch
        return -0.5 * self.z_ctrl, 0.5 * self.z_ctrl


class FootDampingModule(Module):
    """Both feet's torque damping (Eq. 5.1) as a runtime module.

    Reads ``tau_d_<foot>`` and ``tau_<foot>`` (roll, pitch; foot ∈ L, R) from the snapshot and contributes
    δ to ``channel`` as [L roll, L pitch, R roll, R pitch] (additive: the corrections add to the foot
    attitudes, and in ch. 6 δ is the disturbance d of Eq. 6.5). It also writes its own δ and e_τ, same layout,
    on the set channels ``damping_delta`` and ``e_tau`` (SLC's search variables, Fig. 5.4), and takes its gains
    D from channel ``damping_gain`` when someone writes it (SLC, one tick later: :data:`CHANNELS`); else the
    feet keep the D they were built with. ``D`` and ``T`` build both feet (one D per axis, or one for all).
    """

    def __init__(self, D=DAMPING_D_FLAT, T: float = DAMPING_T, channel: str = "foot_damping",
                 name: str = "foot_damping", period: float | None = None):
        super().__init__(name, period)
        self.feet = {"L": FootDamping(D=D, T=T), "R": FootDamping(D=D, T=T)}
        self.channel = channel
        self._out = np.zeros((2, 4))  # δ and e_τ of the tick, [L roll, L pitch, R roll, R pitch]

    def reset(self, snapshot: Snapshot) -> None:
        for foot in self.feet.values():
            foot.reset()

    def update(self, snapshot: Snapshot):
        left, right = self.feet["L"], self.feet["R"]
        gain = snapshot.get(GAIN)
        if gain is not None:
            left.D[:], right.D[:] = gain[:2], gain[2:]
        # both feet's Eq. 5.2 and 5.1 in one compiled call (FootDamping.step's maths, the same IEEE operations)
        _feet_step(self._out, left.delta, left.e_tau, left.saturated, left.D, right.delta, right.e_tau, right.saturated,
                   right.D, snapshot["tau_d_L"], snapshot["tau_d_R"], snapshot["tau_L"], snapshot["tau_R"],
                   (left.T, left.dt, left.limit, right.T, right.dt, right.limit))  # each foot's, read every tick
        if self.recorder is not None:  # the log's signals are formed only when something records them
            self.log(snapshot["t"], **{f"{self.name}.delta_L": left.delta.copy(), f"{self.name}.delta_R": right.delta.copy(),
                                           f"{self.name}.D_L": left.D.copy(), f"{self.name}.D_R": right.D.copy()})
        delta = self._out[0].copy()
        return {self.channel: delta, "damping_delta": delta.copy(), "e_tau": self._out[1].copy()}
