"""The MuJoCo models of ``shintai.sim`` for export (:mod:`shintai.sim.export`)."""

from shintai.sim.corner import CORNER_XML
from shintai.sim.export import model


@model("sim.wall-corner", "a hand on three servoed slide axes in a wall corner (sim.wall-force, seed 000 §2.4.1)")
def wall_corner():
    return CORNER_XML
