"""Kenta (seed 003 §3.7, §4.2, §4.4.3, §5.2.11–5.2.12): the 40-muscle, 10-joint spine with arms, neck and eyes.

body — Kenta's whole body in MuJoCo, and its §4.6.4 encoder zeroing (§3.7, Figs. 3.39–3.52)
constants — Kenta's numbers: the teacher's hands, the stops, the taught postures, the NN's grid (§3.7, §4.2, §4.4.3)
plots — Kenta's pictures: the taught postures replayed (Fig. 4.1), spine, neck and arms at once (Fig. 5.13)
postures — three taught postures replayed in turn (§4.2.1–4.2.2, Fig. 4.1)
spine_neck_arms — spine (forward model, L mode), neck and both arms moving at once (§5.2.11, Fig. 5.13)
statics — why the spine does not hold a posture with its muscle lengths fixed (§3.7.2, §3.6.1)
tracking — eyes, neck and spine tracking loops while both arms swing, the spine's posture by Kenta's NN (§5.2.12, Fig. 5.14)
"""
