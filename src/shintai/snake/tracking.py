"""Two-point runs of seed 001 ch. 3: the rig of the §3.3 tracking experiment (also the caging run's, §3.4.1)
and what one run did (:class:`TrackingRun`), with the MuJoCo run's comparison against the kinematic model.

The rig is the two-point controller (two_point.py) on the kinematic plant (plant.py) or the MuJoCo snake
(mujoco_plant.py), with the §3.3 constants, K_p = 4·I_6 (A5), targets unwrapped (A6) and the candidate set of
constants.TwoPointGains (66 by default; 80 is the literal reading, A8).

Error metrics: e = c_{c,d} − c_c (Fig. 3.6c). A point's position error is the Euclidean norm of its (x, y)
error; ``*_pos_error_m`` takes the larger of head and tail. The final sample is the state after the last step.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from shintai.scenarios.experiment import Rig, Run
from shintai.scenarios.registry import Param
from shintai.snake.constants import CH3_GAINS, CH3_ROBOT, TRACKING, TrackingExperiment
from shintai.snake.model import configuration
from shintai.snake.mujoco_plant import MujocoSnake, head_path_difference, replay_error
from shintai.snake.plant import KinematicSnake
from shintai.snake.targets import PiecewiseLinear
from shintai.snake.two_point import TwoPointController, TwoPointLaw

PLANTS = {"kinematic": KinematicSnake, "mujoco": MujocoSnake}  # plant name -> Body class (w_h0, phi0, geometry, dt)
CONTROLLER = "two_point"  # the controller's name: its signals are logged as two_point.*

PARAMS = (
    Param("plant", "kinematic", "body to run: the thesis's kinematic model, or the physical snake in MuJoCo",
          choices=tuple(PLANTS)),
    Param("duration_s", TRACKING.t_end, "simulated time; the ramp (3.21) keeps t_end = 120 s", lo=0.05, hi=TRACKING.t_end),
    Param("candidates", 66, "candidate modes: 66 (head end counts as lifted) or 80 (literal rules), A8",
          choices=(66, 80)),
)


def two_point_rig(body, law: TwoPointLaw, target, duration: float, select_period: float | None, modules=(),
                  record=None) -> Rig:
    """The two-point controller (period δt, mode selection every ``select_period``, None: frozen after t = 0)
    on ``body`` toward ``target`` for ``duration`` s, with extra ``modules`` (probes, the kinematic box)."""
    controller = TwoPointController(law, target, select_period, name=CONTROLLER)
    view = body.view() if isinstance(body, MujocoSnake) else {}
    return Rig(body, [controller, *modules], duration=duration, record=record or {}, view=view,
               state={"law": law, "target": target, "controller": controller})


def tracking_rig(duration: float, candidates: int = 66, switching: bool = True, plant: str = "kinematic",
                 experiment: TrackingExperiment = TRACKING) -> Rig:
    """The §3.3 experiment for ``duration`` s (ramp (3.21) over t_end); mode frozen after t = 0 unless
    ``switching`` (the ablation of §3.1's claim)."""
    law = TwoPointLaw(CH3_ROBOT, CH3_GAINS, head_end_lifted=(candidates == 66))
    body = PLANTS[plant](experiment.w_h0, experiment.phi0, CH3_ROBOT, CH3_GAINS.dt)
    c0 = law.controlled(configuration(experiment.w_h0, experiment.phi0, CH3_ROBOT.l))
    target = PiecewiseLinear.ramp(c0, experiment.c_e, experiment.t_end)
    return two_point_rig(body, law, target, duration, CH3_GAINS.t_sigma if switching else None)


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

    @classmethod
    def of(cls, run: Run) -> TrackingRun:
        """The series of a finished run of :func:`two_point_rig` (built once: the final snapshot is read once)."""
        if "series" not in run.state:
            law, target, log, body = run.state["law"], run.state["target"], run.log, run.body
            final = body.snapshot()
            c_final = law.controlled(configuration(final["w_h"], final["phi"], law.geometry.l))
            get = lambda key: log.values(f"{CONTROLLER}.{key}")  # noqa: E731
            run.state["series"] = cls(
                name=run.variant,
                t=np.append(log.times(f"{CONTROLLER}.c"), body.t),
                c=np.vstack((get("c"), c_final)),
                c_d=np.vstack((get("c_d"), target(body.t)[0])),
                phi=np.vstack((get("phi"), final["phi"])),
                grounded=get("grounded").astype(bool), mode=get("mode").astype(int),
                stopped=get("stopped").astype(bool), sigma_a=get("sigma_a"), sigma_b=get("sigma_b"),
                V_m=get("V_m"), slip=get("slip"), candidates=len(law.candidates),
                selections=run.state["controller"].selections,
                physics=body.slip_summary() if isinstance(body, MujocoSnake) else {})
        return run.state["series"]

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


def kinematic_comparison(run: TrackingRun, reference: TrackingRun) -> dict:
    """A MuJoCo run against the kinematic model: its slip summary, the head-path difference to the kinematic
    plant's ``reference`` run of the same scenario, and the kinematic model replayed on its measured joints
    over each t_σ window."""
    window = int(round(CH3_GAINS.t_sigma / CH3_GAINS.dt))
    return {**run.physics,
            "head_path_diff_vs_kinematic_m": head_path_difference(run.c, reference.c),
            "head_replay_error_m": replay_error(run.c[:, :3], run.phi, run.grounded, CH3_ROBOT.l, CH3_GAINS.dt, window)}
