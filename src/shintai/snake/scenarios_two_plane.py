"""Scenarios of seed 001 ch. 4: moving between two non-parallel planes, §4.5 conditions 1 (roll) and 2 (pitch).

Both run the head transition, straddling propulsion and connection transitions of two_plane.py on its
kinematic plant, with Table 4.1, n_h = 3, n_{c_max} = 2, ε_d = 0.029 m and the choices of
constants.TwoPlaneSettings / TwoPlaneScene (plane edges, body thickness, initial posture: not in the text).
By default each scenario also reruns the same motion with the null-space term off (k_v = 0) and reports
those metrics with ``_no_nullspace``: what the connection part's redundancy buys (§4.4.2).

Metrics are computed from the plant's snapshots (one per control period δt = 0.2 s, plus the final state):

* head error: ‖(^f x, ^f y)_d − (^f x, ^f y)‖ of (4.36), after the first 2/k_p s of straddling;
* contact errors over every wheel the plant holds on a plane, from the first step with wheel 1 on the front
  plane: |d − r_w| (2.36), |κ| (2.37), and |λ| (2.38) for wheels whose next wheel is on the same plane
  (λ = 0 is what makes the following wheels touch, §2.6.1);
* edge clearance of the lifted body part (two_plane.edge_clearance: wheel discs r_w, link capsules);
* all wheels on the front plane at the end: |d − r_w| < 1 mm, |κ| < 0.01 rad (spec §5.4 #15's tolerances)
  and inside the front rectangle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core import Loop, Module, Recorder
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.snake.constants import (
    CH4_ROBOT,
    CONDITION_1,
    CONDITION_2,
    TWO_PLANE,
    TWO_PLANE_SCENE,
    TwoPlaneCondition,
)
from shintai.snake.model3d import forward_kinematics
from shintai.snake.two_plane import (
    FRONT,
    LIFTED,
    REAR,
    Partition,
    TwoPlaneController,
    TwoPlaneSnake,
    TwoPlaneWorld,
    head_raised_contact,
    initial_posture,
)

ON_PLANE_D_TOL = 1e-3  # m; "on a plane": |d − r_w| below this (spec §5.4 #15)
ON_PLANE_TILT_TOL = 0.01  # rad; and |κ| below this (spec §5.4 #15)
CONTROLLER_LOGS = ("w_f", "w_d", "r", "n_f", "n_c", "n_re", "V", "d_e", "sigma_H", "sigma_A", "u_norm", "r1")
VECTOR_LOGS = ("w_f", "w_d", "r", "r1")
SNAPSHOT_KEYS = ("p_h", "R_h", "psi", "contact", "r_front", "r_rear", "edge_clearance", "wheels", "slip", "snap_m")


def largest(x) -> float:
    """Largest entry, NaN for an empty selection (e.g. a run stopped before the straddling started)."""
    x = np.asarray(x, dtype=float)
    return float(np.nanmax(x)) if x.size and not np.isnan(x).all() else float("nan")


class SnapshotLog(Module):
    """Logs the plant's state and contact measures every body step (contributes no command)."""

    def update(self, snapshot):
        self.log(snapshot["t"], **{f"{self.name}.{k}": snapshot[k] for k in SNAPSHOT_KEYS})


@dataclass
class TwoPlaneRun:
    """Time series of one two-plane run."""

    name: str
    cond: TwoPlaneCondition
    world: TwoPlaneWorld
    k_v: float
    t: np.ndarray  # (N,) plant samples, the last one the final state
    s: dict  # SNAPSHOT_KEYS -> (N, …)
    c: dict  # controller logs: key -> (times, values)
    events: list  # (t, kind, n_f, n_c, n_re)
    t_0: float  # end of the head transition (nan if never)

    def on_plane(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Per sample and wheel: in contact?, |d − r_w|, tilt (|κ|, and |λ| where the next wheel shares the plane)."""
        contact = self.s["contact"].astype(int)
        r = np.where((contact == FRONT)[..., None], self.s["r_front"], self.s["r_rear"])
        touching = contact != LIFTED
        same_next = np.c_[contact[:, 1:] == contact[:, :-1], np.zeros(len(contact), bool)]
        tilt = np.maximum(np.abs(r[..., 1]), np.where(same_next, np.abs(r[..., 2]), 0.0))
        return touching, np.abs(r[..., 0] - self.world.r_w), tilt

    def landing_margins(self) -> list[float]:
        """^f x − edge_x of each wheel as its front shift completes (> 0: it landed on the plane)."""
        out = []
        for t, kind, n_f, _, _ in self.events:
            if kind == "front_shift":
                k = int(np.argmin(np.abs(self.t - t)))
                out.append(float(self.world.to_front(self.s["wheels"][k, n_f - 1])[0] - self.world.edge_x))
        return out

    def all_on_front(self, k: int = -1) -> bool:
        wheels, r = self.s["wheels"][k], self.s["r_front"][k]
        return bool(np.all(np.abs(r[:, 0] - self.world.r_w) < ON_PLANE_D_TOL)
                    and np.all(np.abs(r[:, 1]) < ON_PLANE_TILT_TOL)
                    and all(self.world.on_front(p) for p in wheels))

    def metrics(self) -> dict:
        kinds = [e[1] for e in self.events]
        straddling = self.s["contact"][:, 0] == FRONT
        touching, d_err, tilt = self.on_plane()
        tc, w_f = self.c["w_f"]
        _, w_d = self.c["w_d"]
        late = tc >= self.t_0 + 2.0 / self.cond.k_p
        head_err = np.hypot(*(w_d[late, :2] - w_f[late, :2]).T)
        heading_err = np.abs(np.remainder(w_d[late, 2] - w_f[late, 2] + math.pi, 2 * math.pi) - math.pi)
        landings = self.landing_margins()
        done = [e[0] for e in self.events if e[1] == "front_shift" and e[2] == self.s["contact"].shape[1]]
        return {
            "head_transition_time_s": self.t_0,
            "head_error_after_transient_m": largest(head_err),
            "heading_error_after_transient_rad": largest(heading_err),
            "contact_d_error_max_m": largest(d_err[straddling][touching[straddling]]),
            "max_abs_tilt_rad": largest(tilt[straddling][touching[straddling]]),
            "all_wheels_on_front": int(self.all_on_front()),
            "min_edge_clearance_m": float(self.s["edge_clearance"].min()),
            "max_abs_joint_rad": float(np.abs(self.s["psi"]).max()),
            "max_abs_connection_joint_rad": largest(self.connection_joints()),
            "front_shifts": kinds.count("front_shift"),
            "rear_shifts": kinds.count("rear_shift"),
            "tail_released": int("release" in kinds),
            "rear_shift_after_each_front_shift": int(self.shift_order_ok()),
            "max_connection_wheels": largest(self.c["n_c"][1]),
            "landing_margin_min_m": float(min(landings, default=np.nan)),
            "all_on_front_time_s": float(done[0]) if done else float("nan"),
            "min_sigma_A_p": -largest(-self.c["sigma_A"][1]),
            "min_sigma_H_3": -largest(-self.c["sigma_H"][1]),
            "max_slip_m_s": float(self.s["slip"][1:].max()),
            "landing_snap_m": float(self.s["snap_m"][-1]),
        }

    def connection_joints(self) -> np.ndarray:
        """|ψ_c| of every sample with wheel 1 on the front plane (V_1's joints, sub-task (i) of §4.4.2)."""
        out = [np.abs(psi[Partition.from_contact(c).connection]) for psi, c in zip(self.s["psi"], self.s["contact"])
               if c[0] == FRONT]
        return np.concatenate(out) if out else np.zeros(0)

    def shift_order_ok(self) -> bool:
        """Each completed front shift is followed at once (same instant) by the rear-end shift or the release
        (§4.2.4), as long as the rear end is not already released."""
        ev = self.events
        for j, (t, kind, *_) in enumerate(ev):
            if kind == "front_shift" and not any(e[1] == "release" for e in ev[:j]):
                if j + 1 >= len(ev) or ev[j + 1][0] != t or ev[j + 1][1] not in ("rear_shift", "release"):
                    return False
        return True


def simulate_two_plane(cond: TwoPlaneCondition, duration: float, k_v: float | None = None,
                       recorder: Recorder | None = None, name: str = "tp", progress=None) -> TwoPlaneRun:
    """Run §4.5 under ``cond`` for ``duration`` s from the initial posture of TwoPlaneScene (k_v: Table 4.1 if None)."""
    world = TwoPlaneWorld.build(cond, TWO_PLANE_SCENE, TWO_PLANE.r_w)
    p_h, R_h, psi = initial_posture(world)
    body = TwoPlaneSnake(world, p_h, R_h, psi, head_raised_contact(CH4_ROBOT.n, TWO_PLANE.n_h))
    controller = TwoPlaneController(world, cond, k_v=k_v, name=name)
    logger = SnapshotLog(f"{name}_plant")
    recorder = recorder if recorder is not None else Recorder()
    Loop(body, [logger, controller], recorder).run(duration, progress=progress)
    final = body.snapshot()
    s = {k: np.concatenate((recorder.values(f"{name}_plant.{k}"), [final[k]])) for k in SNAPSHOT_KEYS}
    c = {k: (recorder.times(f"{name}.{k}"), recorder.values(f"{name}.{k}")) if f"{name}.{k}" in recorder
         else (np.zeros(0), np.zeros((0, 3) if k in VECTOR_LOGS else 0))  # a run that ended before straddling
         for k in CONTROLLER_LOGS}
    t_0 = next((e[0] for e in controller.events if e[1] == "head_done"), float("nan"))
    return TwoPlaneRun(name, cond, world, controller.k_v, np.append(recorder.times(f"{name}_plant.psi"), body.t),
                       s, c, controller.events, t_0)


# ----------------------------------------------------------------------------------------------- plots

CONTACT_COLOURS = {FRONT: "tab:red", REAR: "tab:blue"}


def _event_lines(ax, run: TwoPlaneRun, kinds=("rear_shift", "release"), **kw) -> None:
    for t, kind, *_ in run.events:
        if kind in kinds:
            ax.axvline(t, ls="-.", lw=0.8, color="0.4", **kw)


def plot_motion(ctx, run: TwoPlaneRun, name: str = "motion") -> None:
    """Fig. 4.13(a)/4.14(a) analogue: the body at several times, top view and side view, on the two planes."""
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    w, l = run.world, CH4_ROBOT.l
    picks = np.unique(np.r_[0, np.searchsorted(run.t, [e[0] for e in run.events if e[1] == "front_shift"]),
                            len(run.t) - 1])
    with ctx.figure(name, nrows=2, ncols=1, figsize=(10, 6.2), sharex=True) as (fig, ax):
        far = w.edge_x + w.length
        corners = [w.p_f + w.R_f @ [x, y, 0.0] for x, y in ((w.edge_x, -w.half_width), (w.edge_x, w.half_width),
                                                            (far, w.half_width), (far, -w.half_width))]
        corners = np.array(corners + corners[:1])
        ax[0].fill(corners[:, 0], corners[:, 1], color="tab:red", alpha=0.08, label="front plane")
        ax[0].axvspan(-2.0, w.rear_edge_x, color="tab:blue", alpha=0.06, label="rear plane")
        for j, k in enumerate(picks):
            colour = cmap(j / max(len(picks) - 1, 1))
            P = forward_kinematics(run.s["p_h"][k], run.s["R_h"][k], run.s["psi"][k], l).P
            contact = run.s["contact"][k].astype(int)
            wheels = run.s["wheels"][k]
            for a, (i0, i1) in zip(ax, ((0, 1), (0, 2))):
                a.plot(P[:, i0], P[:, i1], "-", color=colour, lw=1.4, label=f"{run.t[k]:.0f} s" if a is ax[0] else None)
                a.plot(P[0, i0], P[0, i1], "^", color=colour, ms=5)
                for code in (FRONT, REAR):
                    sel = contact == code
                    a.scatter(wheels[sel, i0], wheels[sel, i1], s=16, color=CONTACT_COLOURS[code], zorder=3)
                a.scatter(wheels[contact == LIFTED, i0], wheels[contact == LIFTED, i1], s=16, facecolors="white",
                          edgecolors="k", zorder=3)
        ax[0].set_ylabel("y [m]")
        ax[0].set_title("top view; wheels: red on the front plane, blue on the rear plane, white lifted; ▲ head",
                        fontsize=9)
        ax[0].legend(fontsize=6, ncol=6, loc="lower left")
        ys = run.s["wheels"][..., 1]
        xs = np.array([w.edge_x, far])
        low, high = (np.array([w.p_f + w.R_f @ [x, y - w.p_f[1], 0.0] for x in xs])
                     for y in (ys.min(), ys.max()))  # the front plane's profile at the body's extreme y
        ax[1].fill_between(low[:, 0], low[:, 2], high[:, 2], color="tab:red", alpha=0.25, lw=0,
                           label="front plane over the body's y range")
        ax[1].plot([-2.0, w.rear_edge_x], [0.0, 0.0], "-", color="tab:blue", lw=1.5)
        ax[1].set_xlim(run.s["wheels"][..., 0].min() - 0.1, run.s["wheels"][..., 0].max() + 0.3)
        ax[1].set_ylim(-0.05, 0.3)
        ax[1].set_xlabel("x [m]")
        ax[1].set_ylabel("z [m]")
        ax[1].set_title("side view", fontsize=9)
        ax[1].legend(fontsize=7, loc="upper left")
        ax[0].set_ylim(ys.min() - 0.3, ys.max() + 0.3)
        for a in ax:
            a.set_aspect("equal")


def plot_contact(ctx, run: TwoPlaneRun, name: str = "contact") -> None:
    """Fig. 4.13(d)/4.14(d) analogue: r = [d, κ, λ] of the rear end (dash-dot: rear-end shifts), and the contact
    errors of all wheels on a plane."""
    tc, r = run.c["r"]
    touching, d_err, tilt = run.on_plane()
    with ctx.figure(name, nrows=3, ncols=1, figsize=(8, 8), sharex=True) as (fig, ax):
        ax[0].plot(tc, 1e3 * (r[:, 0] - run.world.r_w), lw=1, label="d − r_w (rear end)")
        ax[0].plot(run.t, 1e3 * np.where(touching, d_err, 0.0).max(axis=1), lw=1,
                   label="max |d − r_w|, all contact wheels")
        ax[0].set_ylabel("[mm]")
        ax[1].plot(tc, r[:, 1], lw=1, label="κ (rear end)")
        ax[1].plot(tc, r[:, 2], lw=1, label="λ (rear end)")
        ax[1].plot(run.t, np.where(touching, tilt, 0.0).max(axis=1), lw=1, label="max tilt, all contact wheels")
        ax[1].set_ylabel("[rad]")
        for k in ("n_f", "n_c", "n_re"):
            ax[2].step(run.c[k][0], run.c[k][1], where="post", lw=1, label=k)
        ax[2].set_ylabel("wheels")
        ax[2].set_xlabel("t [s]")
        for a in ax:
            _event_lines(a, run)
            a.legend(fontsize=7, loc="best")
        ax[0].set_title(f"{run.cond.name}: contact of the connection's rear end with the rear plane", fontsize=9)


def plot_head(ctx, run: TwoPlaneRun, name: str = "head") -> None:
    """Fig. 4.13(b)(c) analogue: r_1 during the head transition, and the head in Σ_f against (4.36)."""
    with ctx.figure(name, nrows=3, ncols=1, figsize=(8, 8)) as (fig, ax):
        t1, r1 = run.c["r1"]
        ax[0].plot(t1, 1e3 * (r1[:, 0] - run.world.r_w), label="d_1,f − r_w [mm]")
        ax[0].plot(t1, 1e3 * r1[:, 1], label="κ_1,f [mrad]")
        ax[0].plot(t1, 1e3 * r1[:, 2], label="λ'_1,f [mrad]")
        ax[0].legend(fontsize=7)
        ax[0].set_title("head transition (4.14): r_1 → [r_w, 0, 0]", fontsize=9)
        tc, w_f = run.c["w_f"]
        _, w_d = run.c["w_d"]
        ax[1].plot(tc, w_d[:, 0], "k--", lw=1, label="targets (4.36)")
        ax[1].plot(tc, w_d[:, 1], "k--", lw=1)
        ax[1].plot(tc, w_f[:, 0], lw=1, label="^f x_h")
        ax[1].plot(tc, w_f[:, 1], lw=1, label="^f y_h")
        ax[1].set_ylabel("[m]")
        ax[1].legend(fontsize=7)
        ax[2].semilogy(tc, np.maximum(np.hypot(*(w_d[:, :2] - w_f[:, :2]).T), 1e-9), lw=1, label="position error [m]")
        ax[2].semilogy(tc, np.maximum(np.abs(np.remainder(w_d[:, 2] - w_f[:, 2] + math.pi, 2 * math.pi) - math.pi),
                                      1e-9), lw=1, label="heading error [rad]")
        ax[2].set_xlabel("t [s]")
        ax[2].legend(fontsize=7)
        for a in ax[1:]:
            _event_lines(a, run, kinds=("front_shift",))


def plot_edge(ctx, runs: dict, name: str = "edge", every: float = 2.0) -> None:
    """Fig. 4.5 analogue: the body near the front edge in Σ_f (x–z), every ``every`` s while something is lifted,
    with and without the null-space term; the posture of least clearance in red."""
    from matplotlib import colormaps
    from matplotlib.patches import Circle

    cmap = colormaps["viridis"]
    with ctx.figure(name, nrows=len(runs), ncols=1, figsize=(9, 3.6 * len(runs)), squeeze=False) as (fig, ax):
        for a, (label, run) in zip(ax[:, 0], runs.items()):
            w = run.world
            step = max(1, int(round(every / TWO_PLANE.dt)))
            lifted = np.flatnonzero(np.isfinite(run.s["edge_clearance"]))
            worst = lifted[np.argmin(run.s["edge_clearance"][lifted])]
            for k in np.r_[lifted[::step], worst]:
                q = w.to_front(forward_kinematics(run.s["p_h"][k], run.s["R_h"][k], run.s["psi"][k], CH4_ROBOT.l).P)
                style = dict(color="tab:red", lw=2.0, zorder=4) if k == worst else \
                    dict(color=cmap(run.t[k] / run.t[-1]), lw=0.7, alpha=0.7)
                a.plot(q[:, 0], q[:, 2], "-", **style)
                a.plot(q[2::2, 0], q[2::2, 2], "o", ms=2.5 if k != worst else 4, **style)
            a.fill_between([w.edge_x, w.edge_x + 0.5], [-0.3, -0.3], [0.0, 0.0], color="0.7", label="front plane")
            a.add_patch(Circle((w.edge_x, 0.0), w.r_w, fill=False, ls=":", color="k", label="r_w around the edge"))
            a.set_xlim(w.edge_x - 0.55, w.edge_x + 0.35)
            a.set_ylim(-0.15, 0.25)
            a.set_aspect("equal")
            a.set_xlabel("^f x [m]")
            a.set_ylabel("^f z [m]")
            a.legend(fontsize=7, loc="upper right")
            a.set_title(f"{label} (k_v = {run.k_v:g}): body every {every:g} s in Σ_f, colour = time; red: least "
                        f"clearance {1e3 * run.s['edge_clearance'][worst]:.1f} mm at {run.t[worst]:.1f} s", fontsize=9)


def plot_redundancy(ctx, runs: dict, name: str = "redundancy") -> None:
    """Edge clearance, largest joint angle and V over time, with and without the null-space term (§4.4.2)."""
    with ctx.figure(name, nrows=3, ncols=1, figsize=(8, 8), sharex=True) as (fig, ax):
        for label, run in runs.items():
            clearance = np.where(np.isfinite(run.s["edge_clearance"]), run.s["edge_clearance"], np.nan)
            ax[0].plot(run.t, 1e3 * clearance, lw=1, label=f"{label} (k_v = {run.k_v:g})")
            ax[1].plot(run.t, np.abs(run.s["psi"]).max(axis=1), lw=1, label=label)
            ax[2].plot(*run.c["V"], lw=1, label=label)
        ax[0].axhline(0.0, color="k", lw=0.8)
        ax[0].set_ylabel("edge clearance [mm]\n(none lifted: no line)")
        ax[1].axhline(CH4_ROBOT.joint_limit, color="k", ls=":", lw=1, label="ψ_lim")
        ax[1].set_ylabel("max |ψ_i| [rad]")
        ax[2].set_ylabel("V (4.33)")
        ax[2].set_xlabel("t [s]")
        first = next(iter(runs.values()))
        for a in ax:
            _event_lines(a, first, kinds=("front_shift",))
            a.legend(fontsize=7)
        ax[0].set_title("dash-dot: front shifts (with null space)", fontsize=9)


# ------------------------------------------------------------------------------------------- scenarios

PARAMS = (
    Param("duration_s", 130.0, "simulated time (the head transition and all 8 landings take ~105 s)", lo=1.0, hi=400.0),
    Param("null_space", True, "true: Table 4.1's k_v, plus a k_v = 0 rerun reported as *_no_nullspace; "
                              "false: only the k_v = 0 run (the comparison checks then find no metric)"),
)


def _with_suffix(key: str) -> str:
    """``min_edge_clearance_m`` → ``min_edge_clearance_no_nullspace_m`` (the unit stays last)."""
    for unit in ("_m_s", "_m", "_rad", "_s"):
        if key.endswith(unit):
            return f"{key[: -len(unit)]}_no_nullspace{unit}"
    return f"{key}_no_nullspace"


def checks() -> tuple[Check, ...]:
    n = CH4_ROBOT.n
    return (
        Check("head_transition_time_s", "<=", 20.0,
              "thesis §4.5: head adaptation converged (Fig. 4.13b); 20 s = 20 time constants of K_h = I (chosen)"),
        Check("head_error_after_transient_m", "<=", 0.01,
              "thesis §4.5: the head followed its target on the front plane (Fig. 4.13c, no number); 1 cm after "
              "2/k_p s proposed in spec §5.4 #16"),
        Check("contact_d_error_max_m", "<=", 0.002,
              "thesis §4.5: connection variables tracked well, wheels kept proper contact (Fig. 4.13d); 2 mm from "
              "spec §5.4 #16"),
        Check("max_abs_tilt_rad", "<=", 0.02, "thesis §4.5 (as above); 0.02 rad from spec §5.4 #16"),
        Check("all_wheels_on_front", "==", 1,
              "thesis §4.5: the robot moved onto the front plane (Fig. 4.13a); the last wheels need the tail "
              "release of two_plane.py, not in the thesis"),
        Check("min_edge_clearance_m", ">", 0.0,
              "thesis §4.4.2, §4.5: contact with the plane edges avoided through the redundancy (spec §5.4 #18)"),
        Check("max_abs_joint_rad", "<", CH4_ROBOT.joint_limit, "thesis §4.5: ψ_lim = π/2 avoided (sub-task (i))"),
        Check("front_shifts", "==", n - 1, "derived: wheels 2..n land one by one after the head transition"),
        Check("rear_shifts", "==", n - TWO_PLANE.n_h,
              "derived: the rear end moves from wheel n_h to wheel n (then the tail is released)"),
        Check("rear_shift_after_each_front_shift", "==", 1,
              "thesis §4.2.4: after a front shift n_c < n_c_max, so the rear end shifts at once (spec §5.4 #17)"),
        Check("max_connection_wheels", "<=", TWO_PLANE.n_c_max, f"thesis §4.5: n_c_max = {TWO_PLANE.n_c_max}"),
        Check("min_edge_clearance_m", ">", "min_edge_clearance_no_nullspace_m",
              "thesis §4.4.2: the null-space term keeps the connection off the edge (spec §5.4 #19, comparative)",
              name="redundancy_raises_edge_clearance"),
    )


def thesis_values(cond: TwoPlaneCondition, figure: str) -> dict:
    return {
        "front_plane": ThesisValue(f"p_f = {list(cond.p_f)} m, θ_f = {list(cond.theta_f)} rad", "seed 001 §4.5"),
        "table_4_1": ThesisValue(f"d_d = d_r = {cond.d_d} m, k_c = {cond.k_c}, k_p = {cond.k_p}, k_v = {cond.k_v}, "
                                 f"k_u = ({cond.k_u1}, {cond.k_u2}), v_p = {cond.v_p} m/s, A = {cond.A} m, "
                                 f"T = {cond.T} s", "seed 001 Table 4.1"),
        "head_tracking": ThesisValue("followed the target (no number in the text)", f"seed 001 §4.5, {figure}(c)",
                                     "head_error_after_transient_m"),
        "contact": ThesisValue("connection variables tracked well; proper contact kept", f"seed 001 §4.5, {figure}(d)",
                               "contact_d_error_max_m"),
        "edge_and_joint_limits": ThesisValue("avoided through the redundancy", "seed 001 §4.5, §4.6",
                                             "min_edge_clearance_m"),
        "onto_front_plane": ThesisValue("moved onto the front plane", f"seed 001 §4.5, {figure}(a)",
                                        "all_wheels_on_front"),
    }


def run_condition(ctx, cond: TwoPlaneCondition) -> dict:
    p = ctx.params
    labels = [("with_null_space", None), ("no_null_space", 0.0)] if p["null_space"] else [("no_null_space", 0.0)]
    runs = {}
    for i, (label, k_v) in enumerate(labels):
        runs[label] = simulate_two_plane(cond, p["duration_s"], k_v=k_v, recorder=ctx.recorder, name=label,
                                         progress=lambda f, i=i: ctx.progress((i + f) / len(labels), label))
    ctx.sim_time_s = float(sum(r.t[-1] for r in runs.values()))
    main = next(iter(runs.values()))
    plot_motion(ctx, main)
    plot_contact(ctx, main)
    plot_head(ctx, main)
    plot_redundancy(ctx, runs)
    plot_edge(ctx, runs)
    if p["null_space"]:
        plot_motion(ctx, runs["no_null_space"], name="motion_no_null_space")
    ctx.extra["events"] = {label: run.events for label, run in runs.items()}
    metrics = main.metrics()
    if p["null_space"]:
        metrics.update({_with_suffix(k): v for k, v in runs["no_null_space"].metrics().items()})
    return metrics


@scenario(
    "snake.two-plane-roll",
    source="seed 001 §4.5 condition 1",
    summary="head transition, straddling and connection transitions onto a front plane rolled by −0.107 rad",
    params=PARAMS, checks=checks(), thesis=thesis_values(CONDITION_1, "Fig. 4.13"),
)
def two_plane_roll(ctx) -> dict:
    return run_condition(ctx, CONDITION_1)


@scenario(
    "snake.two-plane-pitch",
    source="seed 001 §4.5 condition 2",
    summary="head transition, straddling and connection transitions onto a front plane pitched by −0.0609 rad",
    params=PARAMS, checks=checks(), thesis=thesis_values(CONDITION_2, "Fig. 4.14"),
)
def two_plane_pitch(ctx) -> dict:
    return run_condition(ctx, CONDITION_2)
