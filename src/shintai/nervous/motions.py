"""Motions a command queued, named by its ``@ID``, and waiting for them without a race.

A command may end with ``@ID``; when the motion it queued ends, the server sends ``done ID`` to the client
that sent it (``done ID cleared`` when a ``:clear`` flushed it, ``done ID stopped`` when its plugin stopped).
``wait ID`` replies when that motion has ended — at once if it already has. Why this cannot race (hrpsys's
``waitInterpolation`` could: it asked "is the interpolator idle?" and a command not yet applied looked
idle): every line of one connection is interpreted in order, between two sensor packets, so a motion is
registered before the next line is read; ``wait`` names the motion, not the interpolator's state; a finished
motion's status is kept (the last :data:`KEEP` per client), so a wait after the end still finds it.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable

from shintai.nervous.protocol import ProtocolError

KEEP = 4096  # chosen: finished ids remembered per client (a few minutes of 20 ms playback)
ENDINGS = ("done", "cleared", "stopped")


class Motion:
    """One queued motion: ``status`` goes ``queued`` → ``done`` | ``cleared`` | ``stopped``."""

    def __init__(self, owner, id: str | None):
        self.owner, self.id, self.status = owner, id, "queued"
        self._callbacks: list[Callable[[Motion], None]] = []

    @property
    def finished(self) -> bool:
        return self.status in ENDINGS

    def finish(self, how: str = "done") -> None:
        if self.finished:
            return
        if how not in ENDINGS:
            raise ValueError(f"a motion ends as one of {ENDINGS}, got {how!r}")
        self.status = how
        callbacks, self._callbacks = self._callbacks, []
        for cb in callbacks:
            cb(self)

    def discard(self) -> None:
        """The command that queued it failed: it ends, nobody is told."""
        self._callbacks.clear()
        self.finish("cleared")

    def when_finished(self, callback: Callable[[Motion], None]) -> None:
        if self.finished:
            callback(self)
        else:
            self._callbacks.append(callback)


class Motions:
    """The motions of every client, by id (anonymous motions are not kept)."""

    def __init__(self):
        self._by_owner: dict[object, OrderedDict[str, Motion]] = {}

    def new(self, owner, id: str | None) -> Motion:
        motion = Motion(owner, id)
        if id is None:
            return motion
        table = self._by_owner.setdefault(owner, OrderedDict())
        old = table.get(id)
        if old is not None and not old.finished:
            raise ProtocolError(f"id @{id} names a motion still under way (use another id, or wait {id})")
        table.pop(id, None)
        table[id] = motion
        while len(table) > KEEP:
            oldest = next(iter(table))
            if not table[oldest].finished:
                break
            table.popitem(last=False)
        return motion

    def get(self, owner, id: str) -> Motion:
        motion = self._by_owner.get(owner, {}).get(id)
        if motion is None:
            raise ProtocolError(f"no motion @{id} from this connection")
        return motion

    def pending(self, owner) -> list[Motion]:
        return [m for m in self._by_owner.get(owner, {}).values() if not m.finished]

    def forget(self, owner) -> None:
        """A client left: its motions play on but nobody hears of them."""
        self._by_owner.pop(owner, None)
