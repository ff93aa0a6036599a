"""The numbers of the HanzouS unit's modules — one place per constant (DESIGN.md), each with its
thesis section or the reason it was chosen; grouped by the module that uses them."""

from __future__ import annotations

import numpy as np


# --- experiments.hanzous_ga ---
GENERATIONS = 3  # short default; the thesis prints no generation count (§5.7.3): --set generations=N

# --- hanzous.body ---
BAR_Z = 1.0  # m, chosen (only the relative heights matter)
N_BARS = 3  # bar 0 (start), bar 1 (the next one), bar 2 (beyond, for the picture)
GRIPPER_OPEN_RAD = 1.0  # the gripper joint's open end; 0 is closed (chosen)

# --- hanzous.brachiation ---
DURATIONS_S = np.array([0.6, 0.45, 0.3, 0.25, 0.2, 0.2, 0.5])  # transitions 1→2 … 7→8, designed
IMPACT_S = 0.3  # the window after the grasp whose peak trunk-root force is the grasp's impact (ours)
HOLD_S = 0.6  # after posture 8: the window in which the grasp must hold (ours)
CONTROL_S = 0.005  # servo and grasp update period (ours; an RC servo's PWM frame is 20 ms)
JOINT_GENE_RAD = 0.4  # ± adjustment of each posture joint (ours)
TIME_GENE = 0.5  # ± fraction of each transition's time step (ours)
