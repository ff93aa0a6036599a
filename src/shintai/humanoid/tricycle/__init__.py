"""HRP2-JSK (and Kenshiro) drive the tricycle (seed 000 chs. 3–4, §7.3–7.4, App. A.1.1):

* :mod:`~shintai.humanoid.tricycle.constants` — the unit's own numbers (colours, collision bits, windows), each with its source.
* :mod:`~shintai.humanoid.tricycle.vehicle` — the tricycle as MjSpec (App. A.1.1).
* :mod:`~shintai.humanoid.tricycle.riding` — HRP2 seated on it with both hands on the handle, one ``MujocoBody`` (ch. 3).
* :mod:`~shintai.humanoid.tricycle.hrp2_limbs` — HRP2's hands and feet as the laws' limbs, on the leg IK.
* :mod:`~shintai.humanoid.tricycle.active` — the active function, Eqs. 3.2–3.12 (trajectories from the offline index).
* :mod:`~shintai.humanoid.tricycle.passive` — the passive function, Eqs. 3.13–3.18 (active impedance, online index).
* :mod:`~shintai.humanoid.tricycle.switching` — switching the indices between two manipulators, Eq. 3.19.
* :mod:`~shintai.humanoid.tricycle.operation` — the operation algorithm as runtime modules (Fig. 3.16, Eq. 3.20).
* :mod:`~shintai.humanoid.tricycle.rig` — HRP2 on the tricycle wired to the operation algorithm (§3.4–3.5).
* :mod:`~shintai.humanoid.tricycle.ride` — steering and pedalling together (§3.5.2, §3.5.4).
* :mod:`~shintai.humanoid.tricycle.kenshiro` — Kenshiro's pedalling, Eqs. 3.21–3.26 (§3.5.5).
* :mod:`~shintai.humanoid.tricycle.ch4_riding` — the seated HRP2 of ch. 4 with a hip–saddle contact (§4.3–4.4).
* :mod:`~shintai.humanoid.tricycle.ch4_drive` — the ch. 4 drives, navigator and corrections' rig pieces (§4.3–4.4, §7.3–7.4).
* :mod:`~shintai.humanoid.tricycle.navigation` — depth sensor, costmap, dynamic-window navigation (§4.4.2, §7.3.2).
* :mod:`~shintai.humanoid.tricycle.localisation` — wheel and visual odometry, self-localisation (§7.3.2).
* :mod:`~shintai.humanoid.tricycle.load_monitor` — the seated robot's load monitor (§4.3.1, §7.4.1).
* :mod:`~shintai.humanoid.tricycle.plots` — the tricycle scenarios' figures (Figs. 3.17–3.35, 4.19–4.22, 7.2, 7.15).
"""
