"""BVH motion-capture files (seed 003 §5.8.2): a strict reader, a writer and forward kinematics.

§5.8.2 describes the format: "HIERARCHY" with nested ``{ }`` links, ``OFFSET X Y Z`` (the initial relative
displacement of adjacent links), ``CHANNELS n …`` (the DOFs between links, in any order, e.g. ``Zrotation
Xrotation Yrotation``), then "MOTION" with the frame count, the frame time and one line of values per frame.

Why a reader of our own, not ``pybvh`` or ``bvhio``: ``notes/bvh-retarget.md``.

Conventions (the de-facto BVH ones): angles in degrees in the file, rotation channels composed in the order
listed (``Zrotation Xrotation Yrotation`` → R = Rz·Rx·Ry, intrinsic), a joint's position in its parent's frame
is ``OFFSET`` + its position channels, a child's world frame is its parent's times its local rotation.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

AXES = {"X": 0, "Y": 1, "Z": 2}
CHANNEL_NAMES = tuple(f"{a}{kind}" for kind in ("position", "rotation") for a in "XYZ")


class BvhError(ValueError):
    """A malformed BVH file: ``str()`` is one line, ``FILE:LINE: expected …, got …``."""


@dataclass
class Joint:
    name: str
    parent: int  # index into Bvh.joints, −1 for the root
    offset: np.ndarray  # (3,)
    channels: tuple[str, ...]
    end_site: np.ndarray | None = None  # offset of the End Site, if any
    first_column: int = 0  # its first channel's column in Bvh.frames


@dataclass
class Bvh:
    joints: list[Joint]
    frames: np.ndarray  # (F, total channels), as in the file (degrees, file units)
    frame_time_s: float
    source: str = ""
    _index: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        self._index = {j.name: i for i, j in enumerate(self.joints)}

    @property
    def n_frames(self) -> int:
        return self.frames.shape[0]

    @property
    def n_channels(self) -> int:
        return sum(len(j.channels) for j in self.joints)

    @property
    def times_s(self) -> np.ndarray:
        return np.arange(self.n_frames) * self.frame_time_s

    def joint(self, name: str) -> Joint:
        if name not in self._index:
            raise KeyError(f"{self.source or 'BVH'}: no joint {name!r} (joints: {', '.join(self._index)})")
        return self.joints[self._index[name]]

    def channel(self, joint: str, channel: str) -> np.ndarray:
        """One channel of one joint over all frames, e.g. ``channel("Chest", "Yrotation")`` [deg]."""
        j = self.joint(joint)
        return self.frames[:, j.first_column + j.channels.index(channel)]

    def local_rotations(self, name: str) -> np.ndarray:
        """(F, 3, 3) rotation of joint ``name`` relative to its parent, channels composed in file order."""
        j = self.joint(name)
        R = np.broadcast_to(np.eye(3), (self.n_frames, 3, 3)).copy()
        for k, ch in enumerate(j.channels):
            if ch.endswith("rotation"):
                R = R @ axis_rotation(ch[0], np.radians(self.frames[:, j.first_column + k]))
        return R

    def local_translation(self, name: str) -> np.ndarray:
        """(F, 3): OFFSET plus the joint's position channels."""
        j = self.joint(name)
        p = np.broadcast_to(j.offset, (self.n_frames, 3)).copy()
        for k, ch in enumerate(j.channels):
            if ch.endswith("position"):
                p[:, AXES[ch[0]]] += self.frames[:, j.first_column + k]
        return p

    def world(self) -> tuple[np.ndarray, np.ndarray]:
        """Forward kinematics: world rotations (F, J, 3, 3) and positions (F, J, 3) of every joint."""
        F, J = self.n_frames, len(self.joints)
        R = np.empty((F, J, 3, 3))
        p = np.empty((F, J, 3))
        for i, j in enumerate(self.joints):  # parents come before children in file order
            local_R, local_p = self.local_rotations(j.name), self.local_translation(j.name)
            if j.parent < 0:
                R[:, i], p[:, i] = local_R, local_p
            else:
                R[:, i] = R[:, j.parent] @ local_R
                p[:, i] = p[:, j.parent] + np.einsum("fab,fb->fa", R[:, j.parent], local_p)
        return R, p


def axis_rotation(axis: str, angle) -> np.ndarray:
    """(…, 3, 3) rotation by ``angle`` [rad] about the X, Y or Z axis."""
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    R = np.zeros(angle.shape + (3, 3))
    a = AXES[axis]
    b, d = (a + 1) % 3, (a + 2) % 3
    R[..., a, a] = 1.0
    R[..., b, b] = c
    R[..., d, d] = c
    R[..., d, b] = s
    R[..., b, d] = -s
    return R


class _Tokens:
    """The file as (line number, words) with one-line errors."""

    def __init__(self, text: str, source: str):
        self.lines = [(i + 1, line.split()) for i, line in enumerate(text.splitlines()) if line.strip()]
        self.pos = 0
        self.source = source
        self.last_line = len(text.splitlines())

    def error(self, expected: str, line: int | None = None, got: str | None = None) -> BvhError:
        if line is None:
            line, words = self.lines[self.pos] if self.pos < len(self.lines) else (self.last_line, None)
            got = got if got is not None else (" ".join(words) if words else "the end of the file")
        return BvhError(f"{self.source}:{line}: expected {expected}, got {got!r}"[:300])

    def peek(self) -> list[str] | None:
        return self.lines[self.pos][1] if self.pos < len(self.lines) else None

    def take(self, expected: str, first: str | None = None, n_words: int | None = None) -> tuple[int, list[str]]:
        words = self.peek()
        if (words is None or (first is not None and words[0] != first)
                or (n_words is not None and len(words) != n_words)):
            raise self.error(expected)
        line = self.lines[self.pos][0]
        self.pos += 1
        return line, words

    def numbers(self, words: list[str], line: int, expected: str) -> list[float]:
        try:
            values = [float(w) for w in words]
        except ValueError:
            raise self.error(expected, line, " ".join(words)) from None
        if not all(np.isfinite(values)):
            raise self.error(expected + " (finite)", line, " ".join(words))
        return values


def parse(text: str, source: str = "<bvh>") -> Bvh:
    """Parse BVH text; :class:`BvhError` (one line) on anything malformed."""
    tok = _Tokens(text, source)
    tok.take("'HIERARCHY'", "HIERARCHY", 1)
    joints: list[Joint] = []
    column = 0

    def node(parent: int) -> None:
        nonlocal column
        keyword = "ROOT" if parent < 0 else "JOINT"
        line, words = tok.take(f"'{keyword} name'", keyword)
        if len(words) != 2:
            raise tok.error(f"one joint name after {keyword}", line, " ".join(words))
        name = words[1]
        if any(j.name == name for j in joints):
            raise tok.error(f"a joint name not used before ({name!r} is)", line, " ".join(words))
        tok.take("'{'", "{", 1)
        line, words = tok.take("'OFFSET x y z'", "OFFSET", 4)
        offset = np.array(tok.numbers(words[1:], line, "three numbers after OFFSET"))
        line, words = tok.take("'CHANNELS n name…'", "CHANNELS")
        if len(words) < 2 or not words[1].isdigit() or int(words[1]) != len(words) - 2:
            raise tok.error("'CHANNELS n' followed by n channel names", line, " ".join(words))
        if any(w not in CHANNEL_NAMES for w in words[2:]) or len(set(words[2:])) != len(words) - 2:
            raise tok.error("distinct channels among " + " ".join(CHANNEL_NAMES), line, " ".join(words))
        index = len(joints)
        joints.append(Joint(name, parent, offset, tuple(words[2:]), first_column=column))
        column += len(words) - 2
        while True:
            words = tok.peek()
            if words is not None and words[0] == "JOINT":
                node(index)
            elif words == ["End", "Site"]:
                tok.take("'End Site'")
                tok.take("'{'", "{", 1)
                line, words = tok.take("'OFFSET x y z'", "OFFSET", 4)
                joints[index].end_site = np.array(tok.numbers(words[1:], line, "three numbers after OFFSET"))
                tok.take("'}'", "}", 1)
            elif words == ["}"]:
                tok.take("'}'")
                return
            else:
                raise tok.error(f"'JOINT name', 'End Site' or '}}' in {name}")

    node(-1)
    if tok.peek() is not None and tok.peek()[0] == "ROOT":
        raise tok.error("'MOTION' (one ROOT per file)")
    tok.take("'MOTION'", "MOTION", 1)
    line, words = tok.take("'Frames: n'", "Frames:", 2)
    if not words[1].isdigit():
        raise tok.error("'Frames: n' with a whole number n", line, " ".join(words))
    n_frames = int(words[1])
    line, words = tok.take("'Frame Time: seconds'", "Frame", 3)
    if words[1] != "Time:":
        raise tok.error("'Frame Time: seconds'", line, " ".join(words))
    (frame_time,) = tok.numbers(words[2:], line, "a frame time in seconds")
    if frame_time <= 0:
        raise tok.error("a positive frame time", line, " ".join(words))
    rows = []
    for k in range(n_frames):
        words = tok.peek()
        if words is None:
            raise tok.error(f"frame {k + 1} of {n_frames} ({column} values)")
        line, words = tok.take("")
        if len(words) != column:
            raise tok.error(f"{column} values in frame {k + 1} (the channels of the hierarchy)", line,
                            f"{len(words)} values")
        rows.append(tok.numbers(words, line, f"{column} numbers in frame {k + 1}"))
    if tok.peek() is not None:
        raise tok.error(f"the end of the file after {n_frames} frames ('Frames: {n_frames}')")
    frames = np.array(rows, dtype=float).reshape(n_frames, column)
    return Bvh(joints, frames, frame_time, source)


def read(path: str | Path) -> Bvh:
    """Read a BVH file; :class:`BvhError` (one line) for a missing, unreadable or malformed file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8", errors="strict")
    except FileNotFoundError:
        raise BvhError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise BvhError(f"{path}: cannot be read as text ({type(exc).__name__})") from None
    return parse(text, str(path))


def dumps(bvh: Bvh, decimals: int = 4) -> str:
    """BVH text of ``bvh`` (tabs for nesting, values at ``decimals`` places, no ``-0``)."""
    children: dict[int, list[int]] = {}
    for i, j in enumerate(bvh.joints):
        children.setdefault(j.parent, []).append(i)

    def num(v: float) -> str:
        text = f"{round(float(v), decimals) + 0.0:.{decimals}f}"
        return text[1:] if text.startswith("-") and float(text) == 0.0 else text

    out = ["HIERARCHY"]

    def node(i: int, depth: int) -> None:
        j, pad = bvh.joints[i], "\t" * depth
        out.append(f"{pad}{'ROOT' if j.parent < 0 else 'JOINT'} {j.name}")
        out.append(pad + "{")
        out.append(f"{pad}\tOFFSET {' '.join(num(v) for v in j.offset)}")
        out.append(f"{pad}\tCHANNELS {len(j.channels)} {' '.join(j.channels)}")
        for c in children.get(i, []):
            node(c, depth + 1)
        if j.end_site is not None:
            out.extend([f"{pad}\tEnd Site", f"{pad}\t{{", f"{pad}\t\tOFFSET {' '.join(num(v) for v in j.end_site)}",
                    f"{pad}\t}}"])
        out.append(pad + "}")

    node(0, 0)
    out += ["MOTION", f"Frames: {bvh.n_frames}", f"Frame Time: {bvh.frame_time_s:.6f}"]
    out += [" ".join(num(v) for v in row) for row in bvh.frames]
    return "\n".join(out) + "\n"
