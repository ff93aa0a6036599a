"""``humanoid.speed-governing``: MLC learns the v and ω PID gains from 0 while HRP2 rides the V-BOARD after a lift
put it on (seed 000 §6.4.1, Figs. 6.13, 6.15; Eqs. 6.17–6.32, 6.33–6.39, 6.40–6.41; Table 6.6). Variant ``learn``
is the thesis's run; ``off`` is the same start with the governor at zero gains and no learning (behaviour
level 2), the baseline that tells what the governor changed; ``boarding`` is Fig. 6.16's as §6.4.1 writes it: the
robot boards from the floor by itself with ch. 5's learned damping gain applied beforehand (D = 40, no SLC) and MLC
starts when both feet have landed; ``boarding_slc`` the same with SLC learning D during the boarding (the SOLC-like
reading, §7.4.2; reported, not checked)."""

from __future__ import annotations

import math

import numpy as np

from shintai.humanoid.constants import CONTROL_PERIOD, DEG
from shintai.humanoid.vboard import plots
from shintai.humanoid.vboard.constants import D_VBOARD, PLANTS, START_DELAY, TAIL_S
from shintai.humanoid.vboard.governed_ride import governed_rig, governor_series, ui_jumps, unstable_intervals
from shintai.scenarios.experiment import per_variant
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment

R, F15, F16 = "reproduction", "000:fig6.15", "000:fig6.16"
AXES = ("v", "omega")
BOARDING = {"boarding": "preset", "boarding_slc": "slc"}  # variant → governed_ride's boarding (vboard.constants.BOARDINGS)


def rig(params, variant, seed):
    return governed_rig(params["plant"], params["learn_s"], "corrected", seed, params["theta_o_error_deg"],
                        params["damping_d"], start_delay=params.get("start_delay_s", START_DELAY),
                        eta_scale=params.get("eta_scale", 1.0), learn=variant != "off", boarding=BOARDING.get(variant))


def variants(params) -> tuple[str, ...]:
    return ("learn",) + (("off",) if params["baseline"] else ()) + (tuple(BOARDING) if params["boarding"] else ())


def summary(run) -> dict:
    """Metrics of one run, times from the learning start (t = 0 of Figs. 6.15–6.16)."""
    ride, log = run.state, run.log
    gov = ride.governor
    t0 = gov.t_start if gov.t_start is not None else math.nan
    t_end = float(ride.body.t)
    out = {"fallen": int(ride.fallen()), "start_s": t0, "ride_s": t_end - t0}
    t = log.times("true_v")
    tail = t >= t_end - TAIL_S
    out["final_abs_v_mps"] = float(np.mean(np.abs(log.values("true_v")[tail])))
    out["final_abs_omega_rad_s"] = float(np.mean(np.abs(log.values("true_omega")[tail])))
    out["drift_m"] = float(log.values("x")[-1] - np.interp(t0, t, log.values("x"))) if np.isfinite(t0) else math.nan
    th = log.values("foot_pitch.theta_R") if "foot_pitch.theta_R" in log.names() else np.zeros(1)
    out["max_foot_pitch_deg"] = float(np.max(np.abs(th))) / DEG
    for a in AXES:
        m, s = gov.mlc[a], governor_series(log, a)
        gains = s["gains"][-1] if s["gains"].size else np.zeros(3)
        for name, g in zip(("K_P", "K_I", "K_D"), gains, strict=True):
            out[f"{a}_{name}"] = float(g)
        out[f"{a}_pi_dominant"] = int(gains[2] < gains[0] and gains[2] < gains[1])
        out[f"{a}_converged"] = int(m.converged)
        out[f"{a}_t_converged_s"] = (m.t_converged - t0) if m.converged else math.nan
        out[f"{a}_batches"] = len(m.batches)
        out[f"{a}_clipped"] = int(sum(int(b.clipped.sum()) for b in m.batches))
        out[f"{a}_J_last"] = m.batches[-1].J if m.batches else math.nan
        iv = unstable_intervals(s["t"] - t0, s["stable"])
        out[f"{a}_unstable_s"] = float(sum(b - a_ for a_, b in iv))
        out[f"{a}_unstable_intervals"] = len(iv)
        ok = np.flatnonzero(s["stable"] > 0)  # Eq. 6.41 first met (the gains start outside it, K_I = 0)
        out[f"{a}_first_stable_s"] = float(s["t"][ok[0]] - t0) if ok.size else math.nan
        out[f"{a}_last_unstable_start_s"] = iv[-1][0] if iv else math.nan
        out[f"{a}_stable_at_end"] = int(s["stable"][-1] > 0) if s["stable"].size else 0
        jumps = ui_jumps(s)
        out[f"{a}_max_ui_jump"] = float(jumps.max()) if jumps.size else 0.0
        out[f"{a}_I_increases"] = int(jumps.size)
        # Eq. 6.38: at an increase the corrected u_I moves by Δt/2 (e(t+Δt) + e(t)) K_I(n+1) only; the relative excess
        KI, e = s["gains"][:, 1], s["e"]
        k = np.flatnonzero(np.diff(KI) > 0) + 2
        k = k[k < e.size]
        if k.size:
            step = 0.5 * CONTROL_PERIOD * np.abs(e[k] + e[k - 1]) * KI[k]
            excess = np.abs(s["uI"][k] - s["uI"][k - 1]) - step
            out[f"{a}_ui_jump_excess"] = float(np.max(excess) / max(float(np.max(step)), 1e-300))
        else:
            out[f"{a}_ui_jump_excess"] = 0.0
    if ride.boarding is not None:  # Fig. 6.16's start: the boarding (ch. 5) before the learning
        st, sched = ride.boarding
        out.update({"slc_window_s": sched.duration if sched.duration is not None else math.nan,
                    "damping_learned": float(sched.D[1]), "plan_end_s": st.duration - t0})
    conv = [out[f"{a}_t_converged_s"] for a in AXES]
    out["converged"] = int(all(out[f"{a}_converged"] for a in AXES))
    out["t_converged_s"] = max(conv) if out["converged"] else math.nan
    return out


def metrics(runs, params):
    out = per_variant({name: summary(run) for name, run in runs.items()})
    pv = next(iter(runs.values())).state.plant
    out.update({"plant_K_v": pv["K_v"], "plant_T_v_s": pv["T_v"], "plant_K_omega": pv["K_omega"],
                "plant_T_omega_s": pv["T_omega"]})
    if "learn" in runs and "off" in runs:
        out["ride_gain_s"] = out["ride_learn_s"] - out["ride_off_s"]
    return out


experiment(
    "humanoid.speed-governing",
    covers=("000:fig6.15", "000:fig6.16"),
    source="seed 000 §6.4.1, Figs. 6.13, 6.15, 6.16, Eqs. 6.17–6.41, Table 6.6",
    summary="MLC learns the v and ω PID gains online from 0 on HRP2 riding the V-BOARD after a lift placed it and "
            "after it boarded by itself (prior-value-correcting integrator, Routh–Hurwitz monitor); against the "
            "governor off",
    params=[
        Param("learn_s", 60.0, "simulated time from the learning start [s] (thesis: converged ≈38 s, Fig. 6.16 ≈54 s)",
              lo=1.0, hi=300.0),
        Param("baseline", True, "also run the 'off' variant (governor at zero gains, no learning: level 2)"),
        Param("boarding", True, "also run Fig. 6.16's start: the robot boards from the floor with D = 40 preset "
              "('boarding', §6.4.1) and with SLC learning D ('boarding_slc'), MLC from both feet landed"),
        Param("plant", "board", "K, T for MLC's sensitivity (Eqs. 6.20–6.29): 'board' = humanoid.vboard-plant-id's "
              "fit to the boards' pitch (its fit from u has K_v < 0), 'table6.2' = the thesis's numbers",
              choices=PLANTS),
        Param("eta_scale", 1.0, "factor on Table 6.6's learning rates (1 = the thesis's)", lo=1e-3, hi=1e6),
        Param("start_delay_s", START_DELAY, "learning starts this long after the lift lets go [s] (ours)",
              lo=0.0, hi=5.0),
        Param("theta_o_error_deg", 0.3, "true θ_O minus the regression intercept [deg] (ours, as "
              "humanoid.vboard-levels)", lo=-3.0, hi=3.0),
        Param("damping_d", D_VBOARD, "foot damping gain D [N m s/rad] (§5.4.2)", lo=1.0, hi=1000.0),
    ],
    checks=[
        Check("fallen_learn", "==", 0, "thesis §6.4.1, Fig. 6.15: the robot rides on while learning, '調速行動が達成"
              "されていることが確認できる'", kind=R, row=F15),
        Check("converged_learn", "==", 1, "thesis §6.4.1: '図 6.15 は約 38[s] … で式 6.32 の学習制御の終了条件を"
              "満たして収束した'", kind=R, row=F15),
        Check("final_abs_v_learn_mps", "<", 0.05, "thesis §6.4.1: v follows v^d = 0 near 35 s, Fig. 6.15 (c1) "
              "('目標値追従より調速行動が達成'; 5 cm/s is our reading of the plot's scale)", kind=R, row=F15),
        Check("final_abs_omega_learn_rad_s", "<", 0.05, "thesis §6.4.1: ω follows ω^d = 0, Fig. 6.15 (c2) "
              "(0.05 rad/s ours)", kind=R, row=F15),
        Check("v_pi_dominant_learn", "==", 1, "thesis §6.4.1: 'Dゲインに比べて Pゲイン,Iゲインが制御系として支配的'",
              kind=R, row=F15),
        Check("v_stable_at_end_learn", "==", 1, "thesis §6.4.1: '学習が収束するにつれて安定な状態が継続して' "
              "(Fig. 6.15 (e), Eq. 6.41)", kind=R, row=F15),
        Check("fallen_boarding", "==", 0, "thesis §6.4.1, Fig. 6.16: after boarding by itself the robot rides on "
              "while learning ('図 6.16 - (c1),(c2) の 50[s] 付近' the targets are followed)", kind=R, row=F16),
        Check("converged_boarding", "==", 1, "thesis §6.4.1: '図 6.16 は約 54[s] で式 6.32 の学習制御の終了条件を"
              "満たして収束した'", kind=R, row=F16),
        Check("final_abs_v_boarding_mps", "<", 0.05, "thesis §6.4.1: v follows v^d = 0 near 50 s, Fig. 6.16 (c1) "
              "(0.05 m/s ours)", kind=R, row=F16),
        Check("final_abs_omega_boarding_rad_s", "<", 0.05, "thesis §6.4.1: ω follows ω^d = 0, Fig. 6.16 (c2) "
              "(0.05 rad/s ours)", kind=R, row=F16),
        Check("v_pi_dominant_boarding", "==", 1, "thesis §6.4.1: 'Dゲインに比べて Pゲイン,Iゲインが制御系として支配的'",
              kind=R, row=F16),
        Check("v_ui_jump_excess_boarding", "<", 1e-9, "follows from Eq. 6.38 (our integrator), as for 'learn'",
              kind="consistency"),
        Check("v_ui_jump_excess_learn", "<", 1e-9, "follows from Eq. 6.38 (our integrator): at an I-gain increase u_I "
              "moves by Δt/2 (e(t+Δt)+e(t)) K_I(n+1) only (relative excess over that step)", kind="consistency"),
    ],
    thesis={"t_converged_learn_s": ThesisValue(38.0, "seed 000 §6.4.1: '図 6.15 は約 38[s] … 収束した'",
                                               "t_converged_learn_s"),
            "t_converged_boarding_s": ThesisValue(54.0, "seed 000 §6.4.1: '図 6.16 は約 54[s]' (after self-boarding)",
                                                  "t_converged_boarding_s"),
            "eta_v": ThesisValue(1e-7, "seed 000 Table 6.6: diag(10⁻⁷, 10⁻⁷, 10⁻⁷) for v", None),
            "eta_omega": ThesisValue(1e-9, "seed 000 Table 6.6: diag(10⁻⁹, 10⁻⁹, 10⁻⁹) for ω", None)},
    rig=rig, variants=variants, filmed=("learn", "boarding", "boarding_slc"), metrics=metrics, plots=plots.speed_governing, video=True,
    stochastic=True,  # the sensors' noise (Table 6.1) is drawn from the run's seed
    smoke={"learn_s": 2.1, "plant": "table6.2", "start_delay_s": 0},  # one mini-batch per variant
)
