"""Shared runtime pieces: Body/Module/Loop/Switcher, the recorder, the online search index, interpolation."""

from shintai.core.recorder import Recorder
from shintai.core.runtime import (ADD, SET, Body, Channel, ChannelError, Loop, Module, SimulationDiverged,
                                  Switcher, declare)

__all__ = ["ADD", "SET", "Body", "Channel", "ChannelError", "Loop", "Module", "Recorder", "SimulationDiverged",
           "Switcher", "declare"]
