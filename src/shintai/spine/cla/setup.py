"""Cla's experimental set-up shared by E9–E11 (seed 003 §4.2, §4.5.2, §4.6.4, §4.7): the zeroing
calibration, S mode's spring law and k_s unit, the LL/T tensions, and the camera that films Cla.
"""

from __future__ import annotations

import numpy as np

from shintai.core.constants import KGF_N
from shintai.spine.actuators import TensionSensor
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.control import CountSpring, Gains, MuscleControl
from shintai.spine.robots import CALIBRATION_KGF, CLA, K_S_UNIT_N_M
from shintai.spine.teaching import zero_encoders

SPRING_LAWS = ("counts", "newtons")  # S mode's spring: on the ADC count as in §4.5.2, or linear in N
# The camera of --video: on the pelvis, from the side-front (each experiment picks its azimuth)
CLA_VIEW = {"fps": 30, "width": 480, "height": 360, "track": "link0", "distance": 0.75, "azimuth": 150.0,
            "elevation": -10}


def calibrated(body: SpineBody, control: MuscleControl) -> np.ndarray:
    """§4.6.4's encoder zeroing at the "just taut" limit (the hand holds the basic posture until the
    next loop lets go); returns the tensions the muscles settled at."""
    return zero_encoders(body, control, CALIBRATION_KGF * KGF_N)


def cla_gains(T_l_kgf: float, T_r_kgf: float) -> Gains:
    """The default gains with the LL limit T_l and the T-mode target T_r given in kgf."""
    return Gains(T_l=T_l_kgf * KGF_N, T_r=T_r_kgf * KGF_N)


def cla_spring(law: str) -> CountSpring | None:
    """S mode's spring law (see :mod:`shintai.spine.control`). "counts": eq. 4.36 on the ADC count
    the controller reads, k_s in counts per encoder pulse (§4.5.2), through Cla's sensor (§3.6.1)
    and encoder (Table 3.2). Its firmware scale is not in the text; chosen (before any run with
    it) so that, linearised at the spring's rest point (l = l_0, T_r = 0), it is as stiff as the
    newton law's :data:`~shintai.spine.robots.K_S_UNIT_N_M` (a scale of 61.6). It hardens with
    tension as the sensor saturates (×2.9 by 20 N, ×21 by 100 N). "newtons": None, the law linear
    in newtons, k_s × K_S_UNIT_N_M N/m."""
    if law not in SPRING_LAWS:
        raise ValueError(f"unknown spring law {law!r}; valid: {', '.join(SPRING_LAWS)}")
    if law == "newtons":
        return None
    return CountSpring.matching(TensionSensor(CLA.sensor), CLA.motors[0].encoder_step_m, K_S_UNIT_N_M)


def k_s_gain(k_s_units: float, law: str) -> float:
    """A thesis k_s (counts / pulse) as the controller's gain for ``law``: itself, or N/m."""
    return k_s_units * K_S_UNIT_N_M if law == "newtons" else k_s_units
