"""Replays of the paper's action tables (seed §5.2 Table 3, §6.2 Tables 6 and 7; §5.7, §6.5 check 4).

* :func:`dead_reckon` composes the printed (ΔXr, ΔYr, Δθr) open-loop from the start destination
  error (-0.15, 2.2) m: p_{k+1} = p_k + R(θ_k)(ΔXr, ΔYr), θ_{k+1} = θ_k + Δθr with Δθr counter-clockwise
  (§5.7). Expected final |e| = 0.076 / 0.034 / 0.026 m, first entry into the 0.2 m goal circle at
  cycle 10 / 10 / 11, and 0.250 / 0.235 / 0.249 m one cycle earlier.
* :func:`replay_executor` executes the same rows (with their Zr and swing orders) by the crawl
  executor in the table's environment, which also reports collisions, joint limits and Br.
* :func:`body_movement_comparison` recomputes Tables 3-5's comparison of swing-order strategies
  (fixed, exhaustive search, the paper's RBFNN choices) with this executor's Br.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import swing_order as S
from shintai.quadruped import world as W

TABLES = {
    "table3": (C.TABLE3_ACTIONS, C.TABLE3_ORDERS, W.scenario_52),
    "table6": (C.TABLE6_ACTIONS, C.TABLE6_ORDERS, W.scenario_621),
    "table7": (C.TABLE7_ACTIONS, C.TABLE7_ORDERS, W.scenario_622),
}


def _table(name: str):
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r} (one of {', '.join(TABLES)})")
    return TABLES[name]


@dataclass(frozen=True)
class DeadReckoning:
    """Destination errors ``errors (n + 1, 2)`` [m] (world) before the first and after every cycle,
    their norms ``distances``, the first cycle ending inside the goal circle (None if never) and
    the distance one cycle before it."""

    errors: np.ndarray
    distances: np.ndarray
    first_entry: int | None
    previous_distance: float | None

    @property
    def final_distance(self) -> float:
        return float(self.distances[-1])


def dead_reckon(name: str) -> DeadReckoning:
    """Open-loop composition of a table's actions from its start destination error (§5.7)."""
    actions, _, env = _table(name)
    zr, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
    pose = np.zeros((1, 3))
    poses = [pose]
    for c in command:
        pose = R.compose(pose, c[None])
        poses.append(pose)
    errors = np.asarray(env().destination) - np.concatenate(poses)[:, :2]
    return _summary(errors)


CONVENTIONS = tuple(dict(dx_sign=a, dtheta_sign=b, turn_first=c, body_frame=d, x_sign=e, y_sign=f)
                    for a in (1, -1) for b in (1, -1) for c in (False, True) for d in (False, True)
                    for e in (1, -1) for f in (1, -1))  # 64 readings of §5.7 and of (x_de, y_de)


def convention_error(name: str, dx_sign: int = 1, dtheta_sign: int = 1, turn_first: bool = False,
                     body_frame: bool = False, x_sign: int = 1, y_sign: int = 1) -> np.ndarray:
    """A table's final (x_de, y_de) [m] under one of :data:`CONVENTIONS`: ΔXr and Δθr each with either
    sign, the cycle's translation in the frame before or after its turn (``turn_first``), the error
    in the world or the final body frame, and x_de, y_de each with either sign. Ours
    (:func:`dead_reckon`) is the first, all defaults."""
    actions, _, env = _table(name)
    _, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
    command = command * np.array([dx_sign, 1.0, dtheta_sign])
    pose = np.zeros(3)
    for c in command:
        heading = pose[2] + c[2] if turn_first else pose[2]
        pose = np.r_[pose[:2] + R.rotate(np.array([heading]), c[None, :2])[0], pose[2] + c[2]]
    error = np.asarray(env().destination) - pose[:2]
    if body_frame:
        error = R.rotate(np.array([-pose[2]]), error[None])[0]
    return error * np.array([x_sign, y_sign])


def convention_search(name: str) -> np.ndarray:
    """Distance [m] of each of the 64 :data:`CONVENTIONS`' final (x_de, y_de) from the thesis's printed vector."""
    paper = np.asarray(C.PAPER_FINAL_ERROR[name])
    return np.array([np.hypot(*(convention_error(name, **c) - paper)) for c in CONVENTIONS])


def convention_name(i: int) -> str:
    """A short name of :data:`CONVENTIONS` ``[i]`` (what differs from ours)."""
    c = CONVENTIONS[i]
    parts = [label for key, label in (("dx_sign", "ΔXr negated"), ("dtheta_sign", "Δθr negated"),
                                      ("x_sign", "x_de negated"), ("y_sign", "y_de negated")) if c[key] == -1]
    parts += ["translation after the turn"] * c["turn_first"] + ["final body frame"] * c["body_frame"]
    return ", ".join(parts) or "ours"


def _summary(errors: np.ndarray) -> DeadReckoning:
    distances = W.length(errors)
    inside = np.flatnonzero(distances[1:] <= C.GOAL_RADIUS)
    first = int(inside[0]) + 1 if len(inside) else None
    return DeadReckoning(errors, distances, first, float(distances[first - 1]) if first else None)


@dataclass(frozen=True)
class ExecutorReplay:
    """A table executed by the crawl executor: the dead-reckoning summary of the executed body
    poses, the per-cycle records, and whether any cycle collided / left the limits / lost stability."""

    reckoning: DeadReckoning
    records: tuple
    collided: bool
    limit: bool
    unstable: bool

    @property
    def br_mm(self) -> np.ndarray:
        return np.array([r.br_mm for r in self.records])


def replay_executor(name: str) -> ExecutorReplay:
    """Execute a table's rows (actions, Zr, swing orders) with the crawl executor in its environment."""
    actions, orders, env = _table(name)
    envs = W.EnvBatch.of([env()])
    zr, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
    state = R.CrawlState.initial(1)
    records, poses = [], [state.pose[0]]
    for k, (z, c, o) in enumerate(zip(zr, command, orders), 1):
        out = R.crawl_cycle(state, c[None], S.ORDERS[[o]], np.array([z]), envs)
        records.append(out.record(0, k, c, S.PERMUTATIONS[o]))
        state = out.state
        poses.append(state.pose[0])
    errors = envs.destination[0] - np.array(poses)[:, :2]
    return ExecutorReplay(_summary(errors), tuple(records), any(r.collided for r in records),
                          any(r.limit for r in records), any(r.unstable for r in records))


@dataclass(frozen=True)
class BodyMovementComparison:
    """Br per cycle [mm] of Table 3's actions under the fixed crawl order, the exhaustive search,
    the paper's RBFNN orders (Table 5) and Table 4's printed orders, the exhaustive search's orders,
    and the paper's sums."""

    fixed: np.ndarray
    exhaustive: np.ndarray
    rbfnn: np.ndarray
    exhaustive_orders: np.ndarray
    table4: np.ndarray
    paper_sums: tuple = (float(C.TABLE3_BR.sum()), float(C.TABLE4_BR.sum()), float(C.TABLE5_BR.sum()))

    @property
    def sums(self) -> tuple[float, float, float]:
        return float(self.fixed.sum()), float(self.exhaustive.sum()), float(self.rbfnn.sum())


def body_movement_comparison() -> BodyMovementComparison:
    """Tables 3-5 recomputed: every order of every Table 3 action on the flat floor from the stance."""
    actions = C.TABLE3_ACTIONS
    zr, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
    br = 1000 * S.body_movement(zr, command)
    best, best_br = S.best_orders(zr, command)
    rows = np.arange(len(br))
    return BodyMovementComparison(br[:, S.CRAWL], 1000 * best_br, br[rows, list(C.TABLE5_ORDERS)], best,
                                  br[rows, list(C.TABLE4_ORDERS)])


def zr_agreement() -> tuple[int, int]:
    """Cycles of Tables 3, 6, 7 whose printed Zr the body-raise rule reproduces, and their number."""
    agree = total = 0
    for actions, orders, env in TABLES.values():
        envs = W.EnvBatch.of([env()])
        zr, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
        state = R.CrawlState.initial(1)
        for z, c, o in zip(zr, command, orders):
            agree += int(np.isclose(R.body_height(state.pose, state.feet, envs)[0], z))
            total += 1
            state = R.crawl_cycle(state, c[None], S.ORDERS[[o]], np.array([z]), envs).state
    return agree, total
