"""The load monitor of the seated robot (seed 000 §4.3.1 Fig. 4.3, §7.4.1 Fig. 7.16): force and joint-torque
norms, the CoM's lateral offset, and the reference model A against the real-robot model B.

§7.4.1: '図 7.16-(I) … 座り直し動作後の図 7.16-(I) の右図では,重心位置が中央に寄り,力・関節トルクの大きさ(ノルム)も
低減され,負荷が解消されていることが分かる'; and the two models

  A '搭乗したヒューマノイドの腰部位置姿勢,関節角度の目標値を反映したモデル'
  B '搭乗したヒューマノイド実機の体幹姿勢推定に基づく姿勢情報、および関節エンコーダによる各関節角度を反映した実環境
    ロボットモデル'

compared with 'モデルAとモデルBの両足支持点(各足の圧力中心の中点)の位置を … 一致させている'.

Ours (:class:`LoadMonitor`, every recorded sample):

* forces: ‖f‖ of the environment's force on each hand and foot from the 6-axis sensors
  (:func:`~shintai.humanoid.robots.hrp2.ft_reaction`); ``force_norm`` is the norm of the four stacked,
  ``hand_force_norm`` of the two hands;
* joint torques: ‖τ‖ over the robot's 32 position servos (MuJoCo's actuator forces; the thesis estimated
  them from the joint tracking errors, §4.3.1), and each servo's |τ| (``joint_loads``, in the order of
  :attr:`LoadMonitor.joints`) for Fig. 4.3's "which joint is most loaded" — its circles' radii are "関節負荷の
  絶対値" — and each servo's tracking error |q_ref − q| (``joint_errors``), what the thesis estimated the load from;
* CoM: the robot's CoM in the vehicle frame, y relative to the saddle top (0 = centred on the saddle);
* model A: the rider's reference model (:class:`~shintai.humanoid.tricycle.ch4_riding.Rider`: the waist at its
  commanded seat pose in the vehicle frame — Eq. 4.9's roll, the CoM shift, the hip lift — and every
  joint at its servo target); model B: every joint at its measured angle and the waist turned as it is
  (the thesis: the trunk-posture estimate; ours: the simulator's waist orientation in the vehicle
  frame). B is translated so that the two feet's midpoints coincide (the sole centres stand for the
  CoPs); reported: the mean distance of the two hands (grasp sites), the waist distance and the waist
  rotation angle between A and B.
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.humanoid.robots.hrp2 import SIDES, ft_reaction
from shintai.humanoid.tricycle.constants import AFTER_S, BEFORE_S, SETTLE_S
from shintai.humanoid.tricycle.riding import ANKLE_FT, HAND, SOLE, WRIST_FT


class LoadMonitor:
    """Fig. 7.16's quantities of ``body`` with ``rider``'s reference model; :meth:`sample` returns them."""

    def __init__(self, body, rider):
        m = body.model
        self.body, self.rider = body, rider
        self.data_a, self.data_b = mujoco.MjData(m), mujoco.MjData(m)
        self.servo_qadr = np.array([m.jnt_qposadr[m.actuator_trnid[i, 0]] for i in range(m.nu)])
        robot = [j for j in range(m.njnt) if m.joint(j).name not in ("tricycle_root", "root")
                 and m.body_rootid[m.jnt_bodyid[j]] == m.body_rootid[body.id("body", "waist")]]
        self.robot_qadr = np.array([m.jnt_qposadr[j] for j in robot])
        self.root = m.joint("root").qposadr[0]
        self.waist = body.id("body", "waist")
        self.hands = [body.id("site", HAND[s]) for s in SIDES]
        self.soles = [body.id("site", SOLE[s]) for s in SIDES]
        self.joints = tuple(m.actuator(i).name for i in range(m.nu))  # the servos, in joint_loads' order

    def vehicle(self) -> tuple[np.ndarray, np.ndarray]:
        d = self.body.data.body("tricycle")
        return d.xpos.copy(), d.xmat.reshape(3, 3).copy()

    def _pose(self, data, q_joints: np.ndarray, rot: np.ndarray, pos) -> None:
        data.qpos[:] = self.body.data.qpos
        data.qpos[self.robot_qadr] = q_joints
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, rot.reshape(-1))
        data.qpos[self.root:self.root + 3] = pos
        data.qpos[self.root + 3:self.root + 7] = quat
        mujoco.mj_kinematics(self.body.model, data)

    def models(self, snapshot) -> dict:
        """Model A against model B (vehicle frame, feet midpoints aligned): hand, waist distances [m] and
        the waist rotation angle [rad]."""
        d = self.body.data
        p_v, r_v = self.vehicle()
        q_a = d.qpos[self.robot_qadr].copy()
        ctrl = dict(zip(self.servo_qadr.tolist(), d.ctrl.tolist()))
        q_a = np.array([ctrl.get(a, q) for a, q in zip(self.robot_qadr.tolist(), q_a)])
        pos_a, rot_a = self.rider.waist_pose(snapshot.get("ref:chest_roll", 0.0), snapshot.get("ref:com_shift", 0.0),
                                             snapshot.get("ref:hip_lift", 0.0))
        rot_b = r_v.T @ d.xmat[self.waist].reshape(3, 3)
        self._pose(self.data_a, q_a, rot_a, pos_a)
        self._pose(self.data_b, d.qpos[self.robot_qadr], rot_b, np.zeros(3))
        mid_a = self.data_a.site_xpos[self.soles].mean(axis=0)
        shift = mid_a - self.data_b.site_xpos[self.soles].mean(axis=0)
        hand = np.linalg.norm(self.data_a.site_xpos[self.hands] - (self.data_b.site_xpos[self.hands] + shift), axis=1)
        waist = np.linalg.norm(self.data_a.xpos[self.waist] - (self.data_b.xpos[self.waist] + shift))
        rel = self.data_a.xmat[self.waist].reshape(3, 3).T @ self.data_b.xmat[self.waist].reshape(3, 3)
        angle = float(np.arccos(np.clip((np.trace(rel) - 1) / 2, -1.0, 1.0)))
        return {"hand_ab": float(hand.mean()), "waist_ab": float(waist), "waist_ab_rad": angle}

    def sample(self, snapshot) -> dict:
        """Everything of one sample: forces [N], joint-torque norm [N m], CoM offset [m], model A/B."""
        d = self.body.data
        f = {f"{kind}_{s}": float(np.linalg.norm(ft_reaction(self.body, snapshot, sensor[s])[0]))
             for kind, sensor in (("hand", WRIST_FT), ("foot", ANKLE_FT)) for s in SIDES}
        p_v, r_v = self.vehicle()
        com = r_v.T @ (d.subtree_com[self.waist] - self.body.site_pos("saddle_top"))
        return {"force_norm": float(np.sqrt(sum(v * v for v in f.values()))),
                "hand_force_norm": float(np.hypot(f["hand_l"], f["hand_r"])),
                "foot_force_norm": float(np.hypot(f["foot_l"], f["foot_r"])),
                "torque_norm": float(np.linalg.norm(d.actuator_force)), "com_y": float(com[1]),
                "joint_loads": np.abs(d.actuator_force), "joint_errors": np.abs(d.ctrl - d.qpos[self.servo_qadr]),
                **self.models(snapshot)}


def window_means(t: np.ndarray, values: dict, start: float, end: float) -> dict:
    """The mean of each recorded signal over ``start`` ≤ t < ``end`` (NaN when no sample is there)."""
    keep = (t >= start) & (t < end)
    return {k: float(np.mean(v[keep])) if keep.any() else float("nan") for k, v in values.items()}


def recovery_windows(t: np.ndarray, recovering: np.ndarray, before: float = BEFORE_S, settle: float = SETTLE_S,
                     after: float = AFTER_S):
    """((start, end) before, (start, end) after) the first recovery in the samples ``recovering`` (bool) at
    times ``t``: ``before`` seconds up to its start, ``after`` seconds from ``settle`` after its end; None
    when no recovery started and ended."""
    recovering = np.asarray(recovering, dtype=bool)
    if not recovering.any():
        return None
    t1 = t[np.flatnonzero(recovering)[0]]
    ended = np.flatnonzero(~recovering & (t > t1))
    if not len(ended):
        return None
    t3 = t[ended[0]]
    return (t1 - before, t1), (t3 + settle, t3 + settle + after)


def fig4_3_metrics(rec, rec_flag, joints) -> dict:
    """Fig. 4.3 (§4.3.1) in the window before the first recovery — Fig. 7.16-(I)'s left, which §7.4.1 says shows
    Fig. 4.3's problems ('図4.3と同様に図7.16-(I)の左図からは(問題1),(問題2)が観察される'): the most loaded joint
    (largest mean |τ| of a servo), whether it is a wrist roll joint, the joint with the largest tracking error (what
    the thesis estimated its loads from) and the wrist roll's rank by it, and the CoM's signed lateral offset."""
    t = rec.times("load.joint_loads")
    windows = recovery_windows(t, rec_flag)
    if windows is None:
        return {"most_loaded_joint_before": "", "most_loaded_is_wrist_roll_before": 0, "largest_error_joint_before": "",
                "com_y_before_m": float("nan")}
    keep = (t >= windows[0][0]) & (t < windows[0][1])
    loads = rec.values("load.joint_loads").reshape(len(t), -1)[keep].mean(axis=0)
    ranked = np.argsort(loads)[::-1]
    top = joints[ranked[0]]
    errors = rec.values("load.joint_errors").reshape(len(t), -1)[keep].mean(axis=0)
    by_error = np.argsort(errors)[::-1]
    return {"largest_error_joint_before": joints[by_error[0]],
            "wrist_roll_error_rank_before": _wrist_roll_rank(by_error, joints),
            "most_loaded_joint_before": top, "most_loaded_is_wrist_roll_before": int(top.endswith("wrist_roll")),
            "most_loaded_joint_before_nm": float(loads[ranked[0]]),
            "wrist_roll_load_before_nm": float(max(loads[joints.index(f"{s}_wrist_roll")] for s in ("l", "r"))),
            "wrist_roll_rank_before": _wrist_roll_rank(ranked, joints),
            "com_y_before_m": float(np.mean(rec.values("load.com_y")[keep]))}


def _wrist_roll_rank(order, joints) -> int:
    """The place (1 = first) of the first wrist roll servo in ``order`` (servo indices, most loaded first)."""
    return int(min(np.flatnonzero([joints[i].endswith("wrist_roll") for i in order])) + 1)
