"""Handcart steering — seed 001 §3.4.2 (Figs. 3.10–3.11): the n = 15 body, the cart and the rig.

The robot raises head and tail and pushes a wheeled cart's handles with them. Controlled: the 6D poses of
head and tail, c_d = [w_h; w_t], through the double-arm model A_{d,σ} ċ_d = B_{d,σ} ψ̇_d (3.24)–(3.25) =
(2.32)–(2.35) (model3d.DoubleArm) under the two-point law with mode selection (3.19) and input limit (3.20)
(spatial.SpatialTwoPoint). Target (3.26): both ends +advance in x, everything else kept (A17). The thesis
gives neither n_h, n_t, the modes, the gains, t_end nor the cart: constants.HandcartSetup.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from shintai.scenarios.experiment import Rig, Run
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, HANDCART, MUJOCO_SNAKE, SnakeGeometry
from shintai.snake.model3d import chain_from_pose, chain_from_wheel, euler_zyx, yaw_joints
from shintai.snake.mujoco_plant import MujocoSnake, Scene, head_path_difference
from shintai.snake.probe import Probe
from shintai.snake.spatial import ANGLES_6, KinematicSpatial, SpatialTwoPoint, base_candidates, double_arm_model
from shintai.snake.targets import PiecewiseLinear

CONTROLLER = "handcart"  # the double-arm controller's name: its signals are logged as handcart.*


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
    """The double-arm model (2.32)–(2.35) as a kinematic plant (spatial.KinematicSpatial) with the cart pushed
    along x only (its wheels have fixed axles): its handle faces move ahead of the tips, never back. The
    snapshot adds ``cart`` (x travelled by the cart)."""

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


def handcart_targets(c0: np.ndarray) -> PiecewiseLinear:
    """(3.26) with c_{d,e} read as both ends +advance in x, everything else kept (A17)."""
    c_e = np.array(c0, float)
    c_e[[0, 6]] += HANDCART.advance
    return PiecewiseLinear.through((0.0, HANDCART.t_end), (c0, c_e), angles=ANGLES_6)


def handcart_rig(duration: float, plant: str = "mujoco") -> Rig:
    """The §3.4.2 run: the double-arm law (model3d.DoubleArm, SpatialTwoPoint) pushing the cart with head and
    tail, on MuJoCo (encoders, mocap 6D head pose; the body settles at rest first and c_d(0) is measured
    there) or on :class:`KinematicDoubleArm`. A probe logs the cart's position and the body's polyline."""
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
        points = body.link_points
        view = body.view(distance=2.0, elevation=-45.0, azimuth=210.0)
    else:
        body = KinematicDoubleArm(w_h0, psi0, geometry, model, handle_x(tips), CH3_GAINS.dt)
        cart_x = lambda: np.array([body.cart, 0.0, 0.0])  # noqa: E731
        points = lambda: chain_from_pose(body.w_h, body.psi, geometry.l).P[:, :2]  # noqa: E731
        view = {}
    c0 = model.matrices(w_h0, psi0, candidates[0])[2]
    controller = SpatialTwoPoint(model, handcart_targets(c0), geometry, gains, name=CONTROLLER)
    probe = Probe("cart", lambda snapshot: {"pos": cart_x(), "body": points()})
    return Rig(body, [controller, probe], duration=duration, view=view, state={"candidates": candidates})


def handcart_series(run: Run) -> dict:
    """The recorded series of a run (``t``, ``c``, ``c_d``, ``error``, ``stopped``, ``mode``, ``cart``, ``body``,
    ``grounded``), the plant's slip summary (MuJoCo) and the number of candidate base modes."""
    h, log, candidates = HANDCART, run.log, run.state["candidates"]
    series = {key: log.values(f"{CONTROLLER}.{key}") for key in ("c", "c_d", "error", "stopped", "mode")}
    grounded = np.zeros((len(series["mode"]), h.n), bool)
    grounded[:, h.n_h - 1:h.n_t] = candidates[series["mode"].astype(int)]
    return {**series, "t": log.times(f"{CONTROLLER}.c"), "cart": log.values("cart.pos"),
            "body": log.values("cart.body"), "grounded": grounded,
            "physics": run.body.slip_summary() if isinstance(run.body, MujocoSnake) else {},
            "candidates": len(candidates)}


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
