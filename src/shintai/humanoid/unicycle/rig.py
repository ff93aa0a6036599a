"""The ``humanoid.unicycle-*`` scenarios' rig and metrics (seed 000 §7.3.3, Figs. 7.7, 7.9–7.10, 7.13):
one :class:`~shintai.humanoid.unicycle.ride.NinebotRide` per run, times from the lift's release."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from shintai.humanoid.unicycle.constants import P0_M, TAIL_S, V_DIVERGED, V_SETTLED, VBOARD_V_KP_KD, VIEW
from shintai.humanoid.unicycle.ride import NinebotRide
from shintai.humanoid.unicycle.vehicle import NINEBOT
from shintai.scenarios.experiment import Rig
from shintai.scenarios.registry import Param

P0_PARAM = Param("p0_m", P0_M, "the Ninebot firmware's moment zero point p⁰, x from the axle [m] (ours; the rider's "
                 "mass centre is placed over the axle)", lo=-0.1, hi=0.1)


def unicycle_rig(duration: float, seed: int, p0: float = P0_M, **ride_kw) -> Rig:
    """A run of ``duration`` s after the release on the Ninebot with moment zero point ``p0`` (m), ending at a fall."""
    ride = NinebotRide(seed=seed, n=replace(NINEBOT, p0=p0), **ride_kw)

    def until(snapshot) -> bool:
        return ride.fallen() or float(snapshot["t"]) >= ride.t0 + duration
    return Rig(ride.body, stages=ride.stages, channels=ride.channels, duration=duration + 5.0, until=until,
               record={5: ride.signals}, view=VIEW, state=ride)


def series(log, name):
    return (log.times(name), log.values(name)) if name in log.names() else (np.zeros(0), np.zeros(0))


def zmp_errors(run, t0: float) -> tuple[float, float, np.ndarray, np.ndarray, np.ndarray]:
    """RMS of final target ZMP x (p^{d**}, the stabilizer's p_d) minus the measured ZMP x over the first 2 s after
    the release and over the last 2 s; and the series (t from release, target, measured)."""
    t, zd = series(run.log, "stabilizer.zmp_d")
    _, za = series(run.log, "stabilizer.zmp_act")
    if not t.size:
        return math.nan, math.nan, t, t, t
    zd, za = zd.reshape(-1, 2)[:, 0], za.reshape(-1, 2)[:, 0]
    t = t - t0
    err = zd - za
    first = (t >= 0) & (t < TAIL_S) & np.isfinite(err)
    last = (t >= t[-1] - TAIL_S) & np.isfinite(err)
    rms = lambda m: float(np.sqrt(np.mean(err[m] ** 2))) if m.any() else math.nan  # noqa: E731
    return rms(first), rms(last), t, zd, za


def summary(run) -> dict:
    """Metrics of one run (module docstring)."""
    ride, log = run.state, run.log
    t0 = ride.t0
    t, v = log.times("true_v") - t0, log.values("true_v")
    after = t >= 0
    out = {"fallen": int(ride.fallen()), "t_release_s": t0, "ride_s": float(ride.body.t - t0)}
    fast = np.flatnonzero(after & (np.abs(v) > V_DIVERGED))
    out["speed_diverged"] = int(fast.size > 0)
    out["t_speed_03_s"] = float(t[fast[0]]) if fast.size else math.nan
    out["max_abs_v_mps"] = float(np.max(np.abs(v[after]))) if after.any() else math.nan
    above = np.flatnonzero(after & (np.abs(v) >= V_SETTLED))
    settled = after & (np.arange(t.size) > (above[-1] if above.size else -1))
    out["t_settled_s"] = float(t[settled][0]) if settled.any() and not ride.fallen() else math.nan
    tail = t >= t[-1] - TAIL_S
    out["final_v_mps"] = float(np.mean(v[tail]))
    out["final_abs_v_mps"] = float(np.mean(np.abs(v[tail])))
    x = log.values("x")
    out["travel_m"] = float(x[-1] - np.interp(0.0, t, x))
    out["max_abs_roll_deg"] = float(np.degrees(np.max(np.abs(log.values("roll")[after])))) if after.any() else 0.0
    out["correction_final_m"] = float(log.values("zmp_mod")[-1])
    first, last, *_ = zmp_errors(run, t0)
    out["zmp_error_first_mm"], out["zmp_error_last_mm"] = first * 1e3, last * 1e3
    for mod, key in ((ride.traj, "traj"), (ride.speed, "v")):
        if mod is None:
            continue
        g = mod.pid.gains
        for name, value in zip(("K_P", "K_I", "K_D"), g, strict=True):
            out[f"{key}_{name}"] = float(value)
        b = mod.mlc.batches
        out[f"{key}_batches"] = len(b)
        out[f"{key}_J_first"] = b[0].J if b else math.nan
        out[f"{key}_J_last"] = b[-1].J if b else math.nan
        out[f"{key}_converged"] = int(mod.mlc.converged)
    if ride.traj is not None:
        g = ride.traj.pid.gains
        out["traj_kp_dominant"] = int(g[0] > g[1] and g[0] > g[2])
        # "K_P^v, K_D^v の学習値は平行二輪電動スクーターでの学習値の 10 分の 1 未満": the largest ratio, gain by gain,
        # against both V-BOARD runs
        kp, kd = ride.speed.pid.gains[0], ride.speed.pid.gains[2]
        out["v_gain_ratio_to_vboard"] = float(max(max(kp / vp, kd / vd) for vp, vd in VBOARD_V_KP_KD.values()))
    return out


