"""BeBe (seed 003 §4.8): visual tracking with 36 on/off muscles and no geometric model.

body — the BeBe plant and the sensor-based tracking rule (§4.8.3)
constants — BeBe's numbers: the pushed region, the cooperating spans (§4.8.3, Fig. 4.55)
plots — BeBe's pictures: view shifts, tracking and disturbances (cf. Figs. 4.53, 4.55, 4.56)
runs — the §4.8.3–4.8.4 experiments: single-muscle calibration, superposition, hysteresis, tracking, pushes
"""
