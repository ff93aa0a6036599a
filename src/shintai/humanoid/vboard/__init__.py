"""HRP2-JSK boards and rides the V-BOARD two-wheeled scooter (seed 000 chs. 5–6, §7.4.2, App. A.1.2):

* :mod:`~shintai.humanoid.vboard.constants` — the unit's numbers with their sources (D on the board, excitation, start delay).
* :mod:`~shintai.humanoid.vboard.vehicle` — the V-BOARD as MjSpec and its firmware (Eqs. A.1–A.4).
* :mod:`~shintai.humanoid.vboard.stand` — HRP2 standing on it, one ``MujocoBody`` (§6.2.1).
* :mod:`~shintai.humanoid.vboard.boarding` — stepping onto it from the floor with SLC (§5.4).
* :mod:`~shintai.humanoid.vboard.ride` — riding it at behaviour levels 1–3 (§6.2.1, Fig. 6.6).
* :mod:`~shintai.humanoid.vboard.governor` — the speed governor: PID Eq. 6.2 with MLC (§6.3.4, Fig. 6.13).
* :mod:`~shintai.humanoid.vboard.plant_id` — identifying the speed plants on the ride (§6.2.2, Eqs. 6.4–6.16).
* :mod:`~shintai.humanoid.vboard.governed_ride` — the ride governed by MLC and its analysis (§6.4, Figs. 6.15–6.17).
* :mod:`~shintai.humanoid.vboard.solc` — SOLC, SLC then MLC on one switcher (§7.4.2, Table 7.7).
* :mod:`~shintai.humanoid.vboard.sign_chain` — issue 26's probe: each link's response to a common-mode foot-pitch step.
* :mod:`~shintai.humanoid.vboard.sole_creep` — issue 26 item 5's probe: the soles' creep on the pads turns level 2.
* :mod:`~shintai.humanoid.vboard.ankle_pivot` — issue 26's candidate (e): the commanded foot pitch as an ankle joint angle.
* :mod:`~shintai.humanoid.vboard.plots` — the V-BOARD scenarios' figures (Figs. 4.10, 5.6–5.8, 6.3–6.4, 6.9, 6.15–6.17, 7.19–7.21).
"""
