"""E6: Rabbit stiffened by pre-compressing its silicone discs (seed 003 §3.5.3 behaviour 1/2, §3.5.4).

The muscle lengths are computed (eq. 4.25) for a joint gap ``precompression`` smaller than the discs'
free thickness and held by the servos; a sideways push ±F at the top gives the lateral stiffness
2F / Δy. On :class:`~shintai.spine.bodies.QuasiStaticSpine` each body step is one equilibrium: the
:class:`SidePush` module writes the lengths on the first tick, +F on the second and −F on the third.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.bodies import QuasiStaticSpine
from shintai.spine.robots import RABBIT, SpineRobot


class SidePush(Module):
    """Lengths, then +F, then −F sideways at the top (one equilibrium each); keeps the snapshot of the
    pre-compressed rest and the top's y under +F."""

    def __init__(self, lengths: np.ndarray, push_n: float, name: str = "side_push"):
        super().__init__(name)
        self.push_n = push_n
        self.commands = [{"length": lengths}, {"push": [0.0, push_n, 0.0]}, {"push": [0.0, -push_n, 0.0]}]
        self.seen: list[Snapshot] = []

    def update(self, snapshot: Snapshot):
        self.seen.append(snapshot)  # the equilibrium of the previous tick's command
        return self.commands[len(self.seen) - 1]


def linear_disc(robot: SpineRobot = RABBIT) -> SpineRobot:
    """The ablation: the same robot with a linear disc (k3 = 0)."""
    return replace(robot, disc=replace(robot.disc, k3_n_m3=0.0))


def stiffening_rig(robot: SpineRobot, precompression_m: float, push_n: float) -> Rig:
    ring = robot.disc
    gap = ring.t_free_m - precompression_m - ring.gap_m
    body = QuasiStaticSpine(robot)
    lengths = robot.model.lengths(np.zeros(3 * robot.n), np.full(robot.n, gap))
    probe = SidePush(lengths, push_n)
    return Rig(body, modules=[probe], duration=3 * body.dt, state=probe)


def stiffness_metrics(body: QuasiStaticSpine, probe: SidePush) -> dict[str, float]:
    """Lateral stiffness [N/mm], mean muscle tension at rest, the discs' compression at rest, and
    whether the rest equilibrium converged."""
    rest, pushed = probe.seen[1], probe.seen[2]
    y_plus, y_minus = pushed["top"][1], body.snapshot()["top"][1]
    ring = body.robot.disc
    return {"stiffness_n_mm": 2 * probe.push_n / (y_plus - y_minus) / 1e3,
            "mean_tension_n": float(rest["tension"].mean()),
            "disc_compression_mm": 1e3 * (ring.t_free_m - ring.gap_m - float(rest["gap"].mean())),
            "solved": int(rest["solved"])}
