"""Seed 004: the TITAN-VIII quadruped that learns obstacle avoidance and its swing order with Gaussian
RBF networks trained by a genetic algorithm (Yamaguchi), as a kinematic, quasi-static simulation.

* ``constants``   every number, with its source or the reason it was chosen;
* ``robot``       leg kinematics (eqs. 1-2), static stability, the crawl-gait executor, body-raise rule;
* ``world``       floor and prism obstacles, the 96 training environments, named and held-out scenes;
* ``swing_order`` Table 2 and the exhaustive-search teacher;
* ``networks``    the action (24-100-3) and swing-order (4-h-24) RBF networks over flat genomes;
* ``episode``     perception, network inputs and the batched walking-cycle loop;
* ``fitness``     GA fitness functions, eqs. (9)-(12) and (13)-(15);
* ``replay``      the paper's action tables replayed (dead reckoning, executor, Br comparison);
* ``training``    the GA training of both networks (seed §4.1.2, §5.1, §6.1) and the trained weights
  (``trained/*.npz``, made by ``shintai run quadruped.train``);
* ``walks``       one recorded walk's outcome, its per-cycle table (Tables 3-7), outcome rates;
* ``ablation``    sensed-feature walks and their comparison with the known features;
* ``plots``       path, leg-height and learning-curve figures;
* ``video``       a kinematically driven TITAN-VIII MJCF rendered to MP4;
* ``experiments/`` one file per scenario (``quadruped.replay``, ``.train``, ``.avoid-known``,
  ``.avoid-unseen``, ``.swing-order``, ``.free-gait``, ``.generalization``, ``.sensing-ablation``),
  their accounts in ``notes/``;
* ``benchmarks``  one GA generation: naive serial vs vectorised vs process pool.

Modules:

br_rules — Candidate rules for the body movement Br of seed 004 Tables 3-5 (§5.1-5.2; Br is not defined there)
coverage — The experiments of seed 004 (Yamaguchi, TITAN-VIII learning obstacle avoidance and its swing order …
models — The quadruped's MuJoCo models for export (``shintai model``, :mod:`shintai.sim.export`): the …
sensing — The ultrasonic sensing of the real TITAN-VIII (§1.4; seed §3.1-3.3, eqs. 3-6, Figs. 6-9), for a …
"""
