"""Hardware abstraction (seed 003 §6.3.1): the four calls nervous makes on a robot, and two interfaces.

§6.3.1 defines the API between nervous and a robot as four functions —

    初期化              int OpenInterface(int, char **);
    センサ情報の取り込み  RobotState GetRobotState(RobotState *);
    アクチュエータ情報の送信 vector SetAngleVector(vector);
    終了処理            int CloseInterface(void);

— "上記 API を実装すれば新たなインタフェースの追加も可能な構成" (implement them and a new interface is added).
:class:`Interface` is that API; :class:`SimInterface` (the thesis's ``jsim``, C.3.7) steps a simulated
shintai body, :class:`DummyInterface` (``nervelib/dummy``, "実機と通信しないで nervous の挙動を試すもの") has
no body: what it is sent is what it reads back.

Pacing (C.2.2): "ロボットボディに送信するスレッドは, ロボットボディからデータが 1 セット受信される度に, そのグ
ローバル変数の値を 1 セット送信している" — one command set is sent per sensor set received. A real body
releases a packet every period; here :meth:`Interface.ready_in` says how long until the next packet is
released: in real time the packet's wall-clock due time, as fast as possible (``realtime=False``) never.
The sim computes a packet when asked; real-time pacing only holds it back until it is due.

Beyond the four calls, :meth:`Interface.servo_state`/:meth:`Interface.set_servo` carry the servo parameters
the thesis's servoplugin changed (§3.6.2: "制御パラメータ (ゲインなど) の動的変更").
"""

from __future__ import annotations

import time
from abc import ABC, abstractmethod
from dataclasses import dataclass, field

import numpy as np

from shintai.nervous import robots
from shintai.nervous.bodies import ServoError
from shintai.nervous.robot import Description

RESYNC_S = 0.1  # chosen: a real-time loop this far behind (a pause, a debugger) restarts its clock


@dataclass
class RobotState:
    """One sensor packet: body time, packet number, the measured DOF positions (wire units), the vector
    sent last (``reference``) and the sensors."""

    t: float
    seq: int
    angle_vector: np.ndarray
    reference: np.ndarray
    sensors: dict[str, np.ndarray] = field(default_factory=dict)

    def snapshot(self) -> dict:
        """The state as a runtime snapshot (``"t"`` plus named arrays)."""
        return {"t": self.t, "seq": self.seq, "angle-vector": self.angle_vector, "reference": self.reference,
                **self.sensors}


class Interface(ABC):
    """The four calls of §6.3.1 (Python names), plus pacing and servo parameters."""

    name: str

    def __init__(self, description: Description, realtime: bool = False):
        self.description = description
        self.period = description.packet_period_s
        self.realtime = realtime
        self.state: RobotState | None = None
        self._epoch: float | None = None  # wall time of packet 0 (real time)
        self.resyncs = 0

    @abstractmethod
    def open_interface(self, args=()) -> int:
        """Connect (OpenInterface); 0 on success. The first packet is then :attr:`state`."""

    @abstractmethod
    def get_robot_state(self) -> RobotState:
        """The next sensor packet (GetRobotState)."""

    @abstractmethod
    def set_angle_vector(self, vector: np.ndarray) -> np.ndarray:
        """Send the targets (SetAngleVector), clipped to the DOF limits; returns what was sent."""

    @abstractmethod
    def close_interface(self) -> int:
        """Disconnect (CloseInterface); 0 on success."""

    def ready_in(self, now: float | None = None) -> float:
        """Seconds until the next packet is released: 0 as fast as possible; in real time the time left
        to its due time (the clock restarts if the loop fell more than :data:`RESYNC_S` behind)."""
        if not self.realtime:
            return 0.0
        now = time.monotonic() if now is None else now
        seq = self.state.seq if self.state is not None else 0
        if self._epoch is None:
            self._epoch = now - seq * self.period
        due = self._epoch + (seq + 1) * self.period
        if now - due > RESYNC_S:
            self._epoch = now - (seq + 1) * self.period
            self.resyncs += 1
            return 0.0
        return max(0.0, due - now)

    def clip(self, vector) -> np.ndarray:
        return np.clip(np.asarray(vector, dtype=float), self.description.lower, self.description.upper)

    def servo_state(self) -> dict:
        return {}

    def set_servo(self, key: str, value: str, dofs: list[int]) -> None:
        raise ServoError(f"the {self.name} interface has no servo parameters")


class SimInterface(Interface):
    """A simulated shintai body (seed 003 App. C.3.7 ``jsim``): each packet advances it one period with the
    targets sent last, its on-body servo loops running."""

    name = "sim"

    def __init__(self, robot: str, realtime: bool = False):
        self.robot_name = robot
        self.robot = robots.build(robot)
        super().__init__(self.robot.description, realtime)

    def open_interface(self, args=()) -> int:
        self.reference = self.description.initial.copy()
        self.robot.command(self.reference)
        self.state = self._read(0)
        return 0

    def _read(self, seq: int) -> RobotState:
        angles, sensors = self.robot.read()
        return RobotState(self.robot.t, seq, angles, self.reference.copy(), sensors)

    def get_robot_state(self) -> RobotState:
        self.robot.advance(self.period)
        self.state = self._read(self.state.seq + 1)
        return self.state

    def set_angle_vector(self, vector) -> np.ndarray:
        self.reference = self.clip(vector)
        self.robot.command(self.reference)
        return self.reference.copy()

    def close_interface(self) -> int:
        self.state = None
        return 0

    def servo_state(self) -> dict:
        return self.robot.servo_state()

    def set_servo(self, key: str, value: str, dofs: list[int]) -> None:
        self.robot.set_servo(key, value, dofs)


class DummyInterface(Interface):
    """No body (``nervelib/dummy``): the angle vector read back is the one sent; sensors read zero unless
    a test sets :attr:`sensors`; time advances one period per packet."""

    name = "dummy"

    def __init__(self, robot: str | Description, realtime: bool = False):
        description = robot if isinstance(robot, Description) else robots.describe(robot)
        super().__init__(description, realtime)
        self.sensors = {s.name: np.zeros(s.size) for s in description.sensors if s.name != "angle-vector"}
        self.servo: dict = dict(description.servo)

    def open_interface(self, args=()) -> int:
        self.reference = self.description.initial.copy()
        self.state = RobotState(0.0, 0, self.reference.copy(), self.reference.copy(),
                                {k: v.copy() for k, v in self.sensors.items()})
        return 0

    def get_robot_state(self) -> RobotState:
        seq = self.state.seq + 1
        self.state = RobotState(seq * self.period, seq, self.reference.copy(), self.reference.copy(),
                                {k: v.copy() for k, v in self.sensors.items()})
        return self.state

    def set_angle_vector(self, vector) -> np.ndarray:
        self.reference = self.clip(vector)
        return self.reference.copy()

    def close_interface(self) -> int:
        self.state = None
        return 0

    def servo_state(self) -> dict:
        return dict(self.servo)

    def set_servo(self, key: str, value: str, dofs: list[int]) -> None:
        self.servo[key] = float(value) if key not in ("mode", "on", "off") else value


INTERFACES = {"sim": SimInterface, "dummy": DummyInterface}


def open_interface(kind: str, robot: str, realtime: bool = False) -> Interface:
    """Build and open an interface by name (``set-interface NAME``)."""
    if kind not in INTERFACES:
        raise KeyError(f"unknown interface {kind!r} (interfaces: {', '.join(INTERFACES)}; the thesis's serial "
                       "links serinerve, msmt, i2c talk to real hardware and are not here)")
    interface = INTERFACES[kind](robot, realtime)
    code = interface.open_interface()
    if code != 0:
        raise RuntimeError(f"interface {kind}: OpenInterface returned {code}")
    return interface
