"""``snake.tracking``: two-point (head + tail) trajectory tracking with periodic mode selection, seed 001 §3.3.
One run per plant: the chosen one and, on MuJoCo, the kinematic run it is compared with."""

from __future__ import annotations

from shintai.scenarios.registry import Check, ThesisValue, experiment
from shintai.snake.constants import CH3_ROBOT
from shintai.snake.plots import plot_modes, plot_time_series, plot_top_view
from shintai.snake.tracking import PARAMS, TrackingRun, kinematic_comparison, tracking_rig


def variants(params):
    return ("mujoco", "kinematic") if params["plant"] == "mujoco" else ("kinematic",)


def rig(params, variant, seed):
    return tracking_rig(params["duration_s"], params["candidates"], plant=variant)


def metrics(runs, params):
    run = TrackingRun.of(runs[params["plant"]])
    if params["plant"] == "kinematic":
        return run.metrics()
    return {**run.metrics(), **kinematic_comparison(run, TrackingRun.of(runs["kinematic"]))}


def plots(ctx, runs, params):
    run = TrackingRun.of(runs[params["plant"]])
    plot_top_view(ctx, run)
    plot_time_series(ctx, run)
    plot_modes(ctx, run)


experiment(
    "snake.tracking",
    source="seed 001 §3.3",
    covers=("001:fig3.6",),
    summary="two-point (head + tail) trajectory tracking with periodic mode selection, n = 9, 120 s",
    params=PARAMS,
    checks=(
        Check("max_pos_error_m", "<=", 0.005,
              "thesis §3.3: all errors 'small' (Fig. 3.6c, no number in the text); 5 mm = 5× the mocap's "
              "1 mm nominal error, spec §5.4 #10", kind="reproduction"),
        Check("max_heading_error_rad", "<=", 0.02, "thesis §3.3 qualitative; threshold proposed in spec §5.4 #10", kind="reproduction"),
        Check("final_pos_error_m", "<=", 0.001, "thesis §3.3 qualitative; spec §5.4 #10 'final errors < 1 mm'", kind="consistency"),
        Check("max_abs_joint_rad", "<", CH3_ROBOT.joint_limit,
              "thesis §3.3 / Fig. 3.7: joints stay inside their limits; limit π/2 chosen (Ch. 4 robot, §4.5)", kind="reproduction"),
        Check("grounded_wheels_max", "<=", 4, "thesis §3.3: every selected mode had n_σ = 4 (allowed 4–5)", kind="reproduction"),
        Check("distinct_modes", ">=", 5, "thesis §3.3: 14 of 66 modes selected; band 5–30 from spec §5.4 #10",
              name="distinct_modes_low", kind="reproduction"),
        Check("distinct_modes", "<=", 30, "thesis §3.3: 14 of 66 modes selected; band 5–30 from spec §5.4 #10",
              name="distinct_modes_high", kind="reproduction"),
        Check("stopped_fraction", "<", 0.05,
              "thesis §3.2.5: the limit stops the robot only near singular configuration II; spec §5.4 #10", kind="consistency"),
        Check("min_sigma_a", ">", 0.01, "sub-task (b), avoid singular configuration I (§3.2.3); spec §5.4 #10", kind="reproduction"),
    ),
    thesis={
        "candidate_count": ThesisValue(66, "seed 001 §3.3 (n = 9, n_l = n_g = 4, n_c = 2)", "candidate_count"),
        "distinct_modes": ThesisValue(14, "seed 001 §3.3 ('only 14 of the 66 modes were selected')",
                                      "distinct_modes"),
        "grounded_wheels": ThesisValue(4, "seed 001 §3.3 (every selected mode had n_σ = 4)", "grounded_wheels_max"),
        "tracking_error": ThesisValue("small (Fig. 3.6c only; no number in the text)", "seed 001 §3.3",
                                      "max_pos_error_m"),
        "joint_limits": ThesisValue("not exceeded (Fig. 3.7)", "seed 001 §3.3", "max_abs_joint_rad"),
    },
    rig=rig, variants=variants, filmed=("mujoco",), metrics=metrics, plots=plots,
    demo=True,
    video=lambda params: params["plant"] == "mujoco",
    demo_params={"plant": "mujoco"},  # the demo films the physical snake (the thesis's own runs are kinematic)
    estimate_s=60.0,
    smoke={"duration_s": 4.0},  # two mode selections (t = 0, 2 s)
)
