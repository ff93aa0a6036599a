"""The posture database (姿勢データベース) of seed 003 §5.9.1–5.9.2 (Fig. 5.29), robot-independent.

§5.9.1 defines it by five properties, each implemented here as written:

* **Elements** — "筋長ベースでセグメンテーションし、データベースのいずれの要素からも一定距離以上離れたデータは、
  新しい要素としてデータベースに追加する": a sample of the m muscle lengths whose Euclidean distance to *every*
  node is at least ``d_len`` becomes a new node (:meth:`PostureDatabase.observe`).
* **Internal sensors** — a node also keeps the posture sensor's value at its creation; the sensor is *not* an
  extra axis of the length space: "姿勢センサ情報は姿勢センサ情報同士で距離を計算する … 閾値を超えていたら新たなノード
  を生成する". A sample therefore matches a node only if it is within ``d_len`` in length *and* within
  ``d_sensor`` in the sensor; with no matching node a new one is made (the extraction's reading, spec §9.6).
* **Posture history** — "これまでにデータベース中のどの要素付近を通ってきたかの履歴を保持する": the node each
  sample is near is appended whenever it changes. While the sample is still near the node the history is at,
  it stays there (chosen: where two nodes' neighbourhoods overlap, "the nearest" would flip with every 20 ms
  sample of sensor noise and write a flicker into the history); otherwise it goes to the nearest matching
  node, or a new one.
* **Use for motion generation** — a motion given as model postures → their muscle lengths (eq. 4.25) → "最も近い
  (姿勢データベース中の) 姿勢から成る列に直して動作を実行する" (:meth:`PostureDatabase.plan`).
* **Always updated** — the caller observes every sample in every mode (§5.9.3 "姿勢データベースとの兼ね合い").

The thesis gives no value for either threshold ("一定距離"); the caller chooses them (the experiment's
constants). Distances are in the units of the lengths given (here metres of encoder wire).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Node:
    """One element: the muscle lengths (m,) and posture-sensor value at creation, when it was made, how often
    the history entered it, and (for evaluation only, the thesis had no such record) the true posture then."""

    id: int
    lengths: np.ndarray
    sensor: np.ndarray | None
    created_at: float
    visits: int = 0
    tag: str = ""  # what the robot was doing when the node was made (teaching mode, nudge, replay, …)
    truth: np.ndarray | None = None


@dataclass
class PostureDatabase:
    """Nodes in muscle-length space with a distance threshold ``d_len`` and, when a posture sensor is used, a
    separate sensor threshold ``d_sensor`` (module doc)."""

    d_len: float
    d_sensor: float | None = None
    nodes: list[Node] = field(default_factory=list)
    history: list[int] = field(default_factory=list)
    history_t: list[float] = field(default_factory=list)

    def __post_init__(self):
        if not np.isfinite(self.d_len) or self.d_len <= 0:
            raise ValueError(f"d_len must be a positive distance, got {self.d_len!r}")
        if self.d_sensor is not None and (not np.isfinite(self.d_sensor) or self.d_sensor <= 0):
            raise ValueError(f"d_sensor must be a positive distance or None, got {self.d_sensor!r}")

    # -- queries --------------------------------------------------------------------------------------------

    @property
    def lengths(self) -> np.ndarray:
        """All nodes' lengths, (k, m)."""
        return np.array([n.lengths for n in self.nodes])

    def distances(self, lengths) -> np.ndarray:
        """Euclidean distance in length space from ``lengths`` to every node, (k,)."""
        if not self.nodes:
            return np.zeros(0)
        return np.linalg.norm(self.lengths - np.asarray(lengths, dtype=float), axis=1)

    def nearest(self, lengths) -> Node:
        """The node nearest in length space (§5.9.1: "筋長配列に最も近い姿勢")."""
        if not self.nodes:
            raise ValueError("the posture database is empty")
        return self.nodes[int(np.argmin(self.distances(lengths)))]

    def matching(self, lengths, sensor=None) -> list[Node]:
        """The nodes a sample is "near": within d_len in length, and within d_sensor in the sensor when both
        the sample and the node have one and a sensor threshold is set."""
        d = self.distances(lengths)
        out = []
        for node, dist in zip(self.nodes, d):
            if dist >= self.d_len:  # "一定距離以上離れた" → not near
                continue
            if self.d_sensor is not None and sensor is not None and node.sensor is not None:
                if np.linalg.norm(np.asarray(sensor, dtype=float) - node.sensor) >= self.d_sensor:
                    continue
            out.append(node)
        return out

    # -- updates --------------------------------------------------------------------------------------------

    def observe(self, lengths, sensor=None, t: float = 0.0, tag: str = "", truth=None) -> tuple[Node, bool]:
        """One monitoring sample: the node it belongs to (made if none matches) and whether it was made; the
        history is extended when the node differs from the last entry."""
        lengths = np.asarray(lengths, dtype=float)
        if not np.all(np.isfinite(lengths)):
            raise ValueError("posture database: non-finite muscle lengths")
        near = self.matching(lengths, sensor)
        created = not near
        if created:
            node = Node(len(self.nodes), lengths.copy(), None if sensor is None else np.asarray(sensor, float).copy(),
                        t, tag=tag, truth=None if truth is None else np.asarray(truth, float).copy())
            self.nodes.append(node)
        elif self.history and any(n.id == self.history[-1] for n in near):
            node = self.nodes[self.history[-1]]  # still near the node the history is at: stay (class doc)
        else:
            d = self.distances(lengths)
            node = min(near, key=lambda n: d[n.id])
        if not self.history or self.history[-1] != node.id:
            self.history.append(node.id)
            self.history_t.append(t)
            node.visits += 1
        return node, created

    def plan(self, lengths_sequence) -> list[int]:
        """§5.9.1 "動作生成への利用": each posture's lengths (eq. 4.25) → the nearest node; repeats dropped."""
        out: list[int] = []
        for lengths in np.atleast_2d(np.asarray(lengths_sequence, dtype=float)):
            k = self.nearest(lengths).id
            if not out or out[-1] != k:
                out.append(k)
        return out

    def edges(self) -> set[tuple[int, int]]:
        """The node graph: consecutive history entries, undirected."""
        return {tuple(sorted(p)) for p in zip(self.history, self.history[1:])}

    def min_separation(self) -> float:
        """The smallest length distance between two nodes (≥ d_len unless the sensor split them)."""
        L = self.lengths
        if len(L) < 2:
            return float("inf")
        d = np.linalg.norm(L[:, None] - L[None], axis=-1)
        return float(d[np.triu_indices(len(L), 1)].min())

    def violations(self) -> int:
        """Pairs of nodes that the definition says should be one: closer than d_len in length and (without a
        sensor threshold, or) closer than d_sensor in the sensor. 0 for a database built by :meth:`observe`."""
        count = 0
        for i, a in enumerate(self.nodes):
            for b in self.nodes[i + 1:]:
                if np.linalg.norm(a.lengths - b.lengths) >= self.d_len:
                    continue
                if self.d_sensor is not None and a.sensor is not None and b.sensor is not None \
                        and np.linalg.norm(a.sensor - b.sensor) >= self.d_sensor:
                    continue
                count += 1
        return count
