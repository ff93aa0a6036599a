"""The commanded foot pitch as an ankle joint angle (issue 26's candidate (e); an option, off by default).

Seed 000 §6.2.2 sends the humanoid "足部の Pitch 傾斜角 θ_R, θ_L の変位量 Δθ_R, Δθ_L" (Eq. 6.5) and does not say where
they enter. hrpsys's boarding posture is a whole-body joint-angle command (§6.2.1: "搭乗姿勢の全身の関節角度をロボット
実機へ指令する"); read as a change of the ankle pitch joint in that command, Δθ turns the reference foot about the
*ankle* (the body keeps its posture above the ankle and the sole swings back under it), where
:class:`~shintai.humanoid.balance.scooter.FootPitch` on the default IK turns it about the sole point. With hrpsys's
ankle foot origin (``StabilizerModule(foot_origin="ankle", ref_ankle_pitch=θ0)``) the reference ankles then stay where
the boarding posture put them, so the CoM and ZMP references, held relative to the ankles, move forward with the
actual ankles when the boards pitch toes-down. ``VboardRide(foot_pitch_about="ankle")`` wires both."""

from __future__ import annotations

import math

import numpy as np

from shintai.humanoid.balance.standing import LegIKModule
from shintai.humanoid.constants import HRP2_LINKS


def pivot_soles(sole_ref, pitch, pitch0, h: float = HRP2_LINKS.ankle_height) -> np.ndarray:
    """The sole targets (left, right rows) of feet turned from ``pitch0`` to ``pitch`` (each (R, L), rad) about their
    ankles: the ankle p_s + R_y(θ0)(0, 0, h) kept, the sole at ankle − R_y(θ)(0, 0, h)."""
    soles = np.array(sole_ref, float)
    for row, k in ((0, 1), (1, 0)):  # sole_ref rows are (left, right); the pitches (R, L)
        th, th0 = float(pitch[k]), float(pitch0[k])
        soles[row, 0] += h * (math.sin(th0) - math.sin(th))
        soles[row, 2] += h * (math.cos(th0) - math.cos(th))
    return soles


class AnklePivotIK(LegIKModule):
    """The leg IK with the commanded pitch ``foot_pitch_ref`` (R, L) turning each foot about its ankle from the
    boarding posture's pitch ``pitch0`` (module docstring); the damping's δ still turns it about the sole point (as
    hrpsys's damping turns the end-effector's target attitude)."""

    def __init__(self, *args, pitch0=(0.0, 0.0), **kw):
        super().__init__(*args, **kw)
        self.pitch0 = tuple(float(p) for p in pitch0)

    def update(self, snapshot):
        ref = snapshot.get("foot_pitch_ref")
        if ref is None:
            return super().update(snapshot)
        snapshot = dict(snapshot)  # the stage's view, with the pivoted sole targets (as unicycle.ride's ZMP shift)
        snapshot["sole_ref"] = pivot_soles(snapshot["sole_ref"], ref, self.pitch0)
        return super().update(snapshot)
