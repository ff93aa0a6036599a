"""Ch. 4 trajectory corrections of the riding posture and for small obstacles (seed 000 §4.3, §4.4.3,
§7.3.1, §7.4.1) as online search indices and runtime modules.

* **Interrupt-type sitting recovery** (§4.3.2, Eqs. 4.2–4.7, Table 4.3, Fig. 4.7; FSM of §7.4.1,
  Table 7.6): :func:`recovery_due` (|θ_roll| over a threshold *and* θ_c = kπ),
  :class:`RecoveryTrigger` (once per kπ), :func:`hip_force` (Eq. 4.2), :func:`recovery_index`
  (Eq. 4.7: y_g(n+1) = y_g(n) − L sgn sin(θ_roll − 0), sgn = −1, through the engine's
  :class:`~shintai.core.search_index.SearchIndex`), and :class:`SittingRecovery`, the
  STAND → SHIFT → RESEAT module a
  :class:`~shintai.core.runtime.Switcher` swaps in for driving (switching processing, §7.4.1).
* **Real-time chest posture control** (Kajita et al. [55], §4.3.3, Eqs. 4.8–4.10):
  :class:`ChestPostureControl` — Δφ_C = −k_C T_C/(1 + T_C s) (φ_C − φ_C^d) (Eq. 4.10 ≡ Eq. 4.8),
  applied as a roll of the reference waist about the hip–saddle contact (Eq. 4.9); a module that
  runs *in parallel* with driving in one :class:`~shintai.core.runtime.Loop` (§7.3.1).
* **Pedalling power detection method** (§4.4.3, Table 4.7, Fig. 4.21): :class:`PedalLoadDetector`
  (force rise on the ankle sensors while the crank stalls; the thesis gives no rule) and
  :func:`push_down_angle` (back-pedal to θ_c^SW = θ_c^init + kπ below the current angle).

Sign conventions: roll positive about the forward x axis (left side up, trunk leaning to −y);
y_g positive to the left.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np

from shintai.core.constants import GRAVITY
from shintai.core.runtime import Module
from shintai.core.search_index import SearchIndex, first_order_gain
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    POSTURE_K_C,
    POSTURE_T_C,
    PPDM_RISE,
    PPDM_WINDOW_S,
    RECOVERY_CRANK_TOLERANCE,
    RECOVERY_LIFT_M,
    RECOVERY_PHASE_S,
    RECOVERY_PUSH_N,
    RECOVERY_ROLL_THRESHOLD,
    THETA_C_INIT,
)


# --- sitting recovery (§4.3.2, §7.4.1) ------------------------------------------------------------


def at_k_pi(theta_c: float, tol: float = RECOVERY_CRANK_TOLERANCE) -> bool:
    """θ_c = kπ (both pedals level, §4.3.2) within ``tol``."""
    return abs(math.remainder(theta_c, math.pi)) <= tol


def recovery_due(theta_roll: float, theta_c: float, threshold: float = RECOVERY_ROLL_THRESHOLD,
                 tol: float = RECOVERY_CRANK_TOLERANCE) -> bool:
    """The DRIVE → STAND guard of Table 7.6: |θ_roll| > threshold and the crank at θ_c = kπ."""
    return abs(theta_roll) > threshold and at_k_pi(theta_c, tol)


class RecoveryTrigger:
    """The DRIVE → STAND guard with memory: :func:`recovery_due`, at most once per crank position
    θ_c = kπ (after a recovery the crank is still at the same kπ; the next chance is the next level
    crank, (k ± 1)π — otherwise the interrupt would fire again before driving resumed)."""

    def __init__(self, threshold: float = RECOVERY_ROLL_THRESHOLD, tol: float = RECOVERY_CRANK_TOLERANCE):
        self.threshold, self.tol = threshold, tol
        self.last_k: int | None = None

    def __call__(self, theta_roll: float, theta_c: float) -> bool:
        k = round(theta_c / math.pi)
        if k == self.last_k or not recovery_due(theta_roll, theta_c, self.threshold, self.tol):
            return False
        self.last_k = k
        return True


def hip_force(mass: float, zdd_g: float, f_feet_z, f_hands_z) -> float:
    """Eq. 4.2: F_hip_z = M (z̈_g + g) − (F_rf_z + F_lf_z + F_rh_z + F_lh_z)."""
    return mass * (zdd_g + GRAVITY) - float(np.sum(f_feet_z)) - float(np.sum(f_hands_z))


def recovery_index(y_g0: float, l_hip_cog: float) -> SearchIndex:
    """Eq. 4.7 as an online control index (Table 4.3): x = sin θ_roll(n), x_d = sin 0 = 0,
    ρ = y_g(n), A = L_hip→COG, sgn[ρ, x] = −1 (Eq. 4.6). One update = Δy_g = L sin θ_roll (Eq. 4.3)."""
    return SearchIndex([y_g0], np.array([[l_hip_cog]]), sgn=[[-1.0]], x_d=[0.0])


class SittingRecovery(Module):
    """The interrupt (Table 7.6): STAND (both legs push down with 320 N each and lift the hip),
    SHIFT (move the waist by Eq. 4.7's Δy_g from the roll measured at the interrupt), RESEAT (back to
    the driving force, sit down). Each phase lasts ``phase_s``; :attr:`done` turns true at the end.

    While it runs, the driving system is not executed: the crank rate is zero and the handle target
    is held (the inactive system's ρ is held, §7.2). ``roll_of(snapshot)`` is the IMU trunk roll;
    ``l_hip_cog`` the hip → CoM distance L_hip→COG. Contributions: ``ref:foot_fz``, ``ref:hip_lift``,
    ``ref:com_shift`` (cumulative over recoveries, the ρ = y_g(n) of Eq. 4.7), ``ref:theta_h``.
    """

    def __init__(self, roll_of, l_hip_cog: float, base_fz: float, push_n: float = RECOVERY_PUSH_N,
                 lift_m: float = RECOVERY_LIFT_M, phase_s: float = RECOVERY_PHASE_S, name: str = "recover"):
        super().__init__(name, CONTROL_PERIOD)
        self.roll_of, self.push_extra, self.lift_m, self.phase_s = roll_of, push_n - base_fz, lift_m, phase_s
        self.index = recovery_index(0.0, l_hip_cog)
        self.done = False
        self.history: list[tuple[float, float, float]] = []  # (t, θ_roll(n), y_g(n+1))

    def reset(self, snapshot) -> None:
        self.t0 = float(snapshot["t"])
        self.theta_h = float(snapshot.get("ref:theta_h", 0.0))
        self.y_from = float(self.index.rho[0])
        self.roll = self.roll_of(snapshot)
        self.y_to = float(self.index.update([math.sin(self.roll)])[0])
        self.history.append((self.t0, self.roll, self.y_to))
        self.done = False

    def held(self, snapshot) -> dict:
        """The contribution while the recovery is *not* running: its ρ = y_g(n) held (§7.2), so the
        reference CoM stays where the last recovery moved it when driving resumes."""
        return {"ref:com_shift": float(self.index.rho[0])}

    def phase(self, t: float) -> str:
        k = int((t - self.t0) / self.phase_s)
        return ("stand", "shift", "reseat")[k] if k < 3 else "over"

    def update(self, snapshot):
        t = float(snapshot["t"])
        s = (t - self.t0) / self.phase_s
        ramp = lambda u: 0.5 - 0.5 * math.cos(math.pi * min(max(u, 0.0), 1.0))  # noqa: E731
        phase = self.phase(t)
        if phase == "stand":
            push, lift, shift = ramp(s), ramp(s), 0.0
        elif phase == "shift":
            push, lift, shift = 1.0, 1.0, ramp(s - 1)
        else:
            push = lift = 1.0 - ramp(s - 2)
            shift = 1.0
            self.done = phase == "over"
        y = self.y_from + shift * (self.y_to - self.y_from)
        self.log(t, **{"recover.phase": float(("stand", "shift", "reseat", "over").index(phase))})
        return {"ref:foot_fz": push * self.push_extra, "ref:hip_lift": lift * self.lift_m, "ref:com_shift": y,
                "ref:theta_h": self.theta_h}


# --- real-time chest posture control (§4.3.3, §7.3.1) ---------------------------------------------


class ChestPostureControl(Module):
    """Kajita's chest posture control, roll component (Eq. 4.8): Δφ̇_C = k_C (φ_C^d − φ_C) − Δφ_C / T_C,
    i.e. Δφ_C = −k_C T_C/(1 + T_C s) (φ_C − φ_C^d) (Eq. 4.10), sampled exactly (zero-order hold) by the
    engine's first-order filter. The correction turns the chest (reference waist) target about the
    hip–saddle contact point (Eq. 4.9): contribution ``ref:chest_roll`` = Δφ_C.

    ``roll_of(snapshot)`` gives φ_C (chest IMU); φ_C^d = ``target`` (0: upright).
    """

    def __init__(self, roll_of, k_c: float = POSTURE_K_C, t_c: float = POSTURE_T_C, target: float = 0.0,
                 period: float = CONTROL_PERIOD, name: str = "posture"):
        super().__init__(name, period)
        if k_c <= 0 or t_c <= 0:
            raise ValueError("Eq. 4.8 needs k_C > 0 and T_C > 0 (Table 4.4: A positive)")
        self.roll_of, self.k_c, self.t_c, self.target = roll_of, k_c, t_c, target
        self.filter = first_order_gain(k_c * t_c, t_c, period)
        self.delta = 0.0

    def reset(self, snapshot) -> None:
        self.filter.reset()
        self.delta = 0.0

    def step(self, phi_c: float) -> float:
        """One control period: the new Δφ_C for the measured φ_C."""
        self.delta = -float(self.filter(np.array([phi_c - self.target]))[0])
        return self.delta

    def update(self, snapshot):
        delta = self.step(self.roll_of(snapshot))
        self.log(snapshot["t"], **{"posture.delta": delta})
        return {"ref:chest_roll": delta}


# --- small obstacles: pedalling power detection (§4.4.3) ------------------------------------------


def push_down_angle(theta_c: float, theta_init: float = THETA_C_INIT) -> float:
    """The push-down posture reached by back-pedalling (§4.4.3): the largest switching angle
    θ_c^SW = θ_c^init + kπ (Eq. 3.19) not above θ_c. Unique from any impact angle (the crank is periodic)."""
    return theta_init + math.floor((theta_c - theta_init) / math.pi) * math.pi


class PedalLoadDetector:
    """PPDM's detection (Fig. 4.20–4.21; the thesis gives no rule, ours): the summed vertical force
    on both ankle sensors rises above (1 + ``rise``) × its mean over the last ``window_s``, while the
    crank turns slower than ``stall_ratio`` of its commanded rate."""

    def __init__(self, dt: float, rise: float = PPDM_RISE, window_s: float = PPDM_WINDOW_S, stall_ratio: float = 0.5):
        self.rise, self.stall_ratio = rise, stall_ratio
        self.window = deque(maxlen=max(2, int(round(window_s / dt))))

    def reset(self) -> None:
        self.window.clear()

    def step(self, fz_sum: float, crank_rate: float, crank_rate_ref: float) -> bool:
        full = len(self.window) == self.window.maxlen
        mean = float(np.mean(self.window)) if self.window else fz_sum
        hit = (full and fz_sum > (1 + self.rise) * mean and crank_rate_ref > 0
               and crank_rate < self.stall_ratio * crank_rate_ref)
        if not hit:
            self.window.append(fz_sum)
        return hit
