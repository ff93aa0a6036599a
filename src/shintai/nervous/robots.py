"""The robots nervous serves (``--robot NAME``): each builds its MuJoCo body and generates its description
from that model (:mod:`shintai.nervous.robot`).

* ``cla`` — Cla's muscle-driven spine (seed 003 §3.6): 8 muscles, tension sensors, encoders, currents,
  accelerometers at the waist and the clavicle; the on-body controller of §4.6 at 1 ms. The trunk loads and
  the arms hanging down are the spine package's (``CLA_TRUNK_LOADS + CLA_ARMS_DOWN``); Cla's limbs, neck and
  foot sensors are not modelled (its 4-DOF servo arms are loads).
* ``hrp2`` — the HRP2-JSK-like humanoid of seed 000 App. A.2.1 standing on the floor: 32 joint servos, F/T
  sensors, the chest IMU; hrpsys's 4 ms period.
* ``snake`` — the wheeled snake of seed 001 §2.1 (n = 9, 17 joint servos, passive wheels) on the floor,
  straight; its 10 ms servo period.
* ``arm3`` — a 3-DOF arm, the thesis's own example robot ("ロボット(3自由度)", App. C.2.1): small and
  quick, for tests and Fig. C.1.

The packet period — one sensor set in, one command set out — is not given in the thesis (spec 003-part2
§12.11: set by the serial link's bandwidth and packet size); chosen: each body's control step (Cla's 1 ms
on-body cycle of §6.4.2, hrpsys's 4 ms, the snake's servo period, 1 ms for the arm).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from shintai.humanoid.robots.hrp2 import build_hrp2
from shintai.nervous.bodies import MuscleRobot, ServoRobot, SimRobot
from shintai.nervous.robot import Description, describe_servos, describe_spine
from shintai.sim.body import MujocoBody
from shintai.snake.constants import CH3_ROBOT
from shintai.snake.mujoco_plant import MujocoSnake
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.control import Gains
from shintai.spine.robots import CLA, CLA_ARMS_DOWN, CLA_TRUNK_LOADS

ARM3_XML = """
<mujoco model="arm3">
  <option timestep="0.0005" integrator="implicitfast"/>
  <default><joint damping="0.02" armature="0.002"/><geom contype="0" conaffinity="0"/></default>
  <worldbody>
    <geom type="cylinder" size="0.04 0.05" pos="0 0 0.05" rgba=".4 .4 .45 1"/>
    <body name="base" pos="0 0 0.1">
      <joint name="j0" type="hinge" axis="0 0 1" range="-170 170"/>
      <geom type="capsule" fromto="0 0 0 0 0 0.1" size="0.02" mass="0.3"/>
      <body name="upper" pos="0 0 0.1">
        <joint name="j1" type="hinge" axis="0 1 0" range="-150 150"/>
        <geom type="capsule" fromto="0 0 0 0.15 0 0" size="0.015" mass="0.2"/>
        <body name="lower" pos="0.15 0 0">
          <joint name="j2" type="hinge" axis="0 1 0" range="-150 150"/>
          <geom type="capsule" fromto="0 0 0 0.12 0 0" size="0.012" mass="0.1"/>
          <site name="tip" pos="0.12 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="j0" joint="j0" kp="40" kv="1.2"/>
    <position name="j1" joint="j1" kp="40" kv="1.2"/>
    <position name="j2" joint="j2" kp="40" kv="1.2"/>
  </actuator>
  <sensor><framepos name="tip" objtype="site" objname="tip"/></sensor>
</mujoco>
"""


@dataclass(frozen=True)
class RobotEntry:
    name: str
    summary: str
    parts: Callable[[], tuple]  # () -> (body, description, *extra): built, not run
    robot: Callable[..., SimRobot]  # the on-body side from those parts
    spine: object = None  # the SpineRobot (its geometric model, eq. 4.25) for the spine's plugins


def _arm3():
    body = MujocoBody(ARM3_XML, substeps=2)
    return body, describe_servos(body.model, "arm3", "seed 003 App. C.2.1 (3-DOF example)", body.dt)


def _hrp2():
    body = build_hrp2()
    return body, describe_servos(body.model, "hrp2", "seed 000 App. A.2.1, Tables A.1/A.2", body.dt,
                                 qpos=body.data.qpos.copy())


def _snake():
    body = MujocoSnake(np.zeros(3), np.zeros(CH3_ROBOT.n)).mj
    return body, describe_servos(body.model, "snake", "seed 001 §2.1", body.dt, qpos=body.data.qpos.copy(),
                                 notes=("the vel<j> actuators (velocity feed-forward of §3.3) stay at 0: dampers",))


def _cla():
    body = SpineBody(CLA, loads=CLA_TRUNK_LOADS + CLA_ARMS_DOWN)
    gains = Gains()
    servo = {"mode": 0.0, **{k: float(v) for k, v in vars(gains).items()}}
    desc = describe_spine(body, "cla", "seed 003 §3.6, Table 3.2", body.dt, servo,
                          notes=("servo mode 0 = L (length control, eq. 4.37); gains of Table 4.6, chosen "
                                 "(spine.control.Gains)", "Cla's limbs, neck and foot sensors are not modelled"))
    return body, desc, gains


ROBOTS: dict[str, RobotEntry] = {
    "arm3": RobotEntry("arm3", "3-DOF arm (the thesis's 3-DOF example, App. C.2.1)", _arm3, ServoRobot),
    "cla": RobotEntry("cla", "Cla's muscle spine, 8 muscles (seed 003 §3.6)", _cla, MuscleRobot, CLA),
    "hrp2": RobotEntry("hrp2", "HRP2-JSK-like humanoid, 32 servos (seed 000 App. A.2.1)", _hrp2, ServoRobot),
    "snake": RobotEntry("snake", "wheeled snake, 17 servos (seed 001 §2.1)", _snake, ServoRobot),
}


class UnknownRobot(KeyError):
    def __str__(self) -> str:
        return self.args[0]


def entry(name: str) -> RobotEntry:
    if name not in ROBOTS:
        raise UnknownRobot(f"unknown robot {name!r} (robots: {', '.join(sorted(ROBOTS))})")
    return ROBOTS[name]


def build(name: str) -> SimRobot:
    """The robot's simulated body with its on-body servo loops, powered up."""
    e = entry(name)
    return e.robot(*e.parts())


def describe(name: str) -> Description:
    """The description of a robot, generated from its model (the model is built, not run)."""
    return entry(name).parts()[1]


def spine_of(name: str):
    """The spine robot (geometry of eq. 4.25) behind a robot name, or None."""
    return entry(name).spine
