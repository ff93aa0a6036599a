"""Scenarios of seed 001 ch. 3: two-point trajectory tracking (§3.3) and the switching ablation (§3.1 claim).

Both run the two-point controller (two_point.py) on the kinematic plant (plant.py) in the shared Loop,
with the §3.3 constants, K_p = 4·I_6 (A5), unwrapped angle targets (A6) and the candidate set chosen in
constants.TwoPointGains (66 by default; ``candidates=80`` runs the literal reading).
``plant=mujoco`` runs the same controller on the physical snake of mujoco_plant.py (mocap head pose,
joint encoders, wheels lifted by the pitch joints; ``--video`` films it) and adds the physical checks of
the kinematic model: ``lateral_slip_fraction`` (sideways slide / rolled distance of the floor-touching
wheels), ``head_path_diff_vs_kinematic_m`` (head paths of the MuJoCo and the kinematic run of the same
scenario), ``head_replay_error_m`` (the kinematic model replayed on the measured joint motion over each
t_σ window) and ``contact_mismatch_fraction``.

Error metrics: e = c_{c,d} − c_c (Fig. 3.6c). A point's position error is the Euclidean norm of its
(x, y) error; ``*_pos_error_m`` takes the larger of head and tail. The final sample is the state after
the last step.
"""

from __future__ import annotations

from contextlib import nullcontext
from dataclasses import dataclass, field

import numpy as np

from shintai.core import Loop, Recorder
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, TRACKING, TrackingExperiment
from shintai.snake.model import body_points, configuration, wheel_poses
from shintai.snake.mujoco_plant import MujocoSnake, head_path_difference, replay_error
from shintai.snake.plant import KinematicSnake
from shintai.snake.targets import Ramp, unwrap_targets
from shintai.snake.two_point import TwoPointController, TwoPointLaw

PLANTS = {"kinematic": KinematicSnake, "mujoco": MujocoSnake}  # plant name -> Body class (w_h0, phi0, geometry, dt)


@dataclass
class TrackingRun:
    """Time series of one two-point run (one sample per control period, plus the final state)."""

    name: str
    t: np.ndarray
    c: np.ndarray  # (N, 6) controlled variables c_c
    c_d: np.ndarray  # (N, 6) targets c_{c,d}
    phi: np.ndarray  # (N, n)
    grounded: np.ndarray  # (N−1, n) selected mode of each control period
    mode: np.ndarray  # (N−1,) candidate index
    stopped: np.ndarray  # (N−1,) input limit (3.20) active
    sigma_a: np.ndarray
    sigma_b: np.ndarray
    V_m: np.ndarray
    slip: np.ndarray
    candidates: int
    selections: int
    physics: dict = field(default_factory=dict)  # MujocoSnake.slip_summary() on the MuJoCo plant

    @property
    def error(self) -> np.ndarray:
        return self.c_d - self.c

    @property
    def pos_error(self) -> np.ndarray:
        """max(‖e_head,xy‖, ‖e_tail,xy‖) per sample."""
        e = self.error
        return np.maximum(np.hypot(e[:, 0], e[:, 1]), np.hypot(e[:, 3], e[:, 4]))

    def metrics(self) -> dict:
        n_sigma = self.grounded.sum(axis=1)
        return {
            "max_pos_error_m": float(self.pos_error.max()),
            "rms_pos_error_m": float(np.sqrt(np.mean(self.pos_error ** 2))),
            "max_heading_error_rad": float(np.abs(self.error[:, [2, 5]]).max()),
            "final_pos_error_m": float(self.pos_error[-1]),
            "distinct_modes": int(len(np.unique(self.mode))),
            "grounded_wheels_min": int(n_sigma.min()),
            "grounded_wheels_max": int(n_sigma.max()),
            "max_abs_joint_rad": float(np.abs(self.phi).max()),
            "stopped_fraction": float(self.stopped.mean()),
            "min_sigma_a": float(self.sigma_a.min()),
            "min_sigma_b": float(self.sigma_b.min()),
            "max_slip_m_s": float(self.slip.max()),
            "candidate_count": self.candidates,
            "mode_selections": self.selections,
        }


def simulate_tracking(duration: float, experiment: TrackingExperiment = TRACKING, candidates: int = 66,
                      switching: bool = True, plant: str = "kinematic", recorder: Recorder | None = None,
                      name: str = "two_point", progress=None, video_path=None) -> TrackingRun:
    """Run the §3.3 experiment for ``duration`` s (ramp (3.21) over t_end); mode frozen after t = 0 unless
    ``switching``. ``video_path``: film the run (MuJoCo plant only)."""
    if candidates not in (66, 80):
        raise ValueError(f"candidates must be 66 or 80, got {candidates!r}")
    if plant not in PLANTS:
        raise ValueError(f"plant must be one of {sorted(PLANTS)}, got {plant!r}")
    if video_path is not None and plant != "mujoco":
        raise ValueError("--video needs --set plant=mujoco (the kinematic plant has nothing to render)")
    law = TwoPointLaw(CH3_ROBOT, CH3_GAINS, head_end_lifted=(candidates == 66))
    body = PLANTS[plant](experiment.w_h0, experiment.phi0, CH3_ROBOT, CH3_GAINS.dt)
    c0 = law.controlled(configuration(experiment.w_h0, experiment.phi0, CH3_ROBOT.l))
    target = Ramp(c0, unwrap_targets(c0, experiment.c_e), experiment.t_end)
    return run_two_point(body, law, target, duration, CH3_GAINS.t_sigma if switching else None, recorder, name,
                         progress, video_path)


def run_two_point(body, law: TwoPointLaw, target, duration: float, select_period: float | None,
                  recorder: Recorder | None = None, name: str = "two_point", progress=None, video_path=None,
                  modules=()) -> TrackingRun:
    """Run the two-point controller (period δt, mode selection every ``select_period``) on ``body`` toward
    ``target`` for ``duration`` s, with extra ``modules`` (probes) in the loop; film it to ``video_path``."""
    controller = TwoPointController(law, target, select_period, name=name)
    recorder = recorder if recorder is not None else Recorder()
    with body.video(video_path) if video_path is not None else nullcontext():
        Loop(body, [controller, *modules], recorder).run(duration, progress=progress)
    final = body.snapshot()
    c_final = law.controlled(configuration(final["w_h"], final["phi"], law.geometry.l))
    get = lambda key: recorder.values(f"{name}.{key}")  # noqa: E731
    return TrackingRun(
        name=name,
        t=np.append(recorder.times(f"{name}.c"), body.t),
        c=np.vstack((get("c"), c_final)),
        c_d=np.vstack((get("c_d"), target(body.t)[0])),
        phi=np.vstack((get("phi"), final["phi"])),
        grounded=get("grounded").astype(bool), mode=get("mode").astype(int), stopped=get("stopped").astype(bool),
        sigma_a=get("sigma_a"), sigma_b=get("sigma_b"), V_m=get("V_m"), slip=get("slip"),
        candidates=len(law.candidates), selections=controller.selections,
        physics=body.slip_summary() if isinstance(body, MujocoSnake) else {},
    )


def kinematic_comparison(run: TrackingRun, duration: float, candidates: int, switching: bool) -> dict:
    """A MuJoCo run against the kinematic model: its slip summary, the head-path difference to the kinematic
    plant's run of the same scenario, and the kinematic model replayed on its measured joints per t_σ."""
    reference = simulate_tracking(duration, candidates=candidates, switching=switching, name="kinematic")
    window = int(round(CH3_GAINS.t_sigma / CH3_GAINS.dt))
    return {**run.physics,
            "head_path_diff_vs_kinematic_m": head_path_difference(run.c, reference.c),
            "head_replay_error_m": replay_error(run.c[:, :3], run.phi, run.grounded, CH3_ROBOT.l, CH3_GAINS.dt, window)}


# ----------------------------------------------------------------------------------------------- plots

def draw_body(ax, w_h, phi, grounded, alpha=1.0, label=None):
    cfg = configuration(w_h, phi, CH3_ROBOT.l)
    pts = body_points(cfg)
    wheels = wheel_poses(cfg)
    ax.plot(pts[:, 0], pts[:, 1], "-", color="0.35", lw=1.5, alpha=alpha, label=label)
    ax.plot(*pts[0], "k^", ms=6, alpha=alpha)
    draw_wheels(ax, wheels, grounded, alpha)


def draw_wheels(ax, wheels, grounded, alpha=1.0, size=28):
    """Wheels (rows x, y, ...) coloured by mode: grounded filled red, lifted hollow blue."""
    grounded = np.asarray(grounded, dtype=bool)
    ax.scatter(wheels[grounded, 0], wheels[grounded, 1], s=size, c="tab:red", zorder=3, alpha=alpha)
    ax.scatter(wheels[~grounded, 0], wheels[~grounded, 1], s=size, facecolors="white", edgecolors="tab:blue",
               zorder=3, alpha=alpha)


def draw_link_points(ax, points, grounded, alpha=1.0, size=22) -> None:
    """A simulated body as logged by scenarios_physical.link_points (head tip, link origins, tail tip; wheel i
    at row 2i): the polyline, the head ▲ and the wheels coloured by mode (:func:`draw_wheels`)."""
    ax.plot(points[:, 0], points[:, 1], "-", color="0.3", lw=2, alpha=alpha)
    ax.plot(*points[0], "^", color="tab:orange", alpha=alpha)
    draw_wheels(ax, points[2::2], grounded, alpha, size)


def draw_track(ax, actual, target, color, label, target_label) -> None:
    """A control point's path (solid) against its target (dashed), both (N, 2)."""
    ax.plot(target[:, 0], target[:, 1], "--", color=color, lw=1, label=target_label)
    ax.plot(actual[:, 0], actual[:, 1], "-", color=color, lw=2, alpha=0.6, label=label)


def wheel_legend(ax, size=28, lifted="lifted wheel") -> None:
    """Legend entries for :func:`draw_wheels`."""
    ax.scatter([], [], c="tab:red", s=size, label="grounded wheel")
    ax.scatter([], [], facecolors="white", edgecolors="tab:blue", s=size, label=lifted)


def shade_stopped(ax, t, stopped, dt=CH3_GAINS.dt) -> None:
    """Red bands over the control periods stopped by the input limit (3.20)."""
    for k in np.flatnonzero(stopped):
        ax.axvspan(t[k], t[k] + dt, color="tab:red", alpha=0.15, lw=0)


def plot_top_view(ctx, run: TrackingRun, name: str = "top_view") -> None:
    """Fig. 3.6(a)(b) analogue: bodies at a few times (wheels red = grounded, hollow blue = lifted), paths vs targets."""
    with ctx.figure(name, figsize=(8.5, 5.0)) as (fig, ax):
        ax.plot(run.c_d[:, 0], run.c_d[:, 1], "--", color="tab:orange", lw=1, label="head target")
        ax.plot(run.c_d[:, 3], run.c_d[:, 4], "--", color="tab:green", lw=1, label="tail target")
        ax.plot(run.c[:, 0], run.c[:, 1], "-", color="tab:orange", lw=2, alpha=0.6, label="head")
        ax.plot(run.c[:, 3], run.c[:, 4], "-", color="tab:green", lw=2, alpha=0.6, label="tail wheel")
        picks = np.unique(np.linspace(0, len(run.mode) - 1, 5).astype(int))
        labelled = []
        for j, k in enumerate(picks):
            draw_body(ax, run.c[k, :3], run.phi[k], run.grounded[k], alpha=0.3 + 0.7 * j / max(len(picks) - 1, 1))
            if all(np.hypot(*(run.c[k, :2] - p)) > 0.02 for p in labelled):  # no overlapping labels at a stall
                ax.annotate(f"{run.t[k]:.0f} s", run.c[k, :2], fontsize=7, xytext=(3, 3), textcoords="offset points")
                labelled.append(run.c[k, :2])
        wheel_legend(ax)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.legend(fontsize=7, loc="best")
        ax.set_title("top view (head ▲); dashed: targets (3.21)", fontsize=9)


def plot_time_series(ctx, run: TrackingRun, name: str = "errors") -> None:
    """Fig. 3.6(c) analogue: errors e_1..e_6, V_m and σ_min(A_c), σ_min(B_c); stopped periods shaded."""
    t, tc = run.t, run.t[:-1]
    with ctx.figure(name, nrows=3, ncols=1, figsize=(7.5, 7.5), sharex=True) as (fig, ax):
        e = run.error
        for i, lab in zip((0, 1, 3, 4), ("e1 head x", "e2 head y", "e4 tail x", "e5 tail y")):
            ax[0].plot(t, 1e3 * e[:, i], lw=1, label=lab)
        ax[0].set_ylabel("position error [mm]")
        ax[1].plot(t, e[:, 2], lw=1, label="e3 head θ")
        ax[1].plot(t, e[:, 5], lw=1, label="e6 tail θ")
        ax[1].set_ylabel("heading error [rad]")
        ax[2].semilogy(tc, run.V_m, lw=1, label="V_m (3.19) = σ_min(B_c,σ)")
        ax[2].semilogy(tc, run.sigma_a, lw=1, label="σ_min(A_c,σ)")
        ax[2].set_ylabel("singular values")
        ax[2].set_xlabel("t [s]")
        for a in ax:
            shade_stopped(a, tc, run.stopped)
            a.legend(fontsize=7, ncol=2, loc="best")
        ax[0].set_title(f"{run.name}: red bands = stopped by the input limit (3.20)", fontsize=9)


def plot_modes(ctx, run: TrackingRun, name: str = "modes") -> None:
    """Mode timeline (Fig. 3.6(c) bottom): grounded (red) / lifted wheels per control period, and the joints (Fig. 3.7)."""
    tc = run.t[:-1]
    with ctx.figure(name, nrows=2, ncols=1, figsize=(7.5, 6.0), sharex=True) as (fig, ax):
        n = run.grounded.shape[1]
        ax[0].imshow(run.grounded.T, aspect="auto", cmap="Reds", vmin=0, vmax=1.4, interpolation="nearest",
                     extent=(tc[0], tc[-1] + CH3_GAINS.dt, n + 0.5, 0.5))
        ax[0].set_ylabel("wheel")
        ax[0].set_yticks(range(1, n + 1))
        ax[0].set_title(f"grounded wheels (red); {len(np.unique(run.mode))} distinct modes of "
                        f"{run.candidates} candidates", fontsize=9)
        for i in range(run.phi.shape[1]):
            ax[1].plot(run.t, run.phi[:, i], lw=1, label=f"φ{i + 1}")
        for s in (-1, 1):
            ax[1].axhline(s * CH3_ROBOT.joint_limit, ls=":", color="k", lw=1)
            ax[1].axhline(s * CH3_GAINS.phi_th, ls="--", color="0.6", lw=0.8)
        ax[1].set_ylabel("yaw joints [rad]")
        ax[1].set_xlabel("t [s]")
        ax[1].legend(fontsize=6, ncol=5, loc="best")


# ------------------------------------------------------------------------------------------- scenarios

COMMON_PARAMS = (
    Param("plant", "kinematic", "body to run: the thesis's kinematic model, or the physical snake in MuJoCo",
          choices=tuple(PLANTS)),
    Param("duration_s", TRACKING.t_end, "simulated time; the ramp (3.21) keeps t_end = 120 s", lo=0.05, hi=TRACKING.t_end),
    Param("candidates", 66, "candidate modes: 66 (head end counts as lifted) or 80 (literal rules), A8",
          choices=(66, 80)),
)


@scenario(
    "snake.tracking",
    source="seed 001 §3.3",
    summary="two-point (head + tail) trajectory tracking with periodic mode selection, n = 9, 120 s",
    params=COMMON_PARAMS,
    checks=(
        Check("max_pos_error_m", "<=", 0.005,
              "thesis §3.3: all errors 'small' (Fig. 3.6c, no number in the text); 5 mm = 5× the mocap's "
              "1 mm nominal error, spec §5.4 #10"),
        Check("max_heading_error_rad", "<=", 0.02, "thesis §3.3 qualitative; threshold proposed in spec §5.4 #10"),
        Check("final_pos_error_m", "<=", 0.001, "thesis §3.3 qualitative; spec §5.4 #10 'final errors < 1 mm'"),
        Check("max_abs_joint_rad", "<", CH3_ROBOT.joint_limit,
              "thesis §3.3 / Fig. 3.7: joints stay inside their limits; limit π/2 chosen (Ch. 4 robot, §4.5)"),
        Check("grounded_wheels_max", "<=", 4, "thesis §3.3: every selected mode had n_σ = 4 (allowed 4–5)"),
        Check("distinct_modes", ">=", 5, "thesis §3.3: 14 of 66 modes selected; band 5–30 from spec §5.4 #10",
              name="distinct_modes_low"),
        Check("distinct_modes", "<=", 30, "thesis §3.3: 14 of 66 modes selected; band 5–30 from spec §5.4 #10",
              name="distinct_modes_high"),
        Check("stopped_fraction", "<", 0.05,
              "thesis §3.2.5: the limit stops the robot only near singular configuration II; spec §5.4 #10"),
        Check("min_sigma_a", ">", 0.01, "sub-task (b), avoid singular configuration I (§3.2.3); spec §5.4 #10"),
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
    demo=True,
    video=True,
    demo_video=False,  # the demo runs the kinematic plant; only plant=mujoco renders
)
def tracking(ctx) -> dict:
    p = ctx.params
    run = simulate_tracking(p["duration_s"], candidates=p["candidates"], plant=p["plant"], recorder=ctx.recorder,
                            progress=ctx.progress, video_path=ctx.video_path if ctx.video else None)
    ctx.sim_time_s = float(run.t[-1])
    plot_top_view(ctx, run)
    plot_time_series(ctx, run)
    plot_modes(ctx, run)
    metrics = run.metrics()
    if p["plant"] == "mujoco":
        metrics.update(kinematic_comparison(run, p["duration_s"], p["candidates"], switching=True))
    return metrics


def labelled(metric: str, label: str) -> str:
    """``metric`` with the run's label before its unit: head_replay_error_m → head_replay_error_fixed_m."""
    return f"{metric[:-2]}_{label}_m" if metric.endswith("_m") else f"{metric}_{label}"


@scenario(
    "snake.switching-ablation",
    source="seed 001 §3.1, §3.3",
    summary="§3.3 targets with the mode frozen after t = 0 vs. periodic switching: does switching matter?",
    params=COMMON_PARAMS,
    checks=(
        Check("final_pos_error_fixed_m", ">=", 0.1,
              "thesis §3.1: with fixed constraints the robot meets singular configuration II and cannot continue; "
              "0.1 m from spec §5.4 #12"),
        Check("final_pos_error_switching_m", "<", 0.005, "thesis §3.3: with switching both points track (Fig. 3.6c)"),
        Check("final_pos_error_fixed_m", ">", "final_pos_error_switching_m", "thesis §3.1 claim: switching helps",
              name="switching_beats_fixed"),
    ),
    thesis={"claim": ThesisValue("fixed constraints stall at singular configuration II; switching continues",
                                 "seed 001 §3.1, §3.2.5")},
    video=True,
)
def switching_ablation(ctx) -> dict:
    p = ctx.params
    runs = {}
    for i, (label, switching) in enumerate((("switching", True), ("fixed", False))):
        video = (ctx.video_path if label == "switching" else ctx.out / "video_fixed.mp4") if ctx.video else None
        runs[label] = simulate_tracking(p["duration_s"], candidates=p["candidates"], switching=switching,
                                        plant=p["plant"], recorder=ctx.recorder, name=label,
                                        progress=lambda f, i=i: ctx.progress((i + f) / 2), video_path=video)
    ctx.sim_time_s = float(sum(r.t[-1] for r in runs.values()))
    with ctx.figure("ablation", nrows=2, ncols=1, figsize=(7.5, 6.0), sharex=True) as (fig, ax):
        for label, run in runs.items():
            ax[0].semilogy(run.t, np.maximum(run.pos_error, 1e-9), lw=1, label=f"{label}: position error")
            ax[1].plot(run.t[:-1], np.cumsum(run.stopped) * CH3_GAINS.dt, lw=1, label=f"{label}: time stopped")
        ax[0].set_ylabel("max(head, tail) error [m]")
        ax[1].set_ylabel("cumulative stopped time [s]")
        ax[1].set_xlabel("t [s]")
        for a in ax:
            a.legend(fontsize=7)
    for label, run in runs.items():
        plot_top_view(ctx, run, name=f"top_view_{label}")
    m = {}
    for label, run in runs.items():
        rm = run.metrics()
        m[f"final_pos_error_{label}_m"] = rm["final_pos_error_m"]
        m[f"max_pos_error_{label}_m"] = rm["max_pos_error_m"]
        m[f"stopped_fraction_{label}"] = rm["stopped_fraction"]
        m[f"min_sigma_b_{label}"] = rm["min_sigma_b"]
        if p["plant"] == "mujoco":
            physical = kinematic_comparison(run, p["duration_s"], p["candidates"], switching=label == "switching")
            m.update({labelled(key, label): value for key, value in physical.items()})
    return m


from shintai.snake import scenarios_caging, scenarios_door, scenarios_handcart  # noqa: F401,E402
from shintai.snake import scenarios_two_plane  # noqa: F401,E402
