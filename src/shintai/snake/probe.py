"""A probe: logs what the simulator shows (not what the robot's sensors report) every control period.

A Rig's ``record`` logs functions of the snapshot; a probe is for quantities the snapshot does not carry
(a box's or cart's position, the simulated body's polyline, the door's angle), read from the simulator
before the step, at the same instant as the snapshot the controllers see.
"""

from __future__ import annotations

from shintai.core.runtime import Module
from shintai.snake.constants import CH3_GAINS


class Probe(Module):
    """Logs ``signals(snapshot)`` (a dict) under ``<name>.<key>`` every ``period`` (the control period δt)."""

    def __init__(self, name: str, signals, period: float = CH3_GAINS.dt):
        super().__init__(name, period)
        self.signals = signals

    def update(self, snapshot):
        self.log(snapshot["t"], **{f"{self.name}.{k}": v for k, v in self.signals(snapshot).items()})
