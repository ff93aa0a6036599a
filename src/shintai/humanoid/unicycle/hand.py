"""A human hand that catches the rider when the Ninebot rolls too far (seed 000 §7.3.3, Fig. 7.12 (a6)).

The thesis rode the Ninebot without training wheels only with a person's help: "手動により目標値を整形する操縦
インターフェース(式 7.6)や図 7.12 -(a6) のように人手による介助を割り込むことで走行行動を可能とした". Its hand is
not described; ours (chosen, the constants ``HAND_*``, declared before any run with it) is a person standing beside
the robot who stays off until the unicycle's roll φ passes ``HAND_CATCH_DEG``, then pushes the chest sideways
toward upright with a spring and damper on the roll, F = (K φ + C φ̇) horizontal, to the vehicle's left (positive
roll about the vehicle's x carries the chest to its right), at most ``HAND_MAX_N``, and lets go once |φ| is back below
``HAND_RELEASE_DEG``. It is a disturbance of the plant, not the robot's control: a ``before_physics`` hook that
owns ``qfrc_applied`` (the lift and the tap own ``xfrc_applied``'s waist and chest rows).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from shintai.humanoid.unicycle.constants import HAND_C, HAND_CATCH_DEG, HAND_K, HAND_MAX_N, HAND_RELEASE_DEG
from shintai.sim.body import MujocoBody


class HumanHand:
    """The catching hand (module docstring): call it before every physics step."""

    def __init__(self, body: MujocoBody, link: str = "chest", catch_deg: float = HAND_CATCH_DEG,
                 release_deg: float = HAND_RELEASE_DEG):
        if not 0.0 <= release_deg < catch_deg:
            raise ValueError(f"hand: need 0 <= release < catch, got {release_deg!r}, {catch_deg!r}")
        self.body = body
        m = body.model
        roll = body.id("joint", "ninebot_roll")
        self._q, self._v = m.jnt_qposadr[roll], m.jnt_dofadr[roll]
        self._link, self._frame = body.id("body", link), body.id("body", "ninebot")
        self.catch, self.release = math.radians(catch_deg), math.radians(release_deg)
        self.holding = False
        self.catches = 0  # times the hand took hold
        self.held_s = 0.0  # physics time spent holding
        self.peak_n = 0.0  # largest force applied
        self._force, self._zero = np.zeros(3), np.zeros(3)

    def force(self) -> np.ndarray:
        """The hand's force now (N, world), zero when it is off."""
        return self._force.copy()

    def __call__(self) -> None:
        d = self.body.data
        phi, rate = float(d.qpos[self._q]), float(d.qvel[self._v])
        if not self.holding and abs(phi) > self.catch:
            self.holding, self.catches = True, self.catches + 1
        elif self.holding and abs(phi) < self.release:
            self.holding = False
        d.qfrc_applied[:] = 0.0
        if not self.holding:
            self._force[:] = 0.0
            return
        push = float(np.clip(HAND_K * phi + HAND_C * rate, -HAND_MAX_N, HAND_MAX_N))
        ahead = d.xmat[self._frame].reshape(3, 3)[:2, 0]  # the vehicle's heading, horizontal
        self._force[:2] = push * np.array([-ahead[1], ahead[0]]) / np.linalg.norm(ahead)  # its left, horizontal
        mujoco.mj_applyFT(self.body.model, d, self._force, self._zero, d.xipos[self._link], self._link,
                          d.qfrc_applied)
        self.held_s += self.body.model.opt.timestep
        self.peak_n = max(self.peak_n, abs(push))
