"""``humanoid.vboard-boarding``: HRP2-JSK boards the V-BOARD, left foot first, with the left-foot pitch
damping gain fixed at the flat-floor D = 22.0 and with SLC tuning it online (seed 000 §5.4, Figs. 5.6–5.8)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from shintai.core.runtime import FunctionModule
from shintai.humanoid.balance.foot_damping import FootDamping
from shintai.humanoid.balance.standing import CHANNELS
from shintai.humanoid.constants import DAMPING_T, DELTA_LIMIT, SLC_D0, SLC_ETA, SLC_Q, SLC_R
from shintai.humanoid.learning.slc import SLCParams, slc_cost
from shintai.humanoid.vboard import plots
from shintai.humanoid.vboard.boarding import boarding_stack, run_summary
from shintai.humanoid.vboard.constants import AFTER_S, BOARDING_ZMP_TRUNCATION
from shintai.humanoid.vboard.vehicle import board_pitch
from shintai.scenarios.experiment import Rig
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment

VARIANTS = ("fixed_d", "slc")


def rig(params, variant, seed):
    """The stack of :class:`~shintai.humanoid.balance.standing.Standing` stepping onto the scooter
    (:mod:`shintai.humanoid.vboard.boarding`); SLC runs after the foot damping, learning (``slc``) or only marking
    the same window (``fixed_d``: D = D₀ throughout)."""
    p = SLCParams(D0=params["D0"], Q=params["Q"], R=params["R"], eta=params["eta"])
    st, sched = boarding_stack(p, params["T"], learn=variant == "slc", zmp_truncation=params["zmp_truncation"])
    body = st.body
    left: FootDamping = st.damping.feet["L"]
    qx = body.model.joint("vboard_x").qposadr[0]
    c = {}  # the stack's channels as the last stage sees them (the runner's loop is not st.loop)
    watch = FunctionModule(lambda snap: c.update({k: snap[k] for k in ("tau_d_L", "tau_L", "f_Lz", "f_Rz")}),
                           name="watch")
    stages = st.stages(observers=[watch])

    def signals(snap):
        theta = board_pitch(snap)
        return {"D_L": sched.D[1], "D_R": sched.D[3], "D_L_roll": sched.D[0],
                "tau_d": float(np.asarray(c["tau_d_L"])[1]), "tau": float(np.asarray(c["tau_L"])[1]),
                "delta": left.delta[1], "e_tau": left.e_tau[1],
                "J": float(slc_cost(left.e_tau[1], left.delta[1], p.Q, p.R)),
                "f_Lz": float(c["f_Lz"]), "f_Rz": float(c["f_Rz"]), "learning": float(sched.state == "learning"),
                "theta_l": theta["l"], "theta_r": theta["r"], "scooter_x": float(body.data.qpos[qx]),
                "switch_l": float(body.firmware.on["l"]), "switch_r": float(body.firmware.on["r"])}

    def ended(snap):
        return st.fallen() or not np.all(np.isfinite(body.data.qpos))  # a fall or a diverging simulation

    duration = min(st.duration + params["after_s"], params["max_s"])
    return Rig(body, stages=stages, channels=CHANNELS.values(), duration=duration,
               until=ended, record={1: signals},
               view={"track": "waist", "distance": 2.6, "azimuth": 215.0, "elevation": -12.0},
               state=SimpleNamespace(st=st, sched=sched, params=p))


def metrics(runs, params):
    fixed, slc = run_summary(runs["fixed_d"]), run_summary(runs["slc"])
    peaks = slc["peaks"]
    m = {
        "fell_without_slc": fixed["fell"], "fell_with_slc": slc["fell"],
        "fall_time_without_slc_s": fixed["end_s"] if fixed["fell"] else math.nan,
        "fall_time_with_slc_s": slc["end_s"] if slc["fell"] else math.nan,
        "fall_after_slc_start_without_s": fixed["fall_after_start_s"],
        "fall_after_slc_start_with_s": slc["fall_after_start_s"],
        "t_left_landing_s": slc["t_left_landing_s"], "t_right_landing_s": slc["t_right_landing_s"],
        "t_left_switch_on_s": slc["t_switch_l_s"], "t_right_switch_on_s": slc["t_switch_r_s"],
        "slc_duration_s": slc["window_s"] if slc["window_s"] is not None else math.nan,
        "window_without_slc_s": fixed["window_s"] if fixed["window_s"] is not None else math.nan,
        "damping_initial": params["D0"], "damping_final": slc["D_final"],
        "damping_rise": slc["D_final"] - params["D0"],
        "right_pitch_damping_final": slc["D_R_final"], "roll_damping_final": slc["D_roll_final"],
        "right_took_learned_d": int(runs["slc"].state.sched.t_stop is not None
                                    and abs(slc["D_R_final"] - slc["D_final"]) < 1e-9),
        "damping_change_outside_window": slc["D_changes_outside_window"],
        "damping_change_without_slc": float(np.ptp(runs["fixed_d"].log.values("D_L"))),
        "delta_max_without_slc_deg": math.degrees(fixed["delta_max_window"]),
        "delta_max_with_slc_deg": math.degrees(slc["delta_max_window"]),
        "delta_max_whole_run_without_deg": math.degrees(fixed["delta_max"]),
        "delta_max_whole_run_with_deg": math.degrees(slc["delta_max"]),
        "delta_limit_deg": math.degrees(DELTA_LIMIT),
        "delta_hit_limit_without_slc": fixed["delta_hit_limit_window"],
        "delta_hit_limit_with_slc": slc["delta_hit_limit_window"],
        "j_tau_peaks_with_slc": [[round(a, 3), b] for a, b in peaks],
        "j_tau_peaks_without_slc": [[round(a, 3), b] for a, b in fixed["peaks"]],
        "j_tau_second_peak_smaller": int(len(peaks) == 2 and peaks[1][1] < peaks[0][1]),
        "board_l_min_without_deg": fixed["board_l_min_deg"], "board_l_min_with_deg": slc["board_l_min_deg"],
        "scooter_travel_without_m": fixed["scooter_travel_m"], "scooter_travel_with_m": slc["scooter_travel_m"],
        "ik_unreachable": fixed["unreachable"] + slc["unreachable"],
    }
    return m


SEC = "thesis §5.4.2"
experiment(
    "humanoid.vboard-boarding",
    covers=("000:fig5.6", "000:fig5.7", "000:fig5.8"),
    source="seed 000 §5.4.1–5.4.2, Figs. 5.5–5.8, Table 5.2, Eqs. 5.1–5.17",
    summary="HRP2 steps onto the V-BOARD left foot first: foot-pitch damping D fixed at 22.0 vs tuned online by SLC",
    params=[
        Param("D0", SLC_D0, "damping gain on the floor and at SLC's start (§5.4.1: 22.0)", lo=1.0, hi=200.0),
        Param("T", DAMPING_T, "damping time constant T [s] (Table 5.2: 1.5)", lo=0.05, hi=10.0),
        Param("Q", SLC_Q, "weight of e_τ² (Table 5.2: 0.1)", lo=1e-6, hi=1e3),
        Param("R", SLC_R, "weight of δ² (Table 5.2: 1.0e5)", lo=1.0, hi=1e8),
        Param("eta", SLC_ETA, "learning rate η (Table 5.2: 0.01)", lo=1e-6, hi=1.0),
        Param("zmp_truncation", BOARDING_ZMP_TRUNCATION, "bound p_d to the stance soles before the distributor "
              "(hrpsys's ZMP truncation; thesis-silent, vboard.constants)"),
        Param("after_s", AFTER_S, "standing on the scooter after the plan's end [s]", lo=0.0, hi=20.0),
        Param("max_s", 30.0, "stop the run after this much sim time [s] (a truncated boarding; the plan is 4.2 s)",
              lo=0.5, hi=30.0),
    ],
    checks=[
        Check("fell_without_slc", "==", 1,
              f"{SEC}: 'D = 22.0 をそのまま用いて乗り込み動作を生成した場合,平行二輪電動スクーター上では適応的に"
              "バランスを安定化できずに図 5.6 -(7),(8) に示すように転倒した'", kind="reproduction", row="000:fig5.6"),
        Check("fell_with_slc", "==", 0,
              f"{SEC}: 'SLC を用いてオンラインでダンピングゲインの学習を行うことで,適応的に平行二輪電動スクーター上"
              "への搭乗行動が実現された' (Fig. 5.7)", kind="reproduction", row="000:fig5.7"),
        Check("damping_final", ">", "damping_initial",
              f"{SEC}: 'ダンピングゲイン D は初期値 D = 22.0 より学習を開始して,増加しながら SLC の終了時点では約 "
              "D = 40.0 の値を獲得した' (Fig. 5.8-(a2)); ours: that D rises", kind="reproduction", row="000:fig5.8"),
        Check("delta_hit_limit_without_slc", "==", 1,
              f"{SEC}: 'SLC を適用しない場合…制御入力 δ は図 5.8-(c1) のように発散が観察された…終端時刻においては"
              "設定した入力制限に飽和し' (δ reaches its limit, ours ±10°, inside the window)", kind="reproduction",
              row="000:fig5.8"),
        Check("delta_hit_limit_with_slc", "==", 0,
              f"{SEC}: '制御入力 δ についても図 5.8 -(c2) のように発散を防ぐことに成功している'",
              kind="reproduction", row="000:fig5.8"),
        Check("j_tau_second_peak_smaller", "==", 1,
              f"{SEC}: '1つめのピーク(0.6[s]付近)に比べて2つめのピーク(1.0[s]付近)が小さくなっており' (Fig. 5.8-(d2))",
              kind="reproduction", row="000:fig5.8"),
        Check("damping_change_outside_window", "<=", 0.0,
              "§5.4.1 / Fig. 5.5: SLC runs from the left landing (f_Lz > F_thre) to the right landing (f_Rz > F_thre) "
              "only: D is constant outside that window (ours by construction)", kind="consistency"),
        Check("damping_change_without_slc", "<=", 0.0,
              "the fixed-D run keeps D = D₀ throughout (§5.4.2's comparison)", kind="consistency"),
        Check("right_took_learned_d", "==", 1,
              "§5.4.1: '右足の Pitch 成分に対するダンピングゲインは,左足の Pitch 成分において SLC より学習・獲得した"
              "ダンピングゲインを利用した値とする' (once SLC stops)", kind="consistency"),
        Check("roll_damping_final", "==", "damping_initial",
              "§5.4.1: 'SLC を適用しない足部の Roll 成分では常時この数値に設定している'", kind="consistency"),
    ],
    thesis={
        "fell_without_slc": ThesisValue(1, f"{SEC}, Fig. 5.6-(7),(8)", "fell_without_slc"),
        "fell_with_slc": ThesisValue(0, f"{SEC}, Fig. 5.7", "fell_with_slc"),
        "slc_duration_s": ThesisValue(1.2, f"{SEC}: 'SLC の実行の総時間は約 1.2[s] の結果となった'", "slc_duration_s"),
        "damping_initial": ThesisValue(22.0, "seed 000 §5.4.1: '平坦な床面上において適応的となる数値 D = 22.0'",
                                       "damping_initial"),
        "damping_final": ThesisValue(40.0, f"{SEC}: 'SLC の終了時点では約 D = 40.0 の値を獲得した'", "damping_final"),
        "j_tau_first_peak_s": ThesisValue(0.6, f"{SEC}: '1つめのピーク(0.6[s]付近)'", "j_tau_peaks_with_slc"),
        "j_tau_second_peak_s": ThesisValue(1.0, f"{SEC}: '2つめのピーク(1.0[s]付近)が小さくなっており'",
                                           "j_tau_peaks_with_slc"),
        "delta_hit_limit_without_slc": ThesisValue(
            1, f"{SEC}: 'Fig. 5.8-(c1) の終端時刻においては設定した入力制限に飽和し'", "delta_hit_limit_without_slc"),
        "table_5_2": ThesisValue({"T": 1.5, "Q": 0.1, "R": 1.0e5, "eta": 0.01}, "seed 000 §5.4.2, Table 5.2"),
        "F_thre_n": ThesisValue(25.0, "seed 000 §5.4.1: '本稿では,F_thre = 25[N] として設定する'"),
    },
    rig=rig, variants=VARIANTS, filmed=VARIANTS, metrics=metrics, plots=plots.boarding, video=True,
    smoke={"max_s": 3.6},  # past both landings, before the fall without SLC
)
