"""The humanoid's MuJoCo models for export (``shintai model``, :mod:`shintai.sim.export`): HRP2-JSK standing
(App. A.2.1), the tricycle (App. A.1.1), HRP2-JSK seated on it with both hands on the handle (ch. 3),
Kenshiro's planar legs on the crank (§3.5.5), the V-BOARD scooter (App. A.1.2) and HRP2-JSK standing on it
(§6.2.1), the Ninebot One S2 unicycle (App. A.1.3) and HRP2-JSK standing on it (§7.3.3). The exported V-BOARD
has its actuators but not its firmware (Python, run before every physics step): in MuJoCo's own viewer its
wheels take torques from ``wheel_s_motor``. Likewise the Ninebot's firmware (Eqs. A.5–A.6) is Python: exported,
its ``ninebot_motor`` is a bare velocity servo."""

from shintai.humanoid.robots.hrp2 import build_hrp2
from shintai.humanoid.robots.kenshiro import build_kenshiro
from shintai.humanoid.tricycle.riding import build_riding
from shintai.humanoid.tricycle.vehicle import build_tricycle
from shintai.humanoid.unicycle.ride import build_ninebot_stand
from shintai.humanoid.unicycle.vehicle import build_ninebot
from shintai.humanoid.vboard.stand import build_vboard_stand
from shintai.humanoid.vboard.vehicle import build_vboard
from shintai.sim.export import model


@model("humanoid.hrp2", "HRP2-JSK-like humanoid standing on the floor (seed 000 App. A.2.1, Tables A.1/A.2)")
def hrp2():
    return build_hrp2()


@model("humanoid.tricycle", "the tricycle of seed 000 App. A.1.1: steered front wheel with cranks, two rear wheels")
def tricycle():
    return build_tricycle()


@model("humanoid.hrp2-tricycle", "HRP2-JSK seated on the tricycle, hands on the handle, soles on the pedals "
                                 "(humanoid.tricycle-pedaling, -steering, -slalom)")
def hrp2_tricycle():
    return build_riding()


@model("humanoid.kenshiro", "Kenshiro's planar legs on the tricycle crank (humanoid.kenshiro-pedaling, §3.5.5)")
def kenshiro():
    return build_kenshiro()


@model("humanoid.vboard", "the V-BOARD of seed 000 App. A.1.2: two boards pitching on one axle, each wheel "
                          "speed-servoed to its board's tilt (Eq. A.1) while its contact switch is on")
def vboard():
    return build_vboard()


@model("humanoid.hrp2-vboard", "HRP2-JSK standing on the V-BOARD, one sole on each board, mass centre over "
                               "the axle (§6.2.1, Fig. 6.1)")
def hrp2_vboard():
    return build_vboard_stand()


@model("humanoid.ninebot", "the Ninebot One S2 of seed 000 App. A.1.3 with its training wheels: one wheel "
                           "speed-servoed to k times the footboards' pitch moment (Eqs. A.5–A.9)")
def ninebot():
    return build_ninebot()


@model("humanoid.hrp2-ninebot", "HRP2-JSK standing on the Ninebot One S2's footboards (training wheels on), mass "
                                "centre over the axle (§7.3.3, Fig. 7.6)")
def hrp2_ninebot():
    return build_ninebot_stand()
