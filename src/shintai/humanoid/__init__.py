"""Seed 000 (Kimura 2018): a humanoid drives a tricycle and rides a two-wheeled scooter and a unicycle.

Shared layers:

* :mod:`~shintai.humanoid.constants` — every shared number, with its source (thesis or *chosen*).
* :mod:`~shintai.humanoid.law_params` — the range check every law's parameters go through.
* :mod:`~shintai.humanoid.corrections` — ch. 4's trajectory corrections (impedance, chest posture, obstacles).
* :mod:`~shintai.humanoid.robots` — HRP2-JSK, Kenshiro's legs, the HRP2 leg IK (App. A.2).
* :mod:`~shintai.humanoid.balance` — standing: ZMP preview, stabilizer, foot damping and attitude (ch. 5).
* :mod:`~shintai.humanoid.learning` — SLC, MLC, the prior-value integrator, the speed plant (chs. 5–6).

Units, one per vehicle, each importing only the shared layers:

* :mod:`~shintai.humanoid.tricycle` — the tricycle and riding it (chs. 3–4, App. A.1.1).
* :mod:`~shintai.humanoid.vboard` — the V-BOARD, boarding it and governing its speed (chs. 5–6, App. A.1.2).
* :mod:`~shintai.humanoid.unicycle` — the Ninebot One S2 and riding it (§7.3.3, App. A.1.3).

Across the units: :mod:`~shintai.humanoid.models` (the models for export), :mod:`~shintai.humanoid.coverage`
(the thesis's experiments, one row each), :mod:`~shintai.humanoid.benchmarks`; one file per scenario in
:mod:`~shintai.humanoid.experiments`, its account in ``notes/``. MjSpec helpers: :mod:`shintai.sim.spec`.
"""
