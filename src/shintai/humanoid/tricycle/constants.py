"""Constants of the tricycle unit (seed 000 chs. 3–4, §4.5): its frame, collision bits, limb and navigation
parameters, each with its source; the tricycle's own specification is :data:`shintai.humanoid.constants.TRICYCLE`
and the laws' gains are in :mod:`shintai.humanoid.constants`."""

# --- the numbers of experiments/obstacle_navigation.py ------------------------------------------------------------
NAV_GOAL = (8.0, 0.0)
EVERY = 25  # control ticks between the recorded samples (0.1 s)

# --- the numbers of experiments/odometry.py -----------------------------------------------------------------------
# The room (ours; the thesis's lab is not described): walls and two pillars the head's depth rays see
# while the tricycle turns right, all on the known map of the localisation.
GREY = (0.75, 0.75, 0.7, 1.0)

STEER_S = 2.5  # s: the handle is turned to θ_h before the crank moves (STEER_RATE 15°/s → 1.7 s), chosen
ODOMETRY_SETTLE_S = 1.5  # s: standing still after the stop before the run ends, chosen

# --- the numbers of experiments/outdoor_run.py --------------------------------------------------------------------
# §3.5.4: E6 12.8 m in 164 s, E7 27.5 m in ≈72 s; the seed states only 7.8×10⁻² m/s, the rest is derived by us
THESIS_SPEED_RATIO = (27.5 / 72.0) / (12.8 / 164.0)  # 4.89

# --- the numbers of tricycle/ch4_riding.py ------------------------------------------------------------------------
SEAT = 8  # collision bit: hip pad (contype) – saddle (conaffinity)
SOLE_BIT, WHEEL_BIT = 2, 4

# --- the numbers of tricycle/load_monitor.py ----------------------------------------------------------------------
# Fig. 7.16 compares the tilted state before the recovery with the state after it; the windows are ours,
# chosen before the runs: the 2 s before the recovery starts (T1 of Table 7.6), and 2 s from 1 s after it
# ends (T3, driving again; the first second is RESEAT's transient). The recovery starts at θ_c = kπ and holds
# the crank, so both windows see the crank near the same phase.
BEFORE_S, SETTLE_S, AFTER_S = 2.0, 1.0, 2.0

# --- the numbers of tricycle/navigation.py ------------------------------------------------------------------------
OBSTACLE_GROUP = 3  # MuJoCo geom group of environment obstacles (walls, steps, boards)

# --- the numbers of tricycle/vehicle.py ---------------------------------------------------------------------------
FRAME = [0.75, 0.12, 0.12, 1]
DARK = [0.12, 0.12, 0.13, 1]
METAL = [0.6, 0.6, 0.62, 1]
