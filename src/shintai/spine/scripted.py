"""The experimenter as modules: a hand that holds the spine, and a schedule of commands (seed 003 §4.2,
§4.5.2, §4.7.2).

In the thesis a person holds or pushes Cla's shoulders (teaching, §4.2.1; the software-spring test,
§4.5.2) and types the next posture and the muscle modes at the keyboard (§4.7.2). Here both are modules
of the first stage, so what they command reaches the body and the later stages through channels:

* :class:`Hand` writes the body's ``hand`` set channel, the posture whose top-link pose the hand holds,
  tick by tick (a tick without a posture lets go);
* :class:`Schedule` writes given channel values at given ticks (events: a posture goal, the modes of
  the next move) and nothing in between.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from shintai.core.runtime import Module, Snapshot


class Hand(Module):
    """Holds the spine at ``postures[k]`` (3n,) on tick k, and at the last entry after the list; an
    entry ``None`` lets go."""

    def __init__(self, postures: Sequence[np.ndarray | None], name: str = "hand"):
        super().__init__(name)
        self.postures = list(postures)
        self.k = 0

    def reset(self, snapshot: Snapshot) -> None:
        self.k = 0

    def update(self, snapshot: Snapshot):
        theta = self.postures[min(self.k, len(self.postures) - 1)]
        self.k += 1
        return None if theta is None else {"hand": theta}


class Schedule(Module):
    """Writes ``events[k]`` (channel → value) on tick k, nothing on the other ticks."""

    def __init__(self, events: Mapping[int, Mapping[str, np.ndarray]], name: str = "schedule"):
        super().__init__(name)
        self.events = dict(events)
        self.k = 0

    def reset(self, snapshot: Snapshot) -> None:
        self.k = 0

    def update(self, snapshot: Snapshot):
        values = self.events.get(self.k)
        self.k += 1
        return values
