"""The gain-learning online search indices of seed 000 (chs. 5–6), shared by the units:

* :mod:`~shintai.humanoid.learning.slc` — SLC, Eqs. 5.4–5.19, and its schedule, the one writer of D (Fig. 5.4).
* :mod:`~shintai.humanoid.learning.mlc` — MLC, Eqs. 6.17–6.32 (mini-batch closed-loop learning of PID gains).
* :mod:`~shintai.humanoid.learning.prior_value_integrator` — the PID with the prior-value-correcting integrator (Eqs. 6.33–6.42).
* :mod:`~shintai.humanoid.learning.speed_governing` — the speed plants, Eq. 6.3's filter, identification, Routh–Hurwitz (§6.2.2, Eq. 6.41).
"""
