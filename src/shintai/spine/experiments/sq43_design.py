"""``spine.sq43-design``: SQ43's compass search over (a1, a2, a3) from the four Table 3.1 starts, on a
compliant spine model of ours (seed 003 §3.2.3, eqs. 3.1–3.2; :mod:`shintai.spine.sq43.design`). A search,
no body and no loop: a compute experiment."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.spine.robots import SQ43_GRID_CHECK_DEG
from shintai.spine.sq43 import design as sq43
from shintai.spine.sq43.constants import STUCK_TRAVEL_DEG
from shintai.spine.sq43.plots import plot_sq43, plot_sq43_shapes


def joined_path(path: sq43.SearchPath, earlier: list) -> int:
    """1-based index of the first earlier path this one meets (a shared point), else 0."""
    visited = {tuple(np.round(a, 6)) for a in path.points}
    for k, other in enumerate(earlier):
        if visited & {tuple(np.round(a, 6)) for a in other.points}:
            return k + 1
    return 0


def local_max_violations(f, paths, step: float) -> int:
    """Ends with a feasible ±step neighbour better than the end itself (eq. 3.2 says none)."""
    bad = 0
    for path in paths:
        for e in np.eye(3):
            for s in (1, -1):
                a = path.end + s * step * e
                if sq43.feasible(a) and f(a) > path.best:
                    bad += 1
    return bad


def grid_optimum(f, step: float) -> tuple[np.ndarray, float]:
    """Best feasible point of an exhaustive grid with spacing ``step`` over |a_i| ≤ 30°."""
    axis = np.arange(-sq43.BOUND_DEG, sq43.BOUND_DEG + 1e-9, step)
    best, best_a = -np.inf, None
    for a in np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), axis=-1).reshape(-1, 3):
        if sq43.feasible(a):
            v = f(a)
            if v > best:
                best, best_a = v, a
    return best_a, best


@scenario(
    "spine.sq43-design",
    source="seed 003 §3.2.3, Table 3.1, eqs. 3.1–3.2",
    covers=("003:table3.1",),
    summary="SQ43: compass search over (a1, a2, a3) from the four Table 3.1 starts; lifted-foot height objective",
    params=(
        Param("step_deg", sq43.STEP_DEG, "search step δa_i/δt (thesis: 0.5°)", lo=0.05, hi=5.0),
        Param("lift_mm", 30.0, "left-front foot lift relative to the shoulder (chosen)", lo=1.0, hi=100.0),
        Param("k_torsion", sq43.SQ43Params.k_torsion, "foam block torsional stiffness [N·m/rad] (chosen)",
              lo=0.1, hi=1000.0),
    ),
    checks=(
        Check("local_max_violations", "==", 0,
              "thesis eq. 3.2: the search stops only where no ±0.5° neighbour is better", kind="consistency"),
        Check("bound_violations", "==", 0, "thesis §3.2.3: |a_i| ≤ 30° for all four parts, a4 from eq. 3.1", kind="consistency"),
        Check("torsional_stiffness_gain", ">", 1.0,
              "thesis §3.2.3: the reshaping is to raise the spine's torsional stiffness (best end vs its start) — "
              "the search only moves to better neighbours of a proxy our model ties to it", kind="consistency"),
        # the thesis's outcome (§3.2.3, Fig. 3.4): "開始点を設計変数2とした場合の最終評価値が最も高い値となっている．
        # また開始点が設計変数1及び設計変数3の場合は，開始後すぐに極小値に陥っていることが分かる．また設計変数4を
        # 開始点とした場合は最適化の途中から，設計変数1の場合の最適化とほぼ同一の経路をたどっており，ほぼ等しい評価値で
        # 収束している"
        # The thesis's outcome (§3.2.3, Fig. 3.4: start 2 ends best, starts 1 and 3 stuck right away, start 4 joins
        # start 1) is reported beside ours in `thesis`, not checked: the landscape the paths cross is our stand-in's,
        # the thesis's rests on its FEM model, which it does not print (row 003:table3.1 is "not comparable")
    ),
    thesis={
        "best_start": ThesisValue(2, "§3.2.3 Fig. 3.4 ('start 2 reached the highest evaluation')", "best_start"),
        "stuck_immediately": ThesisValue(f"starts 1 and 3 fell into local optima right after starting (ours: stuck "
                                         f"= within {STUCK_TRAVEL_DEG:g}° of travel)", "§3.2.3 Fig. 3.4",
                                         "starts_1_3_stuck"),
        "start4_joins": ThesisValue(1, "§3.2.3 ('start 4 followed nearly the same path as start 1')",
                                    "start4_joins_path"),
        "optimum": ThesisValue("not in the text (Fig. 3.5 only)", "§3.2.3", "best_a1_deg"),
    },
    smoke={"step_deg": 2},
)
def sq43_design(ctx) -> dict:
    p = ctx.params
    prm = replace(sq43.SQ43Params(), lift_m=1e-3 * p["lift_mm"], k_torsion=p["k_torsion"])

    def f(a):
        return sq43.lifted_foot_height_mm(a, prm)

    paths = []
    for k, start in enumerate(sq43.TABLE_3_1):
        paths.append(sq43.compass_search(f, start, p["step_deg"], is_feasible=sq43.feasible))
        ctx.progress(0.15 * (k + 1), f"start {k + 1}")
    grid_a, grid_best = grid_optimum(f, SQ43_GRID_CHECK_DEG)
    ctx.progress(1.0, "grid")
    best = int(np.argmax([pa.best for pa in paths]))
    end = paths[best].end
    plot_sq43(ctx, paths, prm, grid_best)
    plot_sq43_shapes(ctx, sq43.TABLE_3_1, [pa.end for pa in paths], prm)
    ctx.extra["paths"] = [{"start": list(sq43.TABLE_3_1[k]), "end": pa.end.tolist(), "steps": len(pa.points) - 1,
                           "start_mm": pa.values[0], "end_mm": pa.best, "evaluations": pa.evaluations}
                          for k, pa in enumerate(paths)]
    metrics = {f"steps_start{k + 1}": len(pa.points) - 1 for k, pa in enumerate(paths)}
    metrics |= {f"travel_deg_start{k + 1}": (len(pa.points) - 1) * p["step_deg"] for k, pa in enumerate(paths)}
    metrics |= {f"end_mm_start{k + 1}": pa.best for k, pa in enumerate(paths)}
    metrics |= {f"start_mm_start{k + 1}": pa.values[0] for k, pa in enumerate(paths)}
    return metrics | {
        "best_start": best + 1,
        "best_value_mm": paths[best].best,
        "best_a1_deg": float(end[0]), "best_a2_deg": float(end[1]), "best_a3_deg": float(end[2]),
        "best_a4_deg": sq43.fourth_angle(end),
        "best_twist_deg": float(np.degrees(sq43.lift_left_front(end, prm).twist_rad)),
        "torsional_stiffness_gain": sq43.torsional_stiffness(end, prm) / sq43.torsional_stiffness(
            sq43.TABLE_3_1[best], prm),
        "start4_joins_path": joined_path(paths[3], paths[:3]),
        "starts_1_3_stuck": sum((len(paths[k].points) - 1) * p["step_deg"] <= STUCK_TRAVEL_DEG for k in (0, 2)),
        "evaluations": int(sum(pa.evaluations for pa in paths)),
        "local_max_violations": local_max_violations(f, paths, p["step_deg"]),
        "bound_violations": int(sum(not sq43.feasible(pa.end) for pa in paths)),
        "grid_best_mm": grid_best,
        "grid_best_a1_deg": float(grid_a[0]), "grid_best_a2_deg": float(grid_a[1]),
        "grid_best_a3_deg": float(grid_a[2]),
    }
