"""Cla (seed 003 §3.4, §4.2–4.7, §5.2, §5.9): the arms-only spine of E9–E11 and the whole-body Cla of chapter 5.

body — the whole-body MuJoCo Cla: the muscle spine with arms, neck, head and legs, seated or standing (§5.2)
constants — the Cla unit's numbers, per behaviour, each with its thesis section or why it was chosen
control — commanding the whole body's spine: encoder zeroing, then L mode with posture targets (§4.6.4)
cop — the arm-swing reflex keeping the centre of pressure centred while standing (§5.2.7)
crawl — Cla on hands and knees, and the crawl whose spine roll a GA evolves (§5.2.9, Figs. 5.10–5.11)
keyframes — hand-made behaviours as posture sequences (§5.2, §6.5)
levelling — shoulder levelling by the accelerometer on a tilting seat (§5.2.2, Fig. 5.2)
modes — E11: the muscle-mode combinations with arms raised, Table 4.8 (§4.7.2–4.7.3)
pick_place — seated pick-up from the floor and placing on the desk (§5.2.5–5.2.6, Fig. 5.7)
plots — Cla's pictures: E9–E11, the posture database session (§5.9) and the chapter-5 behaviours
posture_runs — a posture-database session on the MuJoCo Cla and its metrics (§5.9)
postures — E11's posture protocol: uniform-bend postures played to the muscle controller (§4.7.2, A.1.3)
pull — pulling an object on the desk by leaning with the spine (§5.2.4, Figs. 5.5–5.6)
reach — arm keys solved on Cla's geometric model (§5.2)
roll_over — rolling from back to front by yawing the spine with shoulders and hips (§5.2.8, Fig. 5.9)
setup — the set-up shared by E9–E11: zeroing calibration, S mode's spring law and k_s unit (§4.2, §4.5.2, §4.6.4)
spring_trial — E10's trial: every muscle in S mode, a hand bending the spine (§4.5.2, eq. 4.36, Figs. 4.13–4.17)
teach_runs — E9: direct teaching under tension control and playback in L mode (§4.2)
throw — the throw: spine, then shoulder, then elbow started (§5.2.3, Figs. 5.3–5.4)
tracking — Cla's neck and spine tracking loops on a head-camera target (§5.2.10, Fig. 5.12)
"""
