"""HRP2-JSK standing on the V-BOARD (seed 000 §6.2.1, Fig. 6.1), as one ``MujocoBody`` with the
scooter's firmware installed: the start of the standing stack and of ch. 6's scenarios.

§6.2.1 puts the robot on the scooter in "a statically stable posture with the soles on the boards'
top faces" ([84]) and takes the scooter's centre as the origin and the reference ZMP (0, 0)
(Fig. 6.1). Here: the IK (:mod:`shintai.sim.ik`) puts each sole (its ``s_sole`` site, under the
ankle) on the centre of its foot pad, flat on the pad with the board at θ_O (the loaded scooter at
rest, Eq. A.1), the standing posture pursued in the null space; the waist is then moved along x
until the robot's mass centre is over the axle (a static ZMP at the scooter's centre), and the IK
solved again. Every servo holds that posture (keyframe ``stand``); nothing balances the robot yet
(behaviour level 1 of §6.2.1: on its own the pair drifts, see :mod:`~shintai.humanoid.vboard.vehicle`).

Names: the humanoid's (:mod:`~shintai.humanoid.robots.hrp2`) and the scooter's
(:mod:`~shintai.humanoid.vboard.vehicle`); ``body.firmware`` is the scooter's firmware.
"""

from __future__ import annotations

import mujoco
import numpy as np

from shintai.humanoid.constants import SCENE
from shintai.sim.spec import fill_keyframe, scene_spec, set_joints
from shintai.humanoid.constants import HRP2_LINKS, STANDING_POSTURE, SUBSTEPS, VBOARD, VboardSpec
from shintai.humanoid.robots.hrp2 import LEG, SIDES, add_hrp2, side_posture
from shintai.humanoid.vboard.vehicle import PAD, add_vboard, install_firmware, vboard_state
from shintai.sim import ik
from shintai.sim.body import MujocoBody

SOLE = {s: f"{s}_sole" for s in SIDES}
COM_ITERATIONS = 3  # waist moves then IK; the mass centre settles over the axle to < 1 mm in 2–3


def standing_posture(model: mujoco.MjModel, v: VboardSpec = VBOARD) -> np.ndarray:
    """qpos with the boards at θ_O and the robot's soles on the pads, its mass centre over the axle.

    Raises ValueError if the IK does not reach the pads.
    """
    qpos = model.qpos0.copy()
    vboard_state(model, qpos, None, v)
    return posture_on_pads(model, qpos, v.deck_height, PAD, "vboard_centre", "on the V-BOARD")


def posture_on_pads(model: mujoco.MjModel, qpos: np.ndarray, deck_height: float, pads: dict[str, str],
                    centre_site: str, where: str, flat_soles: bool = False) -> np.ndarray:
    """HRP2 standing with each sole on its pad site (the pads' orientation, or level with ``flat_soles``) and its
    mass centre over ``centre_site`` in x: the standing knee bend, the waist lowered to the deck, then
    :data:`COM_ITERATIONS` rounds of leg IK and a waist shift. Shared by the V-BOARD and the Ninebot.

    Raises ValueError if the IK does not reach the pads.
    """
    posture = side_posture(STANDING_POSTURE)
    set_joints(model, qpos, posture)
    hip, knee = posture["l_hip_pitch"], posture["l_knee_pitch"]
    leg = HRP2_LINKS.thigh * np.cos(hip) + HRP2_LINKS.shank * np.cos(hip + knee)
    root = model.joint("root").qposadr[0]
    qpos[root:root + 3] = [0.0, 0.0, deck_height - HRP2_LINKS.hip_z + leg + HRP2_LINKS.ankle_height]
    data = mujoco.MjData(model)
    waist = model.body("waist").id
    for _ in range(COM_ITERATIONS):
        data.qpos[:] = qpos
        mujoco.mj_kinematics(model, data)
        targets = {SOLE[s]: (data.site(pads[s]).xpos.copy(),
                             np.eye(3) if flat_soles else data.site(pads[s]).xmat.reshape(3, 3).copy())
                   for s in SIDES}
        result = ik.solve(model, targets, qpos, LEG, posture={j: posture[j] for j in LEG if j in posture})
        if not result.ok:
            raise ValueError(f"standing posture {where} not reachable: residual {result.residual[0]:.4f} m, "
                             f"{result.residual[1]:.4f} rad")
        qpos = result.q
        data.qpos[:] = qpos
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        qpos[root] -= data.subtree_com[waist][0] - data.site(centre_site).xpos[0]
    return qpos


def build_vboard_stand(v: VboardSpec = VBOARD, substeps: int = SUBSTEPS) -> MujocoBody:
    """HRP2 standing on the V-BOARD (keyframe ``stand``), the firmware installed."""
    spec = scene_spec("hrp2-vboard", *SCENE)
    add_vboard(spec, spec.worldbody, v=v)
    add_hrp2(spec, spec.worldbody, [0.0, 0.0, 1.0])
    spec.add_key(name="stand")
    model = spec.compile()
    fill_keyframe(model, "stand", standing_posture(model, v))
    body = MujocoBody(model, substeps=substeps, keyframe="stand", spec=spec)
    body.firmware = install_firmware(body, v)
    return body
