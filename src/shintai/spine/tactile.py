"""Push teaching triggers of seed 003 §5.9.3, felt through the muscles of a spine with no touch sensor.

The thesis (Kenta, §5.9.3): analog touch sensors, two per joint DOF, "±roll, pitch, yaw" at both ends of the
spine; "強く押されたかどうかによって挙動を変える":

* "弱く押されたときは相対的な姿勢の指示": from the current posture (for the spine: estimated by the NN of
  §4.4.3) the corresponding axis is changed "センサを押す力に応じた角度だけ", target lengths by §4.4.2 (eq. 4.25),
  controlled by §4.7's mode rules — :func:`nudge_target`;
* "強く押されたときは … 関わりのある関節の全筋を一定張力制御モード (T 制御) にする。するとその関節は脱力状態になり、
  人間の力でその関節を直接動かすことで教示を行う".

Cla, the body this runs on, has no touch sensor (the thesis's Cla senses posture by accelerometers, length by
encoders and tension by sensors, §3.6). A push on its shoulders is felt instead through the tension sensors
while the muscles hold their lengths (L mode): the push's moment about the spine is balanced by the change of
the muscle tensions, so with the moment arms of the uniform bend, J = ∂λ/∂Θ (m × 3, eq. 4.25 differentiated),

    τ̂ = Jᵀ (T − T_base)        [N m, about the whole-spine roll, pitch, yaw axes]

(a muscle pulls to shorten λ; a push that bends +Θ stretches the muscles with ∂λ/∂Θ > 0). T_base is the
tension the spine held before the push. τ̂'s six signed components stand for the thesis's six sensors at one
end of the spine; the largest is "the sensor pressed". Levels, gain and timing are not in the text:
:class:`TriggerLevels` documents the chosen values.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shintai.spine.geometry import SpineModel, uniform_posture

WEAK, STRONG = "weak", "strong"


def moment_arms(model: SpineModel, whole, eps: float = 1e-4) -> np.ndarray:
    """J = ∂λ/∂Θ (m, 3) of the uniform bend (eq. 4.29) at whole-spine angles Θ, by central differences of
    eq. 4.25."""
    whole = np.asarray(whole, dtype=float)
    cols = []
    for axis in range(3):
        d = np.zeros(3)
        d[axis] = eps
        cols.append((model.lengths(uniform_posture(whole + d, model.n))
                     - model.lengths(uniform_posture(whole - d, model.n))) / (2 * eps))
    return np.array(cols).T


def push_moment(arms: np.ndarray, tension, base) -> np.ndarray:
    """τ̂ = Jᵀ (T − T_base) [N m] (module doc)."""
    return arms.T @ (np.asarray(tension, dtype=float) - np.asarray(base, dtype=float))


@dataclass(frozen=True)
class TriggerLevels:
    """The trigger's constants — none is in the thesis ("弱く" / "強く" only); chosen as stated.

    ``weak_nm``: a push starts when |τ̂| reaches it — chosen at 0.15 N m, three times the largest |τ̂| Cla
    showed holding still after a push had been released (≈ 0.05 N m: reel friction keeps some tension;
    a probe of 3–30 N shoulder pushes, notes). ``strong_nm``: a strong push — chosen at 0.6 N m, what a
    ~20 N shoulder push gave in L mode (a firm hand), and well under the 3 N m at which 30 N folded the
    spine 55°. ``gain_deg_per_nm``: the weak push's angle per N m of peak push (chosen: a 0.3 N m push
    turns the spine 6°), at most ``max_nudge_deg`` (chosen 10°). ``release``: the push has ended when |τ̂|
    falls below this fraction of its peak (chosen 0.5; a fixed level would be crossed by the tension reel
    friction leaves). ``min_push_s``: shorter pushes are ignored (chosen 40 ms, two 20 ms samples)."""

    weak_nm: float = 0.15
    strong_nm: float = 0.6
    gain_deg_per_nm: float = 20.0
    max_nudge_deg: float = 10.0
    release: float = 0.5
    min_push_s: float = 0.04

    def __post_init__(self):
        if not 0 < self.weak_nm < self.strong_nm:
            raise ValueError(f"trigger levels: need 0 < weak_nm < strong_nm, got {self.weak_nm}, {self.strong_nm}")


@dataclass
class Fired:
    """A trigger that fired: its level, when, the pressed axis (0 roll, 1 pitch, 2 yaw) and sign, the peak
    |τ̂| [N m] and, for a weak push, the nudge angle [deg]."""

    level: str
    t: float
    axis: int
    sign: float
    peak_nm: float
    nudge_deg: float = 0.0


class PushTrigger:
    """The two-level trigger on the stream of τ̂ (call :meth:`update` every sample while armed).

    A push starts when |τ̂| ≥ weak; it fires STRONG the moment |τ̂| ≥ strong; otherwise, when it ends (|τ̂|
    below ``release`` × its peak) after at least ``min_push_s``, it fires WEAK with the axis and sign of the
    largest component at the peak and a nudge of gain × peak. After a strong push nothing fires until |τ̂| has
    fallen below the weak level (the same push is not felt twice)."""

    def __init__(self, levels: TriggerLevels = TriggerLevels()):
        self.levels = levels
        self.reset()

    def reset(self, latched: bool = False) -> None:
        self.latched = latched  # after a strong push: nothing until |τ̂| falls below the weak level
        self.start: float | None = None
        self.peak = 0.0
        self.peak_tau = np.zeros(3)

    def update(self, tau, t: float) -> Fired | None:
        lv = self.levels
        tau = np.asarray(tau, dtype=float)
        size = float(np.linalg.norm(tau))
        if self.latched:
            self.latched = size >= lv.weak_nm
            return None
        if self.start is None:
            if size < lv.weak_nm:
                return None
            self.start = t
        if size > self.peak:
            self.peak, self.peak_tau = size, tau.copy()
        axis = int(np.argmax(np.abs(self.peak_tau)))
        sign = float(np.sign(self.peak_tau[axis]))
        if size >= lv.strong_nm:
            fired = Fired(STRONG, t, axis, sign, self.peak)
            self.reset(latched=True)
            return fired
        if size < lv.release * self.peak:
            long_enough = t - self.start >= lv.min_push_s
            fired = Fired(WEAK, t, axis, sign, self.peak, min(lv.gain_deg_per_nm * self.peak, lv.max_nudge_deg))
            self.reset()
            return fired if long_enough else None
        return None


def nudge_target(model: SpineModel, estimate_whole, fired: Fired) -> tuple[np.ndarray, np.ndarray]:
    """§5.9.3's weak push: the estimated whole-spine posture Θ (from the NN) changed by the nudge on the
    pressed axis, as target muscle lengths by eq. 4.25 of the uniform bend; returns (lengths (m,), Θ')."""
    whole = np.asarray(estimate_whole, dtype=float).copy()
    whole[fired.axis] += fired.sign * np.radians(fired.nudge_deg)
    return model.lengths(uniform_posture(whole, model.n)), whole
