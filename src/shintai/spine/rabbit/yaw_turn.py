"""Rabbit turns its upper body in yaw (seed 003 §3.5.4, Fig. 3.27): "脊椎構造が、上半身の重量を十分支えて旋回を
行うことができることを確認した".

On :class:`~shintai.spine.bodies.QuasiStaticSpine` each body step is one equilibrium: :class:`YawSweep` writes the
muscle lengths of eq. 4.25 for a posture whose yaw (the third angle of each joint's rpy) is the commanded turn
spread evenly over the five joints, at a joint gap pre-compressing the discs (§3.5.3: "構造体としての、堅い体幹が
要求される場面では … 全ての筋長を短く計算して、制御する"), one step of the sweep per tick. The upper body is a
:class:`~shintai.spine.robots.Load` on the top part; its centre of mass sits ahead of the spine's axis, so a turn
carries it round (:class:`YawTurn`, numbers chosen).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from shintai.core.runtime import Module, Snapshot
from shintai.scenarios.experiment import Rig
from shintai.spine.bodies import QuasiStaticSpine
from shintai.spine.robots import RABBIT, SpineRobot


@dataclass(frozen=True)
class YawTurn:
    """The turn: 0 → +``yaw_deg`` → −``yaw_deg`` → 0 in ``step_deg`` steps. Chosen: ±40° inside the spine's range
    (§3.5.1: "roll, pitch, yaw 各軸とも全体で 90°", i.e. ±45°); 1 mm of disc pre-compression, the stiff end of
    spine.rabbit-stiffening's sweep; the upper body's centre 30 mm ahead of the axis (forelimbs held forward in
    the sitting posture, Fig. 3.25 a — not measured), its mass and height Rabbit's ``upper_body`` load."""

    yaw_deg: float = 40.0
    step_deg: float = 5.0
    precompression_mm: float = 1.0
    forward_mm: float = 30.0

    def commands_deg(self) -> np.ndarray:
        """The commanded total yaw at each tick [deg]."""
        n = round(self.yaw_deg / self.step_deg)
        up = np.linspace(0.0, self.yaw_deg, n + 1)
        return np.concatenate([up, up[::-1][1:], -up[1:], -up[::-1][1:]])


def carried(robot: SpineRobot, forward_m: float, load: bool = True) -> tuple:
    """Rabbit's upper-body load moved ``forward_m`` ahead of the axis (x), or no load."""
    return tuple(replace(ld, com_m=(forward_m, *ld.com_m[1:])) for ld in robot.loads) if load else ()


class YawSweep(Module):
    """Writes the muscle lengths of the turn's next posture each tick (module docstring)."""

    def __init__(self, robot: SpineRobot, turn: YawTurn, name: str = "yaw_sweep"):
        super().__init__(name)
        ring = robot.disc
        gap = np.full(robot.n, ring.t_free_m - 1e-3 * turn.precompression_mm - ring.gap_m)
        self.commands = turn.commands_deg()
        self.lengths = []
        for yaw in self.commands:
            theta = np.zeros(3 * robot.n)
            theta[2::3] = math.radians(yaw) / robot.n
            self.lengths.append(robot.model.lengths(theta, gap))
        self.k = 0

    def update(self, snapshot: Snapshot):
        lengths = self.lengths[min(self.k, len(self.lengths) - 1)]
        self.k += 1
        return {"length": lengths}


def top_pose(robot: SpineRobot, snapshot: Snapshot) -> tuple[float, float, np.ndarray]:
    """The top part's yaw about the base's vertical [deg], the tilt of its axis from the vertical [deg], and its
    origin [m]."""
    R, p, _ = robot.model.chain.frames(snapshot["theta"], snapshot["gap"])
    top = R[-1]
    return math.degrees(math.atan2(top[1, 0], top[0, 0])), math.degrees(math.acos(np.clip(top[2, 2], -1, 1))), p[-1]


def yaw_turn_rig(turn: YawTurn, load: bool = True, robot: SpineRobot = RABBIT) -> Rig:
    """One turn, one equilibrium per commanded step; records after each: the commanded and the top's yaw, the
    top's tilt and height, the largest muscle tension and whether the equilibrium converged."""
    body = QuasiStaticSpine(robot, loads=carried(robot, 1e-3 * turn.forward_mm, load))
    sweep = YawSweep(robot, turn)

    def after(_):  # the loop hands the snapshot before the step: read the equilibrium this tick's command reached
        snap = body.snapshot()
        yaw, tilt, top = top_pose(robot, snap)
        return {"command_deg": float(sweep.commands[min(sweep.k, len(sweep.commands)) - 1]), "yaw_deg": yaw,
                "tilt_deg": tilt, "top_z_mm": 1e3 * float(top[2]), "max_tension_n": float(np.max(snap["tension"])),
                "solved": int(snap["solved"])}

    return Rig(body, modules=[sweep], duration=len(sweep.commands) * body.dt, record={1: after}, state=sweep)


def yaw_turn_metrics(log, robot: SpineRobot = RABBIT) -> dict[str, float]:
    """The turn's reach (achieved yaw range over commanded range), the top's largest tilt, its height range, the
    largest muscle tension and its share of the servo's maximum (§3.5.1), and the unconverged equilibria."""
    cmd, yaw = log.values("command_deg"), log.values("yaw_deg")
    tension = float(np.max(log.values("max_tension_n")))
    z = log.values("top_z_mm")
    return {"yaw_range_deg": float(yaw.max() - yaw.min()), "command_range_deg": float(cmd.max() - cmd.min()),
            "yaw_reach": float((yaw.max() - yaw.min()) / (cmd.max() - cmd.min())),
            "max_yaw_error_deg": float(np.abs(yaw - cmd).max()),
            "max_tilt_deg": float(np.max(log.values("tilt_deg"))), "top_height_range_mm": float(z.max() - z.min()),
            "min_top_z_mm": float(z.min()), "max_tension_n": tension,
            "tension_share_of_servo": tension / min(m.max_tension_n for m in robot.motors),
            "unsolved": int(np.sum(log.values("solved") == 0))}
