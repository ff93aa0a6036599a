"""Recorder: logs named signals per tick into arrays, for ``log.npz`` and plots.

Each signal keeps its own time base, so modules running at different periods (seed 000 §7.2,
seed 003 §6.3) can log at their own rate. ``arrays()`` returns ``{name: values, name + "_t": times}``.

A signal is a :class:`_Column`: float rows of the shape of its first sample, written in place into a
preallocated block that doubles when full, so a tick's logging allocates nothing (the tricycle logs a
dozen signals every 4 ms control tick).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

_FIRST_ROWS = 1024  # rows a new column holds before it first doubles
_PLAIN_NUMBERS = (int, bool)  # scalars a float64 row takes as np.array(value, dtype=float) would convert them


class _Column:
    """One signal: ``n`` samples (rows of ``shape``) and their times, in blocks grown by doubling."""

    __slots__ = ("shape", "rows", "times", "n", "capacity")

    def __init__(self, shape: tuple, capacity: int = _FIRST_ROWS):
        self.shape = shape
        self.rows = np.empty((capacity, *shape))
        self.times = np.empty(capacity)
        self.n, self.capacity = 0, capacity

    def row(self, value):
        """``value`` as a row of this column: a float array of its shape (a sample of another shape is an error)."""
        value = np.asarray(value, dtype=float)
        if value.shape != self.shape:
            raise ValueError(f"a signal's samples keep the shape of its first one, {self.shape}; got {value.shape}")
        return value

    def extend(self, other: _Column) -> None:
        if other.shape != self.shape:
            raise ValueError(f"merged signals differ in shape: {self.shape} and {other.shape}")
        if self.n + other.n > self.capacity:
            self.grow(max(2 * self.capacity, self.n + other.n))
        self.rows[self.n:self.n + other.n] = other.rows[:other.n]
        self.times[self.n:self.n + other.n] = other.times[:other.n]
        self.n += other.n

    def grow(self, capacity: int) -> None:
        rows, times = np.empty((capacity, *self.shape)), np.empty(capacity)
        rows[:self.n], times[:self.n] = self.rows[:self.n], self.times[:self.n]
        self.rows, self.times, self.capacity = rows, times, capacity


class Recorder:
    """Append-only store of named time series."""

    def __init__(self) -> None:
        self._columns: dict[str, _Column] = {}

    def record(self, t: float, **signals) -> None:
        """Log each keyword as one sample of the signal of that name at time ``t``."""
        t = float(t)
        columns = self._columns
        for name, value in signals.items():
            c = columns.get(name)
            if c is None:
                c = columns[name] = _Column(np.shape(value))
            n = c.n
            if n == c.capacity:
                c.grow(2 * n)
            # a float (np.float64 too), int or bool into a scalar column, an array of the column's shape as it is:
            # written with the same conversion to float64 as np.array(value, dtype=float); anything else checked first
            if not (c.shape == () and (isinstance(value, float) or type(value) in _PLAIN_NUMBERS)
                    or type(value) is np.ndarray and value.shape == c.shape):
                value = c.row(value)
            c.rows[n] = value
            c.times[n] = t
            c.n = n + 1

    def __contains__(self, name: str) -> bool:
        return name in self._columns

    def __len__(self) -> int:
        return len(self._columns)

    def names(self) -> list[str]:
        return list(self._columns)

    def values(self, name: str) -> np.ndarray:
        """All samples of ``name`` stacked along axis 0 (a copy)."""
        column = self._columns[name]
        return column.rows[:column.n].copy()

    def times(self, name: str) -> np.ndarray:
        column = self._columns[name]
        return column.times[:column.n].copy()

    def arrays(self) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = {}
        for name in self._columns:
            out[name] = self.values(name)
            out[name + "_t"] = self.times(name)
        return out

    def merge(self, other: Recorder, prefix: str = "") -> None:
        """Append every signal of ``other`` under ``prefix + name``."""
        for name, column in other._columns.items():
            mine = self._columns.get(prefix + name)
            if mine is None:
                mine = self._columns[prefix + name] = _Column(column.shape, max(column.n, 1))
            mine.extend(column)

    def save(self, path: str | Path) -> None:
        """Write every signal into one compressed ``.npz`` (also when nothing was logged)."""
        np.savez_compressed(path, **self.arrays())
