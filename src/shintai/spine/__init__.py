"""Variable-flexibility spines of seed 003 (Mizuuchi 2001), ch. 3–4.

robots — the six robots as parameter sets (Cla, Rabbit, Kenta, SQ43, HanzouS, BeBe);
geometry — the geometric model of §4.3–4.5: rpy vertebra chain, eq. 4.25 muscle lengths, J_m,
τ = −J_mᵀT, tension distribution, K_j = J_mᵀK_mJ_m; actuators — DC motor + gear + pulley,
encoder, tension sensor (eq. 3.3), accelerometer posture (eq. 3.4); control — the L/T/S/LL laws
(eqs. 4.36–4.42) and the interference policy (§4.7) as a runtime Module; bodies — a quasi-static
body; bodies_mujoco — the MuJoCo body (spatial tendons through sites, reels, wrapping);
teaching — direct teaching and playback (§4.2); pictures; scenarios / benchmarks — registered
with shintai.scenarios.
"""
