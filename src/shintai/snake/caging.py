"""Caging transport — seed 001 §3.4.1 (Figs. 3.8–3.9): the box, the two-stage targets and the rig.

The U-shaped n = 9 body (φ(0) of §3.4.1, head w̃_h(0) and every constant and gain as §3.3) encloses a box and
carries it with the two-stage targets (3.22)–(3.23) under the planar two-point law (two_point.py). On MuJoCo
the box is a free body (constants.CagingBox; the thesis gives no size, mass or friction, A12); on the
kinematic plant it is a square pushed by the body (:class:`KinematicBox`).
"""

from __future__ import annotations

import numpy as np
from matplotlib.path import Path as Polygon

from shintai.core.runtime import Module
from shintai.scenarios.experiment import Rig, Run
from shintai.snake.constants import (
    BOX_PUSH_PASSES,
    CAGING,
    CAGING_BOX,
    CH3_GAINS,
    CH3_ROBOT,
    MUJOCO_SNAKE,
    SnakeGeometry,
)
from shintai.snake.model import body_points, configuration
from shintai.snake.mujoco_plant import MujocoSnake, Scene, head_path_difference
from shintai.snake.plant import KinematicSnake
from shintai.snake.probe import Probe
from shintai.snake.targets import PiecewiseLinear
from shintai.snake.tracking import TrackingRun, two_point_rig
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


def caging_targets() -> PiecewiseLinear:
    """(3.22)–(3.23): c_c(0) → c_{c,e1} over [0, t_s1) → c_{c,e2} at t_end (A6, A7)."""
    law = TwoPointLaw(CH3_ROBOT, CH3_GAINS)
    c0 = law.controlled(configuration(CAGING.w_h0, CAGING.phi0, CH3_ROBOT.l))
    return PiecewiseLinear.through((0.0, CAGING.t_s1, CAGING.t_end), (c0, CAGING.c_e1, CAGING.c_e2))


def inside_body_loop(w_h, phi, l: float, point) -> bool:
    """Is ``point`` inside the loop the body polyline (head → tail wheel) makes when closed tail → head?"""
    return bool(Polygon(body_points(configuration(w_h, phi, l))).contains_point(point[:2]))


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
        for _ in range(BOX_PUSH_PASSES):  # one push can move the box into another part of the body
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


def caging_rig(duration: float, plant: str = "mujoco", mocap_noise: float = 0.0, seed: int = 0) -> Rig:
    """The §3.4.1 run with the box in the U: a MuJoCo body (joint encoders and the mocap head pose, as the real
    robot, §3.3; ``seed`` draws the mocap noise) or the kinematic plant with :class:`KinematicBox`."""
    law = TwoPointLaw(CH3_ROBOT, CH3_GAINS)
    if plant == "kinematic":
        body = KinematicSnake(CAGING.w_h0, CAGING.phi0, CH3_ROBOT, CH3_GAINS.dt)
        box = KinematicBox(CAGING_BOX.xy)
        rig = two_point_rig(body, law, caging_targets(), duration, CH3_GAINS.t_sigma, modules=[box])
        rig.state["box"] = lambda: np.array([*box.xy, CAGING_BOX.half[2]])
        return rig
    body = MujocoSnake(CAGING.w_h0, CAGING.phi0, CH3_ROBOT, CH3_GAINS.dt, scene=caging_scene(CAGING_BOX.xy),
                       mocap_noise=mocap_noise, rng=np.random.default_rng(seed))

    def box_signals(snapshot):
        p = body.mj.site_pos("box")
        return {"pos": p, "caged": inside_body_loop(snapshot["w_h"], snapshot["phi"], CH3_ROBOT.l, p)}

    rig = two_point_rig(body, law, caging_targets(), duration, CH3_GAINS.t_sigma, modules=[Probe("box", box_signals)],
                        record={1: lambda s: {"wheels.contact": s["wheel_contact"]}})
    rig.state["box"] = lambda: body.mj.site_pos("box")
    return rig


def box_track(run: Run) -> dict:
    """The box's track: ``pos`` per control period, ``caged`` (inside the body's loop), ``final`` position."""
    log = run.log
    return {"pos": log.values("box.pos"), "caged": log.values("box.caged").astype(bool), "final": run.state["box"]()}


def mismatch_growth(run: TrackingRun, contact: np.ndarray) -> dict:
    """Growth of the position error (mm/s) in the control periods where the wheels touching the floor differ
    from the mode (a grounded wheel hanging or a lifted one touching) and in the others."""
    mismatch = (contact.astype(bool) != run.grounded).any(axis=1)
    growth = np.diff(run.pos_error)
    return {"pos_error_growth_in_mismatch_mm_s": 1e3 * float(growth[mismatch].mean()) / CH3_GAINS.dt
            if mismatch.any() else 0.0,
            "pos_error_growth_otherwise_mm_s": 1e3 * float(growth[~mismatch].mean()) / CH3_GAINS.dt}


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
