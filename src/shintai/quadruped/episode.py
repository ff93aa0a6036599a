"""Episodes: perception, the action network's inputs, and the walking-cycle loop (seed §4, Fig. 16, 29).

Per walking cycle k of every active episode (all batched):

1. perceive: the known obstacles (simulation, seed §4) in the body frame as the features of §2.3,
   the sentinels for an obstacle the robot has passed; or, with a ``perception`` (e.g.
   ``sensing.SensedObstacles``, the ultrasonic sensors of the real robot), its features;
2. body-raise rule (rule-based, not the network): :func:`robot.body_height`;
3. action network: (ΔXr, ΔYr, Δθr) from the 24 inputs, clipped to the robot's displacement range
   (``constants.COMMAND_RANGE``: the ranges of seed §5.1, chosen);
4. swing order: the crawl order 4→2→3→1, or a swing-order policy;
5. one crawl cycle; the walk stops at a collision, a joint-limit violation or lost stability (the
   cycle is not executed, the robot stays where it was), when the CoG is within 0.2 m of the
   destination after a cycle, or after 50 cycles (seed §4.1.1-4.1.2).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import world as W
from shintai.quadruped.networks import ActionNetwork
from shintai.quadruped.swing_order import CRAWL, ORDERS

SENTINELS = np.array([C.SENTINEL_RIGHT, C.SENTINEL_LEFT])  # (2, 6)

ActionPolicy = Callable[[np.ndarray, np.ndarray], np.ndarray]  # (inputs (n, 24), rows (n,)) -> (n, 3)
OrderPolicy = Callable[[np.ndarray, np.ndarray], np.ndarray]  # (zr (n,), command (n, 3)) -> Table 2 numbers


class Perception(Protocol):
    """Obstacle features from something other than the known obstacles: ``reset(envs)`` when a
    rollout over ``envs`` starts; ``(k, rows, state, envs)`` at cycle k (0-based) of the active rows,
    with their state and environments, returns their features ``(n, 2, 6)`` as :func:`obstacle_features`."""

    def reset(self, envs: W.EnvBatch) -> None: ...

    def __call__(self, k: int, rows: np.ndarray, state: R.CrawlState, envs: W.EnvBatch) -> np.ndarray: ...


def obstacle_features(pose: np.ndarray, envs: W.EnvBatch) -> np.ndarray:
    """§2.3 features ``(E, 2, 6)`` of the right and left obstacle in the body frame: (x_max, x_min,
    y_max, y_min, z_max, z_min) with z_max the top and z_min the floor (chosen, §7.13). An obstacle
    entirely behind the body centre (y_max < 0, chosen for "passed", §7.11) gives the sentinels."""
    corners = R.to_body(pose, envs.polygons.reshape(len(pose), -1, 2)).reshape(envs.polygons.shape)
    x, y = corners[..., 0], corners[..., 1]
    z = envs.heights
    feats = np.stack([x.max(-1), x.min(-1), y.max(-1), y.min(-1), z, np.zeros_like(z)], axis=-1)
    return np.where((y.max(-1) < 0)[..., None], SENTINELS, feats)


def destination_error(pose: np.ndarray, destination: np.ndarray) -> np.ndarray:
    """(x_de, y_de) in the body frame (chosen, §7.10) and θ_de, the angle from the heading to the
    destination, counter-clockwise positive like Δθr [rad]; ``(E, 3)``."""
    e = R.to_body(pose, destination[:, None])[:, 0]
    return np.column_stack([e, np.arctan2(-e[:, 0], e[:, 1])])


def action_inputs(state: R.CrawlState, zr: np.ndarray, envs: W.EnvBatch,
                  features: np.ndarray | None = None) -> np.ndarray:
    """The 24 inputs of seed §4 ``(E, 24)``: feet (x_f1, y_f1, ..., x_f4, y_f4) in the body frame, Zr,
    right features, left features, (x_de, y_de, θ_de). ``features (E, 2, 6)`` replace the known
    obstacles' (:func:`obstacle_features`) when given."""
    feet = R.to_body(state.pose, state.feet[..., :2]).reshape(len(zr), 8)
    features = (obstacle_features(state.pose, envs) if features is None else features).reshape(len(zr), 12)
    return np.column_stack([feet, zr, features, destination_error(state.pose, envs.destination)])


def path_inputs(envs: W.EnvBatch, offsets=C.INIT_PATH_OFFSETS, steps: int = C.INIT_PATH_STEPS) -> np.ndarray:
    """Action inputs ``(len(offsets) * steps * E, 24)`` of states the robot could meet: the body at
    ``steps`` poses on the straight line from (offset, 0) to each destination, heading +y, feet at
    the initial stance on the floor, body height by the body-raise rule (the data the initial
    population's RBF centres are drawn from, constants ``INIT_PATH_*``)."""
    n = len(envs)
    rows = []
    for offset in offsets:
        for t in np.linspace(0.0, 1.0, steps):
            pose = np.column_stack([offset + t * (envs.destination[:, 0] - offset), t * envs.destination[:, 1],
                                    np.zeros(n)])
            feet = np.concatenate([R.to_world(pose, np.repeat(R.NOMINAL_FEET[None], n, 0)), np.zeros((n, 4, 1))], -1)
            zr = R.body_height(pose, feet, envs)
            rows.append(action_inputs(R.CrawlState(pose, zr, feet), zr, envs))
    return np.vstack(rows)


@dataclass(frozen=True)
class GenomePolicy:
    """Action networks of ``k`` genomes driving ``k x E`` episodes (row ``i * E + e`` is genome i in
    environment e); the forward pass is one batched call per cycle."""

    net: ActionNetwork
    genomes: np.ndarray
    n_envs: int

    def __call__(self, x: np.ndarray, rows: np.ndarray) -> np.ndarray:
        k = len(self.genomes)
        dense = np.zeros((k * self.n_envs, x.shape[1]))
        dense[rows] = x
        out = self.net.forward(self.genomes, dense.reshape(k, self.n_envs, -1))
        return out.reshape(k * self.n_envs, -1)[rows]


@dataclass
class Episodes:
    """Outcome of a batch of episodes. ``cycles`` is T (the failing cycle counts); ``final_error``
    is destination - CoG [m] (world) where the walk stopped; per-cycle arrays are NaN-padded
    (``poses`` has the start pose at index 0); ``records`` holds :class:`robot.CycleRecord` lists
    when asked for."""

    cycles: np.ndarray
    reached: np.ndarray
    collided: np.ndarray
    limit: np.ndarray
    unstable: np.ndarray
    final_error: np.ndarray
    poses: np.ndarray
    commands: np.ndarray
    zr: np.ndarray
    orders: np.ndarray
    br: np.ndarray
    records: list | None = None


def rollout(envs: W.EnvBatch, action_policy: ActionPolicy, order_policy: OrderPolicy | None = None,
            max_cycles: int = C.MAX_CYCLES, record: bool = False,
            command_range: tuple | None = C.COMMAND_RANGE, perception: Perception | None = None) -> Episodes:
    """Run one episode per environment row in lock-step (module docstring); the action policy's
    commands are clipped to ``command_range`` ``(low, high)`` (``None``: not clipped). ``perception``
    supplies the obstacle features (``None``: the known obstacles, :func:`obstacle_features`)."""
    if perception is not None:
        perception.reset(envs)
    n = len(envs)
    state = R.CrawlState.initial(n)
    active = np.ones(n, dtype=bool)
    ep = Episodes(np.zeros(n, int), np.zeros(n, bool), np.zeros(n, bool), np.zeros(n, bool), np.zeros(n, bool),
                  np.zeros((n, 2)), np.full((n, max_cycles + 1, 3), np.nan), np.full((n, max_cycles, 3), np.nan),
                  np.full((n, max_cycles), np.nan), np.full((n, max_cycles), -1), np.full((n, max_cycles), np.nan),
                  [[] for _ in range(n)] if record else None)
    ep.poses[:, 0] = state.pose
    for k in range(max_cycles):
        rows = np.flatnonzero(active)
        if len(rows) == 0:
            break
        st, env = state.take(rows), envs.take(rows)
        zr = R.body_height(st.pose, st.feet, env)
        features = None if perception is None else perception(k, rows, st, env)
        command = np.asarray(action_policy(action_inputs(st, zr, env, features), rows), dtype=float)
        if command_range is not None:
            command = np.clip(command, *command_range)
        order = np.full(len(rows), CRAWL) if order_policy is None else np.asarray(order_policy(zr, command))
        out = R.crawl_cycle(st, command, ORDERS[order], zr, env)
        _store(ep, k, rows, out, command, order, record)
        ok = ~out.failed
        state.put(rows[ok], out.state.take(ok))
        ep.poses[rows[ok], k + 1] = out.state.pose[ok]
        ep.cycles[rows] = k + 1
        ep.reached[rows[ok]] = W.length(env.destination[ok] - out.state.pose[ok, :2]) <= C.GOAL_RADIUS
        active[rows[out.failed]] = False
        active[rows[ok & ep.reached[rows]]] = False
    ep.final_error = envs.destination - state.pose[:, :2]
    return ep


def _store(ep: Episodes, k: int, rows: np.ndarray, out: R.CycleOutcome, command: np.ndarray, order: np.ndarray,
           record: bool) -> None:
    ep.commands[rows, k] = command
    ep.zr[rows, k] = out.state.zr
    ep.orders[rows, k] = order
    ep.br[rows, k] = out.br
    ep.collided[rows] |= out.collided
    ep.limit[rows] |= out.limit
    ep.unstable[rows] |= out.unstable
    if record:
        for i, row in enumerate(rows):
            ep.records[row].append(out.record(i, k + 1, command[i], ORDERS[order[i]]))
