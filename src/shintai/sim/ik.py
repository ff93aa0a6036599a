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
from numpy.linalg import _umath_linalg

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
        # the moving joints' qpos entries and Jacobian columns (slices for one limb's chain: the same numbers as
        # the index arrays give, without fancy indexing)
        self.coords, self.columns = _as_slice(self.qadr), _as_slice(self.dadr)
        self._jacp, self._jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
        self._sites: dict[str, int] = {}
        # views into the scratch data, taken once (each MjData attribute access builds a new array)
        self.qpos, self.site_xpos, self.site_xmat = self.data.qpos, self.data.site_xpos, self.data.site_xmat
        self._regs: dict = {}
        self._stacks: dict = {}
        limited = model.jnt_limited[ids].astype(bool)
        self.lo = np.where(limited, model.jnt_range[ids, 0], -np.inf)
        self.hi = np.where(limited, model.jnt_range[ids, 1], np.inf)
        self.lo_list, self.hi_list = self.lo.tolist(), self.hi.tolist()

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
        """(3×nv translational, 3×nv rotational) Jacobian of ``site`` (``mj_jacSite`` into reused full-width
        buffers; measured faster than forming the columns from the joint axes in NumPy); the moving joints'
        columns are ``[:, self.columns]``."""
        mujoco.mj_jacSite(self.model, self.data, self._jacp, self._jacr, site)
        return self._jacp, self._jacr

    def stack(self, targets: Mapping[str, TargetSpec]) -> _Stack:
        """The sites of ``targets`` with their error rows and Jacobian buffers (built once per set of sites and
        target kinds, aimed at these targets)."""
        aims = [(name, as_target(spec)) for name, spec in targets.items()]
        key = tuple((name, t.pos is not None, t.rot is not None, t.axis is not None) for name, t in aims)
        stack = self._stacks.get(key)
        if stack is None:
            stack = self._stacks[key] = _Stack(self, key)
        for site, (_, target) in zip(stack.sites, aims):
            site.aim(target)
        return stack


def _as_slice(index: np.ndarray) -> slice | np.ndarray:
    """``index`` as a slice where it runs consecutively (a copy of those columns is the same numbers)."""
    first = int(index[0]) if len(index) else 0
    if np.array_equal(index, np.arange(first, first + len(index))):
        return slice(first, first + len(index))
    return index


_PROBLEMS: dict = {}  # (id(model), joints) -> (model, _Problem): the scratch data and addresses, reused
_PROBLEMS_MAX = 32


def cached_problem(model: mujoco.MjModel, joints: Iterable[str] | None) -> _Problem:
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


def _cross(a, b) -> tuple[float, float, float]:
    """a × b as three Python floats (``tolist``): the same IEEE double arithmetic as on NumPy scalars, without
    their per-element boxing."""
    a0, a1, a2 = a.tolist() if isinstance(a, np.ndarray) else a
    b0, b1, b2 = b.tolist() if isinstance(b, np.ndarray) else b
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / math.sqrt(float(v.dot(v)))  # = np.dot(v, v): ndarray.dot is the same function


class _Site:
    """One target site of a solve: its id, its rows of the data and of the stacked error and Jacobian (views
    from ``row``, :meth:`bind`), and what it is aimed at (:meth:`aim`: the position, the target orientation as a
    quaternion, the axis pair as unit vectors), with scratch quaternions.

    3-vector and 3×3 products are ``ndarray.dot``: the same BLAS call as ``@`` for these shapes and layouts (the
    same bits, checked on 100k random cases per shape), at a third of ``@``'s call cost."""

    __slots__ = ("site", "row", "rows", "kinds", "pos", "q_t", "axis", "a", "local", "q_c", "q_d", "j_r", "xpos",
                 "xmat", "xmat33", "e_pos", "e_rot", "e_axis", "jac_pos", "jac_rot", "jac_axis")

    def __init__(self, problem: _Problem, site: int, kinds: tuple[bool, bool, bool], row: int):
        self.site, self.row, self.rows, self.kinds = site, row, 3 * sum(kinds), kinds
        # the site's rows of the scratch data (views, valid for the problem's lifetime)
        self.xpos, self.xmat = problem.site_xpos[site], problem.site_xmat[site]
        self.xmat33 = self.xmat.reshape(3, 3)
        self.pos = self.axis = self.a = self.local = None
        self.e_pos = self.e_rot = self.e_axis = self.jac_pos = self.jac_rot = self.jac_axis = None
        self.q_t = np.zeros(4) if kinds[1] else None
        self.q_c, self.q_d = np.zeros(4), np.zeros(4)
        # J_r's moving columns for the axis rows, column-major as a fancy-indexed copy is (the layout decides
        # which BLAS kernel forms a J_r, and so its last bits)
        self.j_r = np.zeros((len(problem.dadr), 3)).T if kinds[2] else None

    def bind(self, err: np.ndarray, jac: np.ndarray) -> None:
        """Take this site's rows of the stacked ``err`` and ``jac`` as views, position, rotation, axis in that
        order (once per stack: its buffers are reused from solve to solve)."""
        r = self.row
        for kind, wanted in zip(("pos", "rot", "axis"), self.kinds):
            if wanted:
                setattr(self, f"e_{kind}", err[r:r + 3])
                setattr(self, f"jac_{kind}", jac[r:r + 3])
                r += 3

    def aim(self, target: Target) -> None:
        self.pos = target.pos
        if target.rot is not None:
            mujoco.mju_mat2Quat(self.q_t, np.ascontiguousarray(target.rot).ravel())
        if target.axis is not None:
            self.axis = (self._local_unit(target.axis[0]), _unit(target.axis[1]))

    def _local_unit(self, local) -> np.ndarray:
        """The unit site axis of ``local``, formed again only when its bits change (a hand's bar axis is one
        constant, while the world direction it is aimed at moves every tick)."""
        bits = np.asarray(local, float).tobytes()
        if self.local is None or self.local[0] != bits:
            self.local = (bits, _unit(local))
        return self.local[1]

    def errors(self) -> tuple[float, float]:
        """Write this site's error rows (:meth:`bind`); (position error, rotation error). The axis error is
        the cross product of the site's axis a and the target direction (its size sin of the angle)."""
        pos_err, rot_err = 0.0, 0.0
        if self.pos is not None:
            e = self.e_pos
            np.subtract(self.pos, self.xpos, out=e)
            pos_err = math.sqrt(float(e.dot(e)))
        if self.q_t is not None:
            e = _rotation_error_q(self.q_t, self.xmat, self.q_c, self.q_d, self.e_rot)
            rot_err = math.sqrt(float(e.dot(e)))
        if self.axis is not None:
            local, world = self.axis
            a = self.a = self.xmat33.dot(local)
            across = self.e_axis
            across[:] = _cross(a, world)
            rot_err = max(rot_err, math.atan2(math.sqrt(float(across.dot(across))), float(a.dot(world))))
        return pos_err, rot_err

    def jacobian(self, problem: _Problem) -> None:
        """Write the Jacobian rows (moving dofs) matching :meth:`errors`' rows (after :meth:`errors` at the
        same kinematics, whose axis a it uses)."""
        jacp, jacr = problem.jacobian(self.site)
        cols = problem.columns
        if self.pos is not None:
            self.jac_pos[:] = jacp[:, cols]
        if self.q_t is not None:
            self.jac_rot[:] = jacr[:, cols]
        if self.axis is not None:
            j_r = self.j_r
            j_r[:] = jacr[:, cols]
            a = self.a
            # (I − a aᵀ) J_r: the axis error's rows (a[:, None] * (aᵀ J_r) is np.outer's own product)
            np.subtract(j_r, a[:, None] * a.dot(j_r), out=self.jac_axis)


class _Stack:
    """The sites of one solve and their stacked error vector and Jacobian (buffers reused from solve to solve)."""

    def __init__(self, problem: _Problem, key: tuple):
        self.problem, self.sites, rows = problem, [], 0
        for name, *kinds in key:
            site = _Site(problem, problem.site_id(name), tuple(kinds), rows)
            self.sites.append(site)
            rows += site.rows
        # the stacked Jacobian in the memory order np.concatenate gave its column-major blocks (row-major once
        # an axis block, formed row-major, is among them): the order picks the BLAS kernels of the DLS step
        order = "C" if any(kinds[2] for _, *kinds in key) else "F"
        self.err, self.jac = np.zeros(rows), np.zeros((rows, len(problem.dadr)), order=order)
        for site in self.sites:
            site.bind(self.err, self.jac)

    def errors(self) -> tuple[float, float]:
        """Fill ``err``; the largest position and orientation errors over the sites."""
        if len(self.sites) == 1:  # one limb: no running maxima to take
            return self.sites[0].errors()
        pos_err = rot_err = 0.0
        for s in self.sites:
            p, r = s.errors()
            pos_err, rot_err = max(pos_err, p), max(rot_err, r)
        return pos_err, rot_err

    def jacobian(self) -> np.ndarray:
        mujoco.mj_comPos(self.problem.model, self.problem.data)  # cdof and subtree CoMs, which mj_jacSite needs
        for s in self.sites:
            s.jacobian(self.problem)
        return self.jac


def rotation_error(target: np.ndarray, current: np.ndarray) -> np.ndarray:
    """World rotation vector taking orientation ``current`` to ``target`` (both 3×3)."""
    q_t = np.zeros(4)
    mujoco.mju_mat2Quat(q_t, np.ascontiguousarray(target).ravel())
    return _rotation_error_q(q_t, np.ascontiguousarray(current).ravel(), np.zeros(4), np.zeros(4), np.zeros(3))


def _rotation_error_q(q_t: np.ndarray, current: np.ndarray, q_c: np.ndarray, q_d: np.ndarray,
                      out: np.ndarray) -> np.ndarray:
    """:func:`rotation_error` into ``out`` (3,) with the target already a quaternion ``q_t`` and ``current`` the
    flat (9,) matrix; ``q_c``, ``q_d`` scratch (4,) buffers (the target's quaternion is formed once per solve)."""
    mujoco.mju_mat2Quat(q_c, current)
    mujoco.mju_negQuat(q_c, q_c)
    mujoco.mju_mulQuat(q_d, q_t, q_c)
    mujoco.mju_quat2Vel(out, q_d, 1.0)
    return out


def _dls_step(jac: np.ndarray, err: np.ndarray, damping: float, free: np.ndarray, reg: np.ndarray | None = None) -> np.ndarray:
    """Damped-least-squares step on the free columns (``reg``: damping² I, if the caller has it)."""
    if reg is None:
        reg = damping**2 * np.eye(len(err))
    solve = _solve_regular if damping > 0 else np.linalg.solve
    if free.all():
        return jac.T @ solve(jac @ jac.T + reg, err)
    j = jac[:, free]
    step = np.zeros(jac.shape[1])
    step[free] = j.T @ solve(j @ j.T + reg, err)
    return step


def _null_step(jac: np.ndarray, pull: np.ndarray, free: np.ndarray) -> np.ndarray:
    """``pull`` projected on the null space of the free columns of ``jac``."""
    j = jac[:, free]
    step = np.zeros(jac.shape[1])
    step[free] = pull[free] - np.linalg.pinv(j, rcond=1e-6) @ (j @ pull[free])
    return step


_MAX = np.maximum.reduce  # = ndarray.max of a vector (NaN propagating), without its Python wrapper


def _solve_regular(system: np.ndarray, b: np.ndarray) -> np.ndarray:
    """x of ``system`` x = b for the damped DLS system J Jᵀ + λ² I (λ > 0: symmetric positive definite, never
    singular): the LAPACK gesv gufunc np.linalg.solve calls for a vector b (numpy is pinned, pyproject.toml),
    without its argument checks and error-state context, which cost more than the 6×6 solve itself."""
    return _umath_linalg.solve1(system, b, signature="dd->d")


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
    problem = cached_problem(model, joints)
    stack = problem.stack(targets)
    err = stack.err
    reg = problem.reg(len(err), damping)  # the DLS damping term, formed once
    rest = _posture_vector(problem, posture)
    qadr = problem.coords
    q = np.array(q0, dtype=float)
    q[qadr] = np.minimum(np.maximum(q[qadr], problem.lo), problem.hi)  # = np.clip
    best, converged, moved = (np.inf, q.copy(), (np.inf, np.inf)), None, np.inf
    for _ in range(max_iter):
        problem.kinematics(q)
        residual = stack.errors()
        score = max(residual[0] / tol, residual[1] / rot_tol)
        if score <= 1.0:
            converged = (q.copy(), residual)
            if rest is None or moved < POSTURE_SETTLED:
                break
        elif score < best[0]:
            best = (score, q.copy(), residual)
        jac = stack.jacobian()  # only when a step follows (not on the final check)
        current = q[qadr].copy()
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


def _at_limit(q: np.ndarray, problem: _Problem) -> bool:
    """Some moving joint sits at (or beyond) a limit (= (q <= lo).any() or (q >= hi).any(), on Python floats)."""
    return any(v <= lo or v >= hi for v, lo, hi in zip(q.tolist(), problem.lo_list, problem.hi_list))


def _limited_step(problem: _Problem, q: np.ndarray, jac, err, rest, damping, max_step, posture_gain,
                  reg: np.ndarray | None = None) -> np.ndarray:
    """The moving joints after one DLS step (+ null-space posture pull), inside their limits: a joint
    at a limit that the step pushes further is frozen and the step recomputed without it."""
    lo, hi = problem.lo, problem.hi
    at_limit = _at_limit(q, problem)
    if rest is None and not at_limit:  # the usual tick: one plain DLS step, Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e
        # ndarray.dot: the same BLAS calls (syrk, gemv) as @ for these shapes and layouts, the same bits (checked
        # on 100k random cases per shape), at a third of @'s call cost
        jt = jac.T
        system = jac.dot(jt) + (damping**2 * np.eye(len(err)) if reg is None else reg)
        step = jt.dot(_solve_regular(system, err) if damping > 0 else np.linalg.solve(system, err))
        biggest = float(_MAX(np.abs(step)))
        if biggest > max_step:
            step *= max_step / biggest
        step += q  # = q + step (IEEE addition commutes), in place
        return np.minimum(np.maximum(step, lo, out=step), hi, out=step)  # = np.clip, without its dispatch
    at_lo, at_hi = q <= lo, q >= hi
    free = np.ones(len(q), dtype=bool)
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
