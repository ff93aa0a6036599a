"""Handcart steering — seed 001 §3.4.2 (Figs. 3.10–3.11), scenario ``snake.handcart``.

The robot lengthened to n = 15 wheels (§3.4.2) raises head and tail and pushes a wheeled cart's handles
with them. Controlled: the 6D poses of head and tail, c_d = [w_h; w_t], through the double-arm model
A_{d,σ} ċ_d = B_{d,σ} ψ̇_d (3.24)–(3.25) = (2.32)–(2.35) (model3d.DoubleArm) under the two-point law
(3.3)–(3.6) with mode selection (3.19) and input limit (3.20) (scenarios_physical.SpatialTwoPoint; the
thesis does not write the 3D law out, A17). Target (3.26): c_d(0) → c_{d,e}, read as both ends +0.5 m in
x with everything else kept (the printed 13-entry vector, A17), over t_end.

The thesis gives neither n_h, n_t, the modes, the gains, t_end nor the cart (A17); constants.HandcartSetup
holds the choices and why. ``plant=mujoco`` (default) runs the physical snake and cart (joint encoders,
mocap 6D head pose, §3.3) next to the kinematic plant (:class:`KinematicDoubleArm`) and reports how far
they part; ``plant=kinematic`` runs the model alone.
"""

from __future__ import annotations

from contextlib import nullcontext
from dataclasses import replace

import numpy as np
from matplotlib.patches import Rectangle

from shintai.core import Loop, Recorder
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, HANDCART, MUJOCO_SNAKE, SnakeGeometry
from shintai.snake.model3d import chain_from_pose, chain_from_wheel, euler_zyx, yaw_joints
from shintai.snake.mujoco_plant import MujocoSnake, Scene, head_path_difference
from shintai.snake.scenarios import draw_link_points, draw_track, shade_stopped, wheel_legend
from shintai.snake.scenarios_physical import (
    ANGLES_6,
    KinematicSpatial,
    Probe,
    SpatialTwoPoint,
    Waypoints,
    base_candidates,
    double_arm_model,
    link_points,
)


def handcart_geometry() -> SnakeGeometry:
    return SnakeGeometry(n=HANDCART.n, l=CH3_ROBOT.l)


def handcart_initial() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(p_h, R_h, ψ0): base U on the floor (wheel n_h at the origin, e_x along −x), arms raised (HandcartSetup)."""
    h = HANDCART
    psi = np.zeros(handcart_geometry().joints)
    psi[yaw_joints(2 * h.n_h + 1, 2 * h.n_t - 1)] = h.base_yaw
    for joint, sign in ((2 * h.n_h, -1), (2, 1), (2 * h.n_t, -1), (2 * h.n_t + 4, 1)):
        psi[joint - 1] = sign * h.arm_pitch
    ch = chain_from_wheel(psi, CH3_ROBOT.l, h.n_h, np.array([0.0, 0.0, MUJOCO_SNAKE.wheel_radius]),
                          np.diag([-1.0, -1.0, 1.0]))
    return ch.P[0], ch.R[0], psi


def handle_x(tips: np.ndarray) -> np.ndarray:
    """x of the handle pads' faces in front of the head and tail tips at the start (bar_gap clear of the head
    capsule's end and of the tail wheel's rim)."""
    h, s = HANDCART, MUJOCO_SNAKE
    return np.array([tips[0, 0] + s.link_radius + h.bar_gap, tips[1, 0] + s.wheel_radius + h.bar_gap])


def handcart_scene(tips: np.ndarray) -> Scene:
    """The cart in front of the two raised tips ``tips`` = [[x, y, z] head, [x, y, z] tail]: a board on four
    fixed-axle wheels with a handle pad in front of each tip (constants.HandcartSetup)."""
    h = HANDCART
    pad, pad_w, pad_h = h.pad_half
    x_head, x_tail = handle_x(tips) + pad
    hx, hy, hz = h.cart_half
    cx, cy = max(x_head, x_tail) + pad + hx, tips[:, 1].mean()
    r = h.cart_wheel_radius
    wf = " ".join(str(v) for v in h.cart_wheel_friction)
    wheels = "".join(
        f'<body pos="{sx * (hx - r)} {sy * (hy - h.cart_wheel_inset)} {-hz}"><joint type="hinge" axis="0 1 0" '
        f'damping="{h.cart_wheel_damping}"/>'
        f'<geom type="cylinder" size="{r} {h.cart_wheel_half_width}" quat="0.70710678 0.70710678 0 0" class="object" '
        f'friction="{wf}" mass="{h.cart_wheel_mass}" rgba=".2 .2 .2 1"/></body>' for sx in (-1, 1) for sy in (-1, 1))
    pads = "".join(
        f'<geom name="handle_{name}" class="object" type="box" pos="{x - cx} {tip[1] - cy} {tip[2] - (r + hz)}" '
        f'size="{pad} {pad_w} {pad_h}" mass="{h.pad_mass}" rgba=".9 .5 .1 1"/>'
        f'<geom type="capsule" fromto="{x - cx} {tip[1] - cy} {tip[2] - (r + hz)} {-hx} {tip[1] - cy} 0" '
        f'size="{h.strut_radius}" contype="0" conaffinity="0" mass="{h.strut_mass}" rgba=".5 .5 .5 1"/>'
        for name, x, tip in (("head", x_head, tips[0]), ("tail", x_tail, tips[1])))
    return Scene(worldbody=f"""
    <body name="cart" pos="{cx} {cy} {r + hz}">
      <freejoint name="cart"/>
      <geom name="cart" class="object" type="box" size="{hx} {hy} {hz}" mass="{h.cart_mass}" rgba=".55 .7 .85 1"/>
      <site name="cart" size="0.005"/>
      {pads}{wheels}
    </body>""")


class KinematicDoubleArm(KinematicSpatial):
    """The double-arm model (2.32)–(2.35) as a kinematic plant (scenarios_physical.KinematicSpatial) with the
    cart pushed along x only (its wheels have fixed axles): its handle faces move ahead of the tips, never
    back. The snapshot adds ``cart`` (x travelled by the cart)."""

    def __init__(self, w_h, psi, geometry: SnakeGeometry, model, handles: np.ndarray, dt: float = CH3_GAINS.dt):
        super().__init__(w_h, psi, geometry, model, dt)
        self.handles = np.array(handles, float)
        self.cart = 0.0

    def snapshot(self) -> dict:
        return {**super().snapshot(), "cart": self.cart}

    def tips(self) -> np.ndarray:
        ch = chain_from_pose(self.w_h, self.psi, self.geometry.l)
        return np.array([ch.P[0], ch.wheel_position(self.geometry.n)])

    def step(self) -> None:
        super().step()
        reach = self.tips()[:, 0] + np.array([MUJOCO_SNAKE.link_radius, MUJOCO_SNAKE.wheel_radius])
        self.cart = max(self.cart, float(np.max(reach - self.handles)))


def handcart_targets(c0: np.ndarray) -> Waypoints:
    """(3.26) with c_{d,e} read as both ends +advance in x, everything else kept (A17)."""
    c_e = np.array(c0, float)
    c_e[[0, 6]] += HANDCART.advance
    return Waypoints.through((0.0, HANDCART.t_end), (c0, c_e), angles=ANGLES_6)


def simulate_handcart(duration: float, plant: str = "mujoco", recorder: Recorder | None = None, progress=None,
                      video_path=None, name: str = "handcart") -> dict:
    """The §3.4.2 run: the double-arm law (model3d.DoubleArm, SpatialTwoPoint) pushing the cart with head and
    tail, on MuJoCo (encoders, mocap 6D head pose) or on :class:`KinematicDoubleArm`. Returns the recorded
    series (``t``, ``c``, ``c_d``, ``error``, ``stopped``, ``mode``, ``cart``, ``body``, ``grounded``) and the
    plant's slip summary (MuJoCo)."""
    if plant not in ("kinematic", "mujoco"):
        raise ValueError(f"plant must be 'kinematic' or 'mujoco', got {plant!r}")
    if video_path is not None and plant != "mujoco":
        raise ValueError("--video needs plant=mujoco (the kinematic plant has nothing to render)")
    h = HANDCART
    geometry = handcart_geometry()
    p_h, R_h, psi0 = handcart_initial()
    w_h0 = np.concatenate((p_h, euler_zyx(R_h)))
    ch = chain_from_pose(w_h0, psi0, geometry.l)
    tips = np.array([ch.P[0], ch.wheel_position(geometry.n)])
    candidates = base_candidates(h.n_t - h.n_h + 1, h.n_c, h.n_g, min_lifted=0, fixed=h.fixed_end_wheels)
    model = double_arm_model(geometry, h.n_h, h.n_t, candidates)
    gains = replace(CH3_GAINS, n_c=h.n_c, n_g=h.n_g)
    if plant == "mujoco":
        body = MujocoSnake([p_h[0], p_h[1], np.pi], psi0[::2], geometry, CH3_GAINS.dt, scene=handcart_scene(tips))
        body.place(p_h, R_h, psi0)
        body.settle(h.settle)  # at rest under gravity; c_d(0) of (3.26) is measured there
        start = body.snapshot()
        w_h0, psi0 = start["head_pose"], start["psi"]
        cart_x = lambda: body.mj.site_pos("cart")  # noqa: E731
        points = lambda: link_points(body)  # noqa: E731
    else:
        body = KinematicDoubleArm(w_h0, psi0, geometry, model, handle_x(tips), CH3_GAINS.dt)
        cart_x = lambda: np.array([body.cart, 0.0, 0.0])  # noqa: E731
        points = lambda: chain_from_pose(body.w_h, body.psi, geometry.l).P[:, :2]  # noqa: E731
    c0 = model.matrices(w_h0, psi0, candidates[0])[2]
    controller = SpatialTwoPoint(model, handcart_targets(c0), geometry, gains, name=name)
    probe = Probe("cart", lambda snapshot: {"pos": cart_x(), "body": points()})
    recorder = recorder if recorder is not None else Recorder()
    view = {"distance": 2.0, "elevation": -45.0, "azimuth": 210.0}
    with body.video(video_path, **view) if video_path is not None else nullcontext():
        Loop(body, [controller, probe], recorder).run(duration, progress=progress)
    series = {key: recorder.values(f"{name}.{key}") for key in ("c", "c_d", "error", "stopped", "mode")}
    grounded = np.zeros((len(series["mode"]), geometry.n), bool)
    grounded[:, h.n_h - 1:h.n_t] = candidates[series["mode"].astype(int)]
    return {**series, "t": recorder.times(f"{name}.c"), "cart": recorder.values("cart.pos"),
            "body": recorder.values("cart.body"), "grounded": grounded,
            "physics": body.slip_summary() if plant == "mujoco" else {}, "candidates": len(candidates)}


def handcart_metrics(run: dict, reference: dict | None = None) -> dict:
    """Tracking of both 6D poses, drift of the head–tail offset (the handles' spacing), the cart's travel;
    with the kinematic ``reference`` run, how far the MuJoCo head path departs from it."""
    e, c = run["error"], run["c"]
    pos_error = np.maximum(np.linalg.norm(e[:, :3], axis=1), np.linalg.norm(e[:, 6:9], axis=1))
    offset = c[:, :3] - c[:, 6:9]
    return {"max_pos_error_m": float(pos_error.max()), "final_pos_error_m": float(pos_error[-1]),
            "max_angle_error_rad": float(np.abs(e[:, list(ANGLES_6)]).max()),
            "relative_pose_drift_m": float(np.linalg.norm(offset - offset[0], axis=1).max()),
            "cart_displacement_m": float(run["cart"][-1, 0] - run["cart"][0, 0]),
            "stopped_fraction": float(run["stopped"].mean()),
            "distinct_modes": int(len(np.unique(run["mode"]))), "candidate_count": run["candidates"],
            **run["physics"],
            **({"head_path_diff_vs_kinematic_m": head_path_difference(run["c"], reference["c"]),
                "max_pos_error_kinematic_m": handcart_metrics(reference)["max_pos_error_m"]}
               if reference is not None else {})}


def plot_handcart(ctx, run: dict) -> None:
    """Top view with the cart, and the tracking errors, head–tail drift and cart travel over time."""
    t, body, cart = run["t"], run["body"], run["cart"]
    hx, hy, _ = HANDCART.cart_half
    with ctx.figure("top_view", figsize=(7.5, 6.0)) as (fig, ax):
        picks = np.unique(np.linspace(0, len(t) - 1, 4).astype(int))
        for j, k in enumerate(picks):
            alpha = 0.25 + 0.75 * j / max(len(picks) - 1, 1)
            g = np.zeros(HANDCART.n, bool) if k >= len(run["grounded"]) else run["grounded"][k]
            draw_link_points(ax, body[k], g, alpha)
            ax.add_patch(Rectangle((cart[k, 0] - hx, cart[k, 1] - hy), 2 * hx, 2 * hy, fill=False, ec="tab:blue",
                                   alpha=alpha))
            ax.annotate(f"{t[k]:.0f} s", body[k, 0], fontsize=7, xytext=(3, 3), textcoords="offset points")
        draw_track(ax, run["c"][:, :2], run["c_d"][:, :2], "tab:orange", "head", "head target (3.26)")
        draw_track(ax, run["c"][:, 6:8], run["c_d"][:, 6:8], "tab:green", "tail tip", "tail target")
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        wheel_legend(ax, 22, "lifted (base mode or arm)")
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title("handcart: double-arm model, head and tail raised (cart: blue)", fontsize=9)
    e, c = run["error"], run["c"]
    offset = c[:, :3] - c[:, 6:9]
    with ctx.figure("errors", nrows=3, ncols=1, figsize=(7.5, 7.0), sharex=True) as (fig, ax):
        ax[0].plot(t, 1e3 * np.linalg.norm(e[:, :3], axis=1), label="head position error")
        ax[0].plot(t, 1e3 * np.linalg.norm(e[:, 6:9], axis=1), label="tail position error")
        ax[0].set_ylabel("[mm]")
        ax[1].plot(t, 1e3 * np.linalg.norm(offset - offset[0], axis=1), label="head–tail offset drift")
        ax[1].set_ylabel("[mm]")
        ax[2].plot(t, cart[:, 0] - cart[0, 0], label="cart Δx")
        ax[2].plot(t, c[:, 0] - c[0, 0], "--", label="head Δx")
        ax[2].set_ylabel("[m]")
        ax[2].set_xlabel("t [s]")
        for a in ax:
            shade_stopped(a, t, run["stopped"])
            a.legend(fontsize=7)
        ax[0].set_title("red bands: stopped by the input limit (3.20)", fontsize=9)


@scenario(
    "snake.handcart",
    source="seed 001 §3.4.2",
    summary="n = 15 snake, head and tail raised (double-arm model of model3d), pushes a wheeled cart 0.5 m",
    params=(Param("duration_s", HANDCART.t_end, "simulated time; the ramp (3.26) keeps t_end", lo=0.05,
                  hi=HANDCART.t_end),
            Param("plant", "mujoco", "mujoco: physical snake and cart (joint encoders, mocap head pose); "
                  "kinematic: the double-arm model itself with a pushed cart", choices=("mujoco", "kinematic"))),
    checks=(
        Check("max_pos_error_m", "<=", 0.01, "thesis §3.4.2: controlled variables follow the targets (Fig. 3.10c, "
              "no number); 1 cm as for caging (spec §5.4 #11, #14)"),
        Check("relative_pose_drift_m", "<=", 0.005, "thesis §3.4.2: the head–tail relation is kept, or the ends slip "
              "off the handles; 'a few mm' from spec §5.4 #14"),
        Check("cart_displacement_m", ">=", 0.4, "thesis §3.4.2 / Fig. 3.11: the cart is steered along; both ends "
              "advance 0.5 m"),
    ),
    thesis={"result": ThesisValue("targets followed; cart steered by head and tail (Figs. 3.10–3.11, no numbers)",
                                  "seed 001 §3.4.2", "cart_displacement_m")},
    video=True,
)
def handcart(ctx) -> dict:
    p = ctx.params
    mujoco = p["plant"] == "mujoco"
    run = simulate_handcart(p["duration_s"], plant=p["plant"], recorder=ctx.recorder,
                            progress=lambda f: ctx.progress((0.85 if mujoco else 1.0) * f),
                            video_path=ctx.video_path if ctx.video else None)
    reference = None
    if mujoco:
        reference = simulate_handcart(p["duration_s"], plant="kinematic", name="kinematic")
        ctx.progress(1.0, "kinematic reference")
    ctx.sim_time_s = float(run["t"][-1]) + CH3_GAINS.dt
    if mujoco:
        ctx.extra["notes"] = HANDCART_NOTES
    plot_handcart(ctx, run)
    return handcart_metrics(run, reference)


HANDCART_NOTES = (
    "Root causes of the earlier stall (the double-arm law stopped by (3.20) at 2.5 s, also on the kinematic "
    "plant): (1) base modes with at most one lifted wheel in a row (n_c = 1, taken over from the door) left "
    "too few candidates: within one mode σ_min(B_{d,σ}) fell below 1e−3 in ≈ 1.3 s, before the next selection "
    "at t_σ = 2 s; §3.3's n_c = 2 (the thesis restates no constants for the handcart) tracks on the kinematic "
    "plant to 1e−5 m. (2) On MuJoCo, modes lifting wheel n_h + 1 or n_t − 1 tip the frames of the base end "
    "wheels that (2.16)/(2.29) hold level, and with them the raised arms (9 mm, 23 mrad at each switch): "
    "excluded (scenarios_physical.base_candidates, fixed = 2). (3) The body was started unloaded; its arms "
    "sagged 2–3 cm in the first 0.1 s (33 mm 'error'): it now settles at rest first and c_d(0) is measured "
    "there. Left (reported, not tuned away): at each mode switch the lift transient (wheels lifted at "
    "MujocoSnakeSettings.lift_rate over ≈ 0.25 s) rolls the whole body by ≈ 20 mrad for ≈ 0.2 s, so the "
    "head–tail offset moves by up to ≈ 7 mm, above the 'few mm' bound of spec §5.4 #14, then returns to ≈ 1 mm. "
    "The roll comes from the lift itself, not from the new mode's constraints being applied early: holding u = 0 "
    "while the lift ramps (not in the thesis, which pauses only by (3.20)) raised the drift 6.7 → 8.7 mm in a trial."
)
