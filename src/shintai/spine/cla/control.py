"""Commanding the whole-body Cla's spine (:mod:`~shintai.spine.cla.body`) as every Cla experiment does: the §4.6.4
encoder zeroing, then :class:`~shintai.spine.control.MuscleControl` in L mode (:func:`spine_control`), and the
stages with the posture player between a schedule and the controller (:func:`spine_stages`, :data:`CHANNELS`).
"""

from __future__ import annotations

import numpy as np

from shintai.core.constants import KGF_N
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.cla.setup import cla_gains
from shintai.spine.control import SETPOINTS, Mode, MuscleControl
from shintai.spine.cla.postures import GOAL, WHOLE_REF, PostureTargets
from shintai.spine.robots import CALIBRATION_KGF, CLA
from shintai.spine.teaching import zero_encoders


def spine_control(body: SpineBody, T_l_kgf: float = 2.0, T_r_kgf: float = 1.0,
                  calibration_s: float = 1.0) -> tuple[MuscleControl, np.ndarray]:
    """Cla's muscle controller, calibrated (§4.6.4, :func:`~shintai.spine.cla.setup.calibrated`) and in L mode:
    returns it and the model lengths at the basic posture (the zero of the encoder targets) for
    :class:`~shintai.spine.cla.postures.PostureTargets`. The stages of a Loop are then
    ``[[your schedule writing "goal"], [PostureTargets(CLA.model, zero, move_s)], [control, ...]]`` with the
    channels ``(*control.SETPOINTS, postures.GOAL, postures.WHOLE_REF)``."""
    control = MuscleControl(CLA.m, cla_gains(T_l_kgf, T_r_kgf))
    zero_encoders(body, control, CALIBRATION_KGF * KGF_N, seconds=calibration_s)  # = cla.calibrated, timed
    control.set_modes(Mode.L)
    return control, CLA.model.lengths(np.zeros(3 * CLA.n))


CHANNELS = (*SETPOINTS, GOAL, WHOLE_REF)  # the loop channels of :func:`spine_stages`


def spine_stages(control: MuscleControl, zero, move_s: float, first=(), last=()) -> list[list]:
    """The stages of a Cla run: ``first`` (modules writing ``goal`` and limb targets), then the posture player
    (``move_s`` per goal), then the muscle controller with ``last`` (observers); channels :data:`CHANNELS`."""
    return [list(first), [PostureTargets(CLA.model, zero, move_s)], [control, *last]]
