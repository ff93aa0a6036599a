"""``rotadjust`` — posture control by accelerometer (App. C.3.6 ``rotadjustplugin.c``, "加速度センサによる姿勢
制御"): Cla keeps its shoulders level (seed 003 §5.2.2).

§5.2.2: "3 軸加速度センサにより重力方向を検出し、肩が水平でなければ、脊椎の姿勢を制御して水平になるように動作す
る。動作中は、加速度センサが自分の動作に起因する加速度を検出してしまうので、姿勢の調節とセンサ情報の読み取りはフェイズ
を分けて、姿勢検出 → 脊椎調節量算出 → 動作 という作業を順に繰り返すようにした。" Three phases, repeated:

1. **sense** — once the set-point has not moved for ``settle_ms`` and the clavicle accelerometer reads
   |a| within 2 % of g (still), average it over ``window_ms``; the shoulders' roll is atan2(a_y, a_z)
   (:func:`~shintai.spine.actuators.tilt`);
2. **compute** — if |roll| > ``deadband_deg``, a whole-spine roll correction ΔΦ = −``gain``·roll, spread
   evenly over the joints (eq. 4.29's uniform bend), becomes muscle-length changes through the geometric
   model, Δλ = J_m ΔΘ (eq. 4.25's Jacobian at the basic posture), and encoder changes Δl = −Δλ (the encoder
   grows as the wire winds in, :mod:`shintai.spine.control`);
3. **move** — the correction is added to the muscles' targets over ``move_ms`` (a smooth step), then sense
   again.

The thesis computed the correction through its NN (muscle lengths → posture, §4.4.3); the Jacobian of the
model at the basic posture is used here (chosen: the correction is small and the loop repeats, so the
linearisation's error is corrected by the next cycle). Only the roll is levelled by default — "肩が水平" is
the shoulder line, and the pitch of a taught forward bend is a posture, not a tilt; ``axes=roll,pitch``
levels both. The contribution is a difference added to the target every packet (§6.2.4).
"""

from __future__ import annotations

import math

import numpy as np

from shintai.nervous.plugins.base import ADD, CommandError, Plugin
from shintai.nervous.protocol import fmt, number
from shintai.spine.actuators import tilt
from shintai.spine.geometry import uniform_posture

G = 9.81
TARGET_STILL = 1e-6  # units per packet: a set-point that moves less is holding (float noise of a hold)
STILL_FRACTION = 0.02  # chosen: |a| within 2 % of g counts as still (the self-motion §5.2.2 warns of)
DEFAULTS = {"gain": 0.8, "deadband_deg": 0.3, "settle_ms": 300.0, "window_ms": 100.0, "move_ms": 500.0,
            "max_deg": 30.0}  # chosen: the thesis prints no parameter of §5.2.2
LIMITS = {"gain": (0.0, 2.0), "deadband_deg": (0.0, 10.0), "settle_ms": (0.0, 1e4), "window_ms": (1.0, 1e4),
          "move_ms": (1.0, 1e4), "max_deg": (0.0, 90.0)}


class RotAdjust(Plugin):
    kind = ADD
    summary = "levels Cla's shoulders by the clavicle accelerometer: sense, compute, move (§5.2.2)"

    def __init__(self, host, instance, args):
        super().__init__(host, instance, [])
        spine = host.spine
        if spine is None or host.description.sensor("acc_chest") is None:
            raise CommandError(f"rotadjust: needs a spine robot with a clavicle accelerometer (acc_chest); "
                               f"{host.description.robot} has none")
        self.p = dict(DEFAULTS)
        self.axes = ("roll",)
        for arg in args:
            key, _, value = str(arg).partition("=")
            if key == "axes" and value in ("roll", "roll,pitch"):
                self.axes = tuple(value.split(","))
            elif key in LIMITS:
                self.p[key] = number(value, f"rotadjust {key}", *LIMITS[key])
            else:
                raise CommandError(f"rotadjust: unknown argument {str(arg)[:40]!r} ({', '.join(LIMITS)}, axes=roll|roll,pitch)")
        n = spine.n
        J = spine.model.jacobian(np.zeros(3 * n))  # dλ/dθ at the basic posture (eq. 4.25)
        # encoder change [mm] per radian of whole-spine roll and pitch
        self.per_rad = {axis: -1e3 * J @ uniform_posture(np.eye(3)[k], n) for k, axis in enumerate(("roll", "pitch"))}
        self.offset = np.zeros(host.description.n)
        self.corrections = 0
        self.last_tilt_deg = (math.nan, math.nan)

    def start(self, state):
        self.phase, self.t_phase = "settle", float(state["t"])
        self.samples: list[np.ndarray] = []
        self.last_target = None
        self.move_from = self.move_to = self.offset.copy()

    def process(self, state):
        t = float(state["t"])
        target = state.get("target")
        moving_target = (target is not None and self.last_target is not None
                         and np.abs(np.asarray(target) - self.last_target).max() > TARGET_STILL)
        self.last_target = None if target is None else np.array(target, dtype=float)
        acc = np.asarray(state["acc_chest"], dtype=float)
        still = abs(np.linalg.norm(acc) - G) < STILL_FRACTION * G and not moving_target
        if self.phase == "move":
            s = min((t - self.t_phase) / (1e-3 * self.p["move_ms"]), 1.0)
            s = s * s * (3 - 2 * s)
            self.offset = self.move_from + s * (self.move_to - self.move_from)
            if s >= 1.0:
                self.phase, self.t_phase = "settle", t
        elif not still:
            self.phase, self.t_phase, self.samples = "settle", t, []
        elif self.phase == "settle" and t - self.t_phase >= 1e-3 * self.p["settle_ms"]:
            self.phase, self.t_phase, self.samples = "sense", t, []
        elif self.phase == "sense":
            self.samples.append(acc)
            if t - self.t_phase >= 1e-3 * self.p["window_ms"]:
                self._compute(np.mean(self.samples, axis=0), t)
        return self.offset.copy()

    def _compute(self, acc, t: float) -> None:
        roll, pitch = tilt(acc)
        self.last_tilt_deg = (math.degrees(roll), math.degrees(pitch))
        change = np.zeros_like(self.offset)
        for axis, angle in zip(("roll", "pitch"), (roll, pitch)):
            if axis in self.axes and abs(angle) > math.radians(self.p["deadband_deg"]):
                change += -self.p["gain"] * angle * self.per_rad[axis]
        total = self._total_deg(self.offset + change)
        if total > self.p["max_deg"]:  # never bend the spine further than max_deg for levelling
            change *= max(0.0, (self.p["max_deg"] - self._total_deg(self.offset))) / max(total - self._total_deg(self.offset), 1e-9)
        if np.any(change):
            self.corrections += 1
            self.move_from, self.move_to = self.offset.copy(), self.offset + change
            self.phase, self.t_phase = "move", t
        else:
            self.phase, self.t_phase = "settle", t

    def _total_deg(self, offset) -> float:
        """How far the offset bends the spine (whole-spine roll, pitch), in degrees, by least squares."""
        A = np.stack([self.per_rad["roll"], self.per_rad["pitch"]], axis=1)
        angles, *_ = np.linalg.lstsq(A, offset, rcond=None)
        return float(np.degrees(np.linalg.norm(angles)))

    def cmd_set(self, args, call):
        """KEY VALUE — gain, deadband_deg, settle_ms, window_ms, move_ms, max_deg"""
        if len(args) != 2 or str(args[0]) not in LIMITS:
            raise CommandError(f"set: expected KEY VALUE with KEY one of {', '.join(LIMITS)}")
        self.p[str(args[0])] = number(args[1], f"rotadjust {args[0]}", *LIMITS[str(args[0])])

    def cmd_reset(self, args, call):
        """drop the correction (the spine returns to the played posture)"""
        self.offset = np.zeros_like(self.offset)
        self.move_from = self.move_to = self.offset.copy()
        self.phase = "settle"

    def cmd_status(self, args, call):
        """phase, corrections made, last measured tilt, the correction"""
        return self.describe()

    def describe(self) -> str:
        r, p = self.last_tilt_deg
        return (f"phase={getattr(self, 'phase', 'stopped')} corrections={self.corrections} tilt_deg={fmt(r)},{fmt(p)} "
                f"correction_deg={fmt(self._total_deg(self.offset))}")
