"""Why a commanded foot pitch drives our scooter backwards (issue 26 item 1): the sign chain of seed 000 §6.2.2's
speed plant, link by link, on a common-mode foot-pitch step at behaviour level 2.

Two lift-placed level-2 rides (:class:`~shintai.humanoid.vboard.ride.VboardRide`, sensors' noise off), identical
but for a step of ``step_deg`` in the commanded pitch of both soles at ``t_step`` (one tick's increment of u_v,
Eq. 6.5, integrated by :class:`~shintai.humanoid.balance.scooter.FootPitch` as Eq. 6.7); each link is the run with
the step minus the run without it, at :data:`PROBE_AFTER` s after the step (means over ±:data:`PROBE_WINDOW` s).
The links (:data:`LINKS`), in the order the issue names them: commanded pitch → sole pitch → pad (board) pitch →
wheel speed (Eq. A.1) → scooter v and acceleration → CoM relative to the scooter (along its heading) → the CoM
as the stabilizer reads it (its LIP tracking's x) → LIP's p_d → τᵈ (both feet's pitch, + toe) → δ (the damping's
pitch correction, mean of the feet). Used by ``humanoid.vboard-plant-id`` (plot ``sign_chain``, metrics
``chain_*``) and its test."""

from __future__ import annotations

import math

import numpy as np

from shintai.humanoid.balance.foot_attitude import pitch as rot_pitch
from shintai.humanoid.constants import CONTROL_PERIOD
from shintai.humanoid.vboard.constants import (D_VBOARD, PROBE_AFTER, PROBE_STEP_DEG, PROBE_T_STEP, PROBE_WINDOW,
                                             THETA_O_ERROR_DEG, VIEW)
from shintai.humanoid.vboard.ride import VboardRide
from shintai.humanoid.vboard.vehicle import board_pitch, scooter_velocity, wheel_speeds
from shintai.scenarios.experiment import Rig, run_rig

# (key, label, unit scale, unit): the links, in the chain's order
LINKS = (("cmd_pitch", "commanded pitch", 180 / math.pi, "deg"),
         ("sole_pitch", "sole pitch", 180 / math.pi, "deg"),
         ("pad_pitch", "pad (board) pitch", 180 / math.pi, "deg"),
         ("wheel_speed", "wheel speed Ω", 1.0, "rad/s"),
         ("v", "scooter v", 1.0, "m/s"),
         ("acc", "scooter acceleration", 1.0, "m/s²"),
         ("com_rel", "CoM − scooter centre", 1e3, "mm"),
         ("p_d", "LIP's p_d", 1e3, "mm"),
         ("tau_d", "τᵈ pitch (L + R)", 1.0, "N·m"),
         ("delta", "δ pitch", 180 / math.pi, "deg"))


def step_excite(t_step: float, step_deg: float):
    """u(t) → (u_v, 0): one tick's increment of ``step_deg`` (rad) in u_v at the first tick at or after ``t_step``."""
    fired = [False]

    def u(t: float):
        if not fired[0] and t >= t_step - 1e-9:
            fired[0] = True
            return (math.radians(step_deg), 0.0)
        return (0.0, 0.0)
    return u


def chain_rig(step: bool, seed: int = 0, t_step: float = PROBE_T_STEP, step_deg: float = PROBE_STEP_DEG,
              after: float = max(PROBE_AFTER), D: float = D_VBOARD, theta_o_error_deg: float = THETA_O_ERROR_DEG,
              **ride) -> Rig:
    """One ride of the probe: level 2, noise off, with (``step``) or without the step; ``ride``: more
    :class:`VboardRide` options (e.g. ``com_reading``, ``firmware="torque"``)."""
    excite = step_excite(t_step, step_deg) if step else (lambda t: (0.0, 0.0))
    r = VboardRide(level=2, theta_o_error_deg=theta_o_error_deg, D=D, excite=excite, seed=seed, noise=False, **ride)
    body = r.body
    sole = {s: body.id("site", f"{s}_sole") for s in "lr"}
    stab = r.standing.stabilizer

    def record(snapshot):
        d = body.data
        th, w = board_pitch(snapshot), wheel_speeds(snapshot)
        v, _ = scooter_velocity(snapshot)
        h = np.asarray(snapshot["vboard_heading"], float)
        h = h / (np.linalg.norm(h[:2]) + 1e-12)
        rel = d.subtree_com[body.id("body", "waist")] - body.site_pos("vboard_centre")
        delta = np.asarray(snapshot.get("damping_delta", np.zeros(4)), float)
        return {"cmd_pitch": float(np.mean(r.foot_pitch.theta)),
                "sole_pitch": float(np.mean([rot_pitch(d.site_xmat[sole[s]].reshape(3, 3)) for s in "lr"])),
                "pad_pitch": (th["r"] + th["l"]) / 2, "wheel_speed": (w["r"] + w["l"]) / 2, "v": v,
                "com_rel": float(rel[0] * h[0] + rel[1] * h[1]),
                "p_d": float(np.asarray(snapshot["zmp_d"])[0]),
                "tau_d": float(np.asarray(snapshot["tau_d_L"])[1] + np.asarray(snapshot["tau_d_R"])[1]),
                "delta": float((delta[1] + delta[3]) / 2)}
    return Rig(body, stages=r.stages, channels=r.channels, duration=t_step + after + 2 * PROBE_WINDOW + CONTROL_PERIOD,
               until=lambda s: r.fallen(), record={1: record}, view=VIEW, state=r)


def chain_series(run) -> tuple[np.ndarray, dict]:
    """The recorded links of one probe ride (the acceleration as the 4 ms difference of v)."""
    rec = run.log
    t = rec.times("v")
    out = {k: np.asarray(rec.values(k), float) for k, *_ in LINKS if k != "acc"}
    out["acc"] = np.gradient(out["v"], t)
    return t, out


def chain_difference(step_run, base_run, t_step: float = PROBE_T_STEP) -> tuple[np.ndarray, dict]:
    """(t − t_step, {link: step run − base run}) on the common ticks."""
    (ts, s), (tb, b) = chain_series(step_run), chain_series(base_run)
    n = min(len(ts), len(tb))
    return ts[:n] - t_step, {k: s[k][:n] - b[k][:n] for k in s}


def chain_readings(tau, diff, after=PROBE_AFTER, window: float = PROBE_WINDOW) -> dict:
    """{f"chain_{link}_{ms}ms": the difference's mean over ±window at each ``after``} (NaN if the run ended)."""
    out = {}
    for k, *_ in LINKS:
        for a in after:
            m = np.abs(tau - a) <= window + 1e-9
            out[f"chain_{k}_{round(a * 1000)}ms"] = float(np.mean(diff[k][m])) if m.any() else math.nan
    return out


def probe(seed: int = 0, **kw) -> dict:
    """Both rides and the readings: {"tau", "diff", "readings", "fallen"} (``kw``: :func:`chain_rig`'s)."""
    runs = {step: run_rig(chain_rig(step, seed, **kw)) for step in (True, False)}
    tau, diff = chain_difference(runs[True], runs[False], kw.get("t_step", PROBE_T_STEP))
    return {"tau": tau, "diff": diff, "readings": chain_readings(tau, diff),
            "fallen": int(runs[True].state.fallen() or runs[False].state.fallen())}
