"""E11: the muscle-mode combinations on Cla with arms raised, and Table 4.8 (seed 003 §4.7.2–4.7.3).

One run per mode configuration and axis, from a freshly zeroed spine (§4.6.4): a
:class:`~shintai.spine.scripted.Schedule` commands each posture of §4.7.2's sequence and the modes of
its move — shortening muscles L, lengthening ones the configuration's mode (:func:`interference_modes`)
— the posture player turns it into length targets, the muscle controller follows, and the observer
measures (:mod:`shintai.spine.cla.postures`). :func:`mode_metrics` turns the rows into Table 4.8's columns.
"""

from __future__ import annotations

import numpy as np
from scipy.stats import spearmanr

from shintai.scenarios.experiment import Rig
from shintai.spine.bodies_mujoco import SpineBody
from shintai.spine.cla.constants import CLA_DISC_K_STAR_NM_RAD, CLA_RING_DISC, DISC_LAWS
from shintai.spine.cla.postures import (
    GOAL,
    HOLD_TESTS,
    WHOLE_REF,
    PostureObserver,
    PostureRow,
    PostureTargets,
    axis_sequence,
)
from shintai.spine.cla.setup import CLA_VIEW, calibrated, cla_gains, cla_spring, k_s_gain
from shintai.spine.control import SETPOINTS, Mode, MuscleControl, interference_modes
from shintai.spine.discs import HardeningDiscs
from shintai.spine.geometry import uniform_posture
from shintai.spine.plots import spine_state
from shintai.spine.robots import CLA, E11_LOG_S, E11_SETTLE_S
from shintai.spine.scripted import Schedule

# (shortening mode, lengthening mode, k_s level) — §4.7.2's list; mode 6 is L + T
MODE_CONFIGS = {
    "all_l": (Mode.L, Mode.L, None),
    "all_ll": (Mode.LL, Mode.LL, None),
    "all_s_mid": (Mode.S, Mode.S, "mid"),
    "all_s_high": (Mode.S, Mode.S, "high"),
    "l_ll": (Mode.L, Mode.LL, None),
    "l_t": (Mode.L, Mode.T, None),
    "l_s_mid": (Mode.L, Mode.S, "mid"),
    "l_s_high": (Mode.L, Mode.S, "high"),
}
ABLATION = "all_l_no_interference"  # all-L with the wrap sphere removed (spec §5.3.9)
THESIS_ROW = {"all_l": 1, "all_ll": 2, "all_s_mid": 3, "all_s_high": 4, "l_ll": 5, "l_t": 6, "l_s_mid": 7, "l_s_high": 8}
# Table 4.8: error pitch/roll [deg], max held pitch/roll [deg] (30 = "30 or more"), mean tension
# pitch/roll [kgf], mean current pitch/roll [A]; None = "—" (mode 6 buckled)
TABLE_4_8 = {
    "all_l": (4.73, 3.68, 30, 30, 0.20, 0.13, 0.41, 0.33),
    "all_ll": (2.85, 2.93, 10, 30, 0.48, 0.47, 0.59, 0.64),
    "all_s_mid": (4.83, 4.06, 20, 30, 0.13, 0.13, 0.49, 0.42),
    "all_s_high": (3.86, 4.17, 30, 30, 0.23, 0.25, 0.98, 0.79),
    "l_ll": (3.66, 4.09, 10, 30, 0.09, 0.24, 0.25, 0.38),
    "l_t": (None, None, 0, 0, None, None, None, None),
    "l_s_mid": (5.88, 4.93, 30, 30, 0.26, 0.41, 0.86, 0.99),
    "l_s_high": (6.87, 4.47, 30, 30, 0.25, 0.33, 1.29, 1.04),
}
# Table 4.7 as printed: |model − measured| per posture [deg], None = "—" (caught by hand). Columns: all L, all
# LL, all S high, all S mid, L+LL, L+S mid, L+S high (S high before S mid, unlike Table 4.8; the "—" cells
# agree with Table 4.8's held angles under these labels). Columns 2 and 5 look swapped against Table 4.8: their
# roll means are Table 4.8's L+LL and all-LL roll errors (4.09, 2.93; spec §3.4). Pitch rows follow §4.7.2's
# sequence from −10; the roll rows are printed from +10 (the text starts at −10) and lack the final 0.
TABLE_4_7_COLUMNS = ("all_l", "all_ll", "all_s_high", "all_s_mid", "l_ll", "l_s_mid", "l_s_high")
TABLE_4_7 = {
    "pitch": [(0.65, 2.24, 1.50, 8.37, 0.26, 1.20, 3.52), (2.83, 1.01, 0.91, 3.46, 1.27, 0.86, 2.44),
              (4.17, 3.65, 3.03, 1.76, 3.57, 0.10, 1.89), (9.33, 9.50, 7.75, 7.31, 7.95, 8.98, 11.36),
              (7.17, 2.68, 6.27, 6.37, 2.80, 13.54, 13.34), (4.20, 2.89, 3.72, 1.70, 1.22, 10.58, 8.67),
              (2.04, 0.14, 2.09, 3.38, 6.35, 3.33, 4.04), (4.98, None, 3.27, 6.07, None, 0.67, 0.74),
              (4.95, None, 6.52, None, None, 6.23, 0.57), (9.79, None, 9.34, None, None, 5.29, 2.87),
              (8.29, None, 9.65, None, None, 7.15, 4.26), (6.42, None, 7.08, None, None, 6.71, 5.30)],
    "roll": [(1.81, 3.07, 2.14, 3.53, 1.60, 3.93, 2.13), (4.41, 6.38, 5.84, 5.88, 4.28, 7.15, 6.14),
             (8.01, 8.69, 9.92, 10.28, 7.39, 18.48, 14.45), (6.04, 5.97, 6.88, 9.59, 4.80, 4.11, 11.71),
             (2.97, 3.39, 3.71, 4.99, 2.45, 4.30, 5.91), (0.70, 1.06, 0.77, 1.98, 0.54, 1.24, 1.95),
             (1.34, 1.39, 1.70, 0.03, 0.96, 1.74, 0.59), (3.20, 3.17, 3.07, 0.28, 1.29, 3.93, 1.54),
             (4.97, 5.42, 4.11, 1.56, 6.69, 5.15, 1.70), (4.32, 4.11, 4.31, 2.64, 0.04, 2.72, 1.20),
             (2.69, 2.29, 3.47, 1.91, 2.18, 1.46, 1.21)],
}


TABLE_COLUMNS = ("mean_error_pitch_deg", "mean_error_roll_deg", "max_pitch_held_deg", "max_roll_held_deg",
                 "mean_tension_pitch_kgf", "mean_tension_roll_kgf", "mean_current_pitch_a", "mean_current_roll_a")
AXES = {"pitch": 1, "roll": 0}
SUMMARY_KEYS = ("mean_error_pitch_deg", "mean_error_roll_deg", "max_pitch_held_deg", "max_roll_held_deg",
                "mean_tension_kgf", "mean_current_a", "mean_sway_deg", "collapsed", "max_pitch_held_window_deg",
                "max_roll_held_window_deg", "collapsed_window", "max_pitch_held_fall30_deg",
                "max_roll_held_fall30_deg", "collapsed_fall30", "mean_current_posture_a", "max_error_held_deg",
                "t47_error_gap_pitch_deg", "t47_error_gap_roll_deg", "t47_postures_held_pitch",
                "t47_postures_held_roll")


def mode_rig(config: str, axis_name: str, *, max_angle_deg: float, hold_s: float, move_s: float, window_s: float,
             interference: bool, k_s: dict[str, float], spring_law: str, T_l_kgf: float, T_r_kgf: float,
             disc: str = "linear", wrap: str = "sphere", log: bool = True, picture: bool = False) -> Rig:
    """One axis of §4.7.2 for one mode configuration (module doc): postures up to ``max_angle_deg``, each moved to
    in ``move_s``, held ``hold_s`` and measured over its last ``window_s``; ``k_s`` the software springs by level
    (``mid``, ``high``, thesis units of ``spring_law``); ``disc`` one of ``cla.constants.DISC_LAWS``, ``wrap`` the interference geom
    (:data:`~shintai.spine.bodies_mujoco.WRAPS`). ``picture``: keep
    :func:`~shintai.spine.plots.spine_state` at the largest angle."""
    if disc not in DISC_LAWS:
        raise ValueError(f"disc must be one of {DISC_LAWS}, got {disc!r}")
    shortening, lengthening, spring = MODE_CONFIGS[config]
    body = SpineBody(CLA, interference=interference, wrap=wrap)
    if disc == "hardening":
        HardeningDiscs(body, CLA_RING_DISC)
    elif disc == "linear_upright":
        body.set_disc(2 * CLA_DISC_K_STAR_NM_RAD)
    control = MuscleControl(CLA.m, cla_gains(T_l_kgf, T_r_kgf), spring=cla_spring(spring_law))
    if spring:
        control.set_gains(k_s=k_s_gain(k_s[spring], spring_law))
    calibrated(body, control)
    dt, axis = body.dt, AXES[axis_name]
    settle = int(round(E11_SETTLE_S / dt))
    moving = int(round((move_s + hold_s - window_s) / dt))
    window = max(1, int(round(window_s / dt)))
    targets_deg = axis_sequence(max_angle_deg)[1:]
    events = {0: {"mode": shortening}}
    previous = zero = CLA.model.lengths(np.zeros(3 * CLA.n))
    for j, target in enumerate(targets_deg):
        whole = np.zeros(3)
        whole[axis] = np.radians(target)
        lengths = CLA.model.lengths(uniform_posture(whole, CLA.n))
        modes = interference_modes(previous, lengths, lengthening) if shortening != lengthening else shortening
        events[settle + j * (moving + window)] = {"mode": modes, "goal": whole}
        previous = lengths
    observer = PostureObserver(axis, targets_deg, settle, moving, window,
                               max(1, int(round(E11_LOG_S / dt))) if log else None,
                               max_angle_deg if picture else None, limits_rad=CLA.model.chain.upper)
    if picture:  # the spine as the posture's window ends, after the step (a body after-step hook, like a video)
        def capture():
            if observer.picture_due:
                observer.picture_due, observer.picture = False, spine_state(body)
        body.after_step.append(capture)
    return Rig(body, stages=[[Schedule(events)], [PostureTargets(CLA.model, zero, move_s)], [control, observer]],
               channels=(*SETPOINTS, GOAL, WHOLE_REF),
               duration=(settle + len(targets_deg) * (moving + window)) * dt, until=lambda snap: observer.stopped,
               view=dict(CLA_VIEW, azimuth=210.0 if axis_name == "pitch" else 180.0), state=observer)


def max_held(rows: list[PostureRow], max_deg: int, attr: str = "held") -> float:
    """Table 4.8's "max posture-holding angle" — "up to which posture the mode could hold as the
    model posture was changed" (§4.7.3): 10° short of the first posture lost (all-LL lost +20°
    → 10; L + T lost the first → 0), or the whole range if none was lost. ``attr`` names the hold
    test (:data:`~shintai.spine.cla.postures.HOLD_TESTS`: ``held``, ``held_fall30``, ``held_window``)."""
    lost = next((r for r in rows if not getattr(r, attr)), None)
    return float(max_deg) if lost is None else max(0.0, abs(lost.target_deg) - 10.0)


def rows_until_lost(rows: list[PostureRow], attr: str = "held") -> list[PostureRow]:
    """The postures before the first one lost: the thesis has no data after a "—" (the spine was
    caught; Table 4.7, App. A.2)."""
    out = []
    for r in rows:
        if not getattr(r, attr):
            break
        out.append(r)
    return out


def _mean(values) -> float:
    return float(np.mean(values)) if values else float("nan")


def table_4_7_gap(mode: str, axis_name: str, rows: list[PostureRow]) -> float:
    """|our mean error − Table 4.7's| over the postures both hold (ours: before the first lost; the thesis's:
    not "—"), matched by their place in the sequence (the roll rows mirrored: Table 4.7 prints them from +10,
    the text and ours start at −10, and Cla is left–right symmetric); NaN when nothing is shared or the mode
    is not in Table 4.7."""
    if mode not in TABLE_4_7_COLUMNS:
        return float("nan")
    column = [row[TABLE_4_7_COLUMNS.index(mode)] for row in TABLE_4_7[axis_name]]
    pairs = [(r.error_deg, t) for r, t in zip(rows_until_lost(rows), column) if t is not None]
    if not pairs:
        return float("nan")
    ours, thesis = np.mean(pairs, axis=0)
    return float(abs(ours - thesis))


def table_4_7_held(mode: str, axis_name: str) -> int:
    """How many postures of the sequence Table 4.7 has data for before its first "—" (the spine caught)."""
    column = [row[TABLE_4_7_COLUMNS.index(mode)] for row in TABLE_4_7[axis_name]]
    return next((i for i, v in enumerate(column) if v is None), len(column))


def summarise_mode(rows_by_axis: dict[str, list[PostureRow]], max_deg: int, mode: str = "") -> dict[str, float]:
    """Per mode: Table 4.8's columns, the overall means, and whether the spine collapsed — over the
    postures before the first lost one (``held``, the thesis's criterion); plus the max-held angles and
    collapse flags of the 30° rule (``*_fall30``) and the window-only test (``*_window``), the current
    averaged over whole postures (move, hold and window) rather than the measuring window
    (``mean_current_posture_a``), the largest error of a held posture, the gap to Table 4.7
    (:func:`table_4_7_gap`, when ``mode`` names one of its columns) and the number of postures held before
    the first lost, over Table 4.7's printed rows (``t47_postures_held_*``, for :func:`table_4_7_held`)."""
    out = {}
    every = []
    for axis_name, rows in rows_by_axis.items():
        held = rows_until_lost(rows)
        every += held
        out[f"mean_error_{axis_name}_deg"] = _mean([r.error_deg for r in held])
        for test in HOLD_TESTS:
            out[f"max_{axis_name}_{test}_deg"] = max_held(rows, max_deg, test)
        out[f"mean_tension_{axis_name}_kgf"] = _mean([r.tension_kgf for r in held])
        out[f"mean_current_{axis_name}_a"] = _mean([r.current_a for r in held])
        out[f"t47_error_gap_{axis_name}_deg"] = table_4_7_gap(mode, axis_name, rows)
        # postures held before the first lost, counted over Table 4.7's printed rows (roll: 11, no final 0)
        out[f"t47_postures_held_{axis_name}"] = min(len(held), len(TABLE_4_7[axis_name]))
    out["mean_sway_deg"] = _mean([r.sway_deg for r in every])
    out["mean_tension_kgf"] = _mean([r.tension_kgf for r in every])
    out["mean_current_a"] = _mean([r.current_a for r in every])
    out["mean_current_posture_a"] = _mean([r.current_posture_a for r in every])
    out["max_error_held_deg"] = float(max((r.error_deg for r in every), default=float("nan")))
    for test in HOLD_TESTS:
        out["collapsed" + test[len("held"):]] = int(any(not getattr(r, test) for rows in rows_by_axis.values()
                                                       for r in rows))
    return out


def held_cells(table: dict[str, dict], test: str = "held") -> dict[tuple[str, str], float]:
    """Table 4.8's "最大姿勢保持角" cells of ours, (mode, axis) → angle, under one hold test."""
    suffix = "" if test == "held" else test[len("held"):]
    return {(mode, axis): summary[f"max_{axis}_held{suffix}_deg"] for mode, summary in table.items()
            if mode in TABLE_4_8 for axis in AXES if f"max_{axis}_held{suffix}_deg" in summary}


def mode_metrics(rows_all: dict[str, dict[str, list[PostureRow]]], names, max_deg: int
                 ) -> tuple[dict[str, float], dict[str, dict]]:
    """E11's metrics from the rows of every run (mode → axis → rows), and each mode's summary."""
    metrics, table = {}, {}
    for mode, by_axis in rows_all.items():
        table[mode] = summary = summarise_mode(by_axis, max_deg, mode)
        metrics |= {f"{mode}.{key}": summary[key] for key in SUMMARY_KEYS if key in summary}
    # Table 4.8's held-angle cells: how many change from the thesis's criterion (held) to the 30° rule and to
    # the window-only test, and — over the thesis's ±30° range only — how many agree with Table 4.8 under each
    # (30 = "30以上")
    cells = {test: held_cells(table, test) for test in HOLD_TESTS}
    thesis = {(m, a): TABLE_4_8[m][TABLE_COLUMNS.index(f"max_{a}_held_deg")] for (m, a) in cells["held"]}
    for test in HOLD_TESTS:
        suffix = "" if test == "held" else test[len("held"):]
        if test != "held":
            metrics[f"held_cells_changed{suffix}"] = sum(cells[test][c] != cells["held"][c] for c in cells["held"])
        if max_deg == 30 and thesis:
            metrics[f"held_cells_agree{suffix}"] = sum(cells[test][c] == thesis[c] for c in thesis)
    if max_deg == 30 and thesis:
        metrics["held_cells"] = len(thesis)
    working = [m for m in names if m != "l_t"]
    l_s = [m for m in working if m.startswith("l_s")]
    if l_s and len(working) > len(l_s):
        for key in ("mean_current_a", "mean_current_posture_a"):
            metrics[f"l_s.max_{key}"] = max(table[m][key] for m in l_s)
            metrics[f"others.max_{key}"] = max(table[m][key] for m in working if m not in l_s)
    # §4.7.2's prediction ("張力が大きい筋ほど l_r とのずれが大きくなる"): over every posture held, in every mode and
    # axis, the rank correlation of the mean muscle tension with the posture error
    held = [r for mode, by_axis in rows_all.items() if mode != ABLATION for rows in by_axis.values()
            for r in rows_until_lost(rows)]
    tension, error = np.array([r.tension_kgf for r in held]), np.array([r.error_deg for r in held])
    if len(held) >= 3:  # undefined (NaN) when either is constant
        metrics["error_tension_rank_correlation"] = (float(spearmanr(tension, error)[0]) if np.ptp(tension) > 0
                                                     and np.ptp(error) > 0 else float("nan"))
    if ABLATION in rows_all and "all_l" in rows_all:
        pairs = [(a.error_deg, b.error_deg) for a, b in zip(rows_until_lost(rows_all["all_l"]["pitch"]),
                                                             rows_until_lost(rows_all[ABLATION]["pitch"]))]
        metrics["interference_error_gain_deg"] = float(np.mean([a - b for a, b in pairs])) if pairs else float("nan")
    return metrics, table
