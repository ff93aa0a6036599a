"""``humanoid.sitting-recovery``: a seat slip accumulating with driving — driving ⇄ the interrupt-type
sitting recovery under a Switcher, against driving alone (seed 000 §4.3.2, §7.4.1, Figs. 7.14–7.15)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from shintai.core.runtime import FunctionModule, Group, Switcher
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    DEG,
    DELTA_T,
    FOOT_FOLLOW_F_TRG,
    LEGS_FZ,
    RECOVERY_PEDAL_REVOLUTIONS,
    STEPS_SPEED,
)
from shintai.humanoid.corrections import RecoveryTrigger, SittingRecovery
from shintai.humanoid.tricycle import ch4_riding as cr
from shintai.humanoid.tricycle import plots
from shintai.humanoid.tricycle.ch4_drive import (
    CH4_VIEW,
    DRIVES,
    LEGS_NOTE,
    MOTOR_NOTE,
    SeatSlip,
    hip_to_com,
    lean_left,
    overturned,
)
from shintai.humanoid.tricycle.ch4_riding import REF_CHANNELS, Rider, build_ch4, vehicle_pose2d, vehicle_roll
from shintai.humanoid.tricycle.load_monitor import LoadMonitor, fig4_3_metrics, recovery_windows, window_means
from shintai.humanoid.tricycle.navigation import crank_rate
from shintai.humanoid.tricycle.rig import legs_pedalling, pedal_axles
from shintai.humanoid.tricycle.switching import estimate_crank_angle
from shintai.humanoid.tricycle.vehicle import crank_centre
from shintai.scenarios.experiment import Rig
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment


def rig(params, variant, seed):
    """Drive straight at 0.3 m/s while the seat slips; ``with``: a Switcher runs the driving system or the
    recovery (STAND → SHIFT → RESEAT), each a Group of modules switched together."""
    motor = params["drive"] == "motor"
    body = build_ch4((), hip="contact", crank_motor=motor, grasp=params["grasp"])
    slip = SeatSlip(body, params["slip_rate_n_per_s"], params["slip_max_n"])
    rider = Rider(body, feet=motor)
    cruise = FunctionModule(lambda s: {"ref:crank_rate": crank_rate(STEPS_SPEED), "ref:theta_h": 0.0}, name="drive")
    if motor:
        driving, crank_of, base_fz, feet_rider = cruise, (lambda s: float(s["q:crank"])), FOOT_FOLLOW_F_TRG, None
        always = [rider, cr.CrankMotor()]
    else:  # the ch. 3 pedalling; Table 3.4 / Table 7.6: the driving foot force the STAND raises to 320 N
        legs, feet, _ = legs_pedalling(body, RECOVERY_PEDAL_REVOLUTIONS, DELTA_T * params["time_scale"])
        crank_of = lambda s: estimate_crank_angle(pedal_axles(feet, s), crank_centre())  # noqa: E731
        base_fz = LEGS_FZ
        driving = Group("drive", [cruise, legs], CONTROL_PERIOD)
        feet_rider = Rider(body, feet=True, arms=False, crank_of=crank_of, base_fz=base_fz, name="feet")
        always = [rider]
    recovery = SittingRecovery(lean_left, hip_to_com(body), base_fz)
    # §7.2: the recovery's ρ = y_g(n) is held while driving runs (the CoM stays where the last recovery
    # moved it)
    driving = Group("drive", [driving, FunctionModule(recovery.held, name="held_com")], CONTROL_PERIOD)
    modules, switcher = [FunctionModule(slip, name="seat_slip"), *always], None
    if variant == "with":
        riders = [rider] + ([feet_rider] if feet_rider is not None else [])
        # STAND gives the limbs fresh active functions (offline plans, §4.3.2 step 2): the impedance offsets
        # the slip built up in the hand and foot references are dropped
        replan = FunctionModule(lambda s: None, name="replan")
        replan.reset = lambda s: [r.reset(s) for r in riders]
        recover = Group("recover", [recovery, replan] + ([feet_rider] if feet_rider is not None else []),
                        CONTROL_PERIOD)
        trigger = RecoveryTrigger()
        switcher = Switcher([driving, recover], [
            ("drive", "recover", lambda s: trigger(lean_left(s), crank_of(s))),
            ("recover", "drive", lambda s: recovery.done)], initial="drive", name="osi")
        modules.append(switcher)
    else:
        modules.append(driving)
    start = vehicle_pose2d(body)
    monitor = LoadMonitor(body, rider)

    def signals(snap):
        rel = body.data.body("tricycle").xmat.reshape(3, 3).T @ (body.body_pos("waist") - body.site_pos("saddle_top"))
        active = switcher.active if switcher is not None else "drive"
        return {"roll": lean_left(snap), "vehicle_roll": vehicle_roll(body), "hip_y": rel[1], "slip_force": slip.force,
                "recovering": float(active == "recover"),
                "fz_feet": sum(rider.forces(snap, s)[2] for s in ("l_ankle", "r_ankle")),
                "saddle_fz": body.contact_force("waist")[2],
                "travel": float(np.hypot(*(vehicle_pose2d(body)[:2] - start[:2]))),
                **{f"load.{k}": v for k, v in monitor.sample(snap).items()}}

    return Rig(body, modules, channels=REF_CHANNELS, duration=params["max_s"], until=lambda s: overturned(body),
               record={5: signals}, view={**CH4_VIEW, "azimuth": 180.0, "elevation": -10.0, "distance": 2.8},
               state=SimpleNamespace(body=body, rider=rider, recovery=recovery, start=start, monitor=monitor))


def run_summary(run) -> dict:
    body, start = run.state.body, run.state.start
    end = vehicle_pose2d(body)
    rot = body.data.body("tricycle").xmat.reshape(3, 3)
    return {"overturned": int(overturned(body)), "sim_time_s": float(body.t),
            "foot_slip_m": float(max(np.abs((rot.T @ (body.site_pos(f"{s}_sole") - body.site_pos(f"pedal_{s}_top")))[1])
                                     for s in ("l", "r"))),
            "distance_m": float(np.hypot(*(end[:2] - start[:2])))}


def metrics(runs, params):
    with_, without = run_summary(runs["with"]), run_summary(runs["without"])
    rec, rec_wo = runs["with"].log, runs["without"].log
    recovery = runs["with"].state.recovery
    t_w = rec.times("roll")
    rec_flag = rec.values("recovering") > 0.5
    m = {
        "note": MOTOR_NOTE if params["drive"] == "motor" else LEGS_NOTE,
        "overturned_with_recovery": with_["overturned"], "overturned_without_recovery": without["overturned"],
        "max_roll_deg": float(np.abs(rec.values("roll")).max() / DEG),
        "max_roll_without_recovery_deg": float(np.abs(rec_wo.values("roll")[
            np.abs(rec_wo.values("vehicle_roll")) < 45 * DEG]).max() / DEG),
        "recoveries": len(recovery.history), "recovery_rolls_deg": [r / DEG for _, r, _ in recovery.history],
        "com_shift_m": float(recovery.index.rho[0]), "l_hip_cog_m": hip_to_com(runs["with"].state.body),
        "max_hip_slip_with_m": float(np.abs(rec.values("hip_y")).max()),
        "max_hip_slip_without_m": float(np.abs(rec_wo.values("hip_y")).max()),
        "distance_with_m": with_["distance_m"], "distance_without_m": without["distance_m"],
        "foot_slip_on_pedal_with_m": with_["foot_slip_m"],
        "time_to_overturn_without_s": without["sim_time_s"] if without["overturned"] else float("nan"),
        "drove_on_m": 0.0,
    }
    if rec_flag.any():
        # driving resumed: distance covered after the first recovery while not recovering, before any fall
        after = t_w > t_w[np.flatnonzero(rec_flag)[0]]
        travel = rec.values("travel")
        upright = np.abs(rec.values("vehicle_roll")) < 45 * DEG
        moving = np.diff(travel, prepend=travel[0])
        m["drove_on_m"] = float(np.sum(moving[after & ~rec_flag & upright]))
    m.update(load_metrics(rec, rec_flag))
    m.update(fig4_3_metrics(rec, rec_flag, runs["with"].state.monitor.joints))
    return m


def load_metrics(rec, rec_flag) -> dict:
    """Fig. 7.16 (I) and (II) before and after the first recovery, means over :func:`~shintai.humanoid.tricycle.load_monitor.recovery_windows`."""
    t = rec.times("load.force_norm")
    values = {k: rec.values(f"load.{k}") for k in LOAD_KEYS}
    windows = recovery_windows(t, rec_flag)
    m = {}
    for label, k in zip(("before", "after"), range(2)):
        w = window_means(t, values, *windows[k]) if windows else {key: float("nan") for key in LOAD_KEYS}
        for key, (name, unit, scale) in LOAD_KEYS.items():
            m[f"{name}_{label}_{unit}"] = abs(w[key]) * scale
    return m


LOAD_KEYS = {"force_norm": ("force_norm", "n", 1.0), "hand_force_norm": ("hand_force_norm", "n", 1.0),
             "foot_force_norm": ("foot_force_norm", "n", 1.0), "torque_norm": ("joint_torque_norm", "nm", 1.0),
             "com_y": ("com_offset", "m", 1.0), "hand_ab": ("hand_ab", "m", 1.0), "waist_ab": ("waist_ab", "m", 1.0),
             "waist_ab_rad": ("waist_ab", "deg", 1 / DEG)}


def draw(ctx, runs, params):
    plots.recovery(ctx, runs)
    rec = runs["with"].log
    plots.load_monitor(ctx, rec, recovery_windows(rec.times("load.force_norm"), rec.values("recovering") > 0.5))


experiment(
    "humanoid.sitting-recovery",
    covers=("000:fig4.3", "000:fig7.14", "000:fig7.15", "000:fig7.16"),
    source="seed 000 §4.3.2, §7.4.1, Eqs. 4.2–4.7, Table 7.6, Figs. 7.14–7.16",
    summary="A seat slip accumulating with driving: driving ⇄ interrupt-type sitting recovery (Switcher) vs driving alone",
    params=[
        Param("drive", "legs", "who turns the crank: legs (ch. 3 pedalling, the thesis) or motor (stand-in)",
              choices=DRIVES),
        Param("grasp", "grip", "hands on the grips: grip (hold the bar, can turn in it) or weld (6-DoF, Table 3.1)",
              choices=("grip", "weld")),
        Param("slip_rate_n_per_s", 5.0, "growth of the lateral hip–saddle slip force per second of driving [N/s] (ours)",
              lo=0.5, hi=50.0),
        Param("slip_max_n", 120.0, "largest slip force [N] (ours)", lo=10.0, hi=400.0),
        Param("max_s", 45.0, "driving time [s]", lo=5.0, hi=200.0),
        Param("time_scale", 0.25, "drive=legs only: Δt = 0.8 s × time_scale", lo=0.1, hi=1.0),
    ],
    checks=[
        Check("overturned_with_recovery", "==", 0,
              "thesis §7.4.1: '割り込み処理型座り直し制御を 4.3.2 項で述べた方策により実行することで傾斜を修正した安定化"
              "行動を実現している' (Fig. 7.14 success-1…4); ours against an injected slip force",
              kind="reproduction", row="000:fig7.14"),
        Check("overturned_without_recovery", "==", 1,
              "follows from our input: the injected SeatSlip force (5 N/s of driving, up to 120 N) overturns the rig; "
              "the thesis applies no force — 'Roll まわりの体幹傾斜が運転中に徐々に蓄積されており' (§7.4.1, fail-1…4) — "
              "and at slip_max_n = 10 our driving alone does not overturn", kind="consistency"),
        Check("recoveries", ">=", 1,
              "thesis §7.4.1: 'ヒューマノイドが運転操作中に体幹の Roll 傾斜を検知し(図 7.14 -(success-2))' and the "
              "sitting recovery runs (success-3, Fig. 7.15); trigger (1° at θ_c = kπ) and slip ours",
              kind="reproduction"),
        Check("drove_on_m", ">=", 1.0,
              "thesis §7.4.1: '図 7.14 -(success-4) に示すように継続的に運転の再開を行っている'; Table 7.6 'Drive again "
              "based on active and passive pedaling' (≥ 1 m after the recovery: ours)", kind="reproduction"),
        Check("force_norm_after_n", "<", "force_norm_before_n",
              "thesis §7.4.1 (Fig. 7.16-(I)): '座り直し動作後の図 7.16-(I) の右図では,… 力・関節トルクの大きさ(ノルム)"
              "も低減され,負荷が解消されていることが分かる' (hand and foot 6-axis forces; windows ours)",
              kind="reproduction", row="000:fig7.16"),
        Check("joint_torque_norm_after_nm", "<", "joint_torque_norm_before_nm",
              "thesis §7.4.1 (Fig. 7.16-(I)): '… 力・関節トルクの大きさ(ノルム)も低減され' (our servo torques)",
              kind="reproduction", row="000:fig7.16"),
        Check("com_offset_after_m", "<", "com_offset_before_m",
              "thesis §7.4.1 (Fig. 7.16-(I)): '重心位置が中央に寄り' (|CoM y − saddle| in the vehicle frame)",
              kind="reproduction", row="000:fig7.16"),
        Check("most_loaded_is_wrist_roll_before", "==", 1,
              "thesis §4.3.1, Fig. 4.3: '左手首関節の Roll 方向で特に負荷が大きくみられる' (declared before the first run: "
              "a wrist roll servo has the largest mean |τ| before the first recovery, the window §7.4.1 says shows "
              "Fig. 4.3's problems; either side, since our slip direction is ours)", kind="reproduction",
              row="000:fig4.3"),
        Check("com_y_before_m", ">", 0.0,
              "follows from our input: SeatSlip pushes the hip to +y (left); the thesis's '左側に重心が移動しており' "
              "(§4.3.1) comes from its robot's slip", kind="consistency", row="000:fig4.3"),
        Check("hand_ab_after_m", "<", "hand_ab_before_m",
              "thesis §7.4.1 (Fig. 7.16-(II)): '補正前 … モデルAの手先の把持箇所・腰部位置姿勢と,"
              "実環境ロボットモデルBの手先・腰部のズレが顕著' → '図 7.16 -(II) の右図のようにAとBが"
              "十分近くなった' (hands)",
              kind="reproduction", row="000:fig7.16"),
        Check("waist_ab_after_m", "<", "waist_ab_before_m",
              "thesis §7.4.1 (Fig. 7.16-(II)): '制御の難しい Base フレーム(腰部の骨盤リンク系)の"
              "搭乗位置・姿勢に関しても修正が可能となり' (waist position, feet midpoints aligned)",
              kind="reproduction", row="000:fig7.16"),
    ],
    thesis={"most_loaded_joint": ThesisValue("l_wrist_roll", "seed 000 §4.3.1, Fig. 4.3: '左手首関節の Roll 方向で特に"
                                             "負荷が大きくみられる'", "most_loaded_joint_before"),
            "overturned_without_recovery": ThesisValue(1, "seed 000 §7.4.1, Fig. 7.14 fail-4", "overturned_without_recovery"),
            "overturned_with_recovery": ThesisValue(0, "seed 000 §7.4.1, Fig. 7.14 success", "overturned_with_recovery")},
    rig=rig, variants=("with", "without"), filmed=("with",), metrics=metrics,
    plots=draw,
    video=True,
    smoke={"max_s": 8, "slip_rate_n_per_s": 50},  # a fast slip: one recovery starts (its before/after windows need ≈12 s)
)
