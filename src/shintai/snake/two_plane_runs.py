"""Runs of seed 001 §4.5 (two planes, conditions 1 and 2): the rig, what one run did and its metrics, and the
declarations both scenarios share (parameters, checks, thesis values).

The rig is the kinematic plant of the two-plane world (two_plane_plant.py) under the phases of Fig. 4.4
(two_plane_phases.py), with Table 4.1, n_h = 3, n_{c_max} = 2, ε_d = 0.029 m and the choices of
constants.TwoPlaneSettings / TwoPlaneScene. Metrics are computed from the plant's snapshots (one per control
period δt = 0.2 s, plus the final state):

* head error: ‖(^f x, ^f y)_d − (^f x, ^f y)‖ of (4.36), after the first 2/k_p s of straddling;
* contact errors over every wheel the plant holds on a plane, from the first step with wheel 1 on the front
  plane: |d − r_w| (2.36), |κ| (2.37), and |λ| (2.38) for wheels whose next wheel is on the same plane
  (λ = 0 is what makes the following wheels touch, §2.6.1);
* edge clearance of the lifted body part (two_plane.edge_clearance: wheel discs r_w, link capsules);
* all wheels on the front plane at the end: |d − r_w| and |κ| within constants.ON_PLANE_* and inside the
  front rectangle.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.core.geometry import wrap
from shintai.scenarios.experiment import Rig, Run, per_variant, run_rig
from shintai.scenarios.registry import Check, Param, ThesisValue
from shintai.snake.constants import (
    CH4_ROBOT,
    ON_PLANE_D_TOL,
    ON_PLANE_TILT_TOL,
    TWO_PLANE,
    TWO_PLANE_SCENE,
    TwoPlaneCondition,
)
from shintai.snake.two_plane import FRONT, LIFTED, Partition, TwoPlaneWorld, head_raised_contact, initial_posture
from shintai.snake.two_plane_phases import LOG, events, two_plane_switcher
from shintai.snake.two_plane_plant import TwoPlaneSnake

CONTROLLER_LOGS = ("w_f", "w_d", "r", "n_f", "n_c", "n_re", "V", "d_e", "sigma_H", "sigma_A", "u_norm", "r1")
VECTOR_LOGS = ("w_f", "w_d", "r", "r1")
SNAPSHOT_KEYS = ("p_h", "R_h", "psi", "contact", "r_front", "r_rear", "edge_clearance", "wheels", "slip", "snap_m")
PLANT = "plant"  # the plant's snapshots are recorded as plant.*


def largest(x) -> float:
    """Largest entry, NaN for an empty selection (e.g. a run stopped before the straddling started)."""
    x = np.asarray(x, dtype=float)
    return float(np.nanmax(x)) if x.size and not np.isnan(x).all() else float("nan")


def two_plane_rig(cond: TwoPlaneCondition, duration: float, k_v: float | None = None) -> Rig:
    """§4.5 under ``cond`` for ``duration`` s from the initial posture of TwoPlaneScene (k_v: Table 4.1 if None);
    the plant's snapshot recorded every control period."""
    world = TwoPlaneWorld.build(cond, TWO_PLANE_SCENE, TWO_PLANE.r_w)
    p_h, R_h, psi = initial_posture(world)
    body = TwoPlaneSnake(world, p_h, R_h, psi, head_raised_contact(CH4_ROBOT.n, TWO_PLANE.n_h))
    switcher = two_plane_switcher(world, cond, k_v)
    return Rig(body, [switcher], duration=duration, record={1: lambda s: {f"{PLANT}.{k}": s[k] for k in SNAPSHOT_KEYS}},
               state={"switcher": switcher, "cond": cond, "world": world, "k_v": cond.k_v if k_v is None else float(k_v)})


def simulate_two_plane(cond: TwoPlaneCondition, duration: float, k_v: float | None = None) -> TwoPlaneRun:
    """One run of :func:`two_plane_rig` (outside the scenario runner: tests, benchmarks)."""
    return TwoPlaneRun.of(run_rig(two_plane_rig(cond, duration, k_v)))


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

    @classmethod
    def of(cls, run: Run) -> TwoPlaneRun:
        """The series of a finished run of :func:`two_plane_rig` (built once)."""
        if "series" not in run.state:
            log, final = run.log, run.body.snapshot()
            s = {k: np.concatenate((log.values(f"{PLANT}.{k}"), [final[k]])) for k in SNAPSHOT_KEYS}
            c = {k: (log.times(f"{LOG}.{k}"), log.values(f"{LOG}.{k}")) if f"{LOG}.{k}" in log
                 else (np.zeros(0), np.zeros((0, 3) if k in VECTOR_LOGS else 0))  # a run ended before straddling
                 for k in CONTROLLER_LOGS}
            ev = events(run.state["switcher"])
            t_0 = next((e[0] for e in ev if e[1] == "head_done"), float("nan"))
            run.state["series"] = cls(run.variant, run.state["cond"], run.state["world"], run.state["k_v"],
                                      np.append(log.times(f"{PLANT}.psi"), run.body.t), s, c, ev, t_0)
        return run.state["series"]

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
        heading_err = np.abs(wrap(w_d[late, 2] - w_f[late, 2]))
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


PARAMS = (
    Param("duration_s", 130.0, "simulated time (the head transition and all 8 landings take ~105 s)", lo=1.0, hi=400.0),
    Param("null_space", True, "true: Table 4.1's k_v, plus a k_v = 0 rerun reported as *_no_nullspace; "
                              "false: only the k_v = 0 run (the comparison checks then find no metric)"),
)



def checks() -> tuple[Check, ...]:
    n = CH4_ROBOT.n
    return (
        Check("head_transition_time_s", "<=", 20.0,
              "thesis §4.5: head adaptation converged (Fig. 4.13b); 20 s = 20 time constants of K_h = I (chosen)", kind="consistency"),
        Check("head_error_after_transient_m", "<=", 0.01,
              "thesis §4.5: the head followed its target on the front plane (Fig. 4.13c, no number); 1 cm after "
              "2/k_p s proposed in spec §5.4 #16", kind="reproduction"),
        Check("contact_d_error_max_m", "<=", 0.002,
              "thesis §4.5: connection variables tracked well, wheels kept proper contact (Fig. 4.13d); 2 mm from "
              "spec §5.4 #16", kind="reproduction"),
        Check("max_abs_tilt_rad", "<=", 0.02, "thesis §4.5 (as above); 0.02 rad from spec §5.4 #16", kind="reproduction"),
        Check("all_wheels_on_front", "==", 1,
              "thesis §4.5: the robot moved onto the front plane (Fig. 4.13a); the last wheels need the tail "
              "release of two_plane.py, not in the thesis", kind="reproduction"),
        Check("min_edge_clearance_m", ">", 0.0,
              "thesis §4.4.2, §4.5: contact with the plane edges avoided through the redundancy (spec §5.4 #18)", kind="reproduction"),
        Check("max_abs_joint_rad", "<", CH4_ROBOT.joint_limit, "thesis §4.5: ψ_lim = π/2 avoided (sub-task (i))", kind="reproduction"),
        Check("front_shifts", "==", n - 1, "derived: wheels 2..n land one by one after the head transition", kind="consistency"),
        Check("rear_shifts", "==", n - TWO_PLANE.n_h,
              "derived: the rear end moves from wheel n_h to wheel n (then the tail is released)", kind="consistency"),
        Check("rear_shift_after_each_front_shift", "==", 1,
              "thesis §4.2.4: after a front shift n_c < n_c_max, so the rear end shifts at once (spec §5.4 #17)", kind="consistency"),
        Check("max_connection_wheels", "<=", TWO_PLANE.n_c_max, f"thesis §4.5: n_c_max = {TWO_PLANE.n_c_max}", kind="consistency"),
        Check("min_edge_clearance_m", ">", "min_edge_clearance_no_nullspace_m",
              "thesis §4.4.2: the null-space term keeps the connection off the edge (spec §5.4 #19, comparative)",
              name="redundancy_raises_edge_clearance", kind="consistency"),
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


def variants(null_space: bool) -> tuple[str, ...]:
    """Table 4.1's k_v and the k_v = 0 rerun, or the rerun alone (``null_space`` false)."""
    return ("with_null_space", "no_null_space") if null_space else ("no_null_space",)


def condition_rig(cond: TwoPlaneCondition, duration_s: float, variant: str):
    """The rig of a §4.5 condition for one variant (``no_null_space``: k_v = 0)."""
    return two_plane_rig(cond, duration_s, None if variant == "with_null_space" else 0.0)


def condition_metrics(runs: dict, null_space: bool) -> dict:
    """The first run's metrics; with ``null_space``, the k_v = 0 run's too, named ``*_no_nullspace`` (unit last)."""
    series = {variant: TwoPlaneRun.of(run) for variant, run in runs.items()}
    metrics = next(iter(series.values())).metrics()
    if null_space:
        metrics.update(per_variant({"no_nullspace": series["no_null_space"].metrics()}))
    return metrics
