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

This runs on the shared runtime (issue 12): :class:`CrawlBody` is a batched Body whose step is one
walking cycle (1-2 are its snapshot, 5 its step); the action network is the set-point stage
(:class:`ActionModule`, 3, writing the loop channel ``displacement``) and the swing order the next
stage (:class:`SwingOrderModule`, 4, writing the body's set channels ``command`` and ``order``);
:func:`rollout` runs that Loop until every walk has stopped. Results are bit-identical to the
hand-written cycle loop it replaced.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from shintai.core.runtime import SET, Body, Channel, Loop, Module, declare
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
    environment e); the forward pass runs over the active rows only: the genomes that still walk, each
    with its active rows packed, in a few batched calls — genomes with similar counts of active rows
    together, padded to their group's largest (late in a generation a few long walks remain; one pass
    padded to the largest count did 1.76 times the rows needed, and the full ``k x E`` pass cost more
    than the crawl). A row's output does not depend on the rows evaluated with it (tested)."""

    net: ActionNetwork
    genomes: np.ndarray
    n_envs: int
    fill: float = 7 / 8  # a group's genomes have at least this fraction of its largest count of rows

    def __call__(self, x: np.ndarray, rows: np.ndarray) -> np.ndarray:
        genome = np.asarray(rows) // self.n_envs
        present, slot, counts = np.unique(genome, return_inverse=True, return_counts=True)
        rank = np.empty(len(genome), dtype=int)  # each row's place among its genome's rows
        by_genome = np.argsort(slot, kind="stable")
        rank[by_genome] = np.arange(len(genome)) - np.repeat(np.cumsum(counts) - counts, counts)
        group = self._groups(counts)
        row_group = group[slot]
        place = np.empty(len(counts), dtype=int)  # each genome's place in its group
        out = np.empty((len(genome), self.net.n_out))
        for g in range(group.max(initial=-1) + 1):
            members = np.flatnonzero(group == g)
            place[members] = np.arange(len(members))
            r = np.flatnonzero(row_group == g)
            dense = np.zeros((len(members), counts[members].max(), x.shape[1]))
            dense[place[slot[r]], rank[r]] = x[r]
            out[r] = self.net.forward(self.genomes[present[members]], dense)[place[slot[r]], rank[r]]
        return out

    def _groups(self, counts: np.ndarray) -> np.ndarray:
        """Each genome's group: by falling count, a new group where a count is below ``fill`` of the group's first."""
        group = np.empty(len(counts), dtype=int)
        g, largest = -1, 0
        for i in np.argsort(-counts, kind="stable"):
            if g < 0 or counts[i] < self.fill * largest:
                g, largest = g + 1, counts[i]
            group[i] = g
        return group


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


class CrawlBody(Body):
    """The batched crawl as a :class:`~shintai.core.runtime.Body`: one step is one walking cycle of every
    active episode (quasi-static: ``dt`` = 1, body time counts cycles).

    Snapshot: ``rows`` (the active episodes), their body heights ``zr`` by the body-raise rule and the
    24 action-network ``inputs`` (features from the known obstacles, or from ``perception``); it is
    taken once per cycle (a perception is stateful). Channels (set: one writer each): ``command``
    (ΔXr, ΔYr, Δθr) and ``order`` (Table 2 numbers) of the active rows. A step executes the cycle
    (``robot.crawl_cycle``) and stores it into :attr:`episodes`; a row stops at a collision, a joint
    limit or lost stability (the cycle is not executed), or inside the goal circle.
    """

    dt = 1.0
    channels = declare("command", "order", kind=SET)

    def __init__(self, envs: W.EnvBatch, max_cycles: int = C.MAX_CYCLES, record: bool = False,
                 perception: Perception | None = None):
        if perception is not None:
            perception.reset(envs)
        n = len(envs)
        self.envs, self.max_cycles, self.record, self.perception = envs, max_cycles, record, perception
        envs.normals, envs.circles  # computed once here, taken along with the active rows every cycle
        self.state = R.CrawlState.initial(n)
        self.active = np.ones(n, dtype=bool)
        self.episodes = Episodes(np.zeros(n, int), np.zeros(n, bool), np.zeros(n, bool), np.zeros(n, bool),
                                 np.zeros(n, bool), np.zeros((n, 2)), np.full((n, max_cycles + 1, 3), np.nan),
                                 np.full((n, max_cycles, 3), np.nan), np.full((n, max_cycles), np.nan),
                                 np.full((n, max_cycles), -1), np.full((n, max_cycles), np.nan),
                                 [[] for _ in range(n)] if record else None)
        self.episodes.poses[:, 0] = self.state.pose
        self.k, self.t = 0, 0.0
        self._snap: dict | None = None
        self._command: dict = {}

    @property
    def done(self) -> bool:
        return not self.active.any()

    def snapshot(self) -> dict:
        if self._snap is None:
            rows = np.flatnonzero(self.active)
            st, env = self.state.take(rows), self.envs.take(rows)
            if len(rows) == 0:  # every walk has stopped
                self._cycle = (rows, st, env, np.zeros(0))
                self._snap = {"t": self.t, "rows": rows, "zr": np.zeros(0), "inputs": np.zeros((0, C.ACTION_INPUTS))}
                return self._snap
            zr = R.body_height(st.pose, st.feet, env)
            features = None if self.perception is None else self.perception(self.k, rows, st, env)
            self._cycle = (rows, st, env, zr)
            self._snap = {"t": self.t, "rows": rows, "zr": zr, "inputs": action_inputs(st, zr, env, features)}
        return self._snap

    def apply(self, command: dict) -> None:
        self._command = command

    def step(self) -> None:
        rows, st, env, zr = self._cycle
        if len(rows) == 0 or self.k >= self.max_cycles:  # every walk has stopped: time passes, nothing moves
            self.t = float(self.k)
            self._snap = None
            return
        command, order = self._command["command"], self._command["order"].astype(int)
        ep, k = self.episodes, self.k
        out = R.crawl_cycle(st, command, ORDERS[order], zr, env)
        _store(ep, k, rows, out, command, order, self.record)
        ok = ~out.failed
        self.state.put(rows[ok], out.state.take(ok))
        ep.poses[rows[ok], k + 1] = out.state.pose[ok]
        ep.cycles[rows] = k + 1
        ep.reached[rows[ok]] = W.length(env.destination[ok] - out.state.pose[ok, :2]) <= C.GOAL_RADIUS
        self.active[rows[out.failed]] = False
        self.active[rows[ok & ep.reached[rows]]] = False
        self.k += 1
        self.t = float(self.k)
        self._snap = None

    def finish(self) -> Episodes:
        """The episodes, with the final destination errors where each walk stopped."""
        self.episodes.final_error = self.envs.destination - self.state.pose[:, :2]
        return self.episodes


DISPLACEMENT = Channel("displacement", SET, doc="(ΔXr, ΔYr, Δθr) of the active rows, the action network's "
                                                 "set-point that the swing-order stage reads in the same cycle")


class ActionModule(Module):
    """The action network (seed §4, Fig. 16): the 24 inputs → (ΔXr, ΔYr, Δθr), clipped to the robot's
    displacement range ``command_range`` (``None``: not clipped); writes the ``displacement`` set-point."""

    def __init__(self, policy: ActionPolicy, command_range: tuple | None = C.COMMAND_RANGE):
        super().__init__("action network")
        self.policy, self.command_range = policy, command_range

    def update(self, snapshot: dict) -> dict:
        command = np.asarray(self.policy(snapshot["inputs"], snapshot["rows"]), dtype=float)
        if self.command_range is not None:
            command = np.clip(command, *self.command_range)
        return {"displacement": command}


class SwingOrderModule(Module):
    """The cycle's command: the displacement set-point with a swing order — the crawl order 4→2→3→1
    (seed §4, ``policy=None``) or a swing-order policy of (Zr, displacement) (seed §6, Fig. 29)."""

    def __init__(self, policy: OrderPolicy | None = None):
        super().__init__("swing order")
        self.policy = policy

    def update(self, snapshot: dict) -> dict:
        d = snapshot["displacement"]
        order = np.full(len(d), CRAWL) if self.policy is None else np.asarray(self.policy(snapshot["zr"], d))
        return {"command": d, "order": order}


def crawl_loop(body: CrawlBody, action_policy: ActionPolicy, order_policy: OrderPolicy | None = None,
               command_range: tuple | None = C.COMMAND_RANGE) -> Loop:
    """The crawl's Loop: the action network as the set-point stage, the swing order as the next."""
    return Loop(body, stages=[[ActionModule(action_policy, command_range)], [SwingOrderModule(order_policy)]],
                channels=[DISPLACEMENT])


def rollout(envs: W.EnvBatch, action_policy: ActionPolicy, order_policy: OrderPolicy | None = None,
            max_cycles: int = C.MAX_CYCLES, record: bool = False,
            command_range: tuple | None = C.COMMAND_RANGE, perception: Perception | None = None) -> Episodes:
    """Run one episode per environment row in lock-step (module docstring) through the Loop, one
    step per walking cycle, up to ``max_cycles`` or until every walk has stopped; the action policy's
    commands are clipped to ``command_range`` ``(low, high)`` (``None``: not clipped). ``perception``
    supplies the obstacle features (``None``: the known obstacles, :func:`obstacle_features`)."""
    body = CrawlBody(envs, max_cycles, record, perception)
    if len(envs):
        crawl_loop(body, action_policy, order_policy, command_range).run(max_cycles * body.dt,
                                                                         until=lambda _: body.done)
    return body.finish()


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
