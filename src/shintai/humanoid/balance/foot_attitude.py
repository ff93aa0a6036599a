"""What HRP2-JSK senses of its feet: their world attitude (Eq. 6.1) and the measured ZMP (two ankle F/T).

**Foot attitude, §6.2.1 Eq. 6.1.** The board tilt θ_R, θ_L of the scooter is read from the feet standing
on it: ᴼR_{R,L} = ᴼR_C (ᴮR_C)ᵀ ᴮR_{R,L}, with ᴼR_C the chest attitude from the IMU in the chest, and
ᴮR_C, ᴮR_{R,L} the chest and feet in the pelvis (waist) frame from the joint encoders (Fig. 6.2). Here
ᴮR_C = Rz(waist_yaw) Ry(waist_pitch) (the model's chain, :mod:`shintai.humanoid.robots.hrp2`), ᴮR_{R,L}
the leg chain of :func:`shintai.humanoid.robots.leg_ik.leg_fk`, and ᴼR_C the ``imu_quat`` sensor (the IMU site
is unrotated in the chest). The thesis gives no rule for "the pitch component"; :func:`pitch` is the
pitch of the roll–pitch–yaw decomposition R = Rz Ry Rx (hrpsys's ``rpyFromRot``), the sole's x axis'
angle below the horizontal, + toe down (about +y, the model's sign convention).

**Measured ZMP** (the thesis's "実 ZMP", §6.2.1 Figs. 6.3–6.4, "measured by the 6-axis force sensors
in the soles"; its formula is not in the thesis, this is the standard one, Kajita et al. "Humanoid
Robots" §3): with each foot's reaction (f_j, τ_j) about its sensor point s_j (world frame,
:func:`shintai.humanoid.robots.hrp2.ft_reaction`) and the floor plane z = z₀::

    p_x = Σ_j (s_jx f_jz − τ_jy − (s_jz − z₀) f_jx) / Σ_j f_jz
    p_y = Σ_j (s_jy f_jz + τ_jx − (s_jz − z₀) f_jy) / Σ_j f_jz

over the feet in contact: f_jz > :data:`CONTACT_FZ`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from shintai.core.geometry import rot_y, rot_z
from shintai.humanoid.constants import F_THRE
from shintai.humanoid.robots.hrp2 import ft_reaction
from shintai.humanoid.robots.leg_ik import JOINT_NAMES, leg_fk
from shintai.sim.body import MujocoBody

# A foot counts in the ZMP when the floor pushes it up by more than the thesis's F_thre (§5.4.1).
CONTACT_FZ = F_THRE
SIDES = ("l", "r")


def quat_to_rot(quat) -> np.ndarray:
    """3×3 rotation of a unit quaternion (w, x, y, z), MuJoCo's order (the ``imu_quat`` sensor)."""
    w, x, y, z = (float(v) for v in quat)
    n = w * w + x * x + y * y + z * z
    if not (math.isfinite(n) and n > 0):
        raise ValueError(f"foot_attitude: the IMU quaternion must be finite and non-zero, got {quat!r}")
    s = 2.0 / n
    return np.array([[1 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)],
                     [s * (x * y + w * z), 1 - s * (x * x + z * z), s * (y * z - w * x)],
                     [s * (x * z - w * y), s * (y * z + w * x), 1 - s * (x * x + y * y)]])


def chest_in_waist(waist_yaw: float, waist_pitch: float) -> np.ndarray:
    """ᴮR_C from the two waist joints."""
    return rot_z(waist_yaw) @ rot_y(waist_pitch)


def foot_in_waist(side: str, leg_q) -> np.ndarray:
    """ᴮR_{R,L} from the six leg joints (hip yaw, roll, pitch, knee, ankle pitch, roll)."""
    return leg_fk(side, leg_q, np.zeros(3), np.eye(3))[1]


def foot_attitude(imu_rot, waist_yaw: float, waist_pitch: float, side: str, leg_q) -> np.ndarray:
    """Eq. 6.1: ᴼR_foot = ᴼR_C (ᴮR_C)ᵀ ᴮR_foot."""
    return np.asarray(imu_rot, float) @ chest_in_waist(waist_yaw, waist_pitch).T @ foot_in_waist(side, leg_q)


def pitch(rot) -> float:
    """The pitch of R = Rz(yaw) Ry(pitch) Rx(roll): θ = atan2(−R₂₀, √(R₀₀² + R₁₀²)), + toe down."""
    r = np.asarray(rot, float)
    return math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0]))


def feet_attitude(snapshot) -> dict[str, np.ndarray]:
    """Eq. 6.1 for both feet from a :class:`~shintai.sim.body.MujocoBody` snapshot of the hrp2 model
    (its ``imu_quat`` and the ``q:<joint>`` encoder readings): {"l": ᴼR_L, "r": ᴼR_R}."""
    imu = quat_to_rot(snapshot["imu_quat"])
    yaw, pitch_ = snapshot["q:waist_yaw"], snapshot["q:waist_pitch"]
    return {s: foot_attitude(imu, yaw, pitch_, s, [snapshot[f"q:{s}_{j}"] for j in JOINT_NAMES]) for s in SIDES}


class Zmp(NamedTuple):
    """``zmp`` (x, y) on the plane z = z₀ (NaN when no foot is in contact), ``fz`` the summed vertical
    force of the feet in contact (N), ``contacts`` their sides."""

    zmp: np.ndarray
    fz: float
    contacts: tuple[str, ...]


def two_foot_zmp(wrenches: dict, z0: float = 0.0, contact_fz: float = CONTACT_FZ) -> Zmp:
    """The ZMP of the feet's reactions (module docstring). ``wrenches``: side → (sensor point s,
    force f, torque τ about s), world frame, the environment acting on the foot."""
    if not (math.isfinite(contact_fz) and contact_fz >= 0):
        raise ValueError(f"two_foot_zmp: contact_fz must be a finite force ≥ 0 N, got {contact_fz!r}")
    num, fz, contacts = np.zeros(2), 0.0, []
    for side, (s, f, tau) in wrenches.items():
        s, f, tau = (np.asarray(v, float) for v in (s, f, tau))
        if not (np.all(np.isfinite(s)) and np.all(np.isfinite(f)) and np.all(np.isfinite(tau))):
            raise ValueError(f"two_foot_zmp: foot {side!r} has a non-finite wrench or sensor point")
        if f[2] <= contact_fz:
            continue
        lever = s[2] - z0
        num += (s[0] * f[2] - tau[1] - lever * f[0], s[1] * f[2] + tau[0] - lever * f[1])
        fz += f[2]
        contacts.append(side)
    return Zmp(num / fz if contacts else np.full(2, np.nan), fz, tuple(contacts))


def measured_zmp(body: MujocoBody, snapshot, z0: float | None = None, contact_fz: float = CONTACT_FZ) -> Zmp:
    """The hrp2 model's ZMP from its two ankle F/T sensors (:func:`ft_reaction`, world frame from the
    body's current FK). ``z0``: the floor plane; default the mean height of the two sole sites."""
    wrenches = {}
    for side in SIDES:
        force, torque = ft_reaction(body, snapshot, f"{side}_ankle")
        wrenches[side] = (body.site_pos(f"{side}_ankle_ft"), force, torque)
    if z0 is None:
        z0 = float(np.mean([body.site_pos(f"{s}_sole")[2] for s in SIDES]))
    return two_foot_zmp(wrenches, z0, contact_fz)
