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

from shintai.humanoid.balance.scooter import posture_on_pads
from shintai.humanoid.constants import SCENE, SUBSTEPS, VBOARD, VboardSpec
from shintai.humanoid.robots.hrp2 import add_hrp2
from shintai.humanoid.vboard.constants import FIRMWARE_LAW, NOSLIP_ITERATIONS
from shintai.humanoid.vboard.vehicle import PAD, add_vboard, install_firmware, vboard_state
from shintai.sim.body import MujocoBody
from shintai.sim.spec import fill_keyframe, scene_spec


def standing_posture(model: mujoco.MjModel, v: VboardSpec = VBOARD) -> np.ndarray:
    """qpos with the boards at θ_O and the robot's soles on the pads, its mass centre over the axle.

    Raises ValueError if the IK does not reach the pads.
    """
    qpos = model.qpos0.copy()
    vboard_state(model, qpos, None, v)
    return posture_on_pads(model, qpos, v.deck_height, PAD, "vboard_centre", "on the V-BOARD")


def build_vboard_stand(v: VboardSpec = VBOARD, substeps: int = SUBSTEPS, law: str = FIRMWARE_LAW) -> MujocoBody:
    """HRP2 standing on the V-BOARD (keyframe ``stand``), the firmware (its ``law``) installed."""
    spec = scene_spec("hrp2-vboard", *SCENE)
    spec.option.noslip_iterations = NOSLIP_ITERATIONS  # the soles do not creep on the pads (vboard.constants)
    add_vboard(spec, spec.worldbody, v=v)
    add_hrp2(spec, spec.worldbody, [0.0, 0.0, 1.0])
    spec.add_key(name="stand")
    model = spec.compile()
    fill_keyframe(model, "stand", standing_posture(model, v))
    body = MujocoBody(model, substeps=substeps, keyframe="stand", spec=spec)
    body.firmware = install_firmware(body, v, law=law)
    return body
