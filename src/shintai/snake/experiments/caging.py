"""``snake.caging``: caging transport, seed 001 §3.4.1 — a box inside the U carried by the two-stage targets
(3.22)–(3.23), on MuJoCo (compared with the kinematic run) or on the kinematic plant."""

from __future__ import annotations

from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.snake.caging import box_track, caging_metrics, caging_rig, mismatch_growth
from shintai.snake.constants import CAGING, CH3_ROBOT
from shintai.snake.plots import plot_box, plot_caging, plot_modes, plot_time_series
from shintai.snake.tracking import TrackingRun


def rig(params, variant, seed):
    return caging_rig(params["duration_s"], variant, params["mocap_noise_m"], seed)


def variants(params):
    return ("mujoco", "kinematic") if params["plant"] == "mujoco" else ("kinematic",)


def metrics(runs, params):
    main = runs[params["plant"]]
    run = TrackingRun.of(main)
    reference = None
    if params["plant"] == "mujoco":
        run.physics.update(mismatch_growth(run, main.log.values("wheels.contact")))
        reference = TrackingRun.of(runs["kinematic"])
    return caging_metrics(run, box_track(main), reference)


def plots(ctx, runs, params):
    main = runs[params["plant"]]
    run, track = TrackingRun.of(main), box_track(main)
    plot_caging(ctx, run, track)
    plot_box(ctx, run, track)
    plot_time_series(ctx, run)
    plot_modes(ctx, run)


experiment(
    "snake.caging",
    source="seed 001 §3.4.1",
    covers=("001:fig3.8",),
    summary="caging transport: a box inside the U carried by the two-stage targets (3.22)–(3.23), MuJoCo or kinematic",
    params=(
        Param("plant", "mujoco", "mujoco: physical snake with a box (joint encoders, mocap head pose); kinematic: "
              "the thesis's model with a pushed square", choices=("mujoco", "kinematic")),
        Param("duration_s", CAGING.t_end, "simulated time; the targets keep t_s1 = 30 s, t_end = 120 s",
              lo=0.05, hi=CAGING.t_end),
        Param("mocap_noise_m", 0.0, "head-position noise σ of the motion capture [m] (OptiTrack nominal 1 mm, §3.3)",
              lo=0.0, hi=0.01),
    ),
    checks=(
        Check("max_pos_error_m", "<=", 0.01, "thesis §3.4.1: controlled variables 'follow the targets well' "
              "(Fig. 3.8c, no number); 1 cm from spec §5.4 #11 (kinematic prototype: 4.1 mm)", kind="reproduction"),
        Check("rms_pos_error_m", "<=", 0.001, "spec §5.4 #11 (kinematic prototype: 0.22 mm)", kind="consistency"),
        Check("final_pos_error_m", "<=", 0.001, "spec §5.4 #11: final head and tail within 1 mm", kind="consistency"),
        Check("max_abs_joint_rad", "<", CH3_ROBOT.joint_limit, "thesis §3.2.3 sub-task (a); spec §5.4 #11", kind="consistency"),
        Check("stopped_fraction", "<", 0.1, "thesis §3.2.5; spec §5.4 #11 (prototype 2 %)", kind="consistency"),
        Check("box_left_cage", "==", 0, "thesis §3.4.1 / Fig. 3.9: the box stays enclosed and is carried", kind="reproduction"),
        Check("box_advance_x_m", ">=", 0.275, "thesis §3.4.1: the box is carried as the robot advances; the "
              "targets advance 0.55 m in x, so at least half of it", kind="reproduction"),
    ),
    thesis={
        "tracking": ThesisValue("follows the targets well (Fig. 3.8c, no number in the text)", "seed 001 §3.4.1",
                                "max_pos_error_m"),
        "box": ThesisValue("carried as the robot advances (Fig. 3.9)", "seed 001 §3.4.1", "box_advance_x_m"),
        "modes": ThesisValue("the mode changes with the situation", "seed 001 §3.4.1", "distinct_modes"),
    },
    rig=rig, variants=variants, filmed=("mujoco",), metrics=metrics, plots=plots,
    video=lambda params: params["plant"] == "mujoco",
    smoke={"duration_s": 0.5},
)
