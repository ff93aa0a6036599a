"""Why Kenta's spine does not hold a posture with its muscle lengths fixed (seed 003 §3.7.2, §3.6.1).

§3.7.2: "各節 roll, pitch, yaw の 3 自由度 × 10 節 = 30 自由度とすれば、最少で 31 本の筋が必要である。3.4.1 節で
述べたように、復元力を持つ脊椎なので筋の本数が足りなくても姿勢は定まる" and §3.6.1: "筋が足りなくても，外力が
無ければ椎間板の復元力と筋張力が釣り合いにより姿勢が決まる". Kenta's 40 muscles all run from the hip or the
shoulder block to the blocks or to vertebrae 2, 4, 6, 8 (§3.7.2's list): the odd vertebrae carry no muscle, so
the muscles act on 24 of the 30 joint coordinates (eq. 4.14's J_m has rank 24), and, because a wire only pulls,
they cannot resist a torque in most directions (no strictly positive tension set balances, J_mᵀ t = 0, t > 0:
Gordan's alternative gives motions that lengthen no muscle). Under gravity (an external force) what holds such
a motion is only the discs and ligaments, whose constants the thesis does not give.

* :func:`muscle_span` — rank of J_m and the joint-torque directions ±e_k no non-negative tensions produce.
* :func:`unstretched_bend` — the fastest forward bend (d Σpitch) along which no muscle lengthens (an LP).
* :func:`lock_reels` — the reels of a :class:`~shintai.spine.bodies_mujoco.SpineBody` fixed where they are
  (two-sided stops on the reel joints: an ideal length control).
* :func:`upright_stiffness`, :func:`upright_margin`, :func:`critical_disc_stiffness` — the thesis's criterion
  for the discs (§7.1.1, §4.6.2), shared with Cla in :mod:`shintai.spine.discs` (robots.KENTA_DISC_NM_RAD =
  2 × k*).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog
from shintai.spine.kenta.constants import LOCK_SOLREF_S, LOCK_TOLERANCE_M
from shintai.spine.discs import critical_disc_stiffness, upright_margin, upright_stiffness

__all__ = ["muscle_span", "unstretched_bend", "lock_reels", "upright_stiffness", "upright_margin",
           "critical_disc_stiffness"]


def muscle_span(model, theta, tol: float = 1e-6) -> dict:
    """``rank`` of J_m at θ, ``unresisted`` the list of pure joint torques ±e_k (names like "j3y+") that no
    tensions t ≥ 0 produce (τ = −J_mᵀ t, eq. 4.22), ``balanced`` whether some t > 0 gives τ = 0 (the
    condition for the muscles to hold every direction: positive spanning)."""
    J = model.jacobian(np.asarray(theta, dtype=float))
    m, k = J.shape
    s = np.linalg.svd(J, compute_uv=False)
    rank = int(np.sum(s > tol * s[0]))
    unresisted = []
    for j in range(k):
        for sign in (1.0, -1.0):
            tau = np.zeros(k)
            tau[j] = sign
            if not linprog(np.ones(m), A_eq=-J.T, b_eq=tau, bounds=[(0, None)] * m).success:
                unresisted.append(f"j{j // 3 + 1}{'rpy'[j % 3]}{'+' if sign > 0 else '-'}")
    # max s such that J^T t = 0, Σt = 1, t ≥ s: s > 0 iff a strictly positive balanced tension exists
    c = np.r_[np.zeros(m), -1.0]
    A_eq = np.vstack([np.hstack([J.T, np.zeros((k, 1))]), np.r_[np.ones(m), 0.0]])
    res = linprog(c, A_ub=np.hstack([-np.eye(m), np.ones((m, 1))]), b_ub=np.zeros(m), A_eq=A_eq,
                  b_eq=np.r_[np.zeros(k), 1.0], bounds=[(0, None)] * m + [(None, None)])
    balanced = bool(res.success and res.x[-1] > 1e-9)
    return {"rank": rank, "unresisted": unresisted, "balanced": balanced}


def unstretched_bend(model, theta) -> tuple[float, np.ndarray]:
    """The largest rate of whole-spine forward bend d(Σ pitch) over joint velocities |θ̇_k| ≤ 1 rad/s along which
    no muscle lengthens (J_m θ̇ ≤ 0): > 0 means fixed muscle lengths do not stop the spine bending forward.
    Returns (rate, θ̇)."""
    J = model.jacobian(np.asarray(theta, dtype=float))
    c = np.zeros(J.shape[1])
    c[1::3] = -1.0  # θ is (roll, pitch, yaw) per joint (eq. 4.1)
    res = linprog(c, A_ub=J, b_ub=np.zeros(J.shape[0]), bounds=[(-1.0, 1.0)] * J.shape[1])
    return float(-res.fun), res.x


def lock_reels(body) -> None:
    """Fix every reel of ``body`` at its present winding: two-sided joint stops ±``LOCK_TOLERANCE_M`` on the reel
    slides and the motors off — the muscle lengths inside the blocks can no longer change."""
    m, d = body.model, body.data
    for name in body.robot.muscle_names:
        j = body.id("joint", f"{name}:reel")
        q = d.qpos[m.jnt_qposadr[j]]
        m.jnt_range[j] = [q - LOCK_TOLERANCE_M, q + LOCK_TOLERANCE_M]
        m.jnt_solref[j] = [LOCK_SOLREF_S, 1.0]
    d.ctrl[body._motor] = 0.0
