"""Constants of the unicycle unit (seed 000 §7.3.3), each with its source; the Ninebot's own specification
(App. A.1.3) is :data:`shintai.humanoid.unicycle.vehicle.NINEBOT`."""

T_TRAJ = 0.05  # s, Eq. 7.3's LPF time constant T_traj: not given; chosen: a 50 ms smoothing of a 4 ms difference
# η for K^traj: not given (Table 7.4 gives A = 1 for the trajectory only). Chosen: a 0.1 m/s error held over one
# batch moves K_P^traj by ≈1e-3 (gradient ≈ 2 K_traj ⟨e ∫e⟩ ≈ 50), the order of the P gain that makes the
# loop K_traj K_P/(s(1+T s)) critically damped (1/(4 T K_traj) = 4e-3)
ETA_TRAJ = (2e-5, 2e-5, 2e-5)
START_DELAY = 0.0  # s after the lift's release; the thesis's 0–2 s are its first (unlearned) batch
JOY_FULL = 0.05  # rad of vehicle roll at full stick (chosen, the operator model of RollShaping)
PLACEMENTS = ("after_lip", "reference")
VIEW = {"track": "waist", "azimuth": 60.0, "elevation": -10.0, "distance": 3.5}
V_DIVERGED = 0.3  # m/s, the brief's threshold for speed_diverged / the time to |v| > 0.3 m/s
TAIL_S = 2.0  # s, "final" values are means over the last 2 s (one mini-batch)
V_SETTLED = 0.01  # m/s, chosen: "settled" = |v| below 1 cm/s from then to the end of the run (Fig. 7.9 (d)'s ≈18 s)
# Our V-BOARD's learned (K_P^v, K_D^v), the thesis's comparison (§7.3.3: against Figs. 6.15 (b1) and 6.16 (b1)):
# humanoid.speed-governing at its defaults on main, 2026-12-05 (variant `learn` = Fig. 6.15; README's reproduction
# table carries the run), after the soles stopped creeping on the pads (issue 26 item 5). Fig. 6.16's runs learn none:
# both fall before MLC's first update (`boarding` 0.71 s, `boarding_slc` 1.08 s after the start). Measured, not chosen
# — re-measure when that scenario changes.
VBOARD_V_KP_KD = {"fig6.15": (1.11e-3, 1.12e-3)}
# p⁰ of the scenarios: the firmware's moment zero point 10 mm ahead of the axle, over which the rider's mass centre
# is placed (chosen: the thesis says the boards-to-wheel relation is unknown to the rider, §7.3.3; with p⁰ exactly
# under the rider's mass centre the only error left is the stack's own ≈1 mm, see the notes)
P0_M = 0.01

# --- the numbers of experiments/unicycle_free.py ------------------------------------------------------------------
V_STEP = 0.3  # m/s, the thesis's step 'v^d = 0.3[m/s]のステップ指令'
# the gains ``humanoid.unicycle-learning`` learned at its defaults, variant reference (the as-written variant's
# run away; notes): (K_P, K_I, K_D) of C_traj and of C_v — measured, copied here; re-measure when that scenario changes
LEARNED_TRAJ = (9.05e-5, 3.93e-4, 2.47e-5)
LEARNED_V = (2.86e-7, 1.20e-6, 6.63e-8)
TAP_N, TAP_AT_S = 10.0, 2.0  # N sideways on the chest for 0.1 s at this body time, ≈1 s after the lift lets go
# (chosen: the world's asymmetry; a perfectly symmetric simulation balances a unicycle on its tyre's crown for ever)

# --- the numbers of unicycle/hand.py (the human hand of Fig. 7.12 (a6); the thesis describes none: all chosen,
# declared before any run with the hand, issue 26 item 6) -------------------------------------------------------------
HAND_CATCH_DEG = 5.0  # the person takes hold once the unicycle's roll passes 5° (a lean plainly visible)
HAND_RELEASE_DEG = 1.0  # and lets go when it is back within 1°
# Gravity topples rider + Ninebot (67.5 kg, mass centre 0.83 m up) with ≈552 N·m/rad about the tyre's contact; a
# push at the chest (1.27 m up) of K φ rights it for K > 435 N/rad. K = 1000 N/rad nets ≈718 N·m/rad; C = 300 N·s/rad
# at the chest (≈380 N·m·s/rad about the contact) is about critical for the ≈47 kg·m² roll inertia (measured on
# the model, build_ninebot_stand; tests/humanoid/unicycle/test_hand.py)
HAND_K = 1000.0  # N/rad
HAND_C = 300.0  # N·s/rad
HAND_MAX_N = 150.0  # N, a person's one-handed push (chosen)

# --- the numbers of unicycle/vehicle.py ---------------------------------------------------------------------------
SHELL = [0.95, 0.95, 0.97, 1]
RUBBER = [0.1, 0.1, 0.11, 1]
TYRE = [0.15, 0.15, 0.16, 1]
METAL = [0.6, 0.6, 0.62, 1]
