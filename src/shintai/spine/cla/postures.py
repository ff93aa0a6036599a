"""E11's posture protocol (seed 003 §4.7.2, Appendix A.1.3): uniform-bend postures commanded one after
another, played to the muscle controller, and measured.

* :class:`PostureTargets` — the seqplugin player: a goal Θ = (φ_s, θ_s, ψ_s) arriving on the ``goal``
  channel is reached with minimum jerk in ``move_s``; each tick the model's lengths (eq. 4.25) of the
  player's posture become the encoder targets ``l_r`` (and S mode's natural lengths ``l_0``) that the
  muscle controller reads in the next stage; ``whole_ref`` carries the player's posture for observers.
* :class:`PostureObserver` — per commanded posture: the moving and holding part (the largest fall off
  the reference, whether a joint reached its stop, the current) and the static measuring window at its
  end (the accelerometer angle of eq. 3.4, tension, current, sway, and whether the spine is still moving
  away from the reference) → a :class:`PostureRow` with three hold tests (:data:`HOLD_TESTS`); the
  sequence stops once every test has lost a posture (the thesis's "—": the experimenter caught the spine).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shintai.core.constants import KGF_N
from shintai.core.interpolation import SequencePlayer
from shintai.core.runtime import SET, Channel, Module, Snapshot
from shintai.spine.control import encoder_targets
from shintai.spine.geometry import SpineModel, uniform_posture, whole_spine
from shintai.spine.robots import HOLD_FALL_DEG, HOLD_LIMIT_DEG, RANGE_END_MARGIN_DEG, REST_DRIFT_DEG

GOAL = Channel("goal", SET, doc="the next uniform-bend posture Θ = (φ_s, θ_s, ψ_s) [rad], on the tick it is "
                                "commanded")
WHOLE_REF = Channel("whole_ref", SET, doc="the posture player's whole-spine reference Θ this tick [rad]")

# The hold tests of a posture (robots.py): ``held`` — the thesis's criterion as a
# simulation can apply it: the spine came to rest at the posture (no joint at its stop while commanded, not
# still moving away from the reference at the end of the hold); ``held_fall30`` — the earlier 30° rule;
# ``held_window`` — the window-only test. Only ``held`` decides Table 4.8's columns.
HOLD_TESTS = ("held", "held_fall30", "held_window")


def axis_sequence(max_deg: int) -> list[int]:
    """§4.7.2's sequence 0 → −10 → … → −max → … → +max → … → 0 in 10° steps."""
    down = list(range(0, -max_deg - 1, -10))
    up = list(range(-max_deg + 10, max_deg + 1, 10))
    back = list(range(max_deg - 10, -1, -10))
    return down + up + back


class PostureTargets(Module):
    """Uniform-bend posture commands (Appendix A.1.3) through the seqplugin player (module doc). While
    idle (the targets already set) the player is not stepped, only its clock kept, and ``l_r``/``l_0``
    are not written (the controller keeps them)."""

    def __init__(self, model: SpineModel, zero_lengths, move_s: float, name: str = "posture"):
        super().__init__(name)
        self.model, self.zero, self.move_s = model, np.asarray(zero_lengths, dtype=float), move_s
        self.player = SequencePlayer(np.zeros(3), method="minjerk", channel="whole")
        self._idle: dict | None = None

    def reset(self, snapshot: Snapshot) -> None:
        self.player.reset(snapshot)

    def update(self, snapshot: Snapshot):
        goal = snapshot.get("goal")
        if goal is not None:
            self.player.push(goal, self.move_s)
            self._idle = None
        busy = self.player.busy
        if not busy and self._idle is not None:
            self.player.reset(snapshot)  # nothing moves; keep the player's clock
            return self._idle
        whole = self.player.update(snapshot)["whole"]
        l_r = encoder_targets(self.model.lengths(uniform_posture(whole, self.model.n)), self.zero)
        self._idle = None if busy else {"whole_ref": whole}
        return {"l_r": l_r, "l_0": l_r, "whole_ref": whole}


@dataclass
class PostureRow:
    """One commanded posture of §4.7.2's sequence and what the spine did there."""

    target_deg: float
    measured_deg: float
    error_deg: float
    worst_deg: float  # largest |true whole-spine angle − target| during the window
    sway_deg: float  # standard deviation of the true whole-spine angle during the window
    held: bool  # came to rest: not range_end and drift_deg ≤ REST_DRIFT_DEG (the thesis's criterion, robots.py)
    tension_kgf: float  # mean over the 8 muscles and the measuring window
    current_a: float  # mean |I| over the 8 muscles and the window
    worst_posture_deg: float = float("nan")  # largest |true angle − reference| over the whole posture
    held_window: bool = True  # the window-only test: error ≤ HOLD_LIMIT_DEG and worst_deg ≤ HOLD_FALL_DEG
    current_posture_a: float = float("nan")  # mean |I| over the 8 muscles and the whole posture
    held_fall30: bool = True  # the 30° rule: error ≤ HOLD_LIMIT_DEG and worst_posture_deg ≤ HOLD_FALL_DEG
    range_end: bool = False  # a joint came within RANGE_END_MARGIN_DEG of its stop while the posture was commanded
    drift_deg: float = 0.0  # growth of |Θ_true − Θ_ref| across the window (mean of its last fifth − first fifth)
    range_end_joint: int = -1  # the first joint direction (index into θ, 3 per joint: roll, pitch, yaw) at its stop


class PostureObserver(Module):
    """Measures each posture of the sequence (module doc) from the snapshot and ``whole_ref``.

    Timing in ticks: ``settle`` before the first posture, then per posture ``moving`` ticks (move and
    hold) and ``window`` ticks of static measurement; ``targets_deg`` are the commanded angles about
    ``axis`` (0 roll, 1 pitch). With ``log_every``, the accelerometer angle averaged over that many
    ticks, the reference and the mean tension are logged during the moving part. ``limits_rad``: the
    joints' stops (3n,), for the range-end test (None: no stops). ``stopped`` is set at the end of the
    posture by which every hold test has lost one (or the last); ``picture_due`` at the end of the posture
    at ``picture_deg``.
    """

    def __init__(self, axis: int, targets_deg, settle: int, moving: int, window: int, log_every: int | None = None,
                 picture_deg: float | None = None, limits_rad=None, name: str = "observer"):
        super().__init__(name)
        self.axis, self.targets = axis, list(targets_deg)
        self.settle, self.moving, self.window = settle, moving, window
        self.log_every, self.picture_deg = log_every, picture_deg
        self.stops = None if limits_rad is None else np.abs(np.asarray(limits_rad, dtype=float)) - math.radians(
            RANGE_END_MARGIN_DEG)
        self.rows: list[PostureRow] = []
        self.k, self.stopped, self.picture_due = 0, False, False
        self.picture: dict | None = None  # what the rig captured when picture_due (modes.mode_rig)

    def update(self, snapshot: Snapshot):
        k, self.k = self.k - self.settle, self.k + 1
        if k < 0 or k >= len(self.targets) * (self.moving + self.window):  # before the first, after the last
            return None
        r = k % (self.moving + self.window)
        if r == 0:
            self.worst, self.current, self.acc, self.range_end, self.range_end_joint = 0.0, 0.0, 0.0, False, -1
            self.w_posture, self.w_tension, self.w_current, self.w_true, self.w_off = 0.0, 0.0, 0.0, [], []
        axis, snap = self.axis, snapshot
        theta = snap["theta"]
        if self.stops is not None and not self.range_end:
            at_stop = np.abs(theta) >= self.stops
            if at_stop.any():
                self.range_end, self.range_end_joint = True, int(at_stop.argmax())
        # means over the muscles as sum / count: np.mean's own arithmetic, without its overhead
        current = float(np.abs(snap["current"]).sum()) / snap["current"].size
        if r < self.moving:
            self.worst = max(self.worst, abs(math.degrees(float(theta[axis::3].sum()) - snap["whole_ref"][axis])))
            self.current += current
            if self.log_every is not None:
                self.acc += snap["posture"][axis]
                if (r + 1) % self.log_every == 0:
                    self.log(snap["t"], measured_deg=np.degrees(self.acc / self.log_every),
                             reference_deg=np.degrees(snap["whole_ref"][axis]),
                             tension_kgf=float(snap["tension_true"].sum()) / snap["tension_true"].size / KGF_N)
                    self.acc = 0.0
            return None
        self.w_posture += snap["posture"][axis]
        self.w_tension += float(snap["tension_true"].sum()) / snap["tension_true"].size
        self.w_current += current
        whole = whole_spine(theta)
        self.w_true.append(math.degrees(float(whole[axis])))
        self.w_off.append(math.degrees(float(np.linalg.norm(whole - snap["whole_ref"]))))
        if r == self.moving + self.window - 1:
            self._row(self.targets[k // (self.moving + self.window)])
        return None

    def _row(self, target: float) -> None:
        n = self.window
        measured = float(np.degrees(self.w_posture / n))
        true = np.array(self.w_true)
        w_current = self.w_current / n
        error = abs(measured - target)
        worst = float(np.abs(true - target).max())
        worst_posture = max(self.worst, worst)
        ok = bool(np.isfinite(error) and error <= HOLD_LIMIT_DEG)
        held_window = ok and worst <= HOLD_FALL_DEG
        held_fall30 = ok and worst_posture <= HOLD_FALL_DEG
        fifth = max(1, n // 5)
        drift = float(np.mean(self.w_off[-fifth:]) - np.mean(self.w_off[:fifth]))
        held = not self.range_end and bool(np.isfinite(drift)) and drift <= REST_DRIFT_DEG
        current_posture = (self.current + w_current * n) / (self.moving + n)
        self.rows.append(PostureRow(target, measured, error, worst, float(np.std(true)), held,
                                    self.w_tension / n / KGF_N, w_current, worst_posture, held_window,
                                    current_posture, held_fall30, self.range_end, drift, self.range_end_joint))
        self.picture_due = target == self.picture_deg
        every_test_lost = all(any(not getattr(row, test) for row in self.rows) for test in HOLD_TESTS)
        self.stopped = every_test_lost or len(self.rows) == len(self.targets)
