"""The quadruped's MuJoCo models for export (``shintai model``, :mod:`shintai.sim.export`): the kinematic
TITAN-VIII of the videos (``video.titan_mjcf``; contacts off, nothing simulated) in the thesis's scenes."""

from shintai.quadruped import video as QV
from shintai.quadruped import world as W
from shintai.sim.export import model


@model("quadruped.s4.2.1", "TITAN-VIII in seed 004 §4.2.1's scene: right wall, left 0.12 m obstacle, goal circle "
                           "(quadruped.avoid-known)")
def scene_421():
    return QV.titan_mjcf(W.scenario_421())


@model("quadruped.s4.2.2", "TITAN-VIII in seed 004 §4.2.2's scene: left wall, right 0.07 m obstacle, goal circle "
                           "(quadruped.avoid-unseen)")
def scene_422():
    return QV.titan_mjcf(W.scenario_422())


@model("quadruped.s5.2", "TITAN-VIII in seed 004 §5.2's (and §6.2.2's) scene: right 0.12 m obstacle, left wall "
                         "(quadruped.swing-order, quadruped.free-gait)")
def scene_52():
    return QV.titan_mjcf(W.scenario_52())
