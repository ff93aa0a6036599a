"""The V-BOARD's speed governor (seed 000 §6.3.4, Figs. 6.6 and 6.13): the PID of Eq. 6.2 on v and ω with the
prior-value-correcting integrator (Eqs. 6.33–6.39), MLC on its gains every T_L (Eqs. 6.17–6.32,
:mod:`shintai.humanoid.learning.mlc`), and the foot-pitch mixing of Eq. 6.5; gated until learning starts (§6.4.1).
"""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.humanoid.learning.mlc import MLC, MLC_OMEGA, MLC_V
from shintai.humanoid.learning.prior_value_integrator import PID
from shintai.humanoid.learning.speed_governing import foot_pitch_increments, stability_flag

AXES = ("v", "omega")


class SpeedGovernor(Module):
    """Fig. 6.13 for v and ω: PID (Eq. 6.2) with the prior-value-correcting integrator, MLC every T_L, and the
    foot-pitch mixing of Eq. 6.5 to channel ``foot_pitch`` = [Δθ_R, Δθ_L] (additive; the damping module's δ
    adds as the disturbance d). Reads ``v`` and ``omega`` (the filtered speeds) from the snapshot; targets
    ``v_d``/``omega_d`` from the snapshot when present, else 0 (the experiments of §6.4.1).
    ``learn=False`` runs the PID with fixed gains (behaviour level 3 without learning).
    """

    def __init__(self, params=(MLC_V, MLC_OMEGA), gains0=((0.0,) * 3, (0.0,) * 3), mode: str = "corrected",
                 learn: bool = True, channel: str = "foot_pitch", name: str = "speed_governor"):
        super().__init__(name, params[0].dt)
        self.params = dict(zip(AXES, params, strict=True))
        self.pid = {a: PID(p.dt, g, mode) for a, p, g in zip(AXES, params, gains0, strict=True)}
        self.mlc = {a: MLC(p, g) for a, p, g in zip(AXES, params, gains0, strict=True)}
        self.learn = learn
        self.channel = channel

    def update(self, snapshot: Snapshot):
        t = float(snapshot["t"])
        u, signals = {}, {}
        for a in AXES:
            e = float(snapshot.get(f"{a}_d", 0.0)) - float(snapshot[a])
            u[a] = self.pid[a].step(e)  # Eq. 6.2 with the gains in force
            if self.learn and self.mlc[a].observe(e, t):
                self.pid[a].set_gains(self.mlc[a].gains)  # §6.3.4 steps 4–5, effective next sample
            p, pid = self.params[a], self.pid[a]
            signals.update({f"{self.name}.e_{a}": e, f"{self.name}.u_{a}": u[a], f"{self.name}.gains_{a}": pid.gains,
                            f"{self.name}.E_{a}": pid.integrator.E, f"{self.name}.uI_{a}": pid.integrator.u_I,
                            f"{self.name}.stable_{a}": stability_flag(p.K, p.T, pid.gains)})
        self.log(t, **signals)
        return {self.channel: foot_pitch_increments(u["v"], u["omega"])}

    @property
    def converged(self) -> bool:
        return all(m.converged for m in self.mlc.values())


class GatedGovernor(SpeedGovernor):
    """:class:`~shintai.humanoid.vboard.governor.SpeedGovernor` that is off (zero increments, no PID, no learning) until
    ``start(snapshot)`` first holds (§6.4.1: level 2 until learning starts); ``t_start`` is that instant."""

    def __init__(self, start, **kw):
        super().__init__(**kw)
        self.start, self.t_start = start, None

    def update(self, snapshot):
        if self.t_start is None:
            if not self.start(snapshot):
                return {self.channel: np.zeros(2)}
            self.t_start = float(snapshot["t"])
        return super().update(snapshot)
