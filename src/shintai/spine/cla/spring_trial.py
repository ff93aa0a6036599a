"""E10's trial (seed 003 §4.5.2, eq. 4.36, Figs. 4.13–4.17): Cla, arms down, every muscle in S mode with
l_0 the basic posture's lengths; a hand bends the spine, holds it and lets go; the spine returns.

One Loop: the :class:`~shintai.spine.scripted.Hand` writes the body's ``hand`` channel (free while the
spring settles, a 0.5 s bend to ``push_deg`` in roll and pitch, held ``push_s``, then released for
``release_s``); :class:`TrialProbe` keeps the snapshots the metrics need and logs the traces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.cla.setup import CLA_VIEW, calibrated, cla_spring, k_s_gain
from shintai.spine.control import CountSpring, Gains, Mode, MuscleControl
from shintai.spine.geometry import uniform_posture, whole_spine
from shintai.spine.robots import CLA, CLA_ARMS_DOWN, CLA_TRUNK_LOADS, E10_BEND_S, E10_LOG_EVERY, E10_SETTLE_S
from shintai.spine.scripted import Hand


class TrialProbe(Module):
    """Keeps the snapshot of the ticks named in ``keep`` (name → tick) and, with ``log``, logs the
    encoder (as length from l_0 [mm]) and the tension every ``E10_LOG_EVERY`` ticks from ``log_from``."""

    def __init__(self, keep: dict[str, int], log_from: int | None, name: str = "probe"):
        super().__init__(name)
        self.at = {tick: key for key, tick in keep.items()}
        self.log_from = log_from
        self.kept: dict[str, Snapshot] = {}
        self.k = 0

    def update(self, snapshot: Snapshot):
        k, self.k = self.k, self.k + 1
        if k in self.at:
            self.kept[self.at[k]] = snapshot
        if self.log_from is not None and k >= self.log_from and (k + 1) % E10_LOG_EVERY == 0:
            self.log(snapshot["t"], length_error_mm=1e3 * snapshot["encoder"], tension_n=snapshot["tension"])
        return None


@dataclass
class SpringTrial:
    """What :func:`trial_metrics` reads after the run."""

    k_s: float  # thesis units
    spring: CountSpring | None
    control: MuscleControl
    probe: TrialProbe


def spring_rig(k_s: float, push_deg: float, push_s: float, release_s: float, law: str, log: bool = True) -> Rig:
    """The trial for a thesis k_s (counts / pulse) under spring ``law`` (:func:`~shintai.spine.cla.setup.cla_spring`)."""
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    spring = cla_spring(law)
    control = MuscleControl(CLA.m, Gains(k_s=k_s_gain(k_s, law)), spring=spring)
    calibrated(body, control)
    control.set_modes(Mode.S)
    dt = body.dt
    settle, bend = int(round(E10_SETTLE_S / dt)), int(round(E10_BEND_S / dt))
    held, free = int(push_s / dt), int(release_s / dt)
    push = np.radians([push_deg, push_deg, 0.0])
    bending = [uniform_posture(push * (k + 1) / bend, CLA.n) for k in range(bend)]
    hand = Hand([None] * settle + bending + [bending[-1]] * held + [None] * free)
    total = settle + bend + held + free
    probe = TrialProbe({"before": settle, "bent": settle + bend + held - 1, "final": total - 1},
                       settle if log else None)
    return Rig(body, modules=[hand, control, probe], duration=total * dt, view=dict(CLA_VIEW, azimuth=120.0),
               state=SpringTrial(k_s, spring, control, probe))


def trial_metrics(body: SpineBody, trial: SpringTrial) -> dict[str, float]:
    """The tension change while bent (total and per unit length of the stretched muscles),
    ``hardening`` (the spring's local stiffness in newtons at the highest tension while bent over
    that at rest; 1 for the newton law), the posture error after the return, and how far the
    tensions at rest are from the spring law."""
    before, bent, final = (trial.probe.kept[key] for key in ("before", "bent", "final"))
    dl = bent["encoder"] - before["encoder"]
    dT = bent["tension"] - before["tension"]
    stretched = dl < -1e-4
    slope = float(np.sum(np.abs(dT[stretched])) / max(np.sum(np.abs(dl[stretched])), 1e-12))
    spring, k_s = trial.spring, trial.k_s
    hardening = 1.0 if spring is None else float(spring.stiffness_n_m(bent["tension"].max(), k_s)
                                                 / spring.stiffness_n_m(0.0, k_s))
    law = np.maximum(trial.control.spring_reference(final["encoder"]), 0.0)
    rest = whole_spine(before["theta"])
    return {"tension_change_n": float(np.sum(np.abs(dT))),
            "tension_per_length_n_mm": slope / 1e3, "hardening": hardening,
            "return_error_deg": float(np.degrees(np.abs(whole_spine(body.theta()) - rest)).max()),
            "spring_law_error_n": float(np.abs(final["tension"] - law).max())}
