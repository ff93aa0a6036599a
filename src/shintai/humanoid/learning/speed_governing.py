"""The speed-governing control system of seed 000 §6.2.2 (Fig. 6.6) without its learner: the linear velocity
filter (Eq. 6.3), the foot-pitch mixing (Eq. 6.5), the identified robot plant (Eqs. 6.12–6.14, Table 6.2),
its identification (Eqs. 6.14–6.16) and the Routh–Hurwitz monitor (Eqs. 6.40–6.41). The learner (MLC) is
:mod:`shintai.humanoid.learning.mlc`, the PID and its integrator :mod:`shintai.humanoid.learning.prior_value_integrator`.

* (C) linear velocity filter, Eq. 6.3 as printed: v = T_f s/(1 + T_f s) a_x + 1/(1 + T_f s) v_x. The first
  term is an acceleration, not a velocity; read as the complementary filter the text describes (HPF on the
  integrated acceleration, LPF on the VO velocity): v = T_f/(1 + T_f s) a_x + 1/(1 + T_f s) v_x, i.e.
  v̇ = a_x + (v_x − v)/T_f. T_f is not given (chosen below). v_x = dx_VO/dt is the difference of consecutive
  visual-odometry samples (10 ms, Table 6.1), held between samples.
* (D) plant: [Δθ_R, Δθ_L]ᵀ = [[1, 1], [1, −1]] [u_v, u_ω]ᵀ + [d_R, d_L]ᵀ (Eq. 6.5); with K_R ≈ K_L
  (Eq. 6.11) P(s) = diag(K_v/(s(1 + T_v s)), K_ω/(s(1 + T_ω s))) (Eqs. 6.12–6.13), in the time domain
  v̇ = K_v LPF_{T_v}{u_v}, ω̇ = K_ω LPF_{T_ω}{u_ω} (Eq. 6.14). The inputs are foot-pitch increments per control
  period (Eq. 6.7), so (Δθ_R + Δθ_L)/2 drives v and (Δθ_R − Δθ_L)/2 drives ω.
* identification (§6.2.2 (D)): T by phase alignment of LPF_T{u} with the measured ẏ, then K by least squares
  of Σ(ẏ_act − K LPF_T{u})² (Eqs. 6.15–6.16). "Phase alignment" is read as the T that maximises the normalised
  correlation of LPF_T{u} with ẏ_act (a scale-free criterion, so T does not depend on K).
* Routh–Hurwitz: φ(s) = T s³ + (1 + K K_D) s² + K K_P s + K K_I (Eq. 6.40); stable iff K_P > 0, K_I > 0,
  K_D ≥ 0 and K_P (1 + K K_D) − T K_I > 0 (Eq. 6.41); the monitor reports +1 / −1 (Figs. 6.15–6.16 (e)).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize_scalar
from scipy.signal import lfilter

from shintai.core.runtime import Body, declare
from shintai.humanoid.constants import (
    CONTROL_PERIOD,  # Δt ≈ 4 ms of the speed-governing system too (§6.2.2)
    K_OMEGA,
    K_V,
    MIX,
    T_F,
    T_OMEGA,
    T_V,
)
from shintai.humanoid.law_params import check_real


class LinearVelocityFilter:
    """v from a_x (IMU, 4 ms) and x_VO (10 ms) by the complementary filter of Eq. 6.3 (read as in the doc)."""

    def __init__(self, T_f: float = T_F, dt: float = CONTROL_PERIOD):
        self.T_f = check_real("T_f", T_f, 0.0, low_open=True)
        self.dt = check_real("dt", dt, 0.0, low_open=True)
        self._alpha = math.exp(-self.dt / self.T_f)
        self.v = 0.0
        self.v_x = 0.0
        self._vo: tuple[float, float] | None = None

    def vo_sample(self, t: float, x: float) -> float:
        """A new visual-odometry position (robot-local X): v_x = Δx/Δt over consecutive samples."""
        if self._vo is not None and t > self._vo[0]:
            self.v_x = (x - self._vo[1]) / (t - self._vo[0])
        self._vo = (t, x)
        return self.v_x

    def step(self, a_x: float) -> float:
        """One 4 ms step of v̇ = a_x + (v_x − v)/T_f, exact for a_x and v_x held over the step."""
        target = self.v_x + self.T_f * a_x  # the equilibrium of the step
        self.v = target + (self.v - target) * self._alpha
        return self.v


def foot_pitch_increments(u_v: float, u_omega: float, d=(0.0, 0.0)) -> np.ndarray:
    """[Δθ_R, Δθ_L] = [[1, 1], [1, −1]] [u_v, u_ω] + [d_R, d_L] (Eq. 6.5)."""
    return MIX @ np.array([u_v, u_omega], dtype=float) + np.asarray(d, dtype=float)


def plant_inputs(dtheta) -> np.ndarray:
    """The inverse of the mixing: (u_v, u_ω) = ((Δθ_R + Δθ_L)/2, (Δθ_R − Δθ_L)/2)."""
    return np.linalg.solve(MIX, np.asarray(dtheta, dtype=float))


def lowpass(u, T: float, dt: float, w0: float = 0.0) -> np.ndarray:
    """LPF_T{u} of Eq. 6.8: the first-order lag 1/(1 + T s), exact for u held over each sample."""
    a = math.exp(-dt / T)  # w_k = a w_{k−1} + (1 − a) u_k
    return lfilter([1.0 - a], [1.0, -a], np.asarray(u, dtype=float), zi=[a * w0])[0]


class SpeedPlant:
    """y = K/(s(1 + T s)) u (Eqs. 6.13–6.14) for one of v, ω, exact for u held over each ``dt``."""

    def __init__(self, K: float, T: float, dt: float = CONTROL_PERIOD, y0: float = 0.0):
        self.K = check_real("K", K, 0.0, low_open=True)
        self.T = check_real("T", T, 0.0, low_open=True)
        self.dt = check_real("dt", dt, 0.0, low_open=True)
        self._a = math.exp(-self.dt / self.T)
        self.y = float(y0)
        self.w = 0.0  # LPF_T{u}; ẏ = K w

    def step(self, u: float) -> float:
        w, a, T = self.w, self._a, self.T
        self.y += self.K * (u * self.dt + (w - u) * T * (1.0 - a))
        self.w = u + (w - u) * a
        return self.y


class IdentifiedScooterPlant(Body):
    """Fig. 6.6's robot plant (D) as a Body: takes the foot-pitch increments [Δθ_R, Δθ_L] (channel
    ``foot_pitch``, additive: the governor's M u and the damping disturbance d of Eq. 6.5 sum) plus a constant
    ``disturbance`` (d_R, d_L), and shows ``v`` and ``omega``. With the Table 6.2 values it is the model the
    thesis learns on; a speed-governing test or scenario can run MLC on it without the humanoid."""

    channels = declare("foot_pitch")

    def __init__(self, K=(K_V, K_OMEGA), T=(T_V, T_OMEGA), dt: float = CONTROL_PERIOD, disturbance=(0.0, 0.0),
                 y0=(0.0, 0.0)):
        self.dt, self.t = dt, 0.0
        self.axes = [SpeedPlant(k, tc, dt, y) for k, tc, y in zip(K, T, y0, strict=True)]
        self.disturbance = np.asarray(disturbance, dtype=float)
        self.dtheta = np.zeros(2)

    def snapshot(self):
        return {"t": self.t, "v": self.axes[0].y, "omega": self.axes[1].y}

    def apply(self, command):
        self.dtheta = np.asarray(command.get("foot_pitch", np.zeros(2)), dtype=float)

    def step(self):
        u = plant_inputs(self.dtheta + self.disturbance)
        for axis, ui in zip(self.axes, u, strict=True):
            axis.step(ui)
        self.t = round(self.t + self.dt, 9)


def identify_plant(u, y, dt: float, T_bounds=(0.05, 5.0), cutoff_hz: float | None = None) -> dict:
    """Fit ẏ = K LPF_T{u} (Eq. 6.14) to a recorded input u and output y (both sampled at ``dt``).

    ẏ_act is the central difference of y (the thesis differentiates the measured v, ω: Fig. 6.9's noise).
    T maximises the normalised correlation of LPF_T{u} with ẏ_act over ``T_bounds`` (phase alignment); K then
    minimises Σ(ẏ_act − K LPF_T{u})² (Eqs. 6.15–6.16). Returns T, K and the fit's R².

    ``cutoff_hz``: a first-order low-pass at that corner applied to *both* ẏ_act and the model's LPF_T{u} before
    the alignment and the least squares (ours; the thesis fits the raw derivative). Filtering both sides alike
    leaves T and K unbiased and takes the differentiated sensor noise out of R².
    """
    u = np.asarray(u, dtype=float)
    y = np.asarray(y, dtype=float)
    if u.shape != y.shape or u.ndim != 1 or u.size < 10:
        raise ValueError("u and y must be 1-D series of the same length (at least 10 samples)")
    ydot = np.gradient(y, dt)
    tc = None if cutoff_hz is None else 1.0 / (2.0 * math.pi * check_real("cutoff_hz", cutoff_hz, 0.0, low_open=True))

    def smooth(x: np.ndarray) -> np.ndarray:
        return x if tc is None else lowpass(x, tc, dt)

    ydot = smooth(ydot)

    def model(T: float) -> np.ndarray:
        return smooth(lowpass(u, T, dt))

    def misalignment(T: float) -> float:
        w = model(T)
        return -abs(w @ ydot) / (np.linalg.norm(w) * np.linalg.norm(ydot) + 1e-300)

    grid = np.geomspace(*T_bounds, 40)
    best = int(np.argmin([misalignment(T) for T in grid]))
    lo, hi = grid[max(best - 1, 0)], grid[min(best + 1, grid.size - 1)]
    T = float(minimize_scalar(misalignment, bounds=(lo, hi), method="bounded", options={"xatol": 1e-4}).x)
    w = model(T)
    K = float(w @ ydot / (w @ w))
    residual = ydot - K * w
    return {"T": T, "K": K, "r2": 1.0 - float(residual @ residual) / float(ydot @ ydot)}


# --- Routh–Hurwitz (Eqs. 6.40–6.41) ---------------------------------------------------------------------


def characteristic_polynomial(K: float, T: float, gains) -> np.ndarray:
    """φ(s) = T s³ + (1 + K K_D) s² + K K_P s + K K_I (Eq. 6.40), highest power first."""
    KP, KI, KD = gains
    return np.array([T, 1.0 + K * KD, K * KP, K * KI])


def routh_hurwitz(coeffs) -> bool:
    """True iff every root of the polynomial (highest power first, leading coefficient > 0) has a negative real
    part, by the Routh array: every entry of its first column positive. A zero entry means a root on or right
    of the imaginary axis (not asymptotically stable)."""
    c = np.trim_zeros(np.asarray(coeffs, dtype=float), "f")
    if c.size == 0 or c[0] <= 0:
        raise ValueError("routh_hurwitz needs a polynomial with a positive leading coefficient")
    n = c.size
    width = (n + 1) // 2
    rows = [np.zeros(width), np.zeros(width)]
    rows[0][: len(c[0::2])] = c[0::2]
    rows[1][: len(c[1::2])] = c[1::2]
    for _ in range(n - 2):
        a, b = rows[-2], rows[-1]
        if b[0] <= 0:
            return False
        nxt = np.zeros(width)
        nxt[:-1] = (b[0] * a[1:] - a[0] * b[1:]) / b[0]
        rows.append(nxt)
    return bool(all(r[0] > 0 for r in rows[:n]))


def pid_loop_stable(K: float, T: float, gains) -> bool:
    """Eq. 6.41: K_P > 0, K_I > 0, K_D ≥ 0 and K_P (1 + K K_D) − T K_I > 0."""
    KP, KI, KD = gains
    return bool(KP > 0 and KI > 0 and KD >= 0 and KP * (1.0 + K * KD) - T * KI > 0)


def stability_flag(K: float, T: float, gains) -> int:
    """+1 if internally stable by Eq. 6.41, −1 if not (the plots of Figs. 6.15 (e), 6.16 (e))."""
    return 1 if pid_loop_stable(K, T, gains) else -1
