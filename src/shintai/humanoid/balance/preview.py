"""ZMP pattern generation by preview control of the cart-table model (Kajita et al., ICRA 2003 [84]).

The thesis plans HRP2-JSK's boarding steps onto the scooter with the AutoBalancer [85] of hrpsys-base,
which is built on this pattern generator (§5.4.1, "平行二輪電動スクーターへの乗り込み動作生成"; an
*offline* search index in the thesis's terms, §2.3.2 Table 2.1: "歩行パターン軌道生成 [84] に基づく
AutoBalancer [85]"; §6.2.1 computes the statically stable riding posture by [84] too, §7.3.3 runs
AutoBalancer on the Ninebot). The thesis gives none of its equations or parameters; they are Kajita 2003's:

* cart-table model, CoM at constant height z_c: p = x − (z_c/g) ẍ; the state x = (x, ẋ, ẍ) with the
  jerk u as input, discretised exactly at the period T::

      x(k+1) = A x(k) + b u(k),   p(k) = c x(k)
      A = [[1, T, T²/2], [0, 1, T], [0, 0, 1]],  b = (T³/6, T²/2, T),  c = (1, 0, −z_c/g)

* the servo problem with integral action (Katayama et al. 1985, as Kajita 2003 uses it): minimise
  J = Σ Q_e e(k)² + Δxᵀ Q_x Δx + R Δu(k)², e = p − p_ref, on the incremental system
  x̃ = (e, Δx), Ã = [[1, cA], [0, A]], b̃ = (cb, b); P̃ from the discrete Riccati equation
  (``scipy.linalg.solve_discrete_are``) and, with W = (R + b̃ᵀP̃b̃)⁻¹::

      G_i = W b̃ᵀ P̃ (1, 0, 0, 0)ᵀ,   G_x = W b̃ᵀ P̃ (cA; A)
      G_p(1) = −G_i,   G_p(l) = W b̃ᵀ X̃(l−1),   X̃(1) = −Ã_cᵀ P̃ (1, 0, 0, 0)ᵀ,  X̃(l) = Ã_cᵀ X̃(l−1)
      Ã_c = Ã − b̃ W b̃ᵀ P̃ Ã
      u(k) = −G_i Σ_{i≤k} e(i) − G_x x(k) − Σ_{j=1..N_L} G_p(j) p_ref(k+j)

  x and y are two independent copies of the same system and gains. (hrpsys-base's AutoBalancer runs
  the equivalent 4-state "extended_preview_control" of the same cost; g there is 9.80665, here the
  project's 9.81.)

A footstep list becomes the ZMP reference (:func:`zmp_plan`): the ZMP rests on the support foot in
single support and moves linearly to the next support foot in double support.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import mujoco
import numpy as np
import scipy.linalg

from shintai.core.constants import GRAVITY
from shintai.core.runtime import SET, Module, declare
from shintai.humanoid.constants import (
    CONTROL_PERIOD,
    PLAN_HOLD_S,
    PREVIEW_QE,
    PREVIEW_R,
    PREVIEW_TIME,
    STEP_DOUBLE_S,
    STEP_SINGLE_S,
)


CHANNELS = declare("com_ref", "zmp_ref", kind=SET)  # what PreviewModule writes (loop channels)


def _positive(name: str, value: float) -> float:
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"preview: {name} must be a positive finite number, got {value!r}")
    return value


@lru_cache(maxsize=1)
def hrp2_com_height() -> float:
    """z_c of HRP2-JSK: CoM height above the soles in the model's ``stand`` keyframe (≈0.820 m; Kajita
    2003 used 0.814 m for HRP-2)."""
    from shintai.humanoid.robots.hrp2 import (
        build_hrp2,  # the model compiles only when asked
    )

    model = build_hrp2().model
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("stand").id)
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)
    soles = [data.site_xpos[model.site(f"{s}_sole").id][2] for s in "lr"]
    return float(data.subtree_com[model.body("waist").id][2] - np.mean(soles))


@dataclass(frozen=True)
class CartTable:
    """The discrete cart-table model (Kajita 2003): A, b, c at period ``dt`` for CoM height ``zc``."""

    dt: float
    zc: float
    g: float = GRAVITY

    def __post_init__(self):
        for name in ("dt", "zc", "g"):
            _positive(name, getattr(self, name))

    @property
    def A(self) -> np.ndarray:
        t = self.dt
        return np.array([[1.0, t, t * t / 2], [0.0, 1.0, t], [0.0, 0.0, 1.0]])

    @property
    def b(self) -> np.ndarray:
        t = self.dt
        return np.array([t**3 / 6, t * t / 2, t])

    @property
    def c(self) -> np.ndarray:
        return np.array([1.0, 0.0, -self.zc / self.g])


@dataclass(frozen=True)
class PreviewGains:
    """G_i (scalar), G_x (3,), G_p (N_L,) — G_p[j−1] multiplies p_ref(k+j) — and the Riccati P̃ (4×4)."""

    gi: float
    gx: np.ndarray
    gp: np.ndarray
    P: np.ndarray


def preview_gains(model: CartTable, preview_time: float = PREVIEW_TIME, qe: float = PREVIEW_QE,
                  r: float = PREVIEW_R, qx: np.ndarray | None = None) -> PreviewGains:
    """The preview servo gains of Kajita 2003 (module docstring) for ``model``."""
    _positive("preview_time", preview_time)
    _positive("qe", qe)
    _positive("r", r)
    n = round(preview_time / model.dt)
    if n < 1:
        raise ValueError(f"preview: preview_time {preview_time} s is shorter than one period {model.dt} s")
    qx = np.zeros((3, 3)) if qx is None else np.asarray(qx, float)
    if qx.shape != (3, 3) or not np.all(np.isfinite(qx)) or np.any(np.linalg.eigvalsh((qx + qx.T) / 2) < 0):
        raise ValueError("preview: qx must be a finite positive semi-definite 3×3 matrix")
    A, b, c = model.A, model.b, model.c
    At = np.zeros((4, 4))
    At[0, 0], At[0, 1:], At[1:, 1:] = 1.0, c @ A, A
    bt = np.concatenate([[c @ b], b])[:, None]
    Qt = np.zeros((4, 4))
    Qt[0, 0], Qt[1:, 1:] = qe, qx
    P = scipy.linalg.solve_discrete_are(At, bt, Qt, np.array([[r]]))
    w = 1.0 / (r + float((bt.T @ P @ bt)[0, 0]))
    k = w * (bt.T @ P @ At)[0]  # = (G_i, G_x)
    ac = At - bt @ k[None, :]
    gp = np.empty(n)
    gp[0] = -k[0]
    x = -ac.T @ P[:, 0]
    for j in range(1, n):
        gp[j] = w * float(bt[:, 0] @ x)
        x = ac.T @ x
    return PreviewGains(float(k[0]), k[1:].copy(), gp, P)


class PreviewController:
    """The preview servo (Kajita 2003) on x and y at once: state ``x`` (3, 2) = (position, velocity,
    acceleration) × (x, y) of the CoM, ``err_sum`` (2,) = Σ e. :meth:`step` takes p_ref(k..k+N_L)."""

    def __init__(self, model: CartTable, gains: PreviewGains | None = None, com0=(0.0, 0.0)):
        self.model = model
        self.gains = gains or preview_gains(model)
        self.A, self.b, self.c = model.A, model.b, model.c
        self._b = self.b.tolist()
        self.x = np.zeros((3, 2))
        self.x[0] = np.asarray(com0, float)
        self.err_sum = np.zeros(2)

    @property
    def horizon(self) -> int:
        """N_L, the number of future references one step needs (the window is N_L + 1 long)."""
        return len(self.gains.gp)

    def zmp(self) -> np.ndarray:
        """The cart-table ZMP c x(k) (x, y)."""
        return self.c @ self.x

    def start_at_rest(self, window: np.ndarray) -> None:
        """Begin at rest at CoM ``x[0]`` before the first :meth:`step` with ``window`` (its p_ref(0..N_L)):
        Σ e is set so that the law's previous jerk u(−1) is 0 (x(−1) = x(0)).
        The summed law above is the increment law Δu(k) = −G_i e(k) − G_x Δx(k) − Σ G_p(j) Δp_ref(k+j)
        summed from a rest *with the reference constant over the whole window*; Σ e = 0 at a start
        whose window already holds a step would mean a past jerk that never happened (the CoM kicks
        off with a cart-table ZMP spike: 45 mm for 20 ms with a step 1 s ahead)."""
        g = self.gains
        previous = window[:-1]  # p_ref(j − 1), j = 1..N_L
        self.err_sum = -(g.gx @ self.x + g.gp @ previous) / g.gi

    def step(self, window: np.ndarray) -> np.ndarray:
        """One period: ``window`` (N_L + 1, 2) is p_ref(k), …, p_ref(k + N_L). Returns x(k+1) (3, 2).

        The products with the gains and A stay BLAS's (``dot``: the kernels ``@`` calls, with less dispatch; their
        rounding is the pattern's); the rest, element by element, is on Python floats (the same IEEE operations,
        without a dozen tiny arrays a tick)."""
        g = self.gains
        x = self.x
        (px, py), (rx, ry), (ex, ey) = self.c.dot(x).tolist(), window[0].tolist(), self.err_sum.tolist()
        ex, ey = ex + (px - rx), ey + (py - ry)  # Σ e += c x(k) − p_ref(k)
        self.err_sum[0], self.err_sum[1] = ex, ey
        (fx, fy), (wx, wy) = g.gx.dot(x).tolist(), g.gp.dot(window[1:]).tolist()
        ux, uy = -g.gi * ex - fx - wx, -g.gi * ey - fy - wy  # u(k) = −G_i Σ e − G_x x(k) − Σ G_p(j) p_ref(k+j)
        # x(k+1) = A x(k) + b u(k), row by row (position, velocity, acceleration) × (x, y)
        (a0, a1), (a2, a3), (a4, a5) = self.A.dot(x).tolist()
        b0, b1, b2 = self._b
        self.x = np.array([a0 + b0 * ux, a1 + b0 * uy, a2 + b1 * ux, a3 + b1 * uy, a4 + b2 * ux,
                           a5 + b2 * uy]).reshape(3, 2)
        return self.x


@dataclass(frozen=True)
class PreviewResult:
    """A generated pattern, one row per period: CoM position, velocity, acceleration (K, 2) and the
    cart-table ZMP (K, 2) it produces; ``zmp_ref`` the reference tracked."""

    t: np.ndarray
    com: np.ndarray
    com_vel: np.ndarray
    com_acc: np.ndarray
    zmp: np.ndarray
    zmp_ref: np.ndarray


def generate(zmp_ref: np.ndarray, dt: float = CONTROL_PERIOD, zc: float | None = None,
             controller: PreviewController | None = None) -> PreviewResult:
    """The CoM pattern for a ZMP reference (K, 2) sampled at ``dt``, from rest at its first point
    (the offline use of §5.4: the whole plan is known). The reference is held at its last value
    beyond its end, for the preview window. ``zc`` defaults to :func:`hrp2_com_height`."""
    ref = np.asarray(zmp_ref, float)
    if ref.ndim != 2 or ref.shape[1] != 2 or len(ref) < 1 or not np.all(np.isfinite(ref)):
        raise ValueError(f"preview: zmp_ref must be a finite (K, 2) array, got shape {ref.shape}")
    if controller is None:
        controller = PreviewController(CartTable(dt, hrp2_com_height() if zc is None else zc), com0=ref[0])
    n = controller.horizon
    padded = np.concatenate([ref, np.repeat(ref[-1:], n, axis=0)])
    controller.start_at_rest(padded[:n + 1])
    rows = np.empty((len(ref), 4, 2))
    for k in range(len(ref)):
        rows[k, :3], rows[k, 3] = controller.x, controller.zmp()
        controller.step(padded[k:k + n + 1])
    return PreviewResult(np.arange(len(ref)) * controller.model.dt, rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3], ref)


@dataclass(frozen=True)
class Footstep:
    """One step: foot ``side`` ("l"/"r") lands at ``(x, y)`` (the point the ZMP rests on while it supports)."""

    side: str
    x: float
    y: float


@dataclass(frozen=True)
class ZmpPlan:
    """A ZMP reference ``zmp`` (K, 2) at period ``dt`` and, per period, the supporting foot:
    ``support`` "l", "r" (single support, the other foot swinging) or "lr" (double support)."""

    dt: float
    zmp: np.ndarray
    support: tuple[str, ...]

    @property
    def t(self) -> np.ndarray:
        return np.arange(len(self.zmp)) * self.dt


def zmp_plan(left, right, steps, dt: float = CONTROL_PERIOD, single: float = STEP_SINGLE_S,
             double: float = STEP_DOUBLE_S, hold: float = PLAN_HOLD_S) -> ZmpPlan:
    """The ZMP reference of a footstep list (Kajita 2003's walking example's scheme).

    ``left``/``right``: the feet's initial (x, y); ``steps``: :class:`Footstep` in order. The ZMP rests
    ``hold`` s midway between the feet; for each step it moves linearly (``double`` s, double support)
    onto the *other* foot, rests there ``single`` s while the stepping foot swings to its new place;
    after the last step it moves (``double`` s) midway between the feet and rests ``hold`` s.
    """
    dt, single, double, hold = (_positive(n, v) for n, v in (("dt", dt), ("single", single),
                                                             ("double", double), ("hold", hold)))
    feet = {"l": np.asarray(left, float), "r": np.asarray(right, float)}
    for side, p in feet.items():
        if p.shape != (2,) or not np.all(np.isfinite(p)):
            raise ValueError(f"preview: initial foot {side!r} must be a finite (x, y), got {p!r}")
    zmp, support = [], []

    def rest(point, seconds, who):
        n = round(seconds / dt)
        zmp.extend([point] * n)
        support.extend([who] * n)

    def move(a, b, seconds):
        n = round(seconds / dt)
        zmp.extend(a + (b - a) * (i + 1) / n for i in range(n))
        support.extend(["lr"] * n)

    here = (feet["l"] + feet["r"]) / 2
    rest(here, hold, "lr")
    for step in steps:
        if step.side not in feet:
            raise ValueError(f"preview: a footstep's side is 'l' or 'r', got {step.side!r}")
        landing = np.array([step.x, step.y], float)
        if not np.all(np.isfinite(landing)):
            raise ValueError(f"preview: footstep position must be finite, got {landing!r}")
        stance = "r" if step.side == "l" else "l"
        move(here, feet[stance], double)
        here = feet[stance]
        rest(here, single, stance)
        feet[step.side] = landing
    middle = (feet["l"] + feet["r"]) / 2
    move(here, middle, double)
    rest(middle, hold, "lr")
    return ZmpPlan(dt, np.array(zmp), tuple(support))


class PreviewModule(Module):
    """The pattern generator in the control loop: each period it advances a :class:`PreviewController`
    along a :class:`ZmpPlan` and writes ``com_ref`` (x, y, z_c) and ``zmp_ref`` (x, y) (:data:`CHANNELS`,
    set channels of the loop). After the plan it holds its last point."""

    def __init__(self, plan: ZmpPlan, zc: float | None = None, name: str = "preview"):
        super().__init__(name, plan.dt)
        self.plan = plan
        self.zc = hrp2_com_height() if zc is None else _positive("zc", zc)
        self.controller = PreviewController(CartTable(plan.dt, self.zc), com0=plan.zmp[0])
        n = self.controller.horizon
        self._padded = np.concatenate([plan.zmp, np.repeat(plan.zmp[-1:], n + 1, axis=0)])
        self.controller.start_at_rest(self._padded[:n + 1])
        self.k = 0

    def reset(self, snapshot) -> None:
        self.controller.x[:] = 0.0
        self.controller.x[0] = self.plan.zmp[0]
        self.controller.start_at_rest(self._padded[:self.controller.horizon + 1])
        self.k = 0

    def update(self, snapshot):
        n = self.controller.horizon
        k = min(self.k, len(self.plan.zmp) - 1)
        out = self.references(k)
        self.controller.step(self._padded[k:k + n + 1])
        self.k += 1
        return out

    def references(self, k: int) -> dict:
        """What tick ``k`` writes, before its step: ``com_ref`` (x(k), y(k), z_c), ``zmp_ref`` p_ref(k)."""
        x, y = self.controller.x[0].tolist()
        return {"com_ref": np.array([x, y, self.zc]), "zmp_ref": self._padded[k].copy()}
