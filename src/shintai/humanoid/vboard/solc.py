"""Sequential Online Learning Control, SOLC (seed 000 §7.4.2, Table 7.7, Figs. 7.17–7.21): SLC while the humanoid
boards the V-BOARD, then MLC speed governing on it, as one :class:`~shintai.core.runtime.Switcher`.

§7.4.2: "SOLCは, MLCとSLCの2つの学習制御系のカスケード結合で構成されており,その結合点となる適応行動の変化点は …
ヒューマノイドの両足が搭乗型機器である平行二輪電動スクーター上に着地した時点とする.着地の状況把握は,図5.5で提案したように
足部搭載の6軸力センサから足裏反力の値を検出し判定を行う." Table 7.7 switches the online search index: SLC's
(∂J(e_τ, δ)/∂D, ρ = D, A = η) during the boarding, MLC's (∂J(v, ω)/∂ρ_n, ρ_n the PID gains, A = diag(η_P, η_I,
η_D)) after it. The switcher's children (4 ms, one active at a time):

* ``init`` — the robot on the floor (and stepping, the AutoBalancer plan runs throughout): no learning, no
  governor; leaves when the left foot lands on its board (f_Lz > F_thre after ≥ ``air_time`` at or below it);
* ``slc`` — SLC's window: Eq. 5.17 on the left-foot pitch D every tick, D₀ = 22 on entry; leaves when the right
  foot lands (f_Rz, likewise), the right pitch taking the learned D;
* ``mlc`` — the speed governor learning its PID gains from 0 (:class:`~shintai.humanoid.vboard.governor.SpeedGovernor`,
  Table 6.6, Eqs. 6.17–6.32); leaves when Eq. 6.32 holds on both axes;
* ``done`` — the same PID with the learned gains, no more learning (:class:`DonePhase`).

The landing guards are :class:`~shintai.humanoid.learning.slc.LandingWindow`'s (the boarding's own). The switcher
is the stack's supervisor slot (after the stabilizer, whose f_Lz, f_Rz of this tick the guards read); each phase writes SLC's window state on ``slc_window``, and
SLC itself is the boarding stack's :class:`~shintai.humanoid.learning.slc.SLCSchedule` after the damping, the one
writer of D — in the tick order of Fig. 5.4 that every stack runs: δ(t) from D(t), then D(t+Δt) from e_τ(t), δ(t).
"""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import SET, Module, Switcher, declare
from shintai.humanoid.learning.slc import WINDOW, LandingWindow, SLCParams
from shintai.humanoid.vboard.boarding import boarding_stack
from shintai.humanoid.vboard.governed_ride import mlc_params
from shintai.humanoid.vboard.governor import SpeedGovernor
from shintai.humanoid.vboard.ride import VboardRide, scooter_spec

PHASES = ("init", "slc", "mlc", "done")
CHANNEL = "foot_pitch"
SLC_WINDOW = "slc_window"  # the phase as SLC's window state (0, 1, 2 of slc.WINDOW), written by the active phase
CHANNELS = declare(SLC_WINDOW, kind=SET)


def window(state: str) -> dict:
    return {SLC_WINDOW: float(WINDOW.index(state))}


class Idle(Module):
    """``init``: nothing learns, the governor is off (zero foot-pitch increments)."""

    def __init__(self, name: str = "init", period: float | None = None):
        super().__init__(name, period)

    def update(self, snapshot):
        return {CHANNEL: np.zeros(2), **window("waiting")}


class SLCPhase(Module):
    """``slc``: SLC's window is open (Table 7.7's left column); the governor is off."""

    def __init__(self, name: str = "slc", period: float | None = None):
        super().__init__(name, period)

    def update(self, snapshot):
        return {CHANNEL: np.zeros(2), **window("learning")}


class MLCPhase(SpeedGovernor):
    """``mlc``: the speed governor learning from its initial gains (Table 7.7's right column); SLC's window is
    closed, the right foot's pitch holding the D SLC learned (§5.4.1)."""

    def __init__(self, name: str = "mlc", **kw):
        super().__init__(name=name, **kw)

    def update(self, snapshot):
        return {**super().update(snapshot), **window("done")}


class DonePhase(Module):
    """``done``: the governor's PID with the learned gains, learning off (after Eq. 6.32)."""

    def __init__(self, governor: SpeedGovernor, name: str = "done"):
        super().__init__(name, governor.period)
        self.governor = governor

    def reset(self, snapshot) -> None:
        self.governor.learn = False

    def update(self, snapshot):
        return {**self.governor.update(snapshot), **window("done")}


def solc_switcher(params: SLCParams, governor: MLCPhase, detector: LandingWindow | None = None,
                  name: str = "solc") -> Switcher:
    """INIT → SLC → MLC → DONE (module docstring). ``detector``: the landing guards (default: a
    :class:`LandingWindow` on ``params``' F_thre and air time)."""
    det = detector or LandingWindow(params)

    def landed(state: str):
        return lambda snapshot: det.step(snapshot) == state

    transitions = [("init", "slc", landed("learning")), ("slc", "mlc", landed("done")),
                   ("mlc", "done", lambda snapshot: governor.converged)]
    sw = Switcher([Idle(), SLCPhase(), governor, DonePhase(governor)], transitions, initial="init", name=name)
    sw.detector = det
    return sw


def switch_times(sw: Switcher) -> dict[str, float]:
    """When each phase began (s), from the switcher's log (NaN if never reached); ``init`` at 0."""
    out = {p: float("nan") for p in PHASES}
    out["init"] = 0.0
    for t, _src, dst in sw.transitions_log:
        out[dst] = t
    return out


def solc_ride(plant: dict, theta_o_error_deg: float = 0.0, eta_scale: float = 1.0, seed: int = 0,
              params: SLCParams | None = None):
    """HRP2 on the floor before the V-BOARD running SOLC: the boarding stack of
    :func:`~shintai.humanoid.vboard.boarding.boarding_stack` with SLC on the switcher's window, ridden on as
    :class:`~shintai.humanoid.vboard.ride.VboardRide` (sensors, foot-pitch integration) with the switcher
    (module docstring) in its supervisor slot; MLC on ``plant``'s K, T (as ``humanoid.speed-governing``).
    ``ride.switcher``, ``ride.governor`` (the ``mlc`` child), ``ride.slc`` (SLC, the writer of D)."""
    p = params or SLCParams()
    st, slc = boarding_stack(p, v=scooter_spec(theta_o_error_deg), window=SLC_WINDOW)
    gov = MLCPhase(params=mlc_params(plant, eta_scale))
    switcher = solc_switcher(p, gov)
    ride = VboardRide(level=2, standing=st, theta_o_error_deg=theta_o_error_deg, seed=seed, supervisor=switcher)
    ride.switcher, ride.governor, ride.slc = switcher, gov, slc
    ride.channels = ride.channels + list(CHANNELS.values())
    return ride
