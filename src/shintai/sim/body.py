"""MujocoBody: a MuJoCo model and its data behind the :class:`shintai.core.Body` interface.

Every MuJoCo robot in shintai (humanoids, snakes, arms) is a :class:`MujocoBody` built from its
MJCF; modules and the :class:`shintai.core.Loop` only see snapshots and commands.

Conventions
-----------
* **Time.** One body step (``dt``) is ``substeps`` physics steps of ``model.opt.timestep``; e.g. a
  humanoid controlled every 4 ms like hrpsys while MuJoCo integrates at 1 or 2 ms. ``t`` is
  ``data.time``.
* **Snapshot.** ``"t"`` (float), copies of ``"qpos"``, ``"qvel"``, ``"ctrl"``, and every *named*
  MuJoCo sensor under its own name as an array of shape ``(sensor dim,)`` (force/torque at sites,
  framequat/gyro/accelerometer of an IMU, jointpos, ...). Per-joint keys are also there:
  ``"q:<joint>"`` and ``"dq:<joint>"`` for every named joint (a float for hinge and slide joints,
  an array for ball and free joints).
  Values do not change as the simulation runs on: a snapshot makes one copy of
  ``[qpos, qvel, ctrl, sensordata]`` and its arrays are views of that copy. The entries are formed from
  that copy when first read (:class:`Snapshot`, a dict): a 4 ms humanoid tick reads a handful of its ~80
  keys, and forming them all cost 7 % of HRP2's standing tick (issue 30, sampled). MuJoCo computes
  sensors at the *start* of a physics step, so sensor values (and ``site_pos`` etc.) lag
  ``qpos``/``qvel`` by one physics timestep; call :meth:`MujocoBody.forward` when that matters.
* **Command.** A channel is an actuator name (a scalar) or ``"ctrl"`` (the whole vector); values go
  into ``data.ctrl``. What a value means is what the MJCF actuator is: joint position commands go to
  ``<position>`` actuators (servos), torques to ``<motor>`` actuators. The value an actuator gets is
  the sum of everything the command addresses to it (its element of ``"ctrl"`` plus its named
  channel), as contributions add in the Loop; actuators a command does not address keep their
  previous value.
* **Divergence.** After each body step, MuJoCo's instability warnings (NaN, Inf or |x| > 1e10 in
  qpos/qvel/qacc/ctrl) are checked, then the state the last integration produced (NaN, Inf or
  huge); :class:`shintai.core.SimulationDiverged` says when and where. MuJoCo auto-resets the data
  on a bad qpos/qvel/qacc, so after a divergence the state is not the diverged one; the warnings
  are what tells.
"""

from __future__ import annotations

import operator
import os
from collections.abc import Callable, Mapping
from pathlib import Path

import mujoco
import numpy as np

from shintai.core.runtime import Body, SimulationDiverged, declare

ModelSource = str | os.PathLike | mujoco.MjSpec | mujoco.MjModel

_OBJ = {
    "body": mujoco.mjtObj.mjOBJ_BODY, "joint": mujoco.mjtObj.mjOBJ_JOINT,
    "geom": mujoco.mjtObj.mjOBJ_GEOM, "site": mujoco.mjtObj.mjOBJ_SITE,
    "actuator": mujoco.mjtObj.mjOBJ_ACTUATOR, "sensor": mujoco.mjtObj.mjOBJ_SENSOR,
    "equality": mujoco.mjtObj.mjOBJ_EQUALITY, "keyframe": mujoco.mjtObj.mjOBJ_KEY,
    "camera": mujoco.mjtObj.mjOBJ_CAMERA,
}
_COUNT = {"body": "nbody", "joint": "njnt", "geom": "ngeom", "site": "nsite", "actuator": "nu",
          "sensor": "nsensor", "equality": "neq", "keyframe": "nkey", "camera": "ncam"}

# MuJoCo's instability warnings (contiguous in mjtWarning), what their ``lastinfo`` indexes, and
# MuJoCo's own "huge value" limit (mjMAXVAL) squared, for the check of the integrated state.
_BAD_WARNINGS = [
    (mujoco.mjtWarning.mjWARN_BADQPOS, "bad qpos", "qpos"),
    (mujoco.mjtWarning.mjWARN_BADQVEL, "bad qvel", "dof"),
    (mujoco.mjtWarning.mjWARN_BADQACC, "bad qacc", "dof"),
    (mujoco.mjtWarning.mjWARN_BADCTRL, "bad ctrl", "actuator"),
]
_BAD_FIRST = int(_BAD_WARNINGS[0][0])
assert [int(w) for w, _, _ in _BAD_WARNINGS] == list(range(_BAD_FIRST, _BAD_FIRST + len(_BAD_WARNINGS)))
_HUGE = 1e10
_HUGE_SQ = _HUGE**2


_ABSENT = object()


class SnapshotLayout:
    """Where each snapshot entry sits in the concatenation ``[qpos, qvel, ctrl, sensordata]`` (built once per body):
    ``where`` (key → a slice for an array entry, an index for a float one), and the same as the sequences that form
    every entry at once (:meth:`Snapshot.whole`)."""

    def __init__(self, views: list[tuple[str, slice]], scalars: list[tuple[str, int]]):
        self.where = {**dict(views), **dict(scalars)}
        self.view_keys, self.view_slices = [k for k, _ in views], [w for _, w in views]
        self.scalar_keys = [k for k, _ in scalars]
        self.scalar_items = operator.itemgetter(*[i for _, i in scalars], 0, 0)  # ≥ 2 indices: a tuple
        self.scalar_end = 1 + max((i for _, i in scalars), default=-1)

    def entries(self, values: np.ndarray) -> dict:
        """Every body entry of ``values``, in order."""
        out = dict(zip(self.view_keys, map(values.__getitem__, self.view_slices)))
        if self.scalar_keys:
            out.update(zip(self.scalar_keys, self.scalar_items(values[:self.scalar_end].tolist())))
        return out


class Snapshot(dict):
    """A :class:`MujocoBody` snapshot: ``{"t": time}`` and the body's entries, each formed from ``values`` (the
    snapshot's one copy of ``[qpos, qvel, ctrl, sensordata]``, read through a :class:`SnapshotLayout`) on its first
    read and kept, so every read gives the same object.

    It is the eager dict to its readers: ``get``, ``in`` and ``len`` count the unread entries; iterating, comparing,
    copying it into a plain dict (``dict(s)``, ``{**s}``), printing or pickling it forms every entry first, in the
    order the eager dict had (``t``, the body's entries in layout order, then what was written into it);
    :meth:`copy` keeps the unread entries unread (the :class:`~shintai.core.runtime.Loop`'s per-tick view)."""

    __slots__ = ("_values", "_layout")

    def __init__(self, t: float, values: np.ndarray, layout: SnapshotLayout | None):
        self["t"] = t  # (a dict is made empty; dict's own __init__ only fills one)
        self._values, self._layout = values, layout

    def __missing__(self, key):
        where = self._layout.where.get(key) if self._layout is not None and type(key) is str else None
        if where is None:
            raise KeyError(key)
        # a float as tolist gives it (.item), or a view of the copy
        value = self._values.item(where) if type(where) is int else self._values[where]
        dict.__setitem__(self, key, value)
        return value

    def _unread(self, key) -> bool:
        return self._layout is not None and type(key) is str and key in self._layout.where

    def get(self, key, default=None):
        value = dict.get(self, key, _ABSENT)
        if value is _ABSENT:
            return self.__missing__(key) if self._unread(key) else default
        return value

    def __contains__(self, key) -> bool:
        return dict.__contains__(self, key) or self._unread(key)

    def __len__(self) -> int:
        if self._layout is None:
            return dict.__len__(self)
        return dict.__len__(self) + sum(1 for k in self._layout.where if not dict.__contains__(self, k))

    def copy(self) -> Snapshot:
        twin = Snapshot(0.0, self._values, self._layout)
        dict.update(twin, dict.items(self))
        return twin

    def whole(self) -> dict:
        """Every entry, as the plain dict the eager snapshot was (this one's entries all formed, in its order)."""
        self._form_all()
        return dict(dict.items(self))

    def _form_all(self) -> None:
        if self._layout is None:
            return
        body = self._layout.entries(self._values)
        if dict.__len__(self) > 1:  # entries read (the same objects kept) or written: in their places
            own = dict(dict.items(self))
            t = own.pop("t", _ABSENT)
            for k in own.keys() & body.keys():
                body[k] = own.pop(k)
            dict.clear(self)
            if t is not _ABSENT:
                dict.__setitem__(self, "t", t)
            dict.update(self, body)
            dict.update(self, own)
        else:
            dict.update(self, body)
        self._layout = None  # all formed: a plain dict from here on

    def keys(self):
        self._form_all()
        return dict.keys(self)

    def values(self):
        self._form_all()
        return dict.values(self)

    def items(self):
        self._form_all()
        return dict.items(self)

    def __iter__(self):
        self._form_all()
        return dict.__iter__(self)

    def __eq__(self, other) -> bool:
        return self.whole() == (other.whole() if isinstance(other, Snapshot) else other)

    def __ne__(self, other) -> bool:
        return not self == other

    __hash__ = None  # a dict's

    def __repr__(self) -> str:
        return repr(self.whole())

    def __or__(self, other):
        return self.whole() | other

    def __reduce__(self):
        return dict, (self.whole(),)

    def __delitem__(self, key) -> None:
        self._form_all()
        dict.__delitem__(self, key)

    def pop(self, key, *default):
        self._form_all()
        return dict.pop(self, key, *default)

    def popitem(self):
        self._form_all()
        return dict.popitem(self)

    def setdefault(self, key, default=None):
        return self[key] if key in self else dict.setdefault(self, key, default)


def load_model(source: ModelSource) -> mujoco.MjModel:
    """An MjModel from an MJCF path, an MJCF XML string, an MjSpec or an MjModel (returned as is)."""
    if isinstance(source, mujoco.MjModel):
        return source
    if isinstance(source, mujoco.MjSpec):
        return source.compile()
    if isinstance(source, str) and source.lstrip().startswith("<"):
        return mujoco.MjModel.from_xml_string(source)
    path = Path(source)
    if not path.is_file():
        raise FileNotFoundError(f"MJCF file not found: {path}")
    return mujoco.MjModel.from_xml_path(str(path))


def names_line(names) -> str:
    """A short one-line listing of valid names for error messages."""
    names = list(names)
    shown = ", ".join(names[:30])
    return shown + (f", ... ({len(names)} in all)" if len(names) > 30 else "") if names else "none"


class MujocoBody(Body):
    """A MuJoCo simulation as a shintai Body (see the module docstring for the conventions).

    ``source`` is an MJCF file path, an MJCF XML string, a ``mujoco.MjSpec`` or a
    ``mujoco.MjModel`` (used as is, not copied: :meth:`set_contact` edits it). ``keyframe`` (name or
    index) sets the initial state. ``after_step`` holds callables run after every body step (a
    :class:`shintai.sim.VideoRecorder` adds its ``capture`` there); ``before_physics`` holds callables
    run before every *physics* step: the plant's own embedded controllers, which read ``data`` and
    write ``data.ctrl`` of their actuators at the physics rate (a vehicle's firmware, e.g.
    :class:`shintai.humanoid.vboard.vehicle.VboardFirmware`), not the robot's modules.
    """

    def __init__(self, source: ModelSource, substeps: int = 1, keyframe: str | int | None = None,
                 spec: mujoco.MjSpec | None = None):
        if int(substeps) != substeps or substeps < 1:
            raise ValueError(f"substeps must be a positive integer, got {substeps!r}")
        self.model = load_model(source)
        # kept for export (sim/export.py): the source, or the spec a compiled model came from
        self.spec = source if isinstance(source, mujoco.MjSpec) else spec
        self.data = mujoco.MjData(self.model)
        self.substeps = int(substeps)
        self.ids = {kind: self._name_ids(kind) for kind in _OBJ}
        self.channels = declare("ctrl", *self.ids["actuator"])  # additive: the Loop sums into data.ctrl
        self.after_step: list[Callable[[], None]] = []
        self.before_physics: list[Callable[[], None]] = []
        self._contact_saved: dict[int, tuple[int, int]] = {}
        self._views, self._scalars = self._snapshot_layout()
        self._layout = SnapshotLayout(self._views, self._scalars)  # what a Snapshot reads its entries through
        # live views into MjData, read after every step
        self._bad_counts = self.data.warning.number[_BAD_FIRST:_BAD_FIRST + len(_BAD_WARNINGS)]
        self._qpos, self._qvel = self.data.qpos, self.data.qvel
        self._state = (self._qpos, self._qvel, self.data.ctrl, self.data.sensordata)
        self.reset(keyframe)

    # -- construction helpers -------------------------------------------------------------------

    def _name_ids(self, kind: str) -> dict[str, int]:
        count = getattr(self.model, _COUNT[kind])
        names = (mujoco.mj_id2name(self.model, _OBJ[kind], i) for i in range(count))
        return {name: i for i, name in enumerate(names) if name}

    def _snapshot_layout(self) -> tuple[list[tuple[str, slice]], list[tuple[str, int]]]:
        """Where each snapshot entry sits in the concatenation ``[qpos, qvel, ctrl, sensordata]``.

        Returns (key, slice) for vector entries and (key, index) for scalar joint entries.
        """
        m = self.model
        nq, nv, nu = m.nq, m.nv, m.nu
        views = [("qpos", slice(0, nq)), ("qvel", slice(nq, nq + nv)), ("ctrl", slice(nq + nv, nq + nv + nu))]
        base = nq + nv + nu
        for name, i in self.ids["sensor"].items():
            adr = base + m.sensor_adr[i]
            views.append((name, slice(adr, adr + m.sensor_dim[i])))
        scalars = []
        for name, j in self.ids["joint"].items():
            jq, jv = joint_dims(m.jnt_type[j])
            for key, adr, size in ((f"q:{name}", m.jnt_qposadr[j], jq), (f"dq:{name}", nq + m.jnt_dofadr[j], jv)):
                if size == 1:
                    scalars.append((key, int(adr)))
                else:
                    views.append((key, slice(int(adr), int(adr) + size)))
        keys = ["t"] + [k for k, _ in views] + [k for k, _ in scalars]
        clash = sorted({k for k in keys if keys.count(k) > 1})
        if clash:
            raise ValueError(f"sensor names clash with snapshot keys: {clash}")
        return views, scalars

    # -- Body interface -------------------------------------------------------------------------

    @property
    def dt(self) -> float:
        return self.substeps * self.model.opt.timestep

    @property
    def t(self) -> float:
        return self.data.time

    def snapshot(self) -> Snapshot:
        return Snapshot(self.data.time, np.concatenate(self._state), self._layout)  # the one copy, read when read

    def apply(self, command: Mapping[str, np.ndarray | float]) -> None:
        ctrl = self.data.ctrl
        whole = "ctrl" in command
        if whole:
            value = np.asarray(command["ctrl"], dtype=float)
            if value.shape != ctrl.shape:
                raise ValueError(f"command 'ctrl' has shape {value.shape}, the model has {ctrl.shape} actuators")
            ctrl[:] = value
            if len(command) == 1:  # the whole vector only (a stack's leg IK)
                return
        actuators = self.ids["actuator"]
        for channel, value in command.items():
            if channel == "ctrl":
                continue
            i = actuators.get(channel)
            if i is None:
                raise KeyError(f"unknown command channel {channel!r}; valid: ctrl, {names_line(actuators)}")
            if type(value) is not float:
                value = scalar(channel, value)
            ctrl[i] = ctrl[i] + value if whole else value

    def step(self) -> None:
        t0 = self.data.time
        if self.before_physics:
            for _ in range(self.substeps):
                for hook in self.before_physics:
                    hook()
                mujoco.mj_step(self.model, self.data)
        else:
            mujoco.mj_step(self.model, self.data, self.substeps)
        self._check_divergence(t0)
        for callback in self.after_step:
            callback()

    # -- divergence -----------------------------------------------------------------------------

    def _check_divergence(self, t0: float) -> None:
        counts = self._bad_counts.tolist()
        if counts != self._counts_seen:
            fired = [k for k, (now, before) in enumerate(zip(counts, self._counts_seen)) if now > before]
            self._counts_seen = counts  # counts only drop if someone reset the data
            if fired:
                raise SimulationDiverged(self._warning_message(t0, fired[0]))
        # MuJoCo checked qpos/qvel/qacc at the start of each physics step (the warnings above);
        # the state its last integration produced is checked here, NaN failing the comparison.
        q, v = self._qpos, self._qvel
        if not q.dot(q) + v.dot(v) < _HUGE_SQ:  # (the method: @ on two vectors goes through matmul's ufunc machinery)
            raise SimulationDiverged(self._state_message(t0))

    def _state_message(self, t0: float) -> str:
        """Name the largest (or non-finite) element of the integrated qpos/qvel."""
        worst = []
        for name, vec in (("qpos", self._qpos), ("qvel", self._qvel)):
            if vec.size:
                size = np.where(np.isfinite(vec), np.abs(vec), np.inf)
                i = int(np.argmax(size))
                worst.append((size[i], name, i))
        _, name, i = max(worst)
        where = self._qpos_joint(i) if name == "qpos" else self._dof_joint(i)
        vec = self._qpos if name == "qpos" else self._qvel
        return (f"simulation diverged in the step from t={t0:.4f} s: NaN, Inf or huge value in "
                f"{name}[{i}] = {vec[i]:g} ({where})")

    def _warning_message(self, t0: float, k: int) -> str:
        warning, what, kind = _BAD_WARNINGS[k]
        index = int(self.data.warning.lastinfo[warning])
        if kind == "qpos":
            where = f"qpos[{index}] ({self._qpos_joint(index)})"
        elif kind == "dof":
            where = f"dof {index} ({self._dof_joint(index)})"
        else:
            where = f"actuator {index} ({self._name('actuator', index)})"
        return (f"simulation diverged in the step from t={t0:.4f} s: MuJoCo warning {what} "
                f"(NaN, Inf or huge value) at {where}")

    def _name(self, kind: str, i: int) -> str:
        name = mujoco.mj_id2name(self.model, _OBJ[kind], i)
        return f"{kind} {name!r}" if name else f"unnamed {kind} {i}"

    def _qpos_joint(self, index: int) -> str:
        adr = self.model.jnt_qposadr
        return self._name("joint", int(np.searchsorted(adr, index, side="right") - 1))

    def _dof_joint(self, index: int) -> str:
        return self._name("joint", int(self.model.dof_jntid[index]))

    # -- lookups and thin helpers ---------------------------------------------------------------

    def id(self, kind: str, name: str) -> int:
        """The MuJoCo id of a named body/joint/geom/site/actuator/sensor/equality/keyframe/camera."""
        ids = self.ids[kind]
        if name not in ids:
            raise KeyError(f"unknown {kind} {name!r}; valid: {names_line(ids)}")
        return ids[name]

    def reset(self, keyframe: str | int | None = None) -> None:
        """Reset the data (to ``keyframe``, a name or index, if given) and recompute kinematics.

        Equality activations go back to the model's; contacts disabled by :meth:`set_contact` stay
        disabled (they live in the model).
        """
        if keyframe is None:
            mujoco.mj_resetData(self.model, self.data)
        else:
            key = self.id("keyframe", keyframe) if isinstance(keyframe, str) else int(keyframe)
            if not 0 <= key < self.model.nkey:
                raise KeyError(f"keyframe index {key} out of range; the model has {self.model.nkey}")
            mujoco.mj_resetDataKeyframe(self.model, self.data, key)
        mujoco.mj_forward(self.model, self.data)
        self._counts_seen = self._bad_counts.tolist()

    def forward(self) -> None:
        """Recompute kinematics, forces and sensors for the current state (``mj_forward``)."""
        mujoco.mj_forward(self.model, self.data)

    def site_pos(self, name: str) -> np.ndarray:
        return self.data.site_xpos[self.id("site", name)].copy()

    def site_xmat(self, name: str) -> np.ndarray:
        return self.data.site_xmat[self.id("site", name)].reshape(3, 3).copy()

    def body_pos(self, name: str) -> np.ndarray:
        return self.data.xpos[self.id("body", name)].copy()

    def joint_qpos(self, name: str) -> float | np.ndarray:
        """A hinge/slide joint's position as a float; a ball/free joint's as an array copy."""
        j = self.id("joint", name)
        nq, _ = joint_dims(self.model.jnt_type[j])
        adr = self.model.jnt_qposadr[j]
        return float(self.data.qpos[adr]) if nq == 1 else self.data.qpos[adr:adr + nq].copy()

    def jac_site(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """Translational and rotational Jacobians (each 3 x nv) of a site, world frame."""
        jacp = np.zeros((3, self.model.nv))
        jacr = np.zeros((3, self.model.nv))
        mujoco.mj_jacSite(self.model, self.data, jacp, jacr, self.id("site", name))
        return jacp, jacr

    # -- run-time switching ---------------------------------------------------------------------

    def set_equality(self, name: str, active: bool) -> None:
        """Switch an equality constraint (a weld holding a grip, a connect) on or off.

        Re-activated constraints pull toward the relative pose stored in the model, not the
        current one.
        """
        self.data.eq_active[self.id("equality", name)] = bool(active)

    def set_contact(self, geom_name: str, enabled: bool) -> None:
        """Let a geom collide (its original contype/conaffinity) or not (both 0).

        This edits the model. Contacts declared explicitly with ``<contact><pair>`` ignore it.
        """
        g = self.id("geom", geom_name)
        m = self.model
        if g not in self._contact_saved:
            self._contact_saved[g] = (int(m.geom_contype[g]), int(m.geom_conaffinity[g]))
        m.geom_contype[g], m.geom_conaffinity[g] = self._contact_saved[g] if enabled else (0, 0)

    # -- contact forces -------------------------------------------------------------------------

    def contact_force(self, body_a: str, body_b: str | None = None) -> np.ndarray:
        """Total world-frame force (N) on ``body_a`` from its contacts with ``body_b`` (or anything).

        Sign: the force *acting on* ``body_a``; a box resting on the floor gets about ``+m g`` in z
        from ``contact_force("box", "world")``. Only geoms attached directly to each body count.
        """
        a = self.id("body", body_a)
        b = None if body_b is None else self.id("body", body_b)
        total = np.zeros(3)
        d = self.data
        if d.ncon == 0:
            return total
        geoms = d.contact.geom
        bodies = np.where(geoms >= 0, self.model.geom_bodyid[geoms], -1)
        wrench = np.zeros(6)
        for i in np.flatnonzero((bodies == a).any(axis=1)):
            side = 0 if bodies[i, 0] == a else 1
            if b is not None and bodies[i, 1 - side] != b:
                continue
            mujoco.mj_contactForce(self.model, d, int(i), wrench)
            # frame rows are (normal, tangent1, tangent2), normal from geom1 to geom2; the contact
            # force rotated to world is the force geom1 exerts on geom2.
            on_geom2 = d.contact.frame[i].reshape(3, 3).T @ wrench[:3]
            total += on_geom2 if side == 1 else -on_geom2
        return total


def joint_dims(jnt_type: int) -> tuple[int, int]:
    """(qpos size, dof count) of a MuJoCo joint type."""
    if jnt_type == mujoco.mjtJoint.mjJNT_FREE:
        return 7, 6
    if jnt_type == mujoco.mjtJoint.mjJNT_BALL:
        return 4, 3
    return 1, 1


def scalar(channel: str, value) -> float:
    value = np.asarray(value, dtype=float)
    if value.size != 1:
        raise ValueError(f"command channel {channel!r} takes a scalar, got shape {value.shape}")
    return float(value.reshape(()))
