"""The robots of seed 000 (App. A.2), shared by the units:

* :mod:`~shintai.humanoid.robots.hrp2` — the HRP2-JSK-like 32-DoF humanoid as MjSpec (App. A.2.1, Table A.2).
* :mod:`~shintai.humanoid.robots.leg_ik` — HRP2's closed-form 6-DoF leg IK and FK.
* :mod:`~shintai.humanoid.robots.kenshiro` — Kenshiro's sagittal legs on the tricycle's crank (§3.5.5, App. A.2.2).
"""
