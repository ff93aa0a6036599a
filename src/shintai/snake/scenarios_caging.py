"""Caging transport — seed 001 §3.4.1 (Figs. 3.8–3.9), scenario ``snake.caging``.

The U-shaped n = 9 body (φ(0) of §3.4.1, head w̃_h(0) and every constant and gain as §3.3) encloses a box
and carries it with the two-stage targets (3.22)–(3.23), c_{c,e1} = [0.1, 0, π, 0.1, −0.5, 0] at
t_s1 = 30 s and c_{c,e2} = [0.55, 0, π, 0.55, −0.5, 0] at t_end = 120 s (stage 2 read as
(t − t_s1)/(t_end − t_s1), A7; tail heading 0 ≡ 2π, A6), by the planar two-point law of two_point.py.

``plant=mujoco`` (default): mujoco_plant.MujocoSnake with a free box; the controller reads joint encoders
and the mocap head pose as the real robot did (§3.3). The same scenario on the kinematic plant is run
alongside; the metrics say how far physics departs from it (head path difference, measured sideways slip
as a fraction of the rolled distance, contact mismatch). ``plant=kinematic``: the thesis's model, with
the box as a square pushed by the body (:class:`KinematicBox`). The box's size, mass and friction are not
given (A12): constants.CagingBox.
"""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Rectangle

from shintai.core import Recorder
from shintai.core.runtime import Module
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.snake.constants import CAGING, CAGING_BOX, CH3_GAINS, CH3_ROBOT, MUJOCO_SNAKE, SnakeGeometry
from shintai.snake.model import body_points, configuration
from shintai.snake.mujoco_plant import MujocoSnake, Scene, head_path_difference
from shintai.snake.plant import KinematicSnake
from shintai.snake.scenarios import (
    TrackingRun,
    draw_body,
    plot_modes,
    plot_time_series,
    run_two_point,
    wheel_legend,
)
from shintai.snake.scenarios_physical import Probe, Waypoints, inside_body_loop
from shintai.snake.two_point import TwoPointLaw


def caging_scene(box_xy) -> Scene:
    """The box (constants.CagingBox) standing at ``box_xy`` with a site ``box`` at its centre."""
    hx, hy, hz = CAGING_BOX.half
    return Scene(worldbody=f"""
    <body name="box" pos="{box_xy[0]} {box_xy[1]} {hz}">
      <freejoint name="box"/>
      <geom name="box" class="object" type="box" size="{hx} {hy} {hz}" mass="{CAGING_BOX.mass}" rgba=".95 .95 .92 1"/>
      <site name="box" size="0.005"/>
    </body>""")


def caging_targets() -> Waypoints:
    """(3.22)–(3.23): c_c(0) → c_{c,e1} over [0, t_s1) → c_{c,e2} at t_end (A6, A7)."""
    law = TwoPointLaw(CH3_ROBOT, CH3_GAINS)
    c0 = law.controlled(configuration(CAGING.w_h0, CAGING.phi0, CH3_ROBOT.l))
    return Waypoints.through((0.0, CAGING.t_s1, CAGING.t_end), (c0, CAGING.c_e1, CAGING.c_e2))


class KinematicBox(Module):
    """The box on the kinematic plant: a square (constants.CagingBox) that the body pushes, never rotates.

    Quasi-static pushing without friction or inertia (chosen: the kinematic plant has no forces): every δt
    the box is moved by the smallest translation that clears it of the body, the body being the polyline
    head → joints → tail wheel (model.body_points) thickened by the half width of a wheel pair
    (MujocoSnakeSettings.tread / 2 + wheel_half_width). Logs ``box.pos`` and ``box.caged``.
    """

    def __init__(self, xy, geometry: SnakeGeometry = CH3_ROBOT, settings=MUJOCO_SNAKE, period: float = CH3_GAINS.dt):
        super().__init__("box", period)
        self.xy = np.array(xy, dtype=float)
        self.geometry = geometry
        self.reach = np.array(CAGING_BOX.half[:2]) + settings.tread / 2 + settings.wheel_half_width

    def push(self, points: np.ndarray) -> None:
        for _ in range(8):  # a few passes: one push can move the box into another part of the body
            d = points - self.xy
            inside = np.all(np.abs(d) < self.reach, axis=1)
            if not inside.any():
                return
            depth = self.reach - np.abs(d[inside])  # (m, 2) overlap along x and y
            axis = np.argmin(depth, axis=1)  # each point pushes along its shallower axis
            move = np.zeros(2)
            for a in (0, 1):
                sel = axis == a
                if sel.any():
                    shift = -np.sign(d[inside][sel, a]) * depth[sel, a]
                    move[a] = shift[np.argmax(np.abs(shift))]
            self.xy += move

    def update(self, snapshot):
        cfg = configuration(snapshot["w_h"], snapshot["phi"], self.geometry.l)
        pts = body_points(cfg)
        seg = np.linspace(0.0, 1.0, 8, endpoint=False)
        dense = (pts[:-1, None, :] + seg[None, :, None] * (pts[1:] - pts[:-1])[:, None, :]).reshape(-1, 2)
        self.push(np.vstack((dense, pts[-1:])))
        p = np.array([*self.xy, CAGING_BOX.half[2]])
        self.log(snapshot["t"], **{"box.pos": p,
                                   "box.caged": inside_body_loop(snapshot["w_h"], snapshot["phi"], self.geometry.l, p)})


def simulate_caging(duration: float, plant: str = "mujoco", mocap_noise: float = 0.0, seed: int = 0,
                    recorder: Recorder | None = None, progress=None, video_path=None,
                    name: str = "caging") -> tuple[TrackingRun, dict]:
    """The §3.4.1 run with the box in the U: a MuJoCo body (mujoco_plant.MujocoSnake, joint encoders and the
    mocap head pose, as the real robot, §3.3) or the kinematic plant with :class:`KinematicBox`. Returns the
    run and the box's track (``pos`` per control period, ``caged``: inside the body's loop, ``final``)."""
    if plant not in ("kinematic", "mujoco"):
        raise ValueError(f"plant must be 'kinematic' or 'mujoco', got {plant!r}")
    if video_path is not None and plant != "mujoco":
        raise ValueError("--video needs plant=mujoco (the kinematic plant has nothing to render)")
    law = TwoPointLaw(CH3_ROBOT, CH3_GAINS)
    recorder = recorder if recorder is not None else Recorder()
    if plant == "kinematic":
        body = KinematicSnake(CAGING.w_h0, CAGING.phi0, CH3_ROBOT, CH3_GAINS.dt)
        box = KinematicBox(CAGING_BOX.xy)
        run = run_two_point(body, law, caging_targets(), duration, CH3_GAINS.t_sigma, recorder, name, progress,
                            modules=[box])
        final = np.array([*box.xy, CAGING_BOX.half[2]])
    else:
        body = MujocoSnake(CAGING.w_h0, CAGING.phi0, CH3_ROBOT, CH3_GAINS.dt, scene=caging_scene(CAGING_BOX.xy),
                           mocap_noise=mocap_noise, rng=np.random.default_rng(seed))

        def box_signals(snapshot):
            p = body.mj.site_pos("box")
            return {"pos": p, "caged": inside_body_loop(snapshot["w_h"], snapshot["phi"], CH3_ROBOT.l, p)}

        wheels = Probe("wheels", lambda snapshot: {"contact": snapshot["wheel_contact"]})
        run = run_two_point(body, law, caging_targets(), duration, CH3_GAINS.t_sigma, recorder, name, progress,
                            video_path, modules=[Probe("box", box_signals), wheels])
        contact = recorder.values("wheels.contact").astype(bool)
        mismatch = (contact != run.grounded).any(axis=1)  # a grounded wheel hanging or a lifted one touching
        growth = np.diff(run.pos_error)
        run.physics["pos_error_growth_in_mismatch_mm_s"] = 1e3 * float(growth[mismatch].mean()) / CH3_GAINS.dt \
            if mismatch.any() else 0.0
        run.physics["pos_error_growth_otherwise_mm_s"] = 1e3 * float(growth[~mismatch].mean()) / CH3_GAINS.dt
        final = body.mj.site_pos("box")
    return run, {"pos": recorder.values("box.pos"), "caged": recorder.values("box.caged").astype(bool),
                 "final": final}


def caging_metrics(run: TrackingRun, track: dict, reference: TrackingRun | None = None) -> dict:
    """The tracking metrics of the run, the box's motion and, on MuJoCo (``reference`` = the kinematic run of
    the same scenario), the plant's slip summary and how far the head's path departs from the kinematic one."""
    start, end = track["pos"][0], track["final"]
    metrics = {**run.metrics(), **run.physics,
               "box_displacement_m": float(np.hypot(*(end - start)[:2])),
               "box_advance_x_m": float(end[0] - start[0]),
               "box_left_cage": int(not track["caged"].all())}
    if reference is not None:
        metrics["head_path_diff_vs_kinematic_m"] = head_path_difference(run.c, reference.c)
        metrics["max_pos_error_kinematic_m"] = float(reference.pos_error.max())
    return metrics


def plot_caging(ctx, run: TrackingRun, track: dict) -> None:
    """Top view (Figs. 3.8–3.9 analogue): bodies at a few times with the box where it was then."""
    hx, hy, _ = CAGING_BOX.half
    with ctx.figure("top_view", figsize=(8.5, 5.5)) as (fig, ax):
        ax.plot(run.c_d[:, 0], run.c_d[:, 1], "--", color="tab:orange", lw=1, label="head target (3.22)–(3.23)")
        ax.plot(run.c_d[:, 3], run.c_d[:, 4], "--", color="tab:green", lw=1, label="tail target")
        ax.plot(run.c[:, 0], run.c[:, 1], "-", color="tab:orange", lw=2, alpha=0.6, label="head")
        ax.plot(run.c[:, 3], run.c[:, 4], "-", color="tab:green", lw=2, alpha=0.6, label="tail wheel")
        ax.plot(track["pos"][:, 0], track["pos"][:, 1], "-", color="tab:brown", lw=1, label="box centre")
        picks = np.unique(np.linspace(0, len(run.mode) - 1, 4).astype(int))
        for j, k in enumerate(picks):
            alpha = 0.3 + 0.7 * j / max(len(picks) - 1, 1)
            draw_body(ax, run.c[k, :3], run.phi[k], run.grounded[k], alpha=alpha)
            x, y = track["pos"][k, :2]
            ax.add_patch(Rectangle((x - hx, y - hy), 2 * hx, 2 * hy, fill=False, ec="tab:brown", alpha=alpha))
            ax.annotate(f"{run.t[k]:.0f} s", run.c[k, :2], fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        wheel_legend(ax)
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title("caging transport (box: brown squares at the bodies' times)", fontsize=9)


def plot_box(ctx, run: TrackingRun, track: dict) -> None:
    """The box's displacement and whether it stayed inside the body's loop."""
    with ctx.figure("box", figsize=(7.5, 3.8)) as (fig, ax):
        moved = track["pos"] - track["pos"][0]
        ax.plot(run.t[:-1], moved[:, 0], label="box Δx")
        ax.plot(run.t[:-1], moved[:, 1], label="box Δy")
        ax.plot(run.t, run.c[:, 0] - run.c[0, 0], "--", lw=1, label="head Δx")
        lost = np.flatnonzero(~track["caged"])
        if len(lost):
            ax.scatter(run.t[lost], moved[lost, 0], s=8, c="tab:red", label="box outside the loop", zorder=3)
        ax.axvline(CAGING.t_s1, color="0.6", ls=":", lw=1)
        ax.set_xlabel("t [s] (dotted: end of stage 1, t_s1)")
        ax.set_ylabel("displacement [m]")
        ax.legend(fontsize=7)


@scenario(
    "snake.caging",
    source="seed 001 §3.4.1",
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
              "(Fig. 3.8c, no number); 1 cm from spec §5.4 #11 (kinematic prototype: 4.1 mm)"),
        Check("rms_pos_error_m", "<=", 0.001, "spec §5.4 #11 (kinematic prototype: 0.22 mm)"),
        Check("final_pos_error_m", "<=", 0.001, "spec §5.4 #11: final head and tail within 1 mm"),
        Check("max_abs_joint_rad", "<", CH3_ROBOT.joint_limit, "thesis §3.2.3 sub-task (a); spec §5.4 #11"),
        Check("stopped_fraction", "<", 0.1, "thesis §3.2.5; spec §5.4 #11 (prototype 2 %)"),
        Check("box_left_cage", "==", 0, "thesis §3.4.1 / Fig. 3.9: the box stays enclosed and is carried"),
        Check("box_advance_x_m", ">=", 0.275, "thesis §3.4.1: the box is carried as the robot advances; the "
              "targets advance 0.55 m in x, so at least half of it"),
    ),
    thesis={
        "tracking": ThesisValue("follows the targets well (Fig. 3.8c, no number in the text)", "seed 001 §3.4.1",
                                "max_pos_error_m"),
        "box": ThesisValue("carried as the robot advances (Fig. 3.9)", "seed 001 §3.4.1", "box_advance_x_m"),
        "modes": ThesisValue("the mode changes with the situation", "seed 001 §3.4.1", "distinct_modes"),
    },
    video=True,
)
def caging(ctx) -> dict:
    p = ctx.params
    mujoco = p["plant"] == "mujoco"
    run, track = simulate_caging(p["duration_s"], plant=p["plant"], mocap_noise=p["mocap_noise_m"], seed=ctx.seed,
                                 recorder=ctx.recorder, progress=lambda f: ctx.progress((0.8 if mujoco else 1.0) * f),
                                 video_path=ctx.video_path if ctx.video else None)
    reference = None
    if mujoco:
        reference, _ = simulate_caging(p["duration_s"], plant="kinematic", name="kinematic")
        ctx.progress(1.0, "kinematic reference")
    ctx.sim_time_s = float(run.t[-1])
    if mujoco:
        ctx.extra["notes"] = CAGING_NOTES
    plot_caging(ctx, run, track)
    plot_box(ctx, run, track)
    plot_time_series(ctx, run)
    plot_modes(ctx, run)
    return caging_metrics(run, track, reference)


CAGING_NOTES = (
    "On MuJoCo the RMS and final position-error bounds (1 mm, spec §5.4 #11, set from the kinematic prototype's "
    "0.22 mm RMS) are exceeded by a little (reported, not tuned away); the 1 cm bound on the largest error, the "
    "box and the joint checks hold. The error grows while the wheels touching the floor differ from the mode "
    "(pos_error_growth_in_mismatch_mm_s vs _otherwise): with 4 grounded wheels an articulated body on position "
    "servos leaves one hanging by a fraction of a millimetre now and then, or a lift transient at a mode switch "
    "still has a lifted wheel down, and the body then moves by other constraints than the model's. Earlier "
    "(servo kp 60 N·m/rad) the pitch joints sagged 2–3 mm under the lifted parts, mismatches lasted whole t_σ "
    "windows and the error reached 38 mm at t ≈ 83 s; see constants.MujocoSnakeSettings.servo_kp. Holding the "
    "yaw joints (u = 0) until a switch's lift is complete is not done: the thesis switches every t_σ without a "
    "pause and stops only by the input limit (3.20) (§3.2.4–3.2.5), and as a trial it made things worse (RMS "
    "1.20 → 1.47 mm, max 7.5 → 9.2 mm; the targets (3.22)–(3.23) run on while the body waits)."
)
