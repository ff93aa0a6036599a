"""Inverse kinematics: damped least squares on MuJoCo site Jacobians (``mj_jacSite``), for any MuJoCo body.

Written for seed 000, which needs IK twice: the active limbs' joint inputs u for a target end-effector
pose (Eq. 3.10–3.11) and the reachability test of the passive law (Eq. 3.14: keep ξ^ref if ξ(t) is
outside the Reachability Map [133]). The thesis's Reachability Map is not specified (spec §6 item 9);
its stand-in here is :func:`reachable`: the IK converges to the target within tolerance with every
joint inside its limits.

:func:`solve` works on a scratch ``MjData``, so a running simulation is not disturbed. Several sites
are solved at once; each target is a position, a position and an orientation, or a :class:`Target`
(which can also align one site axis with a world direction, leaving the rotation about it free —
e.g. a hand on a bar, or a sole on a pedal that turns freely about its axle). Joint limits are kept
by clamping with an active set: a joint at a limit that the step would push further is frozen for
that step. A ``posture`` (joint values) is pursued in the null space of the targets.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import NamedTuple

import mujoco
import numpy as np

from shintai.sim.body import MujocoBody

POSTURE_SETTLED = 1e-5  # rad: with a posture, iterate on until the joints move less than this
_ONE_DOF = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))


@dataclass(frozen=True)
class Target:
    """What one site should reach (world frame). Give any of:

    ``pos`` (3,) position; ``rot`` (3, 3) orientation of the site frame; ``axis`` = (local, world):
    the site's unit axis ``local`` (site frame) made parallel to the unit vector ``world``.
    """

    pos: np.ndarray | None = None
    rot: np.ndarray | None = None
    axis: tuple[np.ndarray, np.ndarray] | None = None


class IKResult(NamedTuple):
    """``q``: the full qpos found; ``ok``: converged within tolerance (inside the joint limits);
    ``residual``: the largest position error (m) and the largest orientation error (rad)."""

    q: np.ndarray
    ok: bool
    residual: tuple[float, float]


TargetSpec = Target | np.ndarray | tuple


def as_target(spec: TargetSpec) -> Target:
    """A :class:`Target` from a position, a (position, rotation) pair or a Target."""
    if isinstance(spec, Target):
        return spec
    if isinstance(spec, tuple) and len(spec) == 2:
        pos, rot = spec
        return Target(None if pos is None else np.asarray(pos, float), None if rot is None else np.asarray(rot, float))
    pos = np.asarray(spec, dtype=float)
    if pos.shape != (3,):
        raise ValueError(f"an IK target is a position (3,), a (position, rotation) pair or a Target, "
                         f"got shape {pos.shape}")
    return Target(pos=pos)


class _Problem:
    """The model, the scratch data, the moving joints' addresses and limits."""

    def __init__(self, model: mujoco.MjModel, joints: Iterable[str] | None):
        self.model = model
        self.data = mujoco.MjData(model)
        if joints is None:
            ids = [j for j in range(model.njnt) if int(model.jnt_type[j]) in _ONE_DOF]
        else:
            ids = [self._joint_id(name) for name in joints]
        self.qadr = model.jnt_qposadr[ids]
        self.dadr = model.jnt_dofadr[ids]
        self._jacp, self._jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
        self._sites: dict[str, int] = {}
        # views into the scratch data, taken once (each MjData attribute access builds a new array)
        self.qpos, self.site_xpos, self.site_xmat = self.data.qpos, self.data.site_xpos, self.data.site_xmat
        self._regs: dict = {}
        limited = model.jnt_limited[ids].astype(bool)
        self.lo = np.where(limited, model.jnt_range[ids, 0], -np.inf)
        self.hi = np.where(limited, model.jnt_range[ids, 1], np.inf)

    def _joint_id(self, name: str) -> int:
        j = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if j < 0:
            raise KeyError(f"IK: unknown joint {name!r}")
        if int(self.model.jnt_type[j]) not in _ONE_DOF:
            raise ValueError(f"IK moves hinge and slide joints only; {name!r} is not one")
        return j

    def site_id(self, name: str) -> int:
        s = self._sites.get(name)
        if s is None:
            s = self._sites[name] = self._site_id(name)
        return s

    def _site_id(self, name: str) -> int:
        s = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_SITE, name)
        if s < 0:
            raise KeyError(f"IK: unknown site {name!r}")
        return s

    def kinematics(self, qpos: np.ndarray) -> None:
        self.qpos[:] = qpos
        mujoco.mj_kinematics(self.model, self.data)

    def reg(self, rows: int, damping: float) -> np.ndarray:
        """damping² I (rows × rows), read-only, formed once per size and damping."""
        key = (rows, damping)
        r = self._regs.get(key)
        if r is None:
            r = self._regs[key] = damping**2 * np.eye(rows)
            r.setflags(write=False)
        return r

    def jacobian(self, site: int) -> tuple[np.ndarray, np.ndarray]:
        """(3×n translational, 3×n rotational) Jacobian of ``site`` for the moving joints (``mj_jacSite``
        into reused full-width buffers; measured faster than forming the columns from the joint axes
        in NumPy)."""
        mujoco.mj_jacSite(self.model, self.data, self._jacp, self._jacr, site)
        return self._jacp[:, self.dadr], self._jacr[:, self.dadr]


_PROBLEMS: dict = {}  # (id(model), joints) -> (model, _Problem): the scratch data and addresses, reused
_PROBLEMS_MAX = 32


def _problem(model: mujoco.MjModel, joints: Iterable[str] | None) -> _Problem:
    """A cached :class:`_Problem` for this model and joint set (building one allocates an ``MjData``,
    which cost more than the IK itself at one solve per limb per 4 ms control tick)."""
    key = (id(model), None if joints is None else tuple(joints))
    hit = _PROBLEMS.get(key)
    if hit is not None and hit[0] is model:
        return hit[1]
    if len(_PROBLEMS) >= _PROBLEMS_MAX:
        _PROBLEMS.pop(next(iter(_PROBLEMS)))
    problem = _Problem(model, joints)
    _PROBLEMS[key] = (model, problem)
    return problem


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a × b for 3-vectors (``np.cross`` costs ~20 µs a call on small arrays). The products are taken
    on Python floats (``tolist``): the same IEEE double arithmetic as on NumPy scalars, without
    their per-element boxing."""
    a0, a1, a2 = a.tolist() if isinstance(a, np.ndarray) else a
    b0, b1, b2 = b.tolist() if isinstance(b, np.ndarray) else b
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def _prepared(target: Target) -> Target:
    """``target`` with its axis pair as unit float vectors (done once per solve, not per iteration)."""
    if target.axis is None:
        return target
    local, world = (np.asarray(v, float) / math.sqrt(float(np.dot(v, v))) for v in target.axis)
    return Target(target.pos, target.rot, (local, world))


class _Site:
    """One target of a solve, prepared once: its site id, the :class:`Target` (axis pair as unit
    vectors), the target orientation as a quaternion, and scratch quaternions."""

    __slots__ = ("site", "target", "pos", "q_t", "axis", "q_c", "q_d", "rows", "xpos", "xmat", "xmat33")

    def __init__(self, site: int, target: Target, problem: _Problem):
        self.site, self.target, self.pos, self.axis = site, target, target.pos, target.axis
        # the site's rows of the scratch data (views, valid for the problem's lifetime)
        self.xpos, self.xmat = problem.site_xpos[site], problem.site_xmat[site]
        self.xmat33 = self.xmat.reshape(3, 3)
        self.q_t = None
        if target.rot is not None:
            self.q_t = np.zeros(4)
            mujoco.mju_mat2Quat(self.q_t, np.ascontiguousarray(target.rot).ravel())
        self.q_c, self.q_d = np.zeros(4), np.zeros(4)
        self.rows = 3 * ((target.pos is not None) + (target.rot is not None) + (target.axis is not None))


def _errors(problem: _Problem, site: int, target: Target):
    """Error rows and (position error, rotation error) of one target (its axis pair unit vectors,
    :func:`_prepared`)."""
    return _site_errors(problem, _Site(site, target, problem))


def _site_errors(problem: _Problem, s: _Site):
    errors, pos_err, rot_err = [], 0.0, 0.0
    if s.pos is not None:
        e = s.pos - s.xpos
        errors.append(e)
        pos_err = math.sqrt(float(e @ e))
    if s.q_t is not None:
        e = _rotation_error_q(s.q_t, s.xmat, s.q_c, s.q_d)
        errors.append(e)
        rot_err = math.sqrt(float(e @ e))
    if s.axis is not None:
        local, world = s.axis
        a = s.xmat33 @ local
        across = cross(a, world)
        errors.append(across)
        rot_err = max(rot_err, math.atan2(math.sqrt(float(across @ across)), float(a @ world)))
    return errors, pos_err, rot_err


def _jacobian_rows(problem: _Problem, site: int, target: Target, xmat33: np.ndarray | None = None) -> list:
    """The Jacobian rows (moving dofs) matching :func:`_errors`' rows of one target (``xmat33``: the
    site's orientation in the scratch data, if the caller holds the view)."""
    jacp, jacr = problem.jacobian(site)
    jacs = []
    if target.pos is not None:
        jacs.append(jacp)
    if target.rot is not None:
        jacs.append(jacr)
    if target.axis is not None:
        rot = problem.data.site_xmat[site].reshape(3, 3) if xmat33 is None else xmat33
        a = rot @ target.axis[0]
        jacs.append(jacr - np.outer(a, a @ jacr))  # (I − a aᵀ) J_r: the axis error's rows
    return jacs


def rotation_error(target: np.ndarray, current: np.ndarray) -> np.ndarray:
    """World rotation vector taking orientation ``current`` to ``target`` (both 3×3)."""
    q_t = np.zeros(4)
    mujoco.mju_mat2Quat(q_t, np.ascontiguousarray(target).ravel())
    return _rotation_error_q(q_t, np.ascontiguousarray(current).ravel(), np.zeros(4), np.zeros(4))


def _rotation_error_q(q_t: np.ndarray, current: np.ndarray, q_c: np.ndarray, q_d: np.ndarray) -> np.ndarray:
    """:func:`rotation_error` with the target already a quaternion ``q_t`` and ``current`` the flat
    (9,) matrix; ``q_c``, ``q_d`` scratch (4,) buffers (the target's quaternion is formed once per solve)."""
    mujoco.mju_mat2Quat(q_c, current)
    mujoco.mju_negQuat(q_c, q_c)
    mujoco.mju_mulQuat(q_d, q_t, q_c)
    vel = np.zeros(3)
    mujoco.mju_quat2Vel(vel, q_d, 1.0)
    return vel


def _dls_step(jac: np.ndarray, err: np.ndarray, damping: float, free: np.ndarray, reg: np.ndarray | None = None) -> np.ndarray:
    """Damped-least-squares step on the free columns (``reg``: damping² I, if the caller has it)."""
    if reg is None:
        reg = damping**2 * np.eye(len(err))
    if free.all():
        return jac.T @ np.linalg.solve(jac @ jac.T + reg, err)
    j = jac[:, free]
    step = np.zeros(jac.shape[1])
    step[free] = j.T @ np.linalg.solve(j @ j.T + reg, err)
    return step


def _null_step(jac: np.ndarray, pull: np.ndarray, free: np.ndarray) -> np.ndarray:
    """``pull`` projected on the null space of the free columns of ``jac``."""
    j = jac[:, free]
    step = np.zeros(jac.shape[1])
    step[free] = pull[free] - np.linalg.pinv(j, rcond=1e-6) @ (j @ pull[free])
    return step


def solve(body_or_model: MujocoBody | mujoco.MjModel, targets: Mapping[str, TargetSpec], q0: np.ndarray | None = None,
          joints: Iterable[str] | None = None, *, tol: float = 1e-4, rot_tol: float = 1e-3, max_iter: int = 300,
          damping: float = 1e-2, max_step: float = 0.2, posture: Mapping[str, float] | None = None,
          posture_gain: float = 0.2) -> IKResult:
    """Joint values putting each target site (by name) on its target; see the module docstring.

    ``q0``: starting qpos (default: the body's current qpos, or the model's qpos0). ``joints``: the
    hinge/slide joints that may move (default: all of them); everything else keeps its ``q0``
    value. ``tol`` (m) and ``rot_tol`` (rad) decide ``ok``. ``posture``: joint values (of moving
    joints) to approach without disturbing the targets; the search then goes on after the targets
    are reached, until the posture settles.
    """
    model = body_or_model.model if isinstance(body_or_model, MujocoBody) else body_or_model
    if q0 is None:
        q0 = body_or_model.data.qpos if isinstance(body_or_model, MujocoBody) else model.qpos0
    problem = _problem(model, joints)
    sites = [_Site(problem.site_id(name), _prepared(as_target(spec)), problem) for name, spec in targets.items()]
    reg = problem.reg(sum(s.rows for s in sites), damping)  # the DLS damping term, formed once
    rest = _posture_vector(problem, posture)
    qadr = problem.qadr
    q = np.array(q0, dtype=float)
    q[qadr] = np.minimum(np.maximum(q[qadr], problem.lo), problem.hi)  # = np.clip
    best, converged, moved = (np.inf, q.copy(), (np.inf, np.inf)), None, np.inf
    for _ in range(max_iter):
        problem.kinematics(q)
        err, residual = _stack_errors(problem, sites)
        score = max(residual[0] / tol, residual[1] / rot_tol)
        if score <= 1.0:
            converged = (q.copy(), residual)
            if rest is None or moved < POSTURE_SETTLED:
                break
        elif score < best[0]:
            best = (score, q.copy(), residual)
        jac = _stack_jacobian(problem, sites)  # only when a step follows (not on the final check)
        current = q[qadr]
        after = _limited_step(problem, current, jac, err, rest, damping, max_step, posture_gain, reg)
        if rest is not None:  # only a posture's search needs how far the joints moved
            moved = float(np.abs(after - current).max())
        q[qadr] = after
    if converged is not None:
        return IKResult(converged[0], True, converged[1])
    return IKResult(best[1], False, best[2])


def _posture_vector(problem: _Problem, posture: Mapping[str, float] | None) -> np.ndarray | None:
    if not posture:
        return None
    names = [mujoco.mj_id2name(problem.model, mujoco.mjtObj.mjOBJ_JOINT, j)
             for j in problem.model.dof_jntid[problem.dadr]]
    unknown = set(posture) - set(names)
    if unknown:
        raise KeyError(f"IK posture names joints that do not move: {sorted(unknown)}")
    return np.array([posture.get(n, np.nan) for n in names])


def _stack_errors(problem: _Problem, sites: list[_Site]):
    if len(sites) == 1:  # one limb: no running maxima to take
        errors, pos_err, rot_err = _site_errors(problem, sites[0])
        return np.concatenate(errors), (pos_err, rot_err)
    errors, pos_err, rot_err = [], 0.0, 0.0
    for s in sites:
        e, p, r = _site_errors(problem, s)
        errors += e
        pos_err, rot_err = max(pos_err, p), max(rot_err, r)
    return np.concatenate(errors), (pos_err, rot_err)


def _stack_jacobian(problem: _Problem, sites: list[_Site]) -> np.ndarray:
    mujoco.mj_comPos(problem.model, problem.data)  # cdof and subtree CoMs, which mj_jacSite needs
    jacs = []
    for s in sites:
        jacs += _jacobian_rows(problem, s.site, s.target, s.xmat33)
    return np.concatenate(jacs)  # = np.vstack of these 2-D blocks


def _limited_step(problem: _Problem, q: np.ndarray, jac, err, rest, damping, max_step, posture_gain,
                  reg: np.ndarray | None = None) -> np.ndarray:
    """The moving joints after one DLS step (+ null-space posture pull), inside their limits: a joint
    at a limit that the step pushes further is frozen and the step recomputed without it."""
    lo, hi = problem.lo, problem.hi
    at_lo, at_hi = q <= lo, q >= hi
    if rest is None and not (at_lo.any() or at_hi.any()):  # the usual tick: one plain DLS step
        step = jac.T @ np.linalg.solve(jac @ jac.T + (damping**2 * np.eye(len(err)) if reg is None else reg), err)
        biggest = float(np.abs(step).max())
        if biggest > max_step:
            step *= max_step / biggest
        return np.minimum(np.maximum(q + step, lo), hi)  # = np.clip, without its dispatch
    free = np.ones(len(q), dtype=bool)
    at_limit = bool(at_lo.any() or at_hi.any())
    for _ in range(len(q)):
        step = _dls_step(jac, err, damping, free, reg)
        if rest is not None:
            pull = np.where(np.isnan(rest), 0.0, posture_gain * (rest - q))
            step += _null_step(jac, pull, free)
        biggest = float(np.abs(step).max())
        if biggest > max_step:
            step *= max_step / biggest
        if not at_limit:  # no joint at a limit: nothing to freeze
            break
        blocked = free & ((at_lo & (step < 0)) | (at_hi & (step > 0)))
        if not blocked.any():
            break
        free &= ~blocked
    return np.clip(q + step, lo, hi)


def reachable(body_or_model: MujocoBody | mujoco.MjModel, targets: Mapping[str, TargetSpec],
              q0: np.ndarray | None = None, joints: Iterable[str] | None = None, **options) -> bool:
    """The Reachability-Map stand-in of Eq. 3.11/3.14: IK reaches every target within tolerance
    with the joints inside their limits."""
    return solve(body_or_model, targets, q0, joints, **options).ok
