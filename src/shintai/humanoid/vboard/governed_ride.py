"""MLC speed governing on HRP2 riding the V-BOARD (seed 000 §6.4, Figs. 6.13, 6.15–6.17): the riding rig
(:class:`~shintai.humanoid.vboard.ride.VboardRide`, behaviour level 3) with
:class:`~shintai.humanoid.vboard.governor.SpeedGovernor` learning the v and ω PID gains online, for the scenarios
``humanoid.speed-governing`` and ``humanoid.integrator-comparison``.

* **Start** (§6.4.1, Fig. 6.15): "図 6.15,図 6.16 はともに学習の開始までは行動レベル2であり、調速行動制御系を OFF
  にした状態から開始する" — the governor is off (zero foot pitch, no learning) until the lift lets go
  ("開始と同時に人間は手を離し") plus ``START_DELAY`` (chosen); t = 0 of the figures is that instant
  (:class:`GatedGovernor`). Fig. 6.16's start (``boarding``): the robot boards from the floor by itself (ch. 5's
  SLC boarding) and learning starts when both feet have landed (the right foot's sole-force guard of Fig. 5.5).
* **Learning** (Eqs. 6.17–6.30, Table 6.6): mini-batches of T_L = 2 s (500 samples), η = 1e-7 (v) / 1e-9 (ω),
  gains from 0, negative gains clipped to 0 and re-learned, termination Eq. 6.32 with k = 3 — all
  :mod:`shintai.humanoid.learning.mlc`'s. The I action uses the prior-value-correcting integrator (Eqs. 6.33–6.39) or,
  for §6.4.2, the I-gain-ratio saturation r_sat = 1.5 (Eq. 6.42).
* **Plant for the sensitivity recursion** (Eqs. 6.20–6.29 need P's K and T): the thesis uses its identified
  Table 6.2. Ours come from ``humanoid.vboard-plant-id``'s identification at its defaults
  (:func:`shintai.humanoid.vboard.plant_id.identified_plant`). Its fit from the commanded u gives K_v < 0 (R² 0.003: the
  foot damping cancels the commanded pitch,
  see that scenario's notes) — a plant MLC cannot use (K > 0 in Eq. 6.20 and Eq. 6.41) — so ``plant="board"``
  (default) takes the same runs' fit of v̇, ω̇ to the boards' own pitch increments (Eqs. 6.6–6.10's plant,
  R² 0.98 for v); ``plant="table6.2"`` takes the thesis's numbers as printed (its units of u are not ours).
* **Analysis**: Routh–Hurwitz flags (Eq. 6.41) per tick and the intervals flagged unstable
  (:func:`unstable_intervals`); u_I's one-tick change at each I-gain increase (:func:`ui_jumps`); the thesis's
  Fig. 6.17 replay of a run's e_v and K_I^v(n) through the saturated integrator (:func:`replay_integrator`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from shintai.core.recorder import Recorder
from shintai.humanoid.constants import CONTROL_PERIOD, K_OMEGA, K_V, R_SAT_V, T_OMEGA, T_V
from shintai.humanoid.learning.mlc import MLC_OMEGA, MLC_V, MLCParams
from shintai.humanoid.learning.prior_value_integrator import PriorValueIntegrator
from shintai.humanoid.learning.slc import SLCParams
from shintai.humanoid.vboard.boarding import boarding_stack
from shintai.humanoid.vboard.constants import BOARDINGS, D_VBOARD, MODES, PLANTS, START_DELAY, VIEW
from shintai.humanoid.vboard.governor import GatedGovernor
from shintai.humanoid.vboard.plant_id import identified_plant
from shintai.humanoid.vboard.ride import VboardRide, scooter_spec
from shintai.scenarios.experiment import Rig

GOVERNOR = "speed_governor"


def plant_values(plant: str) -> dict:
    """K, T of both axes for MLC's sensitivity recursion (module docstring)."""
    if plant == "table6.2":
        return {"K_v": K_V, "T_v": T_V, "K_omega": K_OMEGA, "T_omega": T_OMEGA, "r2_v": float("nan"),
                "r2_omega": float("nan")}
    if plant not in PLANTS:
        raise ValueError(f"plant must be one of {', '.join(PLANTS)}, got {plant!r}")
    return identified_plant("board")


def mlc_params(plant: dict, eta_scale: float = 1.0) -> tuple[MLCParams, MLCParams]:
    """Table 6.6's rates (× ``eta_scale``, 1 = the thesis's) and Eq. 6.32's termination (mlc.py's constants) with
    the plant's K, T."""
    out = []
    for p, a in ((MLC_V, "v"), (MLC_OMEGA, "omega")):
        out.append(replace(p, K=plant[f"K_{a}"], T=plant[f"T_{a}"], eta=tuple(e * eta_scale for e in p.eta)))
    return tuple(out)


def governed_ride(plant: dict, mode: str = "corrected", learn: bool = True, gains=((0.0,) * 3,) * 2,
                  start_delay: float = START_DELAY, eta_scale: float = 1.0, boarding: str | None = None,
                  theta_o_error_deg: float = 0.0, **ride_kw) -> VboardRide:
    """A lift-placed :class:`VboardRide` at level 3 whose governor is a :class:`GatedGovernor` with MLC on the
    given plant and integrator ``mode``; learning starts ``start_delay`` after the lift lets go (or at
    ``start_delay`` without a lift). ``boarding``: Fig. 6.16's start instead — the robot boards by itself from
    the floor (:func:`~shintai.humanoid.vboard.boarding.boarding_stack`) and learning starts when both feet have
    landed on the boards by Fig. 5.5's sole-force guard (f_Rz > 25 N; §6.4.1 '両足がボード上に着地したタイミング … 図 5.5
    で示したような足裏反力の閾値判定'), ``start_delay`` unused; ``ride.boarding`` is the (stack, SLC schedule).
    :data:`BOARDINGS`: ``"preset"`` as §6.4.1 writes, '第5章で獲得した足部トルクダンピング制御系まわりのゲイン/パラメータを
    事前に適用した状態から実行する' — D = :data:`~shintai.humanoid.vboard.constants.D_VBOARD` (§5.4.2's learned '約 D =
    40.0') from the start, SLC only marking its window; ``"slc"`` SLC learning D from D₀ = 22 during the boarding
    (Table 5.2), which is §7.4.2's SOLC order rather than §6.4.1's."""
    if mode not in MODES:
        raise ValueError(f"mode must be one of {', '.join(MODES)}, got {mode!r}")
    if not start_delay >= 0.0:
        raise ValueError(f"start_delay must be >= 0, got {start_delay!r}")
    stack = sched = None
    if boarding not in (None, *BOARDINGS):
        raise ValueError(f"boarding must be None or one of {', '.join(BOARDINGS)}, got {boarding!r}")
    if boarding is not None:
        preset = boarding == "preset"
        stack = boarding_stack(SLCParams(D0=D_VBOARD) if preset else SLCParams(), learn=not preset,
                               v=scooter_spec(theta_o_error_deg))
        sched = stack[1]
        ride_kw = {k: v for k, v in ride_kw.items() if k != "D"}  # the boarding's own (learned) gains

    def governor(lift):
        def start(snapshot) -> bool:
            if sched is not None:
                return sched.t_stop is not None
            if lift is None:
                return float(snapshot["t"]) >= start_delay
            return lift.released and float(snapshot["t"]) >= lift.t_release + start_delay
        return GatedGovernor(start, params=mlc_params(plant, eta_scale), gains0=gains, mode=mode, learn=learn,
                             name=GOVERNOR)

    ride = VboardRide(level=3, theta_o_error_deg=theta_o_error_deg, governor=governor,
                      standing=stack[0] if stack else None, **ride_kw)
    ride.boarding = stack
    return ride


def governed_rig(plant: str, learn_s: float, mode: str, seed: int, theta_o_error_deg: float, D: float,
                 start_delay: float = START_DELAY, eta_scale: float = 1.0, learn: bool = True,
                 boarding: str | None = None) -> Rig:
    """One run of the scenarios: :func:`governed_ride` on the plant named ``plant`` (:func:`plant_values`),
    stopping at a fall or ``learn_s`` after the learning start; records the ride's signals every 5 ticks.
    ``boarding``: Fig. 6.16's self-boarding start (:data:`BOARDINGS`, :func:`governed_ride`)."""
    pv = plant_values(plant)
    ride = governed_ride(pv, mode=mode, learn=learn, start_delay=start_delay, theta_o_error_deg=theta_o_error_deg,
                         D=D, eta_scale=eta_scale, seed=seed, boarding=boarding)
    ride.plant = pv
    before = ride.boarding[0].duration if boarding is not None else 0.0  # the boarding plan's length: a bound on the start

    def until(snapshot) -> bool:
        t0 = ride.governor.t_start
        return ride.fallen() or (t0 is not None and float(snapshot["t"]) >= t0 + learn_s)
    return Rig(ride.body, stages=ride.stages, channels=ride.channels, duration=before + learn_s + 10.0,
               until=until, record={5: ride.signals}, view=VIEW, state=ride)


# --- analysis -------------------------------------------------------------------------------------------


def governor_series(log: Recorder, axis: str, name: str = GOVERNOR) -> dict:
    """The governor's per-tick signals of one axis ('v' or 'omega'): t, e, u, gains (N×3), E, u_I, stable."""
    key = f"{name}.e_{axis}"
    if key not in log.names():
        empty = np.zeros(0)
        return {"t": empty, "e": empty, "u": empty, "gains": np.zeros((0, 3)), "E": empty, "uI": empty, "stable": empty}
    def g(k):
        return log.values(f"{name}.{k}_{axis}")
    return {"t": log.times(key), "e": g("e"), "u": g("u"), "gains": g("gains").reshape(-1, 3), "E": g("E"),
            "uI": g("uI"), "stable": g("stable")}


def unstable_intervals(t, flag) -> list[tuple[float, float]]:
    """The [start, end) intervals where the Routh–Hurwitz flag (Eq. 6.41) is −1."""
    t, bad = np.asarray(t, float), np.asarray(flag) < 0
    out, start = [], None
    for i, b in enumerate(bad):
        if b and start is None:
            start = t[i]
        elif not b and start is not None:
            out.append((float(start), float(t[i])))
            start = None
    if start is not None:
        out.append((float(start), float(t[-1])))
    return out


def ui_jumps(series: dict) -> np.ndarray:
    """|u_I(t+Δt) − u_I(t)| on the tick where each I-gain increase takes effect (the gain logged at tick k acts
    from tick k+1, prior_value_integrator's choice); an empty array if K_I never rose."""
    KI, uI = series["gains"][:, 1], series["uI"]
    rises = np.flatnonzero(np.diff(KI) > 0) + 1  # ticks whose logged gain is the new one
    k = rises[rises + 1 < uI.size] + 1
    return np.abs(uI[k] - uI[k - 1])


def replay_integrator(series: dict, mode: str, r_sat: float = R_SAT_V, dt: float = CONTROL_PERIOD) -> np.ndarray:
    """u_I of a recorded run's e and K_I(n) re-integrated by another integrator (``mode``, Eq. 6.42's r_sat):
    the thesis's Fig. 6.17 ('図 6.16 の結果を利用して … 飽和制約 r_sat^v = 1.5 を設けた場合の制御入力をプロット').
    The gains are applied with the same one-tick delay as in the run."""
    KI = series["gains"][:, 1]
    integ = PriorValueIntegrator(dt, float(KI[0]) if KI.size else 0.0, mode, r_sat)
    out = np.empty(KI.size)
    for i, e in enumerate(series["e"]):
        out[i] = integ.step(e)  # with the gain in force at tick i
        if i and KI[i] != KI[i - 1]:  # the run's MLC set a new gain at tick i, effective from i+1
            integ.set_gain(KI[i])
    return out


def increase_ticks(s: dict) -> np.ndarray:
    """Ticks k where an I-gain increase first acts (u_I(k) − u_I(k−1) is the jump; see ui_jumps)."""
    k = np.flatnonzero(np.diff(s["gains"][:, 1]) > 0) + 2
    return k[k < s["uI"].size]
