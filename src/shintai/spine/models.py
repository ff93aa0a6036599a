"""The spine robots' MuJoCo models for export (``shintai model``, :mod:`shintai.sim.export`). Rabbit has none:
its ring discs are modelled quasi-statically (:mod:`shintai.spine.bodies`)."""

from shintai.sim.export import model
from shintai.spine.bodies_mujoco import build_spec
from shintai.spine.hanzous_body import build_spec as build_hanzous
from shintai.spine.robots import CLA, KENTA


@model("spine.cla", "Cla's muscle spine: five vertebrae, eight wire muscles on reels, raised arms (seed 003 §3.6)")
def cla():
    return build_spec(CLA)


@model("spine.kenta", "Kenta's spine: ten joints and forty muscles, ligaments included (seed 003 §3.7)")
def kenta():
    return build_spec(KENTA)


@model("spine.hanzous", "HanzouS: 18 servoed joints, a cam-set leaf-spring trunk, hanging from bar 0 of three "
       "(seed 003 §3.3, §5.7)")
def hanzous():
    return build_hanzous()
