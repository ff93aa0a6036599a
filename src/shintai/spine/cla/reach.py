"""Arm keys computed on Cla's geometric model, as the thesis's behaviours were ("人が動作パターンを EusLisp のモデル
上で作成し", §5.2.9): for a whole-spine posture Θ (a uniform bend, eq. 4.29) and a hand target, the arm's
shoulder roll, shoulder pitch and elbow that bring the hand's centre closest to it (bounded least squares on the
MuJoCo model's kinematics, the wrist kept straight). With the spine locked the same target is solved with the
spine straight: the best the arm alone can do.
"""

from __future__ import annotations

import mujoco
import numpy as np
from scipy.optimize import least_squares

from shintai.spine.geometry import uniform_posture

ARM = ("shoulder_roll", "shoulder_pitch", "elbow")


class ArmIK:
    """Kinematics of ``model`` (a whole-body Cla) on a scratch MjData; the pelvis where ``data`` has it."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, spine_joints, n_joints: int):
        self.m = model
        self.d = mujoco.MjData(model)
        self.d.qpos[:] = data.qpos
        self.spine_q = model.jnt_qposadr[[model.joint(j).id for j in spine_joints]]
        self.spine_names = tuple(spine_joints)
        self.n = n_joints

    def _set_spine(self, whole) -> None:
        # θ in eq. 4.1 order (roll, pitch, yaw per joint) → the model's hinges (named j<i>_<axis>)
        theta = uniform_posture(np.asarray(whole, dtype=float), self.n).reshape(self.n, 3)
        for name, adr in zip(self.spine_names, self.spine_q):
            i, axis = int(name[1:name.index("_")]) - 1, name.split("_")[1]
            self.d.qpos[adr] = theta[i, ("roll", "pitch", "yaw").index(axis)]

    def hand(self, side: str, whole, arm: dict[str, float]) -> np.ndarray:
        """The hand's centre for spine posture ``whole`` and arm angles ``arm`` (joint → rad)."""
        self._set_spine(whole)
        for name, value in arm.items():
            self.d.qpos[self.m.jnt_qposadr[self.m.joint(name).id]] = value
        mujoco.mj_kinematics(self.m, self.d)
        return self.d.site_xpos[self.m.site(f"hand_{side}").id].copy()

    def solve(self, side: str, whole, target, guess: dict[str, float] | None = None) -> tuple[dict, float]:
        """The arm angles (``shoulder_roll_<s>``, ``shoulder_pitch_<s>``, ``elbow_<s>``, ``wrist_<s>`` = 0) that
        bring hand ``side`` closest to ``target`` with the spine at ``whole``, and the distance left [m]."""
        names = [f"{j}_{side}" for j in ARM]
        ids = [self.m.joint(n).id for n in names]
        lo, hi = self.m.jnt_range[ids, 0], self.m.jnt_range[ids, 1]
        x0 = np.clip([0.3, 0.5, 0.5] if guess is None else [guess.get(n, 0.3) for n in names], lo + 1e-6, hi - 1e-6)
        target = np.asarray(target, dtype=float)

        def residual(x):
            return self.hand(side, whole, {**dict(zip(names, x)), f"wrist_{side}": 0.0}) - target

        best = None
        for start in (x0, np.clip([0.2, 1.5, 0.3], lo, hi), np.clip([1.0, 0.0, 0.0], lo, hi)):
            sol = least_squares(residual, start, bounds=(lo, hi), xtol=1e-10, ftol=1e-12)
            if best is None or sol.cost < best.cost:
                best = sol
        arm = {**dict(zip(names, (float(v) for v in best.x))), f"wrist_{side}": 0.0}
        return arm, float(np.linalg.norm(residual(best.x)))
