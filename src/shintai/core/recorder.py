"""Recorder: logs named signals per tick into arrays, for ``log.npz`` and plots.

Each signal keeps its own time base, so modules running at different periods (seed 000 §7.2,
seed 003 §6.3) can log at their own rate. ``arrays()`` returns ``{name: values, name + "_t": times}``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np


class Recorder:
    """Append-only store of named time series."""

    def __init__(self) -> None:
        self._values: dict[str, list] = {}
        self._times: dict[str, list[float]] = {}

    def record(self, t: float, **signals) -> None:
        """Log each keyword as one sample of the signal of that name at time ``t``."""
        for name, value in signals.items():
            if name not in self._values:
                self._values[name] = []
                self._times[name] = []
            self._values[name].append(np.array(value, dtype=float, copy=True))
            self._times[name].append(float(t))

    def __contains__(self, name: str) -> bool:
        return name in self._values

    def __len__(self) -> int:
        return len(self._values)

    def names(self) -> list[str]:
        return list(self._values)

    def values(self, name: str) -> np.ndarray:
        """All samples of ``name`` stacked along axis 0."""
        return np.asarray(self._values[name])

    def times(self, name: str) -> np.ndarray:
        return np.asarray(self._times[name])

    def arrays(self) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = {}
        for name in self._values:
            out[name] = self.values(name)
            out[name + "_t"] = self.times(name)
        return out

    def merge(self, other: Recorder, prefix: str = "") -> None:
        """Append every signal of ``other`` under ``prefix + name``."""
        for name in other._values:
            key = prefix + name
            self._values.setdefault(key, []).extend(other._values[name])
            self._times.setdefault(key, []).extend(other._times[name])

    def save(self, path: str | Path) -> None:
        """Write every signal into one compressed ``.npz`` (also when nothing was logged)."""
        np.savez_compressed(path, **self.arrays())
