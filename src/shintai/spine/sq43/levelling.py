"""SQ43's accelerometer levelling (seed 003 §3.2.4, Fig. 3.6): a board lifts and lowers the left front foot and
the levelling bends the left front leg until the shoulder is level.

§3.2.4: "センサの値が定常になった時の値のみを姿勢情報として利用する" — the shoulder accelerometer is read only
when steady; then the left-front leg's length changes toward level (:class:`Levelling`, numbers chosen). The run
is one Loop at the controller's period: the board script (:class:`BoardScript`), then the leg servos with or
without the levelling (:class:`LevellingControl`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core.runtime import SET, Module, Snapshot, declare
from shintai.scenarios.experiment import Rig
from shintai.spine.sq43.body import (
    BODY,
    SQ43Body,
    SQ43BodySpec,
    accelerometer_roll,
    leg_ik,
    roll_of,
    servo_ctrl,
    standing_angles,
)
from shintai.spine.sq43.constants import LF_LENGTH_RANGE_M


@dataclass(frozen=True)
class Levelling:
    """§3.2.4's shoulder levelling: the shoulder accelerometer is read only when steady (its reading varies less
    than ``steady_ms2`` over ``window_s``); then the left-front leg's length changes by ``gain`` × the shoulder
    height error (half body width × sin roll) toward level, and the controller waits for the next steady
    window. Numbers chosen (not in the text)."""

    period_s: float = 0.02
    window_s: float = 0.3
    steady_ms2: float = 0.15
    deadband_deg: float = 0.5
    gain: float = 0.8


def board_height(t, rise_mm: float, times=(1.0, 2.0, 6.0, 7.0)) -> np.ndarray:
    """The board under the left front foot: up from t0 to t1, held, down from t2 to t3 (Fig. 3.6 1→2, 3→4)."""
    t0, t1, t2, t3 = times
    up = np.clip((np.asarray(t) - t0) / (t1 - t0), 0, 1) - np.clip((np.asarray(t) - t2) / (t3 - t2), 0, 1)
    return 1e-3 * rise_mm * up


class BoardBody(SQ43Body):
    """SQ43 with the board under its left front foot, its height above the start the ``board`` channel [m]."""

    def __init__(self, spec: SQ43BodySpec = BODY, substeps: int = 1):
        super().__init__(spec, board=True, substeps=substeps)
        self.channels = {**self.channels, **declare("board", kind=SET)}
        self._board = self.model.body("board").mocapid[0]
        self._board_start = self.data.mocap_pos[self._board].copy()

    def apply(self, command) -> None:
        command = dict(command)
        height = command.pop("board", None)
        if height is not None:
            self.data.mocap_pos[self._board] = self._board_start + [0, 0, float(height)]
        super().apply(command)


class BoardScript(Module):
    """The experimenter raising and lowering the board (:func:`board_height`), written to ``board``."""

    def __init__(self, rise_mm: float):
        super().__init__("board")
        self.rise_mm = rise_mm

    def update(self, snapshot: Snapshot):
        return {"board": float(board_height(snapshot["t"], self.rise_mm))}


class LevellingControl(Module):
    """The leg servos standing, the left front leg at ``lf_length``; with a :class:`Levelling` (else held) each
    steady window of the shoulder accelerometer shortens or lengthens it toward level. ``acted``: when it did."""

    def __init__(self, model, levelling: Levelling | None, spec: SQ43BodySpec = BODY):
        super().__init__("levelling")
        self.model, self.levelling, self.spec = model, levelling, spec
        self.stand = standing_angles(spec)
        self.lf_length = spec.natural_length_m
        self.window: list[np.ndarray] = []
        self.acted: list[float] = []

    def update(self, snapshot: Snapshot):
        law, spec = self.levelling, self.spec
        if law is not None:
            self.window.append(snapshot["acc_shoulder"].copy())
            n = round(law.window_s / law.period_s)
            self.window = self.window[-n:]
            if len(self.window) == n and np.ptp(np.array(self.window), axis=0).max() < law.steady_ms2:
                roll = float(accelerometer_roll(np.mean(self.window, axis=0)))
                if abs(math.degrees(roll)) > law.deadband_deg:
                    self.lf_length -= law.gain * spec.body_width_m * math.sin(roll)
                    self.lf_length = float(np.clip(self.lf_length, *LF_LENGTH_RANGE_M))
                    self.acted.append(snapshot["t"])
                    self.window = []
        legs = dict(self.stand)
        legs["LF"] = leg_ik("LF", [0.0, 0.0, -self.lf_length], spec)
        return {"ctrl": servo_ctrl(self.model, legs)}


def levelling_rig(levelling: Levelling | None, rise_mm: float = 20.0, duration: float = 11.0,
                  spec: SQ43BodySpec = BODY, view=None) -> Rig:
    """One run: the board raised by ``rise_mm`` and lowered, the body stepped at the controller's period (0.02 s
    without a levelling). Records after each period: the body time ``t_s``, ``board_mm``, the true shoulder roll
    ``roll_deg`` (from the orientation), ``acc_roll_deg`` (the accelerometer's) and ``lf_length_mm``."""
    period = levelling.period_s if levelling else 0.02
    body = BoardBody(spec, substeps=round(period / spec.timestep))
    control = LevellingControl(body.model, levelling, spec)
    data, sensor = body.data, body.model.sensor

    def after_period(snap):
        quat, acc = sensor("shoulder_quat"), sensor("acc_shoulder")
        return {"t_s": data.time, "board_mm": 1e3 * float(board_height(data.time, rise_mm)),
                "roll_deg": math.degrees(float(roll_of(data.sensordata[quat.adr[0]:quat.adr[0] + 4]))),
                "acc_roll_deg": math.degrees(float(accelerometer_roll(data.sensordata[acc.adr[0]:acc.adr[0] + 3]))),
                "lf_length_mm": 1e3 * control.lf_length}

    return Rig(body, stages=[[BoardScript(rise_mm)], [control]], duration=duration, record={1: after_period},
               view=view or {}, state=control)
