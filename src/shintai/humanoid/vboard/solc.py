"""Sequential Online Learning Control, SOLC (seed 000 §7.4.2, Table 7.7, Figs. 7.17–7.21): SLC while the humanoid
boards the V-BOARD, then MLC speed governing on it, as one :class:`~shintai.core.runtime.Switcher`.

§7.4.2: "SOLCは, MLCとSLCの2つの学習制御系のカスケード結合で構成されており,その結合点となる適応行動の変化点は …
ヒューマノイドの両足が搭乗型機器である平行二輪電動スクーター上に着地した時点とする.着地の状況把握は,図5.5で提案したように
足部搭載の6軸力センサから足裏反力の値を検出し判定を行う." Table 7.7 switches the online search index: SLC's
(∂J(e_τ, δ)/∂D, ρ = D, A = η) during the boarding, MLC's (∂J(v, ω)/∂ρ_n, ρ_n the PID gains, A = diag(η_P, η_I,
η_D)) after it. The switcher's children (4 ms, one active at a time):

* ``init`` — the robot on the floor (and stepping, the AutoBalancer plan runs throughout): no learning, no
  governor; leaves when the left foot lands on its board (f_Lz > F_thre after ≥ ``air_time`` at or below it);
* ``slc`` — Eq. 5.17 on the left-foot pitch D every tick (:class:`SLCPhase`), D₀ = 22 on entry; leaves when the
  right foot lands (f_Rz, likewise), the right pitch taking the learned D;
* ``mlc`` — the speed governor learning its PID gains from 0 (:class:`~shintai.humanoid.learning.mlc.SpeedGovernor`,
  Table 6.6, Eqs. 6.17–6.32); leaves when Eq. 6.32 holds on both axes;
* ``done`` — the same PID with the learned gains, no more learning (:class:`DonePhase`).

The landing guards are :class:`~shintai.humanoid.learning.slc.SLCSchedule`'s (run with ``learn=False`` as a detector, so the
two boardings share one definition). Order within a tick (chosen; Fig. 5.4's
sequence kept): the switcher is a stage of its own between the stabilizer (whose f_Lz, f_Rz of this tick the guards
read) and the damping, so ``slc`` computes D(t+Δt) from the e_τ, δ the damping produced on the previous tick and the
damping then steps with it — δ from D, then D from e_τ and δ, as SLC inside the damping module does, with SLC's
input one 4 ms tick older.
"""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import Module, Switcher
from shintai.humanoid.vboard.boarding import boarding_stack
from shintai.humanoid.learning.mlc import SpeedGovernor
from shintai.humanoid.learning.slc import PITCH, SLC, SLCParams, SLCSchedule
from shintai.humanoid.vboard.governed_ride import mlc_params
from shintai.humanoid.vboard.ride import VboardRide, scooter_spec

PHASES = ("init", "slc", "mlc", "done")
CHANNEL = "foot_pitch"


class Idle(Module):
    """``init``: nothing learns, the governor is off (zero foot-pitch increments)."""

    def __init__(self, name: str = "init", period: float | None = None):
        super().__init__(name, period)

    def update(self, snapshot):
        return {CHANNEL: np.zeros(2)}


class SLCPhase(Module):
    """``slc``: Eq. 5.17 on the left-foot pitch damping gain every tick (Table 7.7's left column); on entry D = D₀.
    ``feet`` is the :class:`~shintai.humanoid.balance.foot_damping.FootDampingModule`'s feet (``"L"``, ``"R"``)."""

    def __init__(self, feet: dict, slc: SLC | None = None, name: str = "slc", period: float | None = None):
        super().__init__(name, period)
        self.feet, self.slc = feet, slc or SLC()
        self.updates = 0

    def reset(self, snapshot) -> None:
        self.feet["L"].D[PITCH] = self.slc.D

    def update(self, snapshot):
        left = self.feet["L"]
        left.D[PITCH] = self.slc.update(left.e_tau[PITCH], left.delta[PITCH])
        self.updates += 1
        self.log(snapshot["t"], **{f"{self.name}.D": left.D[PITCH]})
        return {CHANNEL: np.zeros(2)}


class MLCPhase(SpeedGovernor):
    """``mlc``: the speed governor learning from its initial gains (Table 7.7's right column); on entry the right
    foot's pitch takes the D SLC learned (§5.4.1)."""

    def __init__(self, feet: dict, name: str = "mlc", **kw):
        super().__init__(name=name, **kw)
        self.feet = feet

    def reset(self, snapshot) -> None:
        self.feet["R"].D[PITCH] = self.feet["L"].D[PITCH]


class DonePhase(Module):
    """``done``: the governor's PID with the learned gains, learning off (after Eq. 6.32)."""

    def __init__(self, governor: SpeedGovernor, name: str = "done"):
        super().__init__(name, governor.period)
        self.governor = governor

    def reset(self, snapshot) -> None:
        self.governor.learn = False

    def update(self, snapshot):
        return self.governor.update(snapshot)


def solc_switcher(feet: dict, slc: SLC, governor: MLCPhase, detector: SLCSchedule | None = None,
                  name: str = "solc") -> Switcher:
    """INIT → SLC → MLC → DONE (module docstring). ``detector``: an :class:`SLCSchedule` with ``learn=False`` whose
    state is the landing guards' (default: one on ``slc``'s F_thre and air time)."""
    det = detector or SLCSchedule(SLC(slc.params), learn=False)

    def landed(state: str):
        return lambda snapshot: det.step(snapshot, feet) == state

    transitions = [("init", "slc", landed("learning")), ("slc", "mlc", landed("done")),
                   ("mlc", "done", lambda snapshot: governor.converged)]
    sw = Switcher([Idle(), SLCPhase(feet, slc), governor, DonePhase(governor)], transitions, initial="init", name=name)
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
    :func:`~shintai.humanoid.vboard.boarding.boarding_stack` without its own SLC schedule, ridden on as
    :class:`~shintai.humanoid.vboard.ride.VboardRide` (sensors, foot-pitch integration), the switcher (module
    docstring) as its own stage after the stabilizer; MLC on ``plant``'s K, T (as ``humanoid.speed-governing``).
    ``ride.switcher``, ``ride.governor`` (the ``mlc`` child)."""
    p = params or SLCParams()
    st, _ = boarding_stack(p, v=scooter_spec(theta_o_error_deg), schedule=False)
    ride = VboardRide(level=2, standing=st, theta_o_error_deg=theta_o_error_deg, seed=seed)
    feet = st.damping.feet
    gov = MLCPhase(feet, params=mlc_params(plant, eta_scale))
    ride.switcher = solc_switcher(feet, SLC(p), gov)
    ride.stages.insert(2, [ride.switcher])  # after [references, sensors] and [stabilizer]
    ride.governor = gov
    return ride
