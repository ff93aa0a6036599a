"""``humanoid.tricycle-slalom``: E3/E5, HRP2 steers ±25° and pedals — a right curve, a left curve and the
slalom of Fig. 3.21 from a joystick script, sequential mode (seed 000 §3.5.2, §3.5.4)."""

from __future__ import annotations

from shintai.humanoid.constants import D_THETA_C, D_THETA_H, DEG, DELTA_T, TRICYCLE
from shintai.humanoid.tricycle import plots
from shintai.humanoid.tricycle.operation import OperationSchedule
from shintai.humanoid.tricycle.ride import MODEL_ERROR_PARAMS, Ride, ride_metrics, slalom_goals
from shintai.humanoid.tricycle.rig import F_TRG
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment


def rig(params, variant, seed):
    goals = slalom_goals(params["curve_deg"] * DEG, params["limit_deg"] * DEG, params["slalom_deg"] * DEG)
    schedule = OperationSchedule(0.0, 0.0, goals, DELTA_T * params["time_scale"], D_THETA_H, D_THETA_C)
    return Ride(schedule, F_TRG, params["crank_error_mm"], params["handle_error_mm"]).rig()


def metrics(runs, params):
    return ride_metrics(runs["run"].log, runs["run"].state)


def draw(ctx, runs, params):
    log = runs["run"].log
    plots.ride(ctx, [(log, "curves at −25°, +25°, then the slalom (Fig. 3.21), sequential mode", F_TRG)])
    plots.paths(ctx, [(log, "vehicle path")])


experiment(
    "humanoid.tricycle-slalom",
    covers=("000:fig3.19", "000:fig3.20", "000:fig3.21", "000:fig3.24"),
    source="seed 000 §3.5.2 (E3, Figs. 3.19–3.21), §3.5.4 (E5, Fig. 3.24), Fig. 3.16, Eqs. 3.7, 3.13–3.14, 3.19",
    summary="E3/E5: HRP2 steers ±25° and pedals — a right curve, a left curve and a slalom from a joystick script",
    params=[
        Param("time_scale", 1.0, "Δt = 0.8 s × time_scale (1 = the thesis's lab setting)", lo=0.1, hi=1.0),
        Param("curve_deg", 180.0, "crank angle pedalled on each of the two curves [deg]", lo=10.0, hi=360.0),
        Param("slalom_deg", 360.0, "crank angle of the slalom, half at −Θ_H, half at +Θ_H [deg] (Fig. 3.21: 360°)",
              lo=20.0, hi=720.0),
        Param("limit_deg", 25.0, "steering amplitude Θ_H [deg] (Table 3.4: 25°)", lo=5.0, hi=25.0),
        *MODEL_ERROR_PARAMS,
    ],
    checks=[
        Check("falls", "==", 0,
              "thesis §3.5.2: the curves at θ_h = −25°, +25° and the slalom driven ('… とした蛇行走行の実験結果を表して"
              "いる', Figs. 3.19–3.21; '搭乗型機器の操作行動が適切に実現されている'); §3.5.4 E5 ('… 運転操作行動を室内の"
              "平坦な床面上で検証した', Fig. 3.24)", kind="reproduction"),
        Check("max_handle_error_deg", "<=", D_THETA_H / DEG,
              "thesis §3.5.2: the commanded θ_h = ∓Θ_H = ∓25° of Figs. 3.19–3.21 reached; the 5° (= Δθ_h) "
              "tolerance is ours", kind="reproduction"),
        Check("leg_role_swaps", "==", "leg_role_swaps_expected",
              "Eq. 3.19 as implemented: one leg swap per switching angle π/2 + δ_c + kπ the crank passes",
              kind="consistency"),
        Check("arm_role_swaps", "==", "arm_role_swaps_expected",
              "Eq. 3.19 (θ_h^init = 0) as implemented: one arm swap per pass of the handle through 0",
              kind="consistency"),
        Check("drive_wheel_travel_per_rev_m", ">=", 0.97 * TRICYCLE.travel_per_rev,
              "follows from our input: D_c = 2.45 m is the tricycle's gear setting (App. A.1.1: '… D_c が 2.45[m] と"
              "なるようなクランクギアに設定している'), built into our model; confirms only that our wheels do not slip "
              "(§3.5.1's assumption) (−3 %)", kind="consistency"),
        Check("drive_wheel_travel_per_rev_m", "<=", 1.03 * TRICYCLE.travel_per_rev, "as above (+3 %)",
              name="drive_wheel_travel_upper", kind="consistency"),
        Check("passive_force_mean_n", ">=", 0.9 * F_TRG,
              "a property of our passive law while driving (the seed reports no forces for E3/E5) (−10 %)",
              kind="consistency"),
        Check("passive_force_mean_n", "<=", 1.1 * F_TRG, "as above (+10 %)", name="passive_force_upper",
              kind="consistency"),
    ],
    thesis={
        "steering_range_deg": ThesisValue([-25.0, 25.0], "seed 000 §3.5.2 (Figs. 3.19–3.21), Table 3.4",
                                          "handle_range_deg"),
        "result": ThesisValue("curves and slalom driven (snapshots only, no numbers)", "seed 000 §3.5.2, §3.5.4"),
    },
    rig=rig, metrics=metrics, plots=draw,
    video=True,
    smoke={"time_scale": 0.25, "curve_deg": 40, "slalom_deg": 60, "limit_deg": 10},  # one leg swap, three arm swaps
)
