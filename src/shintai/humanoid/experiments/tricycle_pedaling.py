"""``humanoid.tricycle-pedaling``: E2/E4, HRP2 pedals one crank revolution with active/passive legs (seed 000
§3.5.2–3.5.3), and the same samples with two active legs for comparison."""

from __future__ import annotations

import numpy as np
from scipy.stats import spearmanr

from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    D_THETA_C,
    DEG,
    DELTA_T,
    MODEL_ERROR_MM,
    PEDAL_FORCE_BAND,
    TRICYCLE,
)
from shintai.humanoid.tricycle import plots, riding
from shintai.humanoid.tricycle.hrp2_limbs import riding_limbs
from shintai.humanoid.tricycle.operation import SIDES, LimbPair, travel_distance
from shintai.humanoid.tricycle.rig import (
    F_TRG,
    LEG_GAINS,
    active_samples,
    crank_estimate_error,
    crank_schedule,
    foot_plan,
    force_errors,
    legs_switcher,
    pedal_rig,
)
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment

AP, BOTH = "active_passive", "both_active"


def variants(params):
    return (AP, BOTH) if params["both_active_revolutions"] > 0 else (AP,)


def rig(params, variant, seed):
    """Active/passive: the left leg starts active at θ_c = 0, the roles swap at 110° and 290° (§3.5.2).
    Both active: the same samples, both feet on the nominal circle under the active impedance."""
    body = riding.build_riding(crank_error=(params["crank_error_mm"] / 1000, params["crank_error_up_mm"] / 1000))
    feet = riding_limbs(body, "foot")
    dt = DELTA_T * params["time_scale"]
    if variant == AP:
        schedule = crank_schedule(params["revolutions"], dt)
        legs, diag = legs_switcher(feet, schedule)
        return pedal_rig(body, legs, feet, schedule, lambda s: legs.active == f"legs:{s}-active", diag)
    schedule = crank_schedule(params["both_active_revolutions"], dt)
    both = LimbPair("legs:both-active", "crank", feet, {leg: "active" for leg in SIDES},
                    {leg: foot_plan(leg) for leg in SIDES}, schedule, LEG_GAINS, CONTROL_PERIOD)
    return pedal_rig(body, both, feet, schedule, lambda s: True)


def pedal_metrics(rec, schedule, diag, dt: float) -> dict:
    """Forces after transients (one command sample, 2Δt, after the start and after each swap), the swaps,
    the revolution time against Eq. 3.20, the travel, and the §3.5.3 diagnostics of the active foot."""
    t = rec.times("crank_true")
    true = rec.values("crank_true")
    advance = true - true[0]
    goal = schedule.samples[-1].theta_c - schedule.theta_c0
    done = np.flatnonzero(advance >= goal - 1 * DEG)
    passive = force_errors(rec, "", 2 * dt, 0.0)
    active_fz, cos_term = active_samples(rec, "", 2 * dt)
    active_fx, _ = active_samples(rec, "", 2 * dt, "fx")
    swaps = np.mod([a for _, a, _ in diag.log], 2 * np.pi) / DEG
    expected = np.where(np.abs(swaps - 110) < np.abs(swaps - 290), 110.0, 290.0)
    travel = rec.values("travel")[-1]
    slip = max(np.linalg.norm(rec.values(f"on_pedal_{side}") - rec.values(f"on_pedal_{side}")[0], axis=1).max()
               for side in SIDES)
    horizontal = 1 / cos_term >= np.cos(PEDAL_FORCE_BAND)  # |cos θ_c|: near the crank horizontal
    dead = 1 / cos_term <= np.sin(PEDAL_FORCE_BAND)  # near TDC/BDC
    return {
        "passive_force_mean_n": float(passive.mean()),
        "passive_force_rms_error_n": float(np.sqrt(np.mean((passive - F_TRG) ** 2))),
        "passive_force_min_n": float(passive.min()),
        "max_sole_slip_mm": float(1000 * slip),
        "active_force_mean_n": float(active_fz.mean()),
        "active_force_cos_corr": float(np.corrcoef(active_fz, cos_term)[0, 1]),
        "active_force_horizontal_n": float(active_fz[horizontal].mean()) if horizontal.any() else float("nan"),
        "active_force_dead_centre_n": float(active_fz[dead].mean()) if dead.any() else float("nan"),
        # diagnostics of §3.5.3's claim (not checked), see the notes
        "active_force_cos_rank_corr": float(spearmanr(active_fz, cos_term)[0]),
        "active_fx_dead_centre_n": float(np.abs(active_fx[dead]).mean()) if dead.any() else float("nan"),
        "active_friction_use_dead_centre": float((np.abs(active_fx) / active_fz)[dead].max()) if dead.any()
        else float("nan"),
        "role_swaps": len(diag.log),
        "revolutions_x2": int(round(2 * goal / (2 * np.pi))),
        "swap_angles_deg": swaps.tolist(),
        "swap_angle_error_deg": float(np.abs(swaps - expected).max()) if len(swaps) else float("nan"),
        "crank_advance_deg": float(advance[-1] / DEG),
        "crank_estimate_error_deg": crank_estimate_error(rec) / DEG,
        "revolution_time_s": float(t[done[0]]) if done.size else float("nan"),
        "eq_3_20_time_s": goal / D_THETA_C * 2 * dt,
        "revolution_time_ratio": float(t[done[0]] / (goal / D_THETA_C * 2 * dt)) if done.size else float("nan"),
        "travel_m": float(travel),
        "travel_per_rev_m": float(travel / advance[-1] * 2 * np.pi),
        "travel_nominal_m": travel_distance(advance[-1], TRICYCLE.travel_per_rev),
    }


def metrics(runs, params):
    dt = DELTA_T * params["time_scale"]
    run = runs[AP]
    m = pedal_metrics(run.log, run.state.schedule, run.state.diag, dt)
    m["unreachable_ticks"] = sum(limb.unreachable for limb in run.state.feet.values())
    if BOTH in runs:
        fz = force_errors(runs[BOTH].log, "", 2 * dt, 1.0)
        m.update(both_active_force_mean_n=float(fz.mean()),
                 both_active_force_rms_error_n=float(np.sqrt(np.mean((fz - F_TRG) ** 2))),
                 both_active_force_std_n=float(fz.std()))
    return m


def draw(ctx, runs, params):
    shown = [(runs[AP].log, "active/passive (Fig. 3.22-(II))", True)]
    if BOTH in runs:
        shown.append((runs[BOTH].log, "both active, crank model off (Fig. 3.22-(I))", False))
    plots.pedaling(ctx, shown, runs[AP].state.diag)


experiment(
    "humanoid.tricycle-pedaling",
    covers=("000:fig3.18", "000:fig3.22", "000:fig3.22-active"),
    source="seed 000 §3.5.2–3.5.3, Eqs. 3.7, 3.13–3.14, 3.19–3.20, Fig. 3.18, Fig. 3.22",
    summary="E2/E4: HRP2 pedals one crank revolution with active/passive legs (150 N), vs. two active legs",
    params=[
        Param("time_scale", 1.0, "Δt = 0.8 s × time_scale (1 = the thesis's lab setting)", lo=0.1, hi=1.0),
        Param("revolutions", 1.0, "crank revolutions of the active/passive run", lo=0.1, hi=2.0),
        Param("both_active_revolutions", 1.0, "crank revolutions of the both-active comparison run", lo=0.0, hi=2.0),
        Param("crank_error_mm", MODEL_ERROR_MM, "true crank centre ahead of the nominal model [mm] (ours: the thesis names no "
              "model error)", lo=0.0, hi=30.0),
        Param("crank_error_up_mm", 0.0, "true crank centre above the nominal model [mm] (a probe, see the notes)",
              lo=0.0, hi=30.0),
    ],
    checks=[
        Check("crank_advance_deg", ">=", 355.0,
              "thesis §3.5.2: one revolution pedalled, Fig. 3.18 (1)–(8) ('Pedaling Manipulation on 1-Cycle by Active "
              "Leg and Passive Leg'; '搭乗型機器の操作行動が適切に実現されている'); the 5° slack is ours",
              name="one_revolution", kind="reproduction", row="000:fig3.18"),
        Check("passive_force_mean_n", ">=", 0.9 * F_TRG,
              "thesis §3.5.3, Fig. 3.22-(II): '片方の脚マニピュレータに受動機能を備えることで,図 3.22 -(II) のように"
              "目標接触力追従が可能となり' (f^trg_z = 150 N, Table 3.4); the ±10 % band is ours (the seed gives none)",
              kind="reproduction", row="000:fig3.22"),
        Check("passive_force_mean_n", "<=", 1.1 * F_TRG, "as passive_force_mean_n (+10 %, ours)",
              name="passive_force_upper", kind="reproduction", row="000:fig3.22"),
        Check("passive_force_min_n", ">", 0.0,
              "thesis §3.5.3: '受動機能側の足とペダルの接触力が十分に保たれていることが分かる'", kind="reproduction",
              row="000:fig3.22"),
        Check("both_active_force_rms_error_n", ">", "passive_force_rms_error_n",
              "thesis §3.5.3: '双脚とも能動機能の場合は両足の目標接触力に対する追従が難しく,160[N] 付近を中心に高低変動"
              "が観察された' against the passive foot's tracking in Fig. 3.22-(II)", kind="reproduction",
              row="000:fig3.22"),
        Check("both_active_force_mean_n", ">", F_TRG,
              "thesis §3.5.3: '能動機能を備えた脚については図 3.22 -(I),(II) ともに 150[N] を上回っている' (in (I) both "
              "legs are active)", name="both_active_force_above_target", kind="reproduction", row="000:fig3.22"),
        Check("both_active_force_mean_n", ">=", 155.0,
              "thesis §3.5.3: '… 160[N] 付近を中心に高低変動が観察された' (Fig. 3.22-(I)); ±5 N ours — half the gap "
              "between the 160 N and the 150 N the thesis tells apart; set when our 151 N was already known, so it is a "
              "judgement, not a blind threshold", name="both_active_force_near_160",
              kind="reproduction", row="000:fig3.22"),
        Check("both_active_force_mean_n", "<=", 165.0, "as both_active_force_near_160 (+5 N, ours)",
              name="both_active_force_near_160_upper", kind="reproduction", row="000:fig3.22"),
        Check("active_force_dead_centre_n", ">", "active_force_horizontal_n",
              "thesis §3.5.3, measured on the real robot (Fig. 3.22-(II)): '上死点及び下死点付近(縦の黒線付近)において"
              "は鉛直接触力の増大が見られ,クランクが水平となる地点 … では下回って 150[N] に近づくような波形が見られる' "
              "(within 30° of TDC/BDC against within 30° of the horizontal: ours)",
              name="active_force_rises_near_dead_centres", kind="reproduction", row="000:fig3.22-active"),
        Check("active_force_mean_n", ">", F_TRG,
              "thesis §3.5.3: '能動機能を備えた脚については図 3.22 -(I),(II) ともに 150[N] を上回っている'",
              name="active_force_above_target", kind="reproduction", row="000:fig3.22-active"),
        Check("role_swaps", "==", "revolutions_x2",
              "Eq. 3.19 as implemented (θ_c^SW = θ_c^init + kπ, §3.4.4): two swaps per revolution by definition",
              kind="consistency"),
        Check("swap_angle_error_deg", "<=", 1.0,
              "Eq. 3.19 at 110°/290°; derived: hysteresis 0.5° plus method (a) error", kind="consistency"),
        Check("revolution_time_ratio", ">=", 0.97,
              "follows from our schedule: Eq. 3.20 is the thesis's estimate ('T_2π = … = 57.6[s] (3.20) と見積ることが"
              "できる', §3.5.2), and our schedule is built from the same Δt = 0.8 s and Δθ_c = 10° (−3 %)",
              kind="consistency"),
        Check("revolution_time_ratio", "<=", 1.03, "as above (+3 %); derived: the crank reaches its last target "
              "(within 1°) as the last sample's passive phase ends, up to a servo lag", name="revolution_time_upper",
              kind="consistency"),
        Check("travel_per_rev_m", ">=", 0.98 * TRICYCLE.travel_per_rev,
              "follows from our input: D_c = 2.45 m is the tricycle's gear setting (App. A.1.1: '… D_c が 2.45[m] と"
              "なるようなクランクギアに設定している') built into our model; confirms only that our wheels do not slip (−2 %)",
              kind="consistency"),
        Check("travel_per_rev_m", "<=", 1.02 * TRICYCLE.travel_per_rev, "as above (+2 %)", name="travel_upper",
              kind="consistency"),
    ],
    thesis={
        "revolution_time_s": ThesisValue(57.6, "seed 000 Eq. 3.20 (an estimate from Δt = 0.8 s, Δθ_c = 10°, not a "
                                         "measurement)", "revolution_time_s"),
        "travel_per_rev_m": ThesisValue(2.45, "seed 000 App. A.1.1 (the gear setting)", "travel_per_rev_m"),
        "active_force_shape": ThesisValue("> 150 N, rising near TDC/BDC, near 150 N at the crank horizontal",
                                          "seed 000 §3.5.3, Fig. 3.22-(II) (measured)", "active_force_dead_centre_n"),
        "both_active_force_centre_n": ThesisValue(160.0, "seed 000 §3.5.3 (Fig. 3.22-(I), ≈160 N)",
                                                  "both_active_force_mean_n"),
        "passive_force_target_n": ThesisValue(150.0, "seed 000 Table 3.4, Fig. 3.22-(II)", "passive_force_mean_n"),
        "swap_angles_deg": ThesisValue([110.0, 290.0], "seed 000 Eq. 3.19, §3.5.2", "swap_angles_deg"),
    },
    rig=rig, variants=variants, filmed=(AP,), metrics=metrics, plots=draw,
    demo=True,
    estimate_s=13.0,
    video=True,
    smoke={"time_scale": 0.25, "revolutions": 0.34, "both_active_revolutions": 0.1},  # one swap at 110°
)
