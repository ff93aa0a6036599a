"""Cla's hand-made behaviours as posture sequences (seed 003 §5.2, §6.5): "ここまでの実験は全て人が動作パターンを
EusLisp のモデル上で作成し, それを実ロボット Cla で実行していた" (§5.2.9) — each behaviour is a list of key postures
(joint-angle vectors, §6.1.3 "関節角度列による姿勢表現") sent one after another with a time to reach each, which the
nervous sequence plugin interpolates by minimum jerk (§6.3.4; :class:`~shintai.core.interpolation.SequencePlayer`).

:class:`Key` is one key posture (only the joints it names change; the rest hold), :class:`KeyframePlayer` plays
a list of them as a module writing the whole joint vector to one channel, and says which key it is in.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from shintai.core.interpolation import SequencePlayer
from shintai.core.runtime import Snapshot
from shintai.spine.control import encoder_targets
from shintai.spine.geometry import uniform_posture


@dataclass(frozen=True)
class Key:
    """A key posture reached in ``duration_s`` [s]: ``targets`` joint name → angle [rad] (joints not named
    keep the previous key's angle); ``label`` names the step (for plots and metrics)."""

    duration_s: float
    targets: Mapping[str, float] = field(default_factory=dict)
    label: str = ""


def key_vectors(names: Sequence[str], start: Mapping[str, float], keys: Sequence[Key]) -> np.ndarray:
    """The full joint vector (len(names),) of every key, in turn (k × n): each key changes only what it names."""
    index = {n: i for i, n in enumerate(names)}
    x = np.array([float(start.get(n, 0.0)) for n in names])
    out = []
    for key in keys:
        unknown = set(key.targets) - set(index)
        if unknown:
            raise ValueError(f"key {key.label!r} names unknown joints {sorted(unknown)}; valid: {', '.join(names)}")
        x = x.copy()
        for n, v in key.targets.items():
            x[index[n]] = v
        out.append(x)
    return np.array(out).reshape(len(keys), len(names))


def key_times(keys: Sequence[Key]) -> np.ndarray:
    """When each key is reached [s from the sequence's start] (its cumulative durations)."""
    return np.cumsum([k.duration_s for k in keys])


class KeyframePlayer(SequencePlayer):
    """Plays ``keys`` from ``start`` by minimum jerk (the seqplugin player), writing the joint vector to
    ``channel``; ``label`` is the key being moved to (the last one once it is reached), ``names`` the
    joints of the vector."""

    def __init__(self, names: Sequence[str], start: Mapping[str, float], keys: Sequence[Key],
                 channel: str = "pose", name: str = "keyframes", period: float | None = None):
        self.names = tuple(names)
        self.keys = tuple(keys)
        self.vectors = key_vectors(self.names, start, self.keys)
        self.times = key_times(self.keys)
        x0 = np.array([float(start.get(n, 0.0)) for n in self.names])
        super().__init__(x0, method="minjerk", channel=channel, name=name, period=period)
        self._x0 = x0

    def reset(self, snapshot: Snapshot) -> None:
        super().reset(snapshot)
        self._t0 = float(snapshot["t"])
        self.x, self.v, self.a = self._x0.copy(), np.zeros_like(self._x0), np.zeros_like(self._x0)
        self.clear()
        for key, vec in zip(self.keys, self.vectors):
            self.push(vec, key.duration_s)

    def step_index(self, t: float) -> int:
        """The index of the key being moved to at time ``t`` (len(keys) − 1 after the last)."""
        return int(min(np.searchsorted(self.times, t - self._t0, side="right"), len(self.keys) - 1))

    def label(self, t: float) -> str:
        return self.keys[self.step_index(t)].label

    def value(self, joint: str) -> float:
        return float(self.x[self.names.index(joint)])


SPINE_AXES = ("spine_roll", "spine_pitch", "spine_yaw")  # the whole-spine Θ = (φ_s, θ_s, ψ_s) of a key [rad]


class WholeBodyKeys(KeyframePlayer):
    """Keys over the whole-spine posture (:data:`SPINE_AXES`, a uniform bend, eq. 4.29) and the limb servos
    (``limbs``: actuator names of :mod:`~shintai.spine.cla.body`). Each tick it writes every limb servo's
    target and, from the spine part, the muscles' encoder targets (eq. 4.25 lengths of the uniform bend
    against the lengths at the calibration posture ``zero_lengths``: ``l_r`` and ``l_0``) for the muscle
    controller of the next stage — as :class:`~shintai.spine.cla.postures.PostureTargets` does, but with the spine
    and the limbs on one minimum-jerk sequence, as one EusLisp angle vector is (§6.5)."""

    def __init__(self, model, zero_lengths, limbs, start: Mapping[str, float], keys: Sequence[Key],
                 name: str = "keys"):
        super().__init__(SPINE_AXES + tuple(limbs), start, keys, channel="pose", name=name)
        self.spine_model, self.zero = model, np.asarray(zero_lengths, dtype=float)
        self.limbs = tuple(limbs)

    def update(self, snapshot: Snapshot):
        x = super().update(snapshot)["pose"]
        l_r = encoder_targets(self.spine_model.lengths(uniform_posture(x[:3], self.spine_model.n)), self.zero)
        return {"l_r": l_r, "l_0": l_r, **{j: float(v) for j, v in zip(self.limbs, x[3:])}}
