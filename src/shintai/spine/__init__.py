"""Variable-flexibility spines of seed 003 (Mizuuchi 2001), ch. 3–4.

robots — the six robots as parameter sets, and the experiments' constants; geometry — the geometric
model of §4.3–4.5: rpy vertebra chain, eq. 4.25 muscle lengths, J_m, τ = −J_mᵀT, tension distribution,
K_j = J_mᵀK_mJ_m; actuators — DC motor + gear + pulley, encoder, tension sensor (eq. 3.3), accelerometer
posture (eq. 3.4); control — the L/T/S/LL laws (eqs. 4.36–4.42) and the interference policy (§4.7) as
a runtime Module fed by set-point channels; bodies — a quasi-static body; bodies_mujoco — the MuJoCo
body (spatial tendons through sites, reels, wrapping, a hand channel); scripted — the experimenter's
hand and command schedule as modules; teaching — zeroing, direct teaching and playback (§4.2);
cla — Cla's set-up shared by E9–E11; teach_runs (E9), spring_trial (E10), postures and modes (E11),
rabbit (E6) — the experiments' runs; inverse_model (§4.4.3), bebe and bebe_runs (§4.8), sq43 (§3.2.3);
sq43_body (the whole-body MuJoCo SQ43, §3.2.2) and sq43_gaits (its levelling, crawl and GA trot, §3.2.4, §5.6);
ga_run (chapter 5's GA in a scenario);
pictures, pictures_learning — plots; experiments/ — one declared scenario per file, notes/ — their
accounts; benchmarks.
"""
