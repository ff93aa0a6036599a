"""Shared runtime pieces: Body/Module/Loop/Switcher, the recorder, the online search index, interpolation."""

from shintai.core.recorder import Recorder
from shintai.core.runtime import Body, Loop, Module, SimulationDiverged, Switcher

__all__ = ["Body", "Loop", "Module", "Recorder", "SimulationDiverged", "Switcher"]
