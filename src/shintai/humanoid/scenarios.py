"""Humanoid scenarios of seed 000 ch. 3.

``humanoid.kenshiro-pedaling`` (E8, §3.5.5, Figs. 3.30–3.35): Kenshiro's two planar legs turn the
crank one revolution in MuJoCo, the right leg active first; the active leg follows Eq. 3.7 with the
ankle posture of Eq. 3.21, the passive leg runs Eq. 3.24, and the roles swap at the switching angles
of Eq. 3.19 measured from the feet (method (a)). The revolution ends at the second swap, when the
crank is back at the angle it started from.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from shintai.core.runtime import Loop
from shintai.humanoid.constants import (
    DEG,
    KENSHIRO,
    KENSHIRO_CONTACT_N,
    KENSHIRO_RELAXED_TENDON,
    KENSHIRO_SAMPLE_PERIOD,
    KENSHIRO_SETTLE_S,
    KENSHIRO_SWITCH_LEAD,
    THETA_C_INIT,
)
from shintai.humanoid.kenshiro import (
    SIDE,
    active_leg_plan,
    contact_of,
    crank_angle_from_feet,
    crank_centre,
    foot_force,
    pedal_plan,
    pedalling_switcher,
    sole_normal,
)
from shintai.humanoid.robots.kenshiro import build_kenshiro
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.sim.render import VideoRecorder

LEGS = tuple(SIDE)


def run_revolution(body, switcher, recorder, max_s: float, progress) -> float:
    """Settle, then pedal until the second role swap (or for ``max_s``); log every tick. Returns the
    time pedalling started."""
    for _ in range(int(round(KENSHIRO_SETTLE_S / body.dt))):
        body.step()
    t0 = body.t
    loop = Loop(body, [switcher], recorder=recorder)
    while body.t < t0 + max_s and len(switcher.transitions_log) < 2:
        snap = loop.step()
        recorder.record(snap["t"], crank_true=snap["q:crank"], crank_est=crank_angle_from_feet(snap),
                        fz_left=foot_force(snap, "left")[1], fz_right=foot_force(snap, "right")[1],
                        right_active=float(switcher.active == "right-active"))
        progress(min((body.t - t0) / max_s, 0.99), "pedalling")
    return t0


def unwrap_from(angle: np.ndarray, start: float) -> np.ndarray:
    return np.unwrap(angle) - np.unwrap(angle)[0] + start


def plan_metrics(k) -> dict:
    """Eqs. 3.21–3.23 on both legs' plans: D_th from the actual chords, and the steps meeting Eq. 3.21."""
    steps = [s for leg in LEGS for s in active_leg_plan(leg, k)[:-1]]
    chords = np.linalg.norm(np.diff(pedal_plan("right", k), axis=0), axis=1)
    return {"d_th_m": float(chords.max() * abs(math.cos(k.phi_min))),
            "plan_steps": len(steps),
            "plan_steps_satisfying_3_21": int(sum(s.margin > 0 for s in steps)),
            "plan_pitch_range_deg": [float(min(s.psi for s in steps) / DEG), float(max(s.psi for s in steps) / DEG)]}


def run_metrics(rec, t0: float, swaps: list) -> dict:
    t = rec.times("crank_true")
    true = rec.values("crank_true")
    est = unwrap_from(rec.values("crank_est"), true[0])
    fz = {leg: rec.values(f"fz_{leg}") for leg in LEGS}
    right_active = rec.values("right_active") > 0.5
    m = {"role_swaps": len(swaps), "crank_estimate_error_deg": float(np.abs(est - true).max() / DEG)}
    if len(swaps) >= 2:
        m["revolution_time_s"] = swaps[1][0] - t0
        m["first_half_s"], m["second_half_s"] = swaps[0][0] - t0, swaps[1][0] - swaps[0][0]
        m["crank_advance_deg"] = float((true[np.searchsorted(t, swaps[1][0])] - true[0]) / DEG)
    active = {"right": right_active, "left": ~right_active}
    for leg in LEGS:
        pushing = fz[leg][active[leg]]
        m[f"{leg}_active_peak_fz_n"] = float(pushing.max()) if pushing.size else float("nan")
    active_fz = np.concatenate([fz[leg][active[leg]] for leg in LEGS])
    passive_fz = np.concatenate([fz[leg][~active[leg]] for leg in LEGS])
    m["active_mean_fz_n"] = float(active_fz.mean())
    m["passive_mean_fz_n"] = float(passive_fz.mean())
    m["passive_peak_fz_n"] = float(passive_fz.max())
    m["passive_contact_fraction"] = float(np.mean(passive_fz >= KENSHIRO_CONTACT_N))
    return m


@scenario(
    "humanoid.kenshiro-pedaling",
    source="seed 000 §3.5.5, Eqs. 3.21–3.26",
    summary="E8: Kenshiro's legs pedal one crank revolution, active leg Eq. 3.7 + ankle rule 3.21, passive leg 3.24",
    params=[
        Param("sample_period_s", KENSHIRO_SAMPLE_PERIOD, "time per plan sample i (the thesis's ≈5 s per 18)", lo=0.064,
              hi=1.0),
        Param("k_n_mm_per_n", KENSHIRO.k_n * 1000, "passive update gain K_n of Eq. 3.24 [mm/N]", lo=0.1, hi=10.0),
        Param("relaxed_tendon", KENSHIRO_RELAXED_TENDON, "passive leg's servo stiffness / active leg's", lo=1e-4,
              hi=1.0),
        Param("max_s", 40.0, "give up after this much pedalling [s]", lo=5.0, hi=120.0),
    ],
    checks=[
        Check("d_th_m", ">=", 0.0150, "thesis Eq. 3.23: D_th ≈ 0.015 m (0.01510 with r = 0.1 m, T = 18)"),
        Check("d_th_m", "<=", 0.0152, "thesis Eq. 3.23 (upper side)", name="d_th_upper"),
        Check("role_swaps", "==", 2, "spec §5.4 check 13: half, swap, half — back at the starting switching angle"),
        Check("crank_advance_deg", ">=", 360 - 2 * KENSHIRO_SWITCH_LEAD / DEG,
              "one revolution, the last swap coming at most the switch lead (5°) early"),
        Check("revolution_time_s", ">=", 9.8,
              "thesis ≈14 s (Fig. 3.34) −30 %; our sample period is calibrated on its first half only"),
        Check("revolution_time_s", "<=", 18.2, "thesis ≈14 s +30 %", name="revolution_time_upper"),
        Check("crank_estimate_error_deg", "<=", 5.0,
              "derived: below Δθ_c/2 = 5°, so each swap falls in its own sample (a foot sliding 9 mm along "
              "the pedal already shifts method (a) by 5° at r = 0.1 m)"),
        Check("passive_contact_fraction", ">=", 0.9,
              "thesis §3.3.3: the pulled (passive) leg keeps its unilateral contact with the pedal"),
    ],
    thesis={
        "d_th_m": ThesisValue(0.015, "seed 000 Eq. 3.23", "d_th_m"),
        "revolution_time_s": ThesisValue(14.0, "seed 000 §3.5.5 (0–5 s half, 5–6 s swap, 6–14 s half)",
                                         "revolution_time_s"),
        "first_half_s": ThesisValue(5.0, "seed 000 §3.5.5", "first_half_s"),
        "second_half_s": ThesisValue(9.0, "seed 000 §3.5.5 (swap 5–6 s + half 6–14 s)", "second_half_s"),
        "right_active_peak_fz_n": ThesisValue(310.0, "seed 000 §3.5.5 (right leg stepping, 4–5 s)",
                                              "right_active_peak_fz_n"),
        "left_active_peak_fz_n": ThesisValue(170.0, "seed 000 §3.5.5 (left leg stepping, 8–9 s)",
                                             "left_active_peak_fz_n"),
    },
    video=True,
)
def kenshiro_pedaling(ctx):
    p = ctx.params
    k = dataclasses.replace(KENSHIRO, k_n=p["k_n_mm_per_n"] / 1000)
    body = build_kenshiro(theta_c=THETA_C_INIT, k=k)
    switcher, _ = pedalling_switcher(body, "right", k, p["sample_period_s"], p["relaxed_tendon"])
    metrics = plan_metrics(k)
    ctx.progress(0.05, "plans")
    video = (VideoRecorder(body, ctx.video_path, fps=30, width=480, height=360, track="waist", distance=1.6,
                           azimuth=90.0, elevation=-5.0) if ctx.video else None)
    try:
        t0 = run_revolution(body, switcher, ctx.recorder, p["max_s"], ctx.progress)
    finally:
        if video is not None:
            video.close()
    ctx.sim_time_s = float(body.t)
    metrics.update(run_metrics(ctx.recorder, t0, switcher.transitions_log))
    _plot_forces(ctx, t0, switcher.transitions_log)
    _plot_plan(ctx, k)
    return metrics


def _plot_forces(ctx, t0: float, swaps: list) -> None:
    """Fig. 3.35: the crank angle (top) and the vertical sole forces (bottom), active phases shaded."""
    rec = ctx.recorder
    t = rec.times("crank_true") - t0
    true = rec.values("crank_true")
    est = unwrap_from(rec.values("crank_est"), true[0])
    right_active = rec.values("right_active") > 0.5
    with ctx.figure("force_trace", 2, 1, figsize=(9, 6), sharex=True) as (fig, ax):
        ax[0].plot(t, true / DEG, label="crank joint θ_c")
        ax[0].plot(t, est / DEG, "--", label="estimated from the feet (method (a))")
        ax[0].set_ylabel("crank angle [deg]")
        for leg, color in (("right", "C3"), ("left", "C0")):
            ax[1].plot(t, rec.values(f"fz_{leg}"), color=color, label=f"{leg} foot F_z")
            mask = right_active if leg == "right" else ~right_active
            ax[1].fill_between(t, 0, 1, where=mask, color=color, alpha=0.08, transform=ax[1].get_xaxis_transform(),
                               label=f"{leg} leg active")
        for axis in ax:
            for ts, _, _ in swaps:
                axis.axvline(ts - t0, color="k", lw=0.8, ls=":")
            axis.legend(fontsize=8, loc="upper left")
        ax[1].set_ylabel("vertical force from the pedal [N]")
        ax[1].set_xlabel("time from the start of pedalling [s] (dotted: role swaps, Eq. 3.19)")


def _plot_plan(ctx, k) -> None:
    """The active leg's plan (Eq. 3.7) with the chosen sole orientation and the Eq. 3.21 margin."""
    with ctx.figure("active_plan", 1, 2, figsize=(11, 4.5)) as (fig, ax):
        c = crank_centre(k)
        circle = c[:, None] + k.crank_radius * np.array([np.sin(np.linspace(0, 2 * np.pi, 200)),
                                                         np.cos(np.linspace(0, 2 * np.pi, 200))])
        ax[0].plot(*circle, color="0.7", lw=1)
        steps = active_leg_plan("right", k)
        for i, s in enumerate(steps):
            color = "0.5" if i == len(steps) - 1 else "C2" if s.margin > 0 else "C3"  # p_T has no step
            contact = contact_of(s.p, s.psi)
            sole = np.array([math.cos(s.psi), -math.sin(s.psi)]) * 0.04
            ax[0].plot(*np.array([contact - sole, contact + sole]).T, color=color, lw=2)
            ax[0].arrow(*contact, *(0.03 * sole_normal(s.psi)), width=0.0008, color="0.4")
        ax[0].plot(*np.array([s.p for s in steps]).T, "k.", ms=4)
        ax[0].set_aspect("equal")
        ax[0].set_title("right leg's active plan p_i, soles (green: Eq. 3.21 holds)", fontsize=9)
        ax[0].set_xlabel("x from the hip [m]")
        ax[0].set_ylabel("z from the hip [m]")
        margins = [s.margin + k.d_th for s in steps[:-1]]
        ax[1].bar(range(len(margins)), margins, color=["C2" if s.margin > 0 else "C3" for s in steps[:-1]])
        ax[1].axhline(k.d_th, color="k", ls="--", lw=1, label=f"D_th = {k.d_th * 1000:.2f} mm")
        ax[1].set_xlabel("sample i")
        ax[1].set_ylabel("−(p_{i+1} − p_i)·u_i [m]")
        ax[1].legend(fontsize=8)


from shintai.humanoid import tricycle_scenarios  # noqa: F401,E402
from shintai.humanoid import driving_scenarios  # noqa: F401,E402
from shintai.humanoid import ch4_scenarios  # noqa: F401,E402
