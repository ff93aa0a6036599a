"""The passive function: online trajectory acquisition by the online control index (seed 000 §3.4.3,
Eqs. 3.13–3.18, Table 3.3).

A passive manipulator runs position-based impedance control (Eq. 3.13, Nozawa et al. [134])

    M_v (ξ̈ − ξ̈^ref) + D_v (ξ̇ − ξ̇^ref) + K_v (ξ − ξ^ref) = f^msr − f^trg,

so ξ(s) = ξ^ref(s) + (M_v s² + D_v s + K_v)⁻¹ (f^msr − f^trg) (Eq. 3.15), and takes the displaced
position as its next reference (Eq. 3.14):

    ξ^ref(t+Δt) := ξ(t) if ξ(t) ∈ ReachabilityMap, else ξ^ref(t),

which is the trajectory-correction rule ρ ← ρ − A sgn[ρ, x] (x − x_d) (Eqs. 2.14, 3.18) with ρ = ξ^ref,
x = f^msr, x_d = f^trg, sgn = −E (Eq. 3.17) and A = (M_v s² + D_v s + K_v)⁻¹ (Table 3.3). Both
limbs use the core engine (:class:`~shintai.core.search_index.SearchIndex` with
:func:`~shintai.core.search_index.impedance_gain`), whose persistent filter state makes the two
forms identical; the proposal ρ − A f of the engine *is* ξ(t).

f^msr is the environment's force on the end effector in the world frame (pressing down on a pedal
gives f_z > 0, as f^trg = (0, 0, 150) N of Table 3.4 requires; spec §6 item 4).

When the reference is acquired (spec §6 item 2 — the thesis leaves open whether Eq. 3.14 runs every
control tick or once per motion phase): once per passive phase, Fig. 3.16 step 3. The impedance
runs every control tick. [DERIVED] Acquiring every tick h makes ρ integrate the displacement at
rate δ/h; against a contact of stiffness k_e that loop (M h s³ + D h s² + (K + k_e) h s + k_e) is
stable only if D h (K + k_e) > M k_e (Routh), i.e. h ≳ M/D = 20 ms for Table 3.4 and a stiff
pedal — the 4 ms tick fails it, the 0.8 s phase passes.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from shintai.core.search_index import SearchIndex, impedance_gain

PASSIVE_SGN = -np.eye(3)  # Eq. 3.17: raising ξ^ref_i lowers f^msr_i; different axes independent


class PassiveFunction:
    """One passive limb: impedance (Eq. 3.13) and reference acquisition (Eq. 3.14 ≡ Eq. 3.18).

    ``step(f_msr, acquire)`` runs one control tick of length ``dt`` and returns ξ(t) = ξ^ref + δ.
    With ``acquire`` the reference becomes ξ(t) if ``reachable(ξ(t))`` (default: always), else it is
    held (Eq. 3.14 second branch; ``unreachable_holds`` counts those). ``displacement`` is the
    impedance displacement δ = ξ − ξ^ref of the tick (Eq. 3.15), for a caller that moves to a new
    reference over a transition time rather than at once (Fig. 3.16 step 3).
    """

    def __init__(self, xi_ref0, M, D, K, f_trg, dt: float,
                 reachable: Callable[[np.ndarray], bool] | None = None):
        self.reachable = reachable
        self.unreachable_holds = 0
        self.xi = np.asarray(xi_ref0, dtype=float).copy()
        self.displacement = np.zeros(3)
        self._acquire = False
        self.index = SearchIndex(xi_ref0, impedance_gain(M, D, K, dt, axes=3), sgn=PASSIVE_SGN,
                                 x_d=f_trg, hold=self._keep)

    @property
    def xi_ref(self) -> np.ndarray:
        return self.index.rho.copy()

    def _keep(self, xi: np.ndarray) -> bool:
        """The engine's proposal ρ − A f is ξ(t) = ξ^ref + δ (Eq. 3.15): record it, adopt it only
        when acquiring and reachable."""
        self.xi = xi.copy()
        self.displacement = xi - self.index.rho
        if not self._acquire:
            return True
        if self.reachable is not None and not self.reachable(xi):
            self.unreachable_holds += 1
            return True
        return False

    def step(self, f_msr, acquire: bool) -> np.ndarray:
        self._acquire = acquire
        self.index.update(f_msr)
        return self.xi.copy()


class ActiveImpedance:
    """The active limb's impedance (Eq. 3.13 with the active Table 3.4 gains): ξ(t) = X_active^ref(t) +
    (M s² + D s + K)⁻¹ (f^msr − f^trg) (Eq. 3.15). Its reference is the offline plan, never acquired."""

    def __init__(self, M, D, K, f_trg, dt: float):
        self.A = impedance_gain(M, D, K, dt, axes=3)
        self.f_trg = np.asarray(f_trg, dtype=float)

    def step(self, x_ref, f_msr) -> np.ndarray:
        return np.asarray(x_ref, dtype=float) + self.A(np.asarray(f_msr, dtype=float) - self.f_trg)
