"""Shared runtime pieces: Body/Module/Loop/Switcher, the recorder, the online search index, interpolation.

Modules:

benchmarks — Benchmark of the runtime: what the Loop costs per module tick over calling the modules by hand
constants — Physical constants shared by every body (one place each)
experiments/ — one declared scenario per file (accounts in notes/)
geometry — Small geometry every body uses, in one place: elementary rotations, the cross-product matrix, angle …
integrators — Fixed-step integrators shared by the kinematic models (one place each)
linear_plant — A quasi-static linear plant x = G ρ + c for the online search index (seed 000 §2.5, spec §2.5 …
plots — The figures of the core experiments (``core.minjerk``, ``core.search-index``), drawn with ``ctx.figure``
search_index — The online search index of seed 000 ch. 2 (spec 000-part1-ch1-3.md §2.1–2.5)
"""

from shintai.core.recorder import Recorder
from shintai.core.runtime import (ADD, SET, Body, Channel, ChannelError, Loop, Module, SimulationDiverged,
                                  Switcher, declare)

__all__ = ["ADD", "SET", "Body", "Channel", "ChannelError", "Loop", "Module", "Recorder", "SimulationDiverged",
           "Switcher", "declare"]
