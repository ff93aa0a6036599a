"""Why behaviour level 2 turned itself about at D = 40 (issue 26 item 5): the soles creeping on the pads.

Two lift-placed level-2 rides (:class:`~shintai.humanoid.vboard.ride.VboardRide`, sensors' noise off), one with
MuJoCo's no-slip passes (the default, :data:`~shintai.humanoid.vboard.constants.NOSLIP_ITERATIONS`) and one without
(``sole_creep=True``: MuJoCo's soft contacts alone, as the rides were before). The chain, each link measured:

1. each sole creeps on its pad (its site's x in the pad's frame, from :data:`CREEP_FROM_S` after the lift lets go);
2. at a steady speed a board carries no torque about its axle, so the pressure stays over the axle and a sole that
   has crept s back reads f_z s more toe torque about its own point: τ_L − τ_R moves by −f̄_z (s_L − s_R);
3. the damping (Eq. 5.1) turns e_τ's difference into δ_R − δ_L, ≈ (T/D)(τ_L − τ_R) once its leak settles;
4. the pads' pitch difference turns the scooter (Eq. A.1, A.3: ≈ 37 rad/s per rad of θ_R − θ_L).

So the soft contacts' differential creep is a ramp input to the turn; with no-slip the soles hold and level 2 keeps
the steady turn that the two sides' θ_O and K of Eq. A.1 give (level 2 has no yaw feedback). Used by
``humanoid.vboard-levels`` (plot ``sole_creep``, metrics ``creep_*``) and its test."""

from __future__ import annotations

import numpy as np

from shintai.humanoid.constants import CONTROL_PERIOD
from shintai.humanoid.vboard.constants import (CREEP_FROM_S, CREEP_RECORD_EVERY, CREEP_S, D_VBOARD, THETA_O_ERROR_DEG,
                                             VIEW)
from shintai.humanoid.vboard.ride import VboardRide
from shintai.humanoid.vboard.vehicle import scooter_velocity
from shintai.scenarios.experiment import Rig, run_rig

RIDES = ("noslip", "creep")  # MuJoCo's no-slip passes on (the default) / off (soft contacts alone)


def creep_rig(creep: bool, seed: int = 0, duration: float = CREEP_S, D: float = D_VBOARD) -> Rig:
    """One ride of the probe: level 2, noise off, the soles held (``creep=False``) or creeping."""
    r = VboardRide(level=2, theta_o_error_deg=THETA_O_ERROR_DEG, D=D, seed=seed, noise=False, sole_creep=creep)
    body = r.body
    sole = {s: body.id("site", f"{s}_sole") for s in "lr"}
    pad = {s: body.id("site", f"board_{s}_top") for s in "lr"}

    def on_pad(s: str) -> float:  # the sole's x on its pad, in the pad's frame
        d = body.data
        return float(d.site_xmat[pad[s]].reshape(3, 3)[:, 0] @ (d.site_xpos[sole[s]] - d.site_xpos[pad[s]]))

    def record(snapshot):
        _, w = scooter_velocity(snapshot)
        delta = np.asarray(snapshot["damping_delta"], float)
        return {"sole_l": on_pad("l"), "sole_r": on_pad("r"), "omega": w,
                "tau_diff": float(snapshot["tau_L"][1] - snapshot["tau_R"][1]),
                "f_z": 0.5 * float(snapshot["f_Lz"] + snapshot["f_Rz"]),
                "delta_diff": float(delta[3] - delta[1])}
    return Rig(body, stages=r.stages, channels=r.channels, duration=duration + CONTROL_PERIOD,
               until=lambda s: r.fallen(), record={CREEP_RECORD_EVERY: record}, view=VIEW, state=r)


def readings(run, name: str) -> dict:
    """{f"creep_{what}_{name}": …}: each sole's creep and their difference (mm), the torque difference's change and
    the part of it the creep gives (N·m), the turn at the end (mean of the last second) and at most (rad/s)."""
    rec = run.log
    t = np.asarray(rec.times("omega"))
    col = {k: np.asarray(rec.values(k), float) for k in ("sole_l", "sole_r", "omega", "tau_diff", "f_z")}
    t0 = run.state.lift.t_release + CREEP_FROM_S
    i = int(np.searchsorted(t, t0))
    if i >= len(t) - 1:
        raise ValueError(f"sole creep probe: the ride ended at {t[-1]:.2f} s, before its window from {t0:.2f} s")
    ds = {s: float(col[f"sole_{s}"][-1] - col[f"sole_{s}"][i]) for s in "lr"}
    tail = t >= t[-1] - 1.0
    return {f"creep_sole_l_mm_{name}": 1e3 * ds["l"], f"creep_sole_r_mm_{name}": 1e3 * ds["r"],
            f"creep_diff_mm_{name}": 1e3 * (ds["l"] - ds["r"]),
            f"creep_tau_diff_change_nm_{name}": float(col["tau_diff"][-1] - col["tau_diff"][i]),
            f"creep_tau_diff_from_creep_nm_{name}": -float(np.mean(col["f_z"][i:])) * (ds["l"] - ds["r"]),
            f"creep_omega_final_{name}": float(np.mean(col["omega"][tail])),
            f"creep_max_abs_omega_{name}": float(np.max(np.abs(col["omega"][i:]))),
            f"creep_fallen_{name}": int(run.state.fallen())}


def probe(seed: int = 0, duration: float = CREEP_S) -> dict:
    """Both rides and their readings: {"runs": {ride: Run}, "readings": {…}}."""
    runs = {name: run_rig(creep_rig(name == "creep", seed, duration)) for name in RIDES}
    out = {}
    for name, run in runs.items():
        out.update(readings(run, name))
    return {"runs": runs, "readings": out}
