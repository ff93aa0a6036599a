"""Variable-flexibility spines of seed 003 (Mizuuchi 2001), ch. 3–5: the shared layers, flat, and one folder per
robot (cla/, kenta/, sq43/, hanzous/, bebe/, mocap/, rabbit/), each importing only these layers.

actuators — DC motor + gear + pulley, encoder, tension sensor and accelerometer posture (§3.6–3.7, eqs. 3.3–3.6)
benchmarks — the spine's benchmarks (a control tick, the inverse model, SQ43's trot rollout)
bodies — the quasi-static spine body: muscles, discs, gravity and loads in equilibrium (§4.3–4.5)
bodies_mujoco — a muscle-driven spine as a MuJoCo body generated with MjSpec (§3.6, §4.4, §4.6–4.7)
control — the L/T/S/LL muscle laws (eqs. 4.36–4.42, Table 4.6) and the interference policy (§4.7) as a Module
coverage — the coverage rows of seed 003, chapters 3–5 and Appendix A
discs — hardening ring discs on a MuJoCo spine and the upright criterion that sizes them (§3.5.3, §3.6.1, §7.1.1)
ga_run — chapter 5's GA inside a scenario: shared parameters, the checkpointed run, the curve
geometry — the geometric model (§4.3–4.5): rpy vertebra chain, eq. 4.25 muscle lengths, J_m, statics
inverse_model — muscle length → posture, f of eq. 4.3, by NN or Jacobian integration (§4.4.3)
models — the spine robots' MuJoCo models for export (``shintai model``)
plots — shared pictures: the 3D spine, the inverse model's learning and errors, the tracking loops
posture_database — the posture database of §5.9.1–5.9.2 (Fig. 5.29), robot-independent
posture_person — the person of a posture-database session: pushes and commands as the Loop's first stage (§5.9)
posture_session — the robot's side of a posture-database session: teaching, replay, nearest node (§5.9)
robots — the six robots as parameter sets and the spine's constants, each with its thesis section
scripted — the experimenter as modules: a hand holding the spine, a schedule of commands (§4.2, §4.5.2, §4.7.2)
tactile — push teaching triggers felt through the muscles (§5.9.3)
teaching — encoder zeroing in LL mode (§4.6.4), direct teaching and playback (§4.2)
tracking_loops — visual tracking loops of different periods in one Loop (§5.2.10, §5.2.12) and their metrics

cla/ — Cla: the arms-only spine of E9–E11 and the whole-body Cla of chapter 5 (§3.4, §4.2–4.7, §5.2, §5.9)
kenta/ — Kenta: the 40-muscle, 10-joint spine with arms, neck and eyes (§3.7, §4.2, §5.2.11–5.2.12)
sq43/ — SQ43: the quadruped with a foam spine (§3.2, §5.6)
hanzous/ — HanzouS: the brachiating robot with a leaf-spring trunk (§3.3, §5.7)
bebe/ — BeBe: visual tracking with 36 on/off muscles and no geometric model (§4.8)
mocap/ — motion capture onto spined robots (§5.8, Fig. 5.28)
rabbit/ — Rabbit: the spine of silicone ring discs, quasi-static (§3.5)
experiments/ — one declared scenario per file; notes/ — their accounts.
"""
