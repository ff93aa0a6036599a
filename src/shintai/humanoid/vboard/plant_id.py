"""Identifying the speed plants P_*(s) = K_*/(s(1 + T_* s)) on HRP2 riding the V-BOARD at behaviour level 2
(seed 000 §6.2.2 (D), Eqs. 6.4–6.16, Table 6.2): a known foot-pitch input, the simulated sensors' v and ω, and
:func:`~shintai.humanoid.learning.speed_governing.identify_plant`. Used by ``humanoid.vboard-plant-id`` (which reports
it) and by MLC's sensitivity recursion in ``humanoid.speed-governing`` (:func:`identified_plant`)."""

from __future__ import annotations

import functools

import numpy as np

from shintai.humanoid.constants import CONTROL_PERIOD, VBOARD
from shintai.humanoid.learning.speed_governing import identify_plant
from shintai.humanoid.vboard.constants import (
    D_VBOARD,
    EXCITE_AMPLITUDE,
    EXCITE_PERIOD,
    EXCITE_S,
    FIT_CUTOFF_HZ,
    START_S,
    TABLE_6_2,
    THETA_O_ERROR_DEG,
    VIEW,
)
from shintai.humanoid.vboard.ride import VboardRide, square_wave
from shintai.scenarios.experiment import Rig, run_rig

AXES = ("v", "omega")
# Eq. 6.10 with K_R ≈ K_L (Eq. 6.11), in our units (u in rad per control period): the board-side gains
K_V_EQ610 = VBOARD.wheel_radius / CONTROL_PERIOD * (VBOARD.gain("r") + VBOARD.gain("l")) / 2
K_OMEGA_EQ610 = VBOARD.wheel_radius / CONTROL_PERIOD * (VBOARD.gain("r") + VBOARD.gain("l")) / VBOARD.track


def excitation(axis: str, amplitude: float = EXCITE_AMPLITUDE, period: float = EXCITE_PERIOD,
               span: float = EXCITE_S):
    """A square wave on u_v (run ``v``) or u_ω (run ``omega``) from START_S for ``span`` s (chosen: the thesis
    does not say what input Fig. 6.9's data had). u_ω's amplitude is u_v's × W/2: the same wheel-speed swing.
    One run per axis, each from a fresh boarding (level 2 leaves yaw free: ω creeps over a long run)."""
    wave = square_wave(amplitude if axis == "v" else amplitude * VBOARD.track / 2, period, START_S)

    def u(t: float):
        x = wave(t) if t < START_S + span else 0.0
        return (x, 0.0) if axis == "v" else (0.0, x)
    return u


def plant_id_rig(axis: str, seed: int, excite_s: float = EXCITE_S, amplitude: float = EXCITE_AMPLITUDE,
                 period: float = EXCITE_PERIOD, theta_o_error_deg: float = THETA_O_ERROR_DEG,
                 D: float = D_VBOARD, **ride) -> Rig:
    """One identification run: level 2 with the :func:`excitation` of ``axis``, recording the boards' pitch;
    ``ride``: more :class:`VboardRide` options (e.g. ``com_reading``)."""
    ride = VboardRide(level=2, theta_o_error_deg=theta_o_error_deg, D=D,
                      excite=excitation(axis, amplitude, period, excite_s), seed=seed, **ride)

    def board(snapshot):
        th = {s: float(snapshot[f"board_{s}_pitch"][0]) for s in "rl"}
        return {"board_R": th["r"], "board_L": th["l"]}
    return Rig(ride.body, stages=ride.stages, channels=ride.channels, duration=START_S + excite_s,
               until=lambda s: ride.fallen(), record={1: board}, view=VIEW, state=ride)


def fit(u, y, window, cutoff_hz: float | None = None):
    """Eq. 6.14's fit on the window; ``cutoff_hz`` the low-pass on both sides (:data:`FIT_CUTOFF_HZ` for the fits
    from u, declared before the run; none for the boards' side, an exact consistency fit)."""
    if window.sum() < 50:
        return {"T": float("nan"), "K": float("nan"), "r2": float("nan")}
    return identify_plant(u[window], y[window], CONTROL_PERIOD, cutoff_hz=cutoff_hz)


def series(run):
    rec = run.log
    n = min(len(rec.values("sensors.v")), len(rec.values("foot_pitch.u_v")), len(rec.values("board_R")))
    t = rec.times("sensors.v")[:n]
    get = lambda k: rec.values(k)[:n]
    return t, {k: get(k) for k in ("sensors.v", "sensors.omega", "sensors.true_v", "sensors.true_omega",
                                   "foot_pitch.u_v", "foot_pitch.u_omega", "board_R", "board_L",
                                   "foot_pitch.theta_R", "foot_pitch.theta_L")}


def window(t):
    return t >= START_S


def identification(runs) -> dict:
    """The fits of both runs (``runs['v']``, ``runs['omega']``), from u and from the boards' pitch."""
    (tv, sv), (tw, sw) = series(runs["v"]), series(runs["omega"])
    wv, ww = window(tv), window(tw)
    c = FIT_CUTOFF_HZ
    fv, fw = fit(sv["foot_pitch.u_v"], sv["sensors.v"], wv, c), fit(sw["foot_pitch.u_omega"], sw["sensors.omega"], ww, c)
    # the board side of Eqs. 6.6–6.10: the boards' measured pitch increments (u + the damping's d) → true v, ω
    dR, dL = (np.diff(sv[k], prepend=sv[k][0]) for k in ("board_R", "board_L"))
    # the same fits against the simulator's truth (the sensors' noise and Eq. 6.3's filter out of the way)
    tv_ = fit(sv["foot_pitch.u_v"], sv["sensors.true_v"], wv, c)
    tw_ = fit(sw["foot_pitch.u_omega"], sw["sensors.true_omega"], ww, c)
    bv = fit((dR + dL) / 2, sv["sensors.true_v"], wv)
    dR, dL = (np.diff(sw[k], prepend=sw[k][0]) for k in ("board_R", "board_L"))
    bw = fit((dR - dL) / 2, sw["sensors.true_omega"], ww)
    # how much of the commanded pitch reaches the boards: slope of the boards' mean pitch on the commanded one
    gv = sv["foot_pitch.theta_R"][wv] + sv["foot_pitch.theta_L"][wv]
    board = (sv["board_R"][wv] + sv["board_L"][wv])
    reach = float(np.polyfit(gv - gv.mean(), board - board.mean(), 1)[0]) if wv.sum() > 50 else float("nan")
    return {"fallen_v": int(runs["v"].state.fallen()), "fallen_omega": int(runs["omega"].state.fallen()),
            "ride_v_s": float(tv[-1]), "ride_omega_s": float(tw[-1]),
            "T_v_s": fv["T"], "K_v": fv["K"], "r2_v": fv["r2"], "T_omega_s": fw["T"], "K_omega": fw["K"], "r2_omega": fw["r2"],
            "T_v_true_s": tv_["T"], "K_v_true": tv_["K"], "r2_v_true": tv_["r2"],
            "T_omega_true_s": tw_["T"], "K_omega_true": tw_["K"], "r2_omega_true": tw_["r2"],
            "T_v_board_s": bv["T"], "K_v_board": bv["K"], "r2_v_board": bv["r2"],
            "T_omega_board_s": bw["T"], "K_omega_board": bw["K"], "r2_omega_board": bw["r2"],
            "K_v_eq610": K_V_EQ610, "K_omega_eq610": K_OMEGA_EQ610,
            "K_v_board_ratio": bv["K"] / K_V_EQ610, "K_omega_board_ratio": bw["K"] / K_OMEGA_EQ610,
            "pitch_reaching_boards": reach,
            **{f"{k}_table_ratio": x / TABLE_6_2[k]  # ours / Table 6.2's, the sensors' fits from u
               for k, x in (("K_v", fv["K"]), ("T_v", fv["T"]), ("K_omega", fw["K"]), ("T_omega", fw["T"]))},
            "v_span_mps": float(np.ptp(sv["sensors.true_v"][wv])) if wv.any() else float("nan"),
            "omega_span_rad_s": float(np.ptp(sw["sensors.true_omega"][ww])) if ww.any() else float("nan")}


@functools.lru_cache(maxsize=2)
def identified_plant(source: str = "board") -> dict:
    """K and T for v and ω identified at the default settings (both axes' runs at seed 0, ≈10 s of wall time,
    cached per process): ``source="board"`` the fit to the boards' pitch increments, ``"u"`` the fit to the commanded u
    (K_v < 0 in our rig). Returns {"K_v", "T_v", "K_omega", "T_omega", "r2_v", "r2_omega"}."""
    if source not in ("board", "u"):
        raise ValueError(f"source must be 'board' or 'u', got {source!r}")
    m = identification({axis: run_rig(plant_id_rig(axis, 0)) for axis in AXES})  # the scenario's seed-0 run
    tag = "_board" if source == "board" else ""
    return {"K_v": m[f"K_v{tag}"], "T_v": m[f"T_v{tag}_s"], "K_omega": m[f"K_omega{tag}"],
            "T_omega": m[f"T_omega{tag}_s"], "r2_v": m[f"r2_v{tag}"], "r2_omega": m[f"r2_omega{tag}"]}
