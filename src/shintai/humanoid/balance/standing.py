"""HRP2-JSK standing and stepping on its stabilizer stack (seed 000 §5.2, §5.4.1; issue 13).

The stack (:mod:`shintai.humanoid.balance.stabilizer`) in one :class:`~shintai.core.runtime.Loop`, at the 4 ms
control period, in four stages:

1. reference — :class:`~shintai.humanoid.balance.preview.PreviewModule` (``com_ref``, ``zmp_ref`` from a
   :func:`~shintai.humanoid.balance.preview.zmp_plan`) and :class:`FootstepModule` (``sole_ref``, ``support``);
2. stabilizer — :class:`~shintai.humanoid.balance.stabilizer.StabilizerModule` (LIP tracking, ZMP distributor,
   force difference control: ``tau_d_*``, ``tau_*``, ``f_*z``, ``sole_dz``);
3. foot damping — :class:`~shintai.humanoid.balance.foot_damping.FootDampingModule` (Eqs. 5.1–5.3: δ on the
   additive ``foot_damping`` channel; D from ``damping_gain``, written by SLC (§5.3) in a stage after it);
4. IK — :class:`LegIKModule`: the waist under the CoM reference, the soles at their references rotated
   by δ and raised by the force-difference heights → :func:`~shintai.humanoid.robots.leg_ik.legs_ik` → ``ctrl``.

The boarding of §5.4 (Fig. 5.6) is this stepping with the left foot's landing raised onto the scooter's
deck, then the right's: :func:`platform_steps` is that plan on a rigid box.

**Swing foot** (chosen; the thesis has none, hrpsys's GaitGenerator offers cycloid orbits): over the
single-support phase, phase s ∈ [0, 1], the sole rises on a cycloid to ``max(z₀, z₁) + SWING_HEIGHT``
at s = ½ and descends to z₁ (each half z = z_a + (z_b − z_a)(θ − sin θ)/2π, θ = 2π·(2s or 2s − 1));
horizontally it moves on one cycloid (θ − sin θ)/2π of (s − d)/(1 − 2d) between s = d and 1 − d
(d = :data:`SWING_DELAY`) — so it clears an edge before moving over it, like hrpsys's CYCLOIDDELAY orbit. The
sole stays flat (no yaw in the plans).

**CoM → waist** (chosen): the waist is placed at ``com_ref`` minus the waist-to-CoM offset of the
``stand`` keyframe (upright waist); hrpsys's AutoBalancer solves a whole-body CoM IK instead. The legs
moving shift the true CoM by a few mm from that (measured in the tests); the LIP feedback sees it as
a CoM error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from shintai.core.runtime import SET, Loop, Module, declare
from shintai.humanoid.balance.foot_damping import CHANNELS as DAMPING_CHANNELS
from shintai.humanoid.balance.foot_damping import FootDampingModule
from shintai.humanoid.balance.preview import CHANNELS as PREVIEW_CHANNELS
from shintai.humanoid.balance.preview import Footstep, PreviewModule, zmp_plan
from shintai.humanoid.balance.stabilizer import CHANNELS as STABILIZER_CHANNELS
from shintai.humanoid.balance.stabilizer import SIDES, SUPPORT_CODE, StabilizerModule
from shintai.humanoid.constants import (
    BOARDING_CROUCH,
    BOARDING_STEP_X,
    CONTROL_PERIOD,
    DAMPING_D_FLAT,
    DAMPING_T,
    FLOOR,
    HRP2_LINKS,
    PLAN_HOLD_S,
    SETTLE_S,
    SOLE,
    SWING_DELAY,
    SWING_HEIGHT,
    VBOARD,
)
from shintai.humanoid.law_params import check_real
from shintai.humanoid.robots.hrp2 import build_hrp2
from shintai.humanoid.robots.leg_ik import JOINT_NAMES, legs_upright
from shintai.sim.body import MujocoBody

_NONE = np.zeros(0)  # no δ or no height correction for legs_upright
PLATFORM_HEIGHT = VBOARD.deck_height  # m, the V-BOARD's pad top (0.12 m, chosen there), what the boarding steps onto
CHANNELS = {**PREVIEW_CHANNELS, **STABILIZER_CHANNELS, **DAMPING_CHANNELS, **declare("sole_ref", "support", kind=SET),
            **declare("foot_damping")}


@dataclass(frozen=True)
class SoleStep:
    """Foot ``side`` lands with its sole point at (x, y, z)."""

    side: str
    x: float
    y: float
    z: float = 0.0


def _cycloid(u: float) -> float:
    """(θ − sin θ)/2π at θ = 2π u, u clipped to [0, 1]: 0 → 1 with zero slope at both ends."""
    u = min(1.0, max(0.0, u))
    th = 2 * math.pi * u
    return (th - math.sin(th)) / (2 * math.pi)


def swing_point(start, end, s: float, height: float = SWING_HEIGHT) -> np.ndarray:
    """The swinging sole point at phase ``s`` ∈ [0, 1] (module docstring)."""
    p0, p1 = np.asarray(start, float), np.asarray(end, float)
    top = max(p0[2], p1[2]) + height
    z = p0[2] + (top - p0[2]) * _cycloid(2 * s) if s < 0.5 else top + (p1[2] - top) * _cycloid(2 * s - 1)
    xy = p0[:2] + (p1[:2] - p0[:2]) * _cycloid((s - SWING_DELAY) / (1 - 2 * SWING_DELAY))
    return np.array([xy[0], xy[1], z])


class FootstepModule(Module):
    """Writes ``sole_ref`` (left row, right row: the sole points) and ``support`` each period along a
    :class:`~shintai.humanoid.balance.preview.ZmpPlan`: during each single-support run the other foot swings
    (:func:`swing_point`) from where it stands to its :class:`SoleStep`'s landing."""

    def __init__(self, plan, soles: dict, steps, height: float = SWING_HEIGHT, name: str = "footsteps"):
        super().__init__(name, plan.dt)
        self.plan, self.height = plan, check_real("swing height", height, 0.0)
        self.start = {s: np.asarray(soles[s], float).copy() for s in SIDES}
        self.steps = list(steps)
        self.support = [SUPPORT_CODE[s] for s in plan.support]
        # the single-support runs, in order, one per step
        runs, k = [], 0
        while k < len(plan.support):
            if plan.support[k] != "lr":
                j = k
                while j < len(plan.support) and plan.support[j] == plan.support[k]:
                    j += 1
                runs.append((k, j))
                k = j
            else:
                k += 1
        if len(runs) != len(self.steps):
            raise ValueError(f"footsteps: the plan has {len(runs)} single-support phases for {len(self.steps)} steps")
        self.runs = runs
        self._table = np.array([self.soles_at(k) for k in range(len(self.support))])  # (K, 2, 3), once
        self._codes = [np.array(c) for c in self.support]
        self.k = 0

    def reset(self, snapshot) -> None:
        self.k = 0

    def soles_at(self, k: int) -> np.ndarray:
        feet = {s: p.copy() for s, p in self.start.items()}
        for (a, b), step in zip(self.runs, self.steps):
            land = np.array([step.x, step.y, step.z])
            if k < a:
                break
            if k < b:
                feet[step.side] = swing_point(feet[step.side], land, (k - a + 1) / (b - a), self.height)
                break
            feet[step.side] = land
        return np.array([feet["l"], feet["r"]])

    def update(self, snapshot):
        k = min(self.k, len(self.support) - 1)
        self.k += 1
        return {"sole_ref": self._table[k], "support": self._codes[k]}


def stance_heights(plan, soles: dict, steps) -> np.ndarray:
    """Per tick of ``plan``, how far the CoM reference is raised above its start (chosen; the thesis and the
    preview control assume a flat floor): during each single support it moves on a cycloid to the
    stance sole's height, and during the last double support (plus the hold after it) to the mean
    height of the two soles. A leg is never asked to reach further than on the flat floor: the CoM
    rises only once the lower foot has left the floor (rising with both feet down overstretched the
    trailing leg: measured, 68 ticks out of reach stepping onto 0.1 m) and a 0.1 m rise over the 0.8 s
    single support peaks at ≈1 m/s² (a tenth of g the cart-table model neglects)."""
    support, n = plan.support, len(plan.support)
    z = {s: float(soles[s][2]) for s in SIDES}
    events = []  # (first tick, last tick + 1, target height)
    steps, i, k = list(steps), 0, 0
    while k < n:
        j = k
        while j < n and support[j] == support[k]:
            j += 1
        if support[k] != "lr":
            events.append((k, j, z[support[k]]))
            if i < len(steps):  # the swinging foot lands at the end of this run
                z[steps[i].side] = float(steps[i].z)
                i += 1
        elif k > 0 and j == n:
            events.append((k, n, float(np.mean(list(z.values())))))
        k = j
    out = np.zeros(n)
    here = float(np.mean([float(soles[s][2]) for s in SIDES]))
    done = 0
    for k0, k1, target in events:
        out[done:k0] = here
        for kk in range(k0, k1):
            out[kk] = here + (target - here) * _cycloid((kk - k0 + 1) / (k1 - k0))
        here, done = target, k1
    out[done:] = here
    return out - out[0]  # relative to where the soles stand at the start (z_c is measured there)


class StepPreview(PreviewModule):
    """:class:`~shintai.humanoid.balance.preview.PreviewModule` with the CoM reference raised by
    :func:`stance_heights` (stepping up and down)."""

    def __init__(self, plan, heights, zc: float | None = None, base: float = 0.0, name: str = "preview"):
        super().__init__(plan, zc=zc, name=name)
        self.heights = np.asarray(heights, float) + base  # z_c is above the start's sole plane z = base
        self.offset = np.zeros(2)  # (x, y) added to both com_ref and zmp_ref (a rig's reference point, e.g. a scooter's centre)
        if len(self.heights) != len(plan.zmp) or not np.all(np.isfinite(self.heights)):
            raise ValueError(f"preview: heights must be {len(plan.zmp)} finite values, one per plan tick")

    def references(self, k: int) -> dict:
        """The preview's references of tick ``k``, the CoM raised by the stance height and both moved by ``offset``."""
        x, y = self.controller.x[0].tolist()
        (ox, oy), (zx, zy) = self.offset.tolist(), self._padded[k].tolist()
        return {"com_ref": np.array([x + ox, y + oy, self.zc + float(self.heights[k])]),
                "zmp_ref": np.array([zx + ox, zy + oy])}


class LegIKModule(Module):
    """Stage 4: reads ``com_ref``, ``sole_ref``, ``foot_damping`` (δ: L roll, L pitch, R roll, R pitch)
    and ``sole_dz``; writes the whole ``ctrl`` vector: the ``stand`` keyframe's targets with the leg
    joints from :func:`~shintai.humanoid.robots.leg_ik.leg_ik` (waist upright at ``com_ref − com_offset``).
    ``unreachable`` counts the legs whose IK missed."""

    def __init__(self, body: MujocoBody, ctrl0, com_offset, name: str = "leg_ik", period: float = CONTROL_PERIOD):
        super().__init__(name, period)
        self.ctrl0 = np.asarray(ctrl0, float).copy()
        self.com_offset = np.asarray(com_offset, float)
        self.index = {s: [body.id("actuator", f"{s}_{j}") for j in JOINT_NAMES] for s in SIDES}
        self.unreachable = 0
        self._eye = np.eye(3)
        self._legs = np.array(self.index["l"] + self.index["r"])  # both legs' actuators, in one assignment

    def update(self, snapshot):
        delta, dz = snapshot.get("foot_damping"), snapshot.get("sole_dz")
        ctrl = self.ctrl0.copy()
        links = HRP2_LINKS
        missed, finite = legs_upright(snapshot["com_ref"] - self.com_offset, snapshot["sole_ref"],
                                      _NONE if delta is None else delta, _NONE if dz is None else dz, links.hip_y,
                                      links.hip_z, links.ankle_height, links.thigh, links.shank, ctrl, self._legs)
        if not finite:
            raise ValueError("leg_ik: target or waist pose is not finite (com_ref, sole_ref, foot_damping or sole_dz)")
        self.unreachable += missed
        return {"ctrl": ctrl}


class Push(Module):
    """A disturbance, not control: an external force ``force`` (N, world x, y, z) on the body ``link`` (default
    the waist) from ``t0`` for ``duration`` seconds (written into MuJoCo's ``xfrc_applied``). As a Loop module it
    acts at the loop's ticks (snapshot time); called with no argument it is a ``before_physics`` hook of the body
    and acts before every physics step (body time)."""

    def __init__(self, body: MujocoBody, force, t0: float, duration: float, name: str = "push", link: str = "waist"):
        super().__init__(name, None)
        force = np.asarray(force, float)
        if force.shape != (3,) or not np.all(np.isfinite(force)):
            raise ValueError(f"push: force must be a finite (x, y, z) in N, got {force!r}")
        self.body, self.force = body, force
        self.t0, self.duration = check_real("push t0", t0, 0.0), check_real("push duration", duration, 0.0)
        self._id = body.id("body", link)

    def apply(self, t: float) -> None:
        on = self.t0 <= t < self.t0 + self.duration
        self.body.data.xfrc_applied[self._id, :3] = self.force if on else 0.0

    def update(self, snapshot):
        self.apply(snapshot["t"])

    def __call__(self) -> None:
        self.apply(self.body.data.time)


def settle_on_floor(body: MujocoBody, seconds: float = SETTLE_S) -> None:
    """Reset to ``stand`` and let the servos hold it on the floor for ``seconds`` before the stack starts
    (clock back to 0): the contacts load up to the weight first, so the SLC's landing guards (f_z rising
    through F_thre, §5.4.1) do not fire on the first ticks (measured: 14.7 N → 277 N per foot in 8 ms)."""
    body.reset("stand")
    for _ in range(round(seconds / body.dt)):
        body.step()  # with the body's hooks (a scooter's firmware runs before each physics step)
    body.data.time = 0.0
    mujoco.mj_forward(body.model, body.data)


def stand_geometry(body: MujocoBody) -> tuple[dict, np.ndarray]:
    """The sole points (side → (x, y, z)) and the waist-to-CoM offset (world, upright) of the body's
    current state (the ``stand`` keyframe after a reset)."""
    mujoco.mj_kinematics(body.model, body.data)
    mujoco.mj_comPos(body.model, body.data)
    root = body.id("body", "waist")
    soles = {s: body.site_pos(f"{s}_sole") for s in SIDES}
    return soles, body.data.subtree_com[root] - body.data.xpos[root]


def platform_body(height: float = PLATFORM_HEIGHT, x: float = 0.38, y: float = 0.0, size=(0.20, 0.35)):
    """HRP2 on the floor with a rigid box (top ``height``, centre (x, y), half-sizes ``size``) in front:
    by default its near edge 45 mm ahead of the standing soles' toes (x = 0.135 m)."""
    body = build_hrp2()
    spec = body.spec
    spec.worldbody.add_geom(name="platform", type=mujoco.mjtGeom.mjGEOM_BOX, size=[size[0], size[1], height / 2],
                            pos=[x, y, height / 2], rgba=[0.5, 0.45, 0.4, 1], contype=FLOOR, conaffinity=SOLE)
    model = spec.compile()
    key, stand = model.key("stand"), body.model.key("stand")
    key.qpos[:], key.qvel[:], key.ctrl[:] = stand.qpos, stand.qvel, stand.ctrl  # build_hrp2 fills the compiled key
    return MujocoBody(model, substeps=body.substeps, keyframe="stand", spec=spec)


class Standing:
    """HRP2 with the stack (module docstring) on a footstep plan (none: standing still), its slots chosen here.

    ``steps``: :class:`SoleStep` s; ``damping=False`` drops stage 3 (no δ: the foot torque damping
    off); ``D``, ``T`` the damping's gains (Eq. 5.1; one D per axis or one for all); ``lip=False`` no LIP
    tracking; ``force_difference=False`` no height corrections; ``push``: (force (3,), t0, duration) on the
    waist; ``body`` another hrp2 body (e.g. :func:`platform_body`); ``hold`` the plan's rest at the start and
    the end (s); ``crouch`` (m): the CoM reference is lowered by this much during the first hold and stays
    lower (long steps: the hip of a straight-enough trailing leg reaches only ≈0.15 m ahead of its ankle at
    the ``stand`` height, see :data:`BOARDING_CROUCH`). Slots: ``stabilizer`` builds stage 2 as
    ``stabilizer(body, lip=, force_difference=)``, ``ik`` stage 4 as ``ik(body, ctrl0, com_offset)``; ``learner``
    (SLC, :class:`~shintai.humanoid.learning.slc.SLCSchedule`) runs in a stage after the damping, reading its δ
    and e_τ and writing its gain (the order of Fig. 5.4).
    :meth:`stages` composes the stack with the modules a rig adds; :attr:`loop` runs it alone.
    """

    def __init__(self, steps=(), damping: bool = True, lip: bool = True, force_difference: bool = True,
                 push=None, body: MujocoBody | None = None, hold: float | None = None, crouch: float = 0.0,
                 D=DAMPING_D_FLAT, T: float = DAMPING_T, learner: Module | None = None, stabilizer=StabilizerModule,
                 ik=None):
        crouch = check_real("crouch", crouch, 0.0, 0.2)
        self.body = body if body is not None else build_hrp2()
        settle_on_floor(self.body)
        soles, offset = stand_geometry(self.body)
        self.soles = soles
        self.steps = [s if isinstance(s, SoleStep) else SoleStep(*s) for s in steps]
        feet = [Footstep(s.side, s.x, s.y) for s in self.steps]
        kw = {} if hold is None else {"hold": hold}
        self.plan = zmp_plan(soles["l"][:2], soles["r"][:2], feet, **kw)
        self.heights = stance_heights(self.plan, soles, self.steps)
        if crouch:  # lowered on a cycloid over the first hold (the ZMP rests, the CoM is still)
            ramp = round((PLAN_HOLD_S if hold is None else hold) / self.plan.dt)
            self.heights -= crouch * np.array([_cycloid((k + 1) / ramp) for k in range(len(self.heights))])
        # z_c: the CoM above the soles as the body stands (≈ hrp2_com_height() on the floor; any stand)
        base = float(np.mean([soles[s][2] for s in SIDES]))
        self.preview = StepPreview(self.plan, self.heights, zc=float(self.body.data.subtree_com[
            self.body.id("body", "waist")][2]) - base, base=base)
        self.footsteps = FootstepModule(self.plan, soles, self.steps)
        self.stabilizer = stabilizer(self.body, lip=lip, force_difference=force_difference)
        self.damping = FootDampingModule(D=D, T=T) if damping else None
        # the reference CoM height: the keyframe's (PreviewModule writes z_c above z = 0, the floor)
        self.ik = (ik or LegIKModule)(self.body, self.body.data.ctrl, offset + np.array([0.0, 0.0, 0.0]))
        self.push = Push(self.body, *push) if push is not None else None
        self.learner = learner
        self._loop = None

    def stages(self, references=(), governor=(), supervisor=(), beside_damping=(), observers=()) -> list[list[Module]]:
        """The stack's stages with a rig's modules in its slots: ``references`` beside the preview (stage 1),
        ``governor`` a stage of their own before the stabilizer, ``supervisor`` a stage after it (a switcher whose
        guards read its sole forces), ``beside_damping`` in the damping's stage, ``observers`` beside the IK (they
        see every channel of the tick)."""
        stages = [[*([self.push] if self.push else []), self.preview, self.footsteps, *references]]
        if governor:
            stages.append(list(governor))
        stages.append([self.stabilizer])
        if supervisor:
            stages.append(list(supervisor))
        if self.damping is not None:
            stages.append([self.damping, *beside_damping])
        if self.learner is not None:
            stages.append([self.learner])
        stages.append([self.ik, *observers])
        return stages

    @property
    def loop(self) -> Loop:
        """The stack alone in a Loop (built on first use)."""
        if self._loop is None:
            self._loop = Loop(self.body, stages=self.stages(), channels=CHANNELS.values())
        return self._loop

    @property
    def duration(self) -> float:
        return len(self.plan.zmp) * self.plan.dt

    def run(self, seconds: float, every=None) -> None:
        self.loop.run(seconds, every=every)

    def com(self) -> np.ndarray:
        return self.body.data.subtree_com[self.body.id("body", "waist")].copy()

    def fallen(self) -> bool:
        """The waist has dropped 0.15 m below its stand height or tilted more than 0.5 rad."""
        d = self.body.data
        w = self.body.id("body", "waist")
        return bool(d.xpos[w][2] < self._waist_z0 - 0.15 or d.xmat[w][8] < math.cos(0.5))

    @property
    def _waist_z0(self) -> float:
        return float(self.body.model.key("stand").qpos[2])


def push_recovery(force, t0: float = 0.5, duration: float = 0.1, settle: float = 2.5, **stack) -> dict:
    """Stand, push the waist with ``force`` (N, world) for ``duration`` s at ``t0``, run ``settle`` s more.
    ``recovered``: not :meth:`Standing.fallen`, and the CoM back within 10 mm of its reference relative
    to the feet (the soles' mean point) with the soles within 20 mm of where they stood."""
    st = Standing(push=(np.asarray(force, float), t0, duration), **stack)
    try:
        st.run(t0 + duration + settle)
    except Exception:  # noqa: BLE001  a diverged simulation is a fall
        return {"recovered": False, "fallen": True, "com_error_m": math.nan, "sole_shift_m": math.nan}
    feet = np.mean([st.body.site_pos(f"{s}_sole")[:2] for s in SIDES], axis=0)
    ref_feet = np.mean([st.soles[s][:2] for s in SIDES], axis=0)
    com_error = float(np.linalg.norm((st.com()[:2] - feet) - (np.asarray(st.loop.command["com_ref"])[:2] - ref_feet)))
    shift = float(max(np.linalg.norm(st.body.site_pos(f"{s}_sole")[:2] - st.soles[s][:2]) for s in SIDES))
    fallen = st.fallen()
    return {"recovered": bool(not fallen and com_error < 0.01 and shift < 0.02), "fallen": fallen,
            "com_error_m": com_error, "sole_shift_m": shift}


def largest_push(axis: int = 0, forces=range(50, 501, 25), **stack) -> float:
    """The largest push (N for 0.1 s on the waist along world ``axis``) of ``forces``, in increasing
    order, recovered before the first one that is not (0 if none)."""
    best = 0.0
    for f in forces:
        force = np.zeros(3)
        force[axis] = f
        if not push_recovery(force, **stack)["recovered"]:
            break
        best = float(f)
    return best


def platform_steps(soles: dict, x: float = BOARDING_STEP_X, height: float = PLATFORM_HEIGHT,
                   y: float | None = VBOARD.pad_y) -> list[SoleStep]:
    """The boarding's steps on a box: the left foot up onto it (``x`` ahead), then the right beside it,
    each at ±``y`` (default: the V-BOARD's pad centres, ±0.1175 m; ``None``: where the feet stand)."""
    ys = {s: soles[s][1] if y is None else (y if s == "l" else -y) for s in SIDES}
    return [SoleStep("l", x, ys["l"], height), SoleStep("r", x, ys["r"], height)]
