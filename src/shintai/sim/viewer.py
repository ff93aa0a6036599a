"""A live view of a running MujocoBody in MuJoCo's own viewer (``shintai run ID --view``).

The viewer runs passively beside the simulation: after every body step it shows the new state, paced to
real time (a run that simulates faster waits; one that is slower shows what it can). Closing the window
stops the viewing, not the run. It needs a display; :func:`display_available` says whether there is one.
"""

from __future__ import annotations

import os
import threading
import time

from shintai.sim.body import MujocoBody


def display_available() -> bool:
    """Whether a window can be opened (an X or Wayland display is set)."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


class LiveViewer:
    """MuJoCo's passive viewer following ``body`` (attach as a context manager around a run)."""

    def __init__(self, body: MujocoBody, title: str = "shintai", realtime: bool = True):
        import mujoco.viewer

        if not display_available():
            raise RuntimeError("no display to show the viewer on (DISPLAY is not set)")
        self.body, self.title, self.realtime = body, title, realtime
        self._threads = set(threading.enumerate())
        self.handle = mujoco.viewer.launch_passive(body.model, body.data)
        self._wall0, self._sim0 = time.perf_counter(), body.t
        body.after_step.append(self.show)

    def show(self) -> None:
        """Show the current state (called after every body step), waiting to keep to real time."""
        if not self.handle.is_running():
            return
        if self.realtime:
            ahead = (self.body.t - self._sim0) - (time.perf_counter() - self._wall0)
            if ahead > 0:
                time.sleep(ahead)
        self.handle.sync()

    def close(self) -> None:
        """Stop following the body and close the window (waiting for the viewer's thread: leaving it to the
        interpreter's exit crashes GLFW)."""
        if self.show in self.body.after_step:
            self.body.after_step.remove(self.show)
        self.handle.close()
        for thread in set(threading.enumerate()) - self._threads:
            thread.join(timeout=5.0)

    def __enter__(self) -> LiveViewer:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
