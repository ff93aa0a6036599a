"""``humanoid.tricycle-steering``: E1, HRP2 steers −25° → +25° with active/passive arms (seed 000 §3.5.2,
Fig. 3.17), and the same command with two active arms for comparison."""

from __future__ import annotations

import numpy as np

from shintai.humanoid.constants import CONTROL_PERIOD, D_THETA_H, DEG, DELTA_T
from shintai.humanoid.tricycle import plots, riding
from shintai.humanoid.tricycle.hrp2_limbs import riding_limbs
from shintai.humanoid.tricycle.operation import SIDES, LimbPair, role_switcher
from shintai.humanoid.tricycle.rig import (
    ARM_GAINS,
    hand_plan,
    handle_diagnostic,
    sample_end_errors,
    steer_rig,
    steer_schedule,
)
from shintai.humanoid.tricycle.switching import active_arm
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment

AP, BOTH = "active_passive", "both_active"
VIEW = {"azimuth": 160.0, "elevation": -30.0, "distance": 2.0}


def variants(params):
    return (AP, BOTH) if params["both_active"] else (AP,)


def rig(params, variant, seed):
    """Active/passive: the left arm active from 0 to −25° and back, the right arm after the measured
    handle passes 0°, up to +25° (§3.5.2). Both active: the same command on the nominal grip plans."""
    schedule = steer_schedule(DELTA_T * params["time_scale"], params["limit_deg"] * DEG)
    body = riding.build_riding(handle_error=(params["handle_error_mm"] / 1000, 0.0, 0.0),
                               grip_error=params["grip_error_mm"] / 1000, rake_error=params["rake_error_deg"] * DEG,
                               grasp=params["grasp"])
    hands = riding_limbs(body, "hand")
    plans = {arm: hand_plan(arm) for arm in SIDES}
    if variant == AP:
        diag = handle_diagnostic(hands)
        arms = role_switcher("arms", "handle", hands, plans, diag, active_arm(0.0, heading=-1.0), schedule, ARM_GAINS,
                             CONTROL_PERIOD, {arm: limb.reachable for arm, limb in hands.items()})
        return steer_rig(body, arms, hands, schedule, lambda s: arms.active == f"arms:{s}-active", diag, VIEW)
    both = LimbPair("arms:both-active", "handle", hands, {arm: "active" for arm in SIDES}, plans, schedule,
                    ARM_GAINS, CONTROL_PERIOD)
    return steer_rig(body, both, hands, schedule, lambda s: True, None, VIEW)


def steer_metrics(rec, schedule, dt: float) -> dict:
    """Handle tracking at the end of each sample; forces counted after the first sample (2Δt)."""
    t = rec.times("handle_true")
    late = t >= 2 * dt
    true = rec.values("handle_true")

    def rms(name):
        return float(np.sqrt(np.mean(rec.values(name)[late] ** 2)))

    passive = np.concatenate([rec.values(f"f_{side}")[late & (rec.values(f"active_{side}") == 0.0)] for side in SIDES])
    active = np.concatenate([rec.values(f"f_{side}")[late & (rec.values(f"active_{side}") == 1.0)] for side in SIDES])
    return {"max_handle_error_deg": float(np.abs(sample_end_errors(rec, schedule)).max() / DEG),
            "handle_range_deg": [float(true.min() / DEG), float(true.max() / DEG)],
            "internal_force_rms_n": rms("internal"), "squeeze_rms_n": rms("squeeze"), "net_force_rms_n": rms("net"),
            "passive_hand_force_rms_n": float(np.sqrt(np.mean(passive**2))) if passive.size else float("nan"),
            "active_hand_force_rms_n": float(np.sqrt(np.mean(active**2))) if active.size else float("nan")}


def metrics(runs, params):
    dt = DELTA_T * params["time_scale"]
    run = runs[AP]
    m = steer_metrics(run.log, run.state.schedule, dt)
    swaps = [a for _, a, _ in run.state.diag.log]
    m.update(role_swaps=len(swaps), swap_angle_deg=float(np.abs(swaps).max() / DEG) if swaps else float("nan"),
             unreachable_ticks=sum(limb.unreachable for limb in run.state.hands.values()))
    if BOTH in runs:
        both = steer_metrics(runs[BOTH].log, runs[BOTH].state.schedule, dt)
        m.update(internal_force_both_active_rms_n=both["internal_force_rms_n"],
                 squeeze_both_active_rms_n=both["squeeze_rms_n"],
                 net_force_both_active_rms_n=both["net_force_rms_n"],
                 max_handle_error_both_active_deg=both["max_handle_error_deg"],
                 hand_force_both_active_rms_n=both["active_hand_force_rms_n"])
    return m


def draw(ctx, runs, params):
    run = runs[AP]
    plots.steering(ctx, run.log, runs[BOTH].log if BOTH in runs else None, run.state.schedule, run.state.diag)


experiment(
    "humanoid.tricycle-steering",
    covers=("000:fig3.17",),
    source="seed 000 §3.5.2, Eqs. 3.2, 3.13–3.14, 3.19, Fig. 3.17",
    summary="E1: HRP2 steers −25° → +25° with active/passive arms (swap at 0°), vs. two active arms",
    params=[
        Param("time_scale", 1.0, "Δt = 0.8 s × time_scale (1 = the thesis's lab setting)", lo=0.1, hi=1.0),
        Param("limit_deg", 25.0, "steering amplitude Θ_H [deg] (Table 3.4: 25°)", lo=5.0, hi=25.0),
        Param("grip_error_mm", 10.0, "true grips farther out from the steering axis than the nominal model, "
              "each side [mm] (handlebar half-width error; spec §5.4 check 9)", lo=-30.0, hi=30.0),
        Param("handle_error_mm", 0.0, "true steering axis ahead of the nominal model [mm]", lo=0.0, hi=30.0),
        Param("rake_error_deg", 0.0, "true steering axis inclined this much more than the nominal rake [deg]",
              lo=-5.0, hi=5.0),
        Param("grasp", "grip", "hand hold: grip (position + bar direction, turns about the bar), weld "
              "(6-DoF, Table 3.1), connect (point)", choices=("grip", "weld", "connect")),
        Param("both_active", 1, "also run the both-active comparison (1) or not (0)", choices=(0, 1)),
    ],
    checks=[
        Check("max_handle_error_deg", "<=", D_THETA_H / DEG,
              "thesis §3.5.2: 'ハンドル回しの操舵範囲は … −25[deg] ≤ θ_h ≤ 25[deg] とした', Fig. 3.17 '(1) −25 [deg] "
              "(2) 0 [deg] (3) 25 [deg]' — the steering range achieved; the 5° (= Δθ_h) tolerance is ours",
              kind="reproduction"),
        Check("role_swaps", "==", 1,
              "Eq. 3.19 with θ_h^init = 0 (§3.5.2) as implemented: the role table is the thesis's input, not a "
              "measurement", kind="consistency"),
        Check("swap_angle_deg", "<=", 1.0, "Eq. 3.19 at 0°; derived: hysteresis 0.5° plus method (a) error",
              kind="consistency"),
        Check("internal_force_rms_n", "<", "internal_force_both_active_rms_n",
              "a property of our method on our mismodelled handle: the seed has no both-active steering run and "
              "no hand-force measurement (§3.3.2 only motivates the split: '双腕のエンドエフェクタ同士は互いに大きく"
              "影響し合う'); the result reverses for a shifted steering axis", kind="consistency"),
        Check("squeeze_rms_n", "<", "squeeze_both_active_rms_n",
              "as internal_force_rms_n: the squeeze along the hand-to-hand line, ours against ours (the thesis "
              "measured no hand forces)", kind="consistency"),
        Check("passive_hand_force_rms_n", "<", "hand_force_both_active_rms_n",
              "as internal_force_rms_n: the passive hand carries less force than a hand of the both-active pair "
              "(RMS of ‖f‖; ours against ours, the thesis gives no number)", kind="consistency"),
    ],
    thesis={
        "steering_range_deg": ThesisValue([-25.0, 25.0], "seed 000 §3.5.2, Table 3.4", "handle_range_deg"),
        "switch_angle_deg": ThesisValue(0.0, "seed 000 Eq. 3.19 (θ_h^init = 0)", "swap_angle_deg"),
    },
    rig=rig, variants=variants, filmed=(AP,), metrics=metrics, plots=draw,
    video=True,
    smoke={"time_scale": 0.25, "limit_deg": 10},
)
