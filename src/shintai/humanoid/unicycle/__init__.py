"""HRP2-JSK rides the Ninebot One S2 unicycle (seed 000 §7.3.3, App. A.1.3):

* :mod:`~shintai.humanoid.unicycle.constants` — the unit's numbers with their sources (C_traj's, the scenarios' thresholds).
* :mod:`~shintai.humanoid.unicycle.vehicle` — the Ninebot as MjSpec and its firmware (Eqs. A.5–A.9).
* :mod:`~shintai.humanoid.unicycle.ride` — HRP2 on it with the stack, C_traj and C_v in parallel (Eqs. 7.1–7.6).
* :mod:`~shintai.humanoid.unicycle.hand` — the person of Fig. 7.12 (a6) who catches the unicycle's roll.
* :mod:`~shintai.humanoid.unicycle.rig` — the ``humanoid.unicycle-*`` scenarios' rig and metrics.
* :mod:`~shintai.humanoid.unicycle.plots` — their figures (Figs. 7.7–7.12).
"""
