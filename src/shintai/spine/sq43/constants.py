"""The numbers of the SQ43 unit's modules — one place per constant (DESIGN.md), each with its
thesis section or the reason it was chosen; grouped by the module that uses them."""

from __future__ import annotations

import numpy as np

from shintai.core.constants import KGF_N
from shintai.spine.robots import RABBIT_SERVO


# --- experiments.sq43_design ---
# "開始後すぐに極小値に陥っている" (§3.2.3) has no number and Fig. 3.4 is not in the text: "right after starting" is
# taken as within 10 of the thesis's 0.5° steps, 5° of travel (declared before comparing; not fitted to a result)
STUCK_TRAVEL_DEG = 5.0

# --- experiments.sq43_levelling ---
UP, DOWN = (5.0, 6.0), (10.0, 11.0)  # the windows the settled roll is averaged over (board held up / down) [s]

# --- experiments.sq43_trot_ga ---
THESIS_SECONDS_PER_INDIVIDUAL = 30 * 60.0  # §5.6.2 '1 個体の数秒間の運動の解析に約 30 分程度'

# --- sq43.gaits ---
GENE_LO = np.array([2.0, 40.0, 208.0, 5.0, -30.0, -30.0])  # §5.6.2
GENE_HI = np.array([4.0, 80.0, 228.0, 25.0, 30.0, 30.0])  # §5.6.2
DUTY = 0.5  # §5.6.2
W_TWIST_MM_PER_DEG = 2.0  # ours (module docstring)
W_SWING = 0.5  # ours, mm of fitness per mm of swing height
RAMP_S = 0.5  # from standing into the gait's first pose (ours)
TROT_DURATION_S = 6.0  # "1 個体の数秒間の運動" (§5.6.2): several seconds; ours 6 s (2 cycles at 3 s)

# --- sq43.levelling ---
LF_LENGTH_RANGE_M = (0.15, 0.245)  # chosen: the left front leg's commanded length stays within its reach

# --- sq43.standup / experiments.sq43_standup ---
# The leg servos' torque limit for the stand-up (§3.2.4: "各脚のアクチュエータのトルクがそれほど大きくない"). The
# seed names no servo for SQ43 (§3.2.1–3.2.2 say only "サーボモジュール"); the only RC servo whose torque it prints
# is the Futaba S9204 (gear-modified) of Rabbit's spine and limbs, "サーボモジュールの最大トルク (12.6[kgf·cm])"
# (§3.5.1; the same type for the limbs, §3.5.2) — the lab's servo of the next robot, taken as SQ43's; not a
# datasheet value (none is in the seed or the stored sources). Fixed before the first run; the other SQ43 scenarios
# keep the body's chosen 1.0 N·m (SQ43BodySpec.servo_torque_nm).
SERVO_TORQUE_NM = RABBIT_SERVO.torque_kgf_cm * KGF_N / 100
