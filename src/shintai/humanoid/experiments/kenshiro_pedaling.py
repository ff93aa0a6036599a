"""``humanoid.kenshiro-pedaling``: E8, Kenshiro's two planar legs turn the crank one revolution in MuJoCo
(seed 000 §3.5.5, Figs. 3.30–3.35): the active leg Eq. 3.7 with the ankle rule of Eq. 3.21, the passive leg
Eq. 3.24, the roles swapping at Eq. 3.19's angles measured from the feet."""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np

from shintai.core.geometry import unwrap_from
from shintai.humanoid.constants import (
    DEG,
    KENSHIRO,
    KENSHIRO_CONTACT_N,
    KENSHIRO_DELTA_F,
    KENSHIRO_DELTA_F_READINGS,
    KENSHIRO_RELAXED_TENDON,
    KENSHIRO_SAMPLE_PERIOD,
    KENSHIRO_SWITCH_LEAD,
    THETA_C_INIT,
)
from shintai.humanoid.robots.kenshiro import build_kenshiro
from shintai.humanoid.tricycle import plots
from shintai.humanoid.tricycle.kenshiro import (
    SIDE,
    active_leg_plan,
    crank_angle_from_feet,
    foot_force,
    pedal_plan,
    pedalling_switcher,
    settle,
)
from shintai.scenarios.experiment import Rig
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment

LEGS = tuple(SIDE)
VIEW = {"fps": 30, "track": "waist", "distance": 1.6, "azimuth": 90.0, "elevation": -5.0}


def spec(params):
    return dataclasses.replace(KENSHIRO, k_n=params["k_n_mm_per_n"] / 1000)


def rig(params, variant, seed):
    """Settle, then pedal until the second role swap (or for ``max_s``), recording every tick."""
    k = spec(params)
    body = build_kenshiro(theta_c=THETA_C_INIT, k=k)
    switcher, _ = pedalling_switcher(body, "right", k, params["sample_period_s"], params["relaxed_tendon"],
                                     params["delta_f"])
    settle(body)

    def signals(snap):
        return {"crank_true": snap["q:crank"], "crank_est": crank_angle_from_feet(snap),
                "fz_left": foot_force(snap, "left")[1], "fz_right": foot_force(snap, "right")[1],
                "right_active": float(switcher.active == "right-active")}

    return Rig(body, [switcher], duration=params["max_s"], until=lambda s: len(switcher.transitions_log) >= 2,
               record={1: signals}, view=VIEW, state=SimpleNamespace(t0=body.t, swaps=switcher.transitions_log))


def plan_metrics(k) -> dict:
    """Eqs. 3.21–3.23 on both legs' plans: D_th from the actual chords, and the steps meeting Eq. 3.21."""
    steps = [s for leg in LEGS for s in active_leg_plan(leg, k)[:-1]]
    chords = np.linalg.norm(np.diff(pedal_plan("right", k), axis=0), axis=1)
    return {"d_th_m": float(chords.max() * abs(math.cos(k.phi_min))),
            "plan_steps": len(steps),
            "plan_steps_satisfying_3_21": int(sum(s.margin > 0 for s in steps)),
            "plan_pitch_range_deg": [float(min(s.psi for s in steps) / DEG), float(max(s.psi for s in steps) / DEG)]}


def metrics(runs, params):
    run = runs["run"]
    rec, t0, swaps = run.log, run.state.t0, run.state.swaps
    t = rec.times("crank_true")
    true = rec.values("crank_true")
    est = unwrap_from(rec.values("crank_est"), true[0])
    fz = {leg: rec.values(f"fz_{leg}") for leg in LEGS}
    right_active = rec.values("right_active") > 0.5
    m = {**plan_metrics(spec(params)), "role_swaps": len(swaps),
         "crank_estimate_error_deg": float(np.abs(est - true).max() / DEG)}
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


def draw(ctx, runs, params):
    run = runs["run"]
    plots.kenshiro_forces(ctx, run.log, run.state.t0, run.state.swaps)
    plots.kenshiro_plan(ctx, spec(params))


experiment(
    "humanoid.kenshiro-pedaling",
    covers=("000:fig3.34", "000:fig3.35"),
    source="seed 000 §3.5.5, Eqs. 3.21–3.26",
    summary="E8: Kenshiro's legs pedal one crank revolution, active leg Eq. 3.7 + ankle rule 3.21, passive leg 3.24",
    params=[
        Param("sample_period_s", KENSHIRO_SAMPLE_PERIOD, "time per plan sample i (the thesis's ≈5 s per 18)", lo=0.064,
              hi=1.0),
        Param("k_n_mm_per_n", KENSHIRO.k_n * 1000, "passive update gain K_n of Eq. 3.24 [mm/N]", lo=0.1, hi=10.0),
        Param("relaxed_tendon", KENSHIRO_RELAXED_TENDON, "passive leg's servo stiffness / active leg's", lo=1e-4,
              hi=1.0),
        Param("max_s", 40.0, "give up after this much pedalling [s]", lo=5.0, hi=120.0),
        Param("delta_f", KENSHIRO_DELTA_F, "Eq. 3.24's Δf_i: the change over one control period ('previous', a "
              "stiffness, the thesis's word for K_n) or the deviation from the passive phase's starting force ('start')",
              choices=KENSHIRO_DELTA_F_READINGS),
    ],
    checks=[
        Check("d_th_m", ">=", 0.0150,
              "follows from the inputs: Eq. 3.23 (§3.5.5) recomputed from the thesis's own r = 0.1 m, T = 18, "
              "Φ = 5π/6 — 'D_th = 0.1 √(2(1 − cos π/18)) |cos 5π/6| ≈ 0.015'; a design threshold, not a result",
              kind="consistency"),
        Check("d_th_m", "<=", 0.0152, "as d_th_m: Eq. 3.23 recomputed (upper side)", name="d_th_upper",
              kind="consistency"),
        Check("role_swaps", "==", 2,
              "our stop rule: the run ends at the second swap (half, swap, half), so 2 holds unless max_s runs out",
              kind="consistency"),
        Check("crank_advance_deg", ">=", 360 - 2 * KENSHIRO_SWITCH_LEAD / DEG,
              "thesis §3.5.5: '… 再び半回転操作(… 約 6[s]~約 14[s])することで1回転のペダリング操作を実現した'; the "
              "10° slack (the last swap at most 2 × the 5° switch lead early) is ours. Consistency: the run stops at "
              "the second swap, 5° before the plan's 360°, so the value is 355° whenever two swaps happen",
              kind="consistency"),
        Check("revolution_time_s", ">=", 9.8,
              "the plan's own duration: 36 samples × the sample period (0.272 s, chosen from the thesis's first "
              "half, ≈5 s / 18) = 9.79 s — the crank cannot finish before its plan", kind="consistency"),
        Check("revolution_time_s", "<=", 18.2,
              "thesis §3.5.5: one revolution in ≈14 s ('0[s]~約 5[s]' half, '約 5[s]~約 6[s]' swap, '約 6[s]~約 14[s]' "
              "half); +30 % ours", name="revolution_time_upper", kind="reproduction", row="000:fig3.34"),
        Check("second_half_s", ">=", 0.7 * 9.0,
              "thesis §3.5.5: from the swap ('約 5[s]~約 6[s]') to the end of the second half ('約 6[s]~約 14[s]') "
              "≈9 s; −30 % ours (our first half is calibrated on the thesis's, this one is not)",
              kind="reproduction", row="000:fig3.34"),
        Check("second_half_s", "<=", 1.3 * 9.0, "as second_half_s, +30 % ours", name="second_half_upper",
              kind="reproduction", row="000:fig3.34"),
        Check("crank_estimate_error_deg", "<=", 5.0,
              "derived: below Δθ_c/2 = 5°, so each swap falls in its own sample (a foot sliding 9 mm along "
              "the pedal already shifts method (a) by 5° at r = 0.1 m)", kind="consistency"),
        Check("passive_contact_fraction", ">=", 0.9,
              "a property of our Eq. 3.24 leg (it keeps its unilateral contact); not a Kenshiro result — the thesis's "
              "passive leg escapes the pedal after each force peak (§3.5.5, Fig. 3.35)", kind="consistency"),
        Check("right_active_peak_fz_n", ">=", 0.7 * 310.0,
              "thesis §3.5.5 (Fig. 3.35): '能動機能の脚の踏み込み力が右脚(4~5[s] で約 310[N])…'; ±30 % ours",
              kind="reproduction", row="000:fig3.35"),
        Check("right_active_peak_fz_n", "<=", 1.3 * 310.0, "as right_active_peak_fz_n, +30 % ours",
              name="right_active_peak_upper", kind="reproduction", row="000:fig3.35"),
        Check("left_active_peak_fz_n", ">=", 0.7 * 170.0,
              "thesis §3.5.5 (Fig. 3.35): '…左脚(8~9[s] で約 170[N])で異なっている'; ±30 % ours",
              kind="reproduction", row="000:fig3.35"),
        Check("left_active_peak_fz_n", "<=", 1.3 * 170.0, "as left_active_peak_fz_n, +30 % ours",
              name="left_active_peak_upper", kind="reproduction", row="000:fig3.35"),
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
    rig=rig, metrics=metrics, plots=draw,
    video=True,
    smoke={},  # the experiment itself: one revolution is ≈11 s of body time, ≈2 s of wall
)
