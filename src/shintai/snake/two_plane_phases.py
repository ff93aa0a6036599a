"""The motions of seed 001 §4.2 (Fig. 4.4) and their transition conditions (§4.2.4) as a Switcher of phases.

The phases are the head transition (A–B), and for each partition of the body into front, connection and
rear parts (two_plane.Partition) straddling propulsion (C) and the front-end shift (D–E). A rear-end shift
changes the partition: it is a transition from straddling with one partition to straddling with the next.

    head ─r_1 within ε_1 (§4.4.1)→ straddle(1, n_h − 2)
    straddle(p) ─n_c < n_c_max, rear end not released→ straddle(p.rear_shift())     "rear_shift" / "release"
    straddle(p) ─n_c ≥ 1 and d_e < ε_d→ front_shift(p)                               "front_shift_start"
    front_shift(p) ─|ψ_{c,1}| < front_shift_tol→ straddle(p.front_shift())           "front_shift"

for every partition reachable from the first (:func:`two_plane_switcher`), the guards of one phase tested in
this order. Transitions whose guards hold at the same instant happen in one control period
(``Switcher(chain=True)``): a completed front shift and the rear shift it allows are one instant (§4.2.4).
The running phase writes the contact code of every wheel, the body's set channel ``contact``.
"""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import Module, Switcher
from shintai.snake.constants import CH4_ROBOT, TWO_PLANE, SnakeGeometry, TwoPlaneCondition, TwoPlaneSettings
from shintai.snake.model3d import forward_kinematics
from shintai.snake.two_plane import (
    Partition,
    TwoPlaneWorld,
    head_input,
    head_raised_contact,
    head_relation,
    head_target,
    straddle_input,
    straddle_model,
)

HEAD, STRADDLE, FRONT_SHIFT = 0, 1, 2  # phase codes, logged as <log>.phase (Fig. 4.4: A–B, C, D–E)
LOG = "tp"  # the phases' signals are logged as tp.*


class HeadTarget:
    """^f w̃_{h,d}(t), ^f ẇ̃_{h,d}(t) of (4.36) from where and when the head transition ended: latched at its
    first call, which is in the control period the straddling starts (A20: sin(2π(t − t_0)/T))."""

    def __init__(self, cond: TwoPlaneCondition):
        self.cond, self.t_0, self.origin = cond, None, None

    def __call__(self, t: float, w_f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if self.t_0 is None:
            self.t_0, self.origin = t, np.array(w_f, dtype=float)
        return head_target(t, self.t_0, self.origin, self.cond)


class HeadTransition(Module):
    """Head transition (4.14): the head part drives r_1 to [r_w, 0, 0] with wheel n_h and the base fixed."""

    def __init__(self, world: TwoPlaneWorld, geometry: SnakeGeometry = CH4_ROBOT,
                 settings: TwoPlaneSettings = TWO_PLANE):
        super().__init__("head", settings.dt)
        self.world, self.geometry, self.settings = world, geometry, settings

    def chain(self, snapshot):
        return forward_kinematics(snapshot["p_h"], snapshot["R_h"], snapshot["psi"], self.geometry.l)

    def landed(self, snapshot) -> bool:
        """Its end (§4.4.1): max|r_{1,d} − r_1| < ε_1. Logs r_1 (``tp.r1``) each period it is tested."""
        r_1 = head_relation(self.chain(snapshot), self.world)
        self.log(float(snapshot["t"]), **{f"{LOG}.r1": r_1})
        return not np.abs(r_1 - [self.world.r_w, 0.0, 0.0]).max() >= self.settings.eps_1

    def update(self, snapshot):
        u, _ = head_input(self.chain(snapshot), self.world, self.settings.n_h, self.settings.k_h)
        return {"psi_dot": u, "contact": head_raised_contact(self.geometry.n, self.settings.n_h).astype(float)}


class Straddle(Module):
    """Straddling propulsion (4.16)–(4.22) with the partition ``part`` or, ``shifting_front``, the front-end shift
    (4.27)–(4.30) that drives ψ_{c,1} → 0; the head follows ``target`` (:class:`HeadTarget`)."""

    def __init__(self, part: Partition, shifting_front: bool, world: TwoPlaneWorld, cond: TwoPlaneCondition,
                 k_v: float, target: HeadTarget, geometry: SnakeGeometry = CH4_ROBOT,
                 settings: TwoPlaneSettings = TWO_PLANE):
        super().__init__(phase_name(part, shifting_front), settings.dt)
        self.part, self.shifting_front, self.world, self.cond, self.k_v = part, shifting_front, world, cond, k_v
        self.target, self.geometry = target, geometry

    def update(self, snapshot):
        t = float(snapshot["t"])
        ch = forward_kinematics(snapshot["p_h"], snapshot["R_h"], snapshot["psi"], self.geometry.l)
        w_f = self.world.planar(ch.P[0], ch.R[0])
        w_d, w_d_dot = self.target(t, w_f)
        model = straddle_model(self.world, self.part, w_f, ch.psi, self.geometry.l)
        step = straddle_input(model, w_f, w_d, w_d_dot, self.cond, self.world.r_w, self.geometry.joint_limit,
                              self.k_v, self.shifting_front)
        part, first = self.part, self.part.n_f + 1
        d_e = self.world.d_e(model.ch.wheel_position(first)) if first <= part.n else np.nan
        self.log(t, **{f"{LOG}.w_f": w_f, f"{LOG}.w_d": w_d, f"{LOG}.r": np.r_[model.r, np.full(3 - len(model.r), np.nan)],
                       f"{LOG}.phase": FRONT_SHIFT if self.shifting_front else STRADDLE, f"{LOG}.n_f": part.n_f,
                       f"{LOG}.n_c": part.n_c, f"{LOG}.n_re": 0 if part.released else part.n_re,
                       f"{LOG}.V": step.V, f"{LOG}.d_e": d_e, f"{LOG}.sigma_H": step.sigma_H,
                       f"{LOG}.sigma_A": step.sigma_A, f"{LOG}.u_norm": float(np.linalg.norm(step.psi_dot))})
        return {"psi_dot": step.psi_dot, "contact": part.contact.astype(float)}


def phase_name(part: Partition, shifting_front: bool) -> str:
    kind = "front_shift" if shifting_front else "straddle"
    return f"{kind} {part.n_f}/{part.n_c}" + (" released" if part.released else "")


def two_plane_switcher(world: TwoPlaneWorld, cond: TwoPlaneCondition, k_v: float | None = None,
                       geometry: SnakeGeometry = CH4_ROBOT, settings: TwoPlaneSettings = TWO_PLANE) -> Switcher:
    """The phases of Fig. 4.4 over every partition reachable from the first, with the guards of §4.2.4 (module
    docstring). ``k_v``: Table 4.1's if None."""
    k_v = cond.k_v if k_v is None else float(k_v)
    target = HeadTarget(cond)
    head = HeadTransition(world, geometry, settings)
    first = Partition(geometry.n, 1, settings.n_h - 2)
    modules, transitions = {"head": head}, [("head", phase_name(first, False), head.landed)]
    todo = [first]
    while todo:
        p = todo.pop(0)
        here = phase_name(p, False)
        if here in modules:
            continue
        modules[here] = Straddle(p, False, world, cond, k_v, target, geometry, settings)
        if p.n_c < settings.n_c_max and not p.released:
            q = p.rear_shift()
            transitions.append((here, phase_name(q, False), lambda s: True))
            todo.append(q)
        if p.n_c >= 1:
            shifting = phase_name(p, True)
            modules[shifting] = Straddle(p, True, world, cond, k_v, target, geometry, settings)
            transitions.append((here, shifting, lambda s, i=p.n_f: world.d_e(s["wheels"][i]) < settings.eps_d))
            q = p.front_shift()
            transitions.append((shifting, phase_name(q, False),
                                lambda s, j=p.connection[0]: abs(s["psi"][j]) < settings.front_shift_tol))
            todo.append(q)
    return Switcher(list(modules.values()), transitions, initial="head", name="phases", period=settings.dt, chain=True)


def events(switcher: Switcher) -> list[tuple[float, str, int, int, int]]:
    """The transitions as (t, kind, n_f, n_c, n_re) of the partition after each (n_re = 0 once released)."""
    out = []
    for t, src, dst in switcher.transitions_log:
        before, after = switcher.modules[src], switcher.modules[dst]
        p = after.part
        kind = ("head_done" if src == "head" else "front_shift_start" if after.shifting_front
                else "front_shift" if before.shifting_front else "release" if p.released else "rear_shift")
        out.append((t, kind, p.n_f, p.n_c, 0 if p.released else p.n_re))
    return out
