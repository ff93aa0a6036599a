"""SGD-based open-loop Learning Control, SLC (seed 000 §5.3–5.4.1, Eqs. 5.4–5.19, Tables 5.1–5.2).

SLC tunes the damping gain D of the foot torque damping controller C_τ(s) = T / (D (1 + T s)) (Eq. 5.3,
:mod:`shintai.humanoid.balance.foot_damping`) every control period while the humanoid boards the scooter.

* cost, no batch (Eq. 5.4):        J_τ(D) = ½ (Q e_τ(t)² + R δ(t)²)
* gradient (Eqs. 5.5–5.13): the loop is cut virtually (Fig. 5.3). Holding e_τ fixed (Eq. 5.7) gives
  ∂δ/∂D = (∂C_τ/∂D) e_τ = −δ/D (Eqs. 5.8, 5.11); holding δ fixed (Eq. 5.9) gives
  ∂e_τ/∂D = −(1/C_τ)(∂C_τ/∂D) e_τ = e_τ/D (Eqs. 5.10, 5.12); hence
                                   ∇J_τ(D) = Q e_τ²/D − R δ²/D          (Eq. 5.13)
* update (Eq. 5.14):               D := D − η ∇J_τ(D)
  with Q′ = ηQ and R′ = ηR (Eqs. 5.15–5.16):
                                   D := D − Q′ e_τ²/D + R′ δ²/D          (Eq. 5.17)
  Q′ and R′ involve neither T nor Δt: the thesis's gradient is instantaneous (no time integral), and the
  4 ms period enters only as the rate at which Eq. 5.17 is applied (§5.3.1).
* as an online search index (Eqs. 5.18–5.19, Table 5.1): x = (e_τ, δ)ᵀ, x_d = 0, W = ½ diag(Q, R),
  ρ = D, A = η — it runs on :class:`shintai.core.search_index.SearchIndex` (Eq. 2.13) below.
* schedule (§5.4.1, Fig. 5.5): on the left-foot pitch only; start "at the first foot placement onto the
  scooter" when f_Lz > F_thre, stop "at the right foot's placement on the other board" when f_Rz > F_thre,
  F_thre = 25 N; the roll gains stay at 22.0 and the right-foot pitch takes the learned D.

Choices where the thesis is silent (each tested):
* the guards fire on *landings*, i.e. on f_z rising through F_thre. Read as levels, the start guard would hold
  while both feet stand on the floor (Phase 1) and the stop guard the moment SLC starts, because the right
  foot is still on the floor then (Phase 3);
* a landing is a *foot placement* (§5.4.1's 足配置): f_z rises through F_thre after the foot has been in the
  air, f_z ≤ F_thre without a break for at least ``air_time`` (default :data:`SLC_AIR_TIME`). A foot
  unloading before it lifts reads f_z jittering about F_thre (HRP2 boarding the V-BOARD: f_Lz 25.2 → 24.8 →
  25.3 → 24.7 N at t = 1.20 s, the real landing at 1.98 s; the right foot rattles 12 ↔ 54 N in 4–8 ms
  bounces as it lifts): read as rising edges only, those fired SLC 0.8 s early and stopped it on the
  right foot's lift-off;
* the right-foot pitch takes the learned D once, when SLC stops (its foot is in the air while SLC runs);
* D has no lower bound in the thesis, yet divides Eqs. 5.1 and 5.17: an update that would take D below
  ``D_min`` (default 1.0) is refused and D kept (the engine's ``hold``, as Eq. 3.14 keeps a reference);
* order within one step: δ(t) from D(t) (Eq. 5.1), then D(t+Δt) from e_τ(t), δ(t) (Fig. 5.4 steps 1–3); D reaches
  the damping on a channel with a one-tick delay (:class:`SLCSchedule`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.core.search_index import MatrixGain, QuadraticCost, SearchIndex
from shintai.humanoid.constants import (
    F_THRE,  # landing threshold of the start/stop guards (§5.4.1)
    SLC_AIR_TIME,
    SLC_D0,
    SLC_D_MIN,
    SLC_ETA,
    SLC_ETA_MAX,
    SLC_Q,
    SLC_R,
)
from shintai.humanoid.balance.foot_damping import GAIN  # the channel SLC writes: D as [L roll, L pitch, R roll, R pitch]
from shintai.humanoid.law_params import check_real


def slc_cost(e_tau, delta, Q: float = SLC_Q, R: float = SLC_R):
    """J_τ = ½ (Q e_τ² + R δ²) (Eq. 5.4)."""
    return 0.5 * (Q * np.square(e_tau) + R * np.square(delta))


def slc_gradient(e_tau, delta, D, Q: float = SLC_Q, R: float = SLC_R):
    """∇J_τ(D) = Q e_τ²/D − R δ²/D (Eq. 5.13)."""
    return (Q * np.square(e_tau) - R * np.square(delta)) / D


def slc_update(D, e_tau, delta, Q_prime: float, R_prime: float):
    """D − Q′ e_τ²/D + R′ δ²/D (Eq. 5.17)."""
    return D - Q_prime * np.square(e_tau) / D + R_prime * np.square(delta) / D


@dataclass(frozen=True)
class SLCParams:
    """Table 5.2 and §5.4.1; every field checked (one ValueError line naming it). Table 5.2's T = 1.5 s belongs
    to the damping controller (:data:`shintai.humanoid.constants.DAMPING_T`): Eq. 5.17 does not use it."""

    D0: float = SLC_D0
    Q: float = SLC_Q
    R: float = SLC_R
    eta: float = SLC_ETA
    F_thre: float = F_THRE
    D_min: float = SLC_D_MIN
    air_time: float = SLC_AIR_TIME

    def __post_init__(self):
        check_real("D0", self.D0, 0.0, low_open=True)
        check_real("Q", self.Q, 0.0, low_open=True)
        check_real("R", self.R, 0.0, low_open=True)
        check_real("eta", self.eta, 0.0, SLC_ETA_MAX, low_open=True)
        check_real("F_thre", self.F_thre, 0.0)
        check_real("D_min", self.D_min, 0.0, self.D0, low_open=True)
        check_real("air_time", self.air_time, 0.0)

    @property
    def Q_prime(self) -> float:
        """Q′ = ηQ (Eq. 5.15)."""
        return self.eta * self.Q

    @property
    def R_prime(self) -> float:
        """R′ = ηR (Eq. 5.16)."""
        return self.eta * self.R


class SLC:
    """The SLC learning law on the shared engine: ρ = D, x = (e_τ, δ), A = η (Table 5.1, Eq. 2.13).

    ``update(e_tau, delta)`` applies Eq. 5.14 ≡ Eq. 5.17 once and returns the new D.
    """

    def __init__(self, params: SLCParams | None = None):
        self.params = p = params or SLCParams()
        self.cost = QuadraticCost(W=0.5 * np.diag([p.Q, p.R]), x_d=np.zeros(2))  # Eq. 5.18
        self.index = SearchIndex(p.D0, MatrixGain([[p.eta]]), gradient=self._gradient,
                                 hold=lambda D: bool(D[0] < p.D_min))

    def _gradient(self, x: np.ndarray, rho: np.ndarray) -> np.ndarray:
        return np.array([slc_gradient(x[0], x[1], rho[0], self.params.Q, self.params.R)])

    @property
    def D(self) -> float:
        return float(self.index.rho[0])

    def J(self, e_tau: float, delta: float) -> float:
        """J_τ through the engine's quadratic cost (Eq. 2.10 with Eq. 5.18) — equal to Eq. 5.4."""
        return self.cost(np.array([e_tau, delta]))

    def update(self, e_tau: float, delta: float) -> float:
        check_real("e_tau", e_tau)
        check_real("delta", delta)
        return float(self.index.update(np.array([e_tau, delta]))[0])


PITCH = 1  # index of pitch in FootDamping's (roll, pitch)
WINDOW = ("waiting", "learning", "done")  # the states of the SLC window, coded 0, 1, 2 on a ``window`` channel


class LandingWindow:
    """When SLC runs during boarding (§5.4.1, Fig. 5.5): ``waiting`` → (left foot lands: f_Lz rises through
    F_thre after ≥ ``air_time`` at or below it) → ``learning`` → (right foot lands, likewise on f_Rz) → ``done``.
    ``step(snapshot)`` reads ``f_Lz`` and ``f_Rz`` (N) and returns the state; ``t_start``, ``t_stop`` the landings."""

    def __init__(self, params: SLCParams | None = None):
        self.params = params or SLCParams()
        self.state = "waiting"
        self.t_start: float | None = None
        self.t_stop: float | None = None
        self._prev: dict[str, float] | None = None
        self._below_since: dict[str, float | None] = {"f_Lz": None, "f_Rz": None}  # start of the run ≤ F_thre

    @property
    def duration(self) -> float | None:
        """SLC run time (thesis ≈1.2 s, §5.4.2), once stopped."""
        return None if self.t_stop is None else self.t_stop - self.t_start

    def _landed(self, key: str, f: float, t: float) -> bool:
        """f rises through F_thre after the foot was in the air (≤ F_thre for ≥ ``air_time``)."""
        p = self.params
        since = self._below_since[key]
        return (self._prev is not None and self._prev[key] <= p.F_thre < f and since is not None
                and t - since >= p.air_time - 1e-9)

    def step(self, snapshot: Snapshot) -> str:
        f = {k: float(snapshot[k]) for k in ("f_Lz", "f_Rz")}
        t = float(snapshot["t"])
        landed = {k: self._landed(k, f[k], t) for k in f}
        for k, value in f.items():  # the runs of f ≤ F_thre (in the air or unloading)
            if value > self.params.F_thre:
                self._below_since[k] = None
            elif self._below_since[k] is None:
                self._below_since[k] = t
        if self.state == "waiting" and landed["f_Lz"]:
            self.state, self.t_start = "learning", t
        elif self.state == "learning" and landed["f_Rz"]:
            self.state, self.t_stop = "done", t
        self._prev = f
        return self.state


class SLCSchedule(Module):
    """SLC on the foot damping's left-foot pitch gain during its window (§5.4.1), as a module of the stack.

    Reads the damping's ``e_tau`` and ``damping_delta`` ([L roll, L pitch, R roll, R pitch]) of this tick and
    writes D on channel ``damping_gain`` (same layout), which the damping reads one tick later (declared
    delay): Fig. 5.4 runs steps 1–3 every 4 ms on the search variables (e_τ(t), δ(t)) the damping controller
    C_τ(s) just produced with the current D, and the updated D "updates C_τ(s)" for its next step — δ(t) from
    D(t), then D(t+Δt) from e_τ(t), δ(t). Every stack runs this one order, with this module in a stage after
    the damping. ``D`` is the gains it writes, starting at D₀ on every axis (Table 5.2, §5.4.1: the roll stays
    at D₀); while learning the left pitch follows Eq. 5.17, at ``done`` the right pitch takes the learned value.

    The window is its own :class:`LandingWindow` (``window=None``), or the state (0, 1, 2 of :data:`WINDOW`)
    a switcher writes on the set channel named ``window`` (SOLC, §7.4.2). ``learn=False`` keeps the window
    and writes nothing (D = D₀ throughout: the fixed-D run of Figs. 5.6 and 5.8-(a1–d1)).
    """

    def __init__(self, slc: SLC | None = None, learn: bool = True, window: str | None = None, name: str = "slc",
                 period: float | None = None):
        super().__init__(name, period)
        self.slc = slc or SLC()
        self.learn = bool(learn)
        self.window = window
        self.landings = LandingWindow(self.slc.params) if window is None else None
        self.state = "waiting"
        self.D = np.full(4, self.slc.params.D0)
        self.updates = 0

    @property
    def t_start(self) -> float | None:
        return self.landings.t_start

    @property
    def t_stop(self) -> float | None:
        return self.landings.t_stop

    @property
    def duration(self) -> float | None:
        return self.landings.duration

    def update(self, snapshot: Snapshot):
        if self.window is None:
            state = self.landings.step(snapshot)
        else:
            state = WINDOW[int(snapshot[self.window])]
        entered, self.state = state != self.state, state
        if self.learn:
            if entered and state == "learning":
                self.D[PITCH] = self.slc.D
            elif entered and state == "done":
                self.D[2 + PITCH] = self.slc.D
            if state == "learning":
                self.D[PITCH] = self.slc.update(snapshot["e_tau"][PITCH], snapshot["damping_delta"][PITCH])
                self.updates += 1
        self.log(snapshot["t"], **{f"{self.name}.D_L": self.D[PITCH], f"{self.name}.D_R": self.D[2 + PITCH]})
        return {GAIN: self.D.copy()} if self.learn else None
