"""One recorded walk of a trained network and what the seed reports of it (§4.2, §5.2, §6.2): the
outcome (reached, final error, cycles, failures, the legs on the obstacles), the per-cycle table of
Tables 3-7, and the outcome rates over many environments. Used by the walking experiments.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import plots as PL
from shintai.quadruped import robot as R
from shintai.quadruped import swing_order as S
from shintai.quadruped import training as T
from shintai.quadruped import video as QV
from shintai.quadruped import world as W
from shintai.quadruped.episode import Episodes
from shintai.scenarios.registry import Check, Param

WEIGHTS = Param("weights", "", "action-network .npz (empty: the shipped fixed-order network)")

MARGIN_BASIS = ("consistency: the executor shifts the body so that the CoG stays inside the support triangle "
                "(thesis §2.2, §4.1.1) and stops a walk that cannot; a reached walk holds it by construction")


def avoid_checks(section: str, climbers: str, grounded: str, cycles: int = 9,
                 legs_basis: str = "", cycles_quote: str = "") -> tuple[Check, ...]:
    """The checks of a §4.2 walk: ``climbers`` are the legs the thesis puts on the surmountable obstacle
    (e.g. "1 and 3"), ``grounded`` the legs it keeps on the ground, both quoted from ``section`` (or, where
    the thesis names no legs for the walk, ``legs_basis`` says where they come from); ``cycles`` the walking
    cycles it reports (``cycles_quote``: the seed's sentence, when it is not §4.2's)."""
    cycles_quote = cycles_quote or f"ゴールまでに要した歩行周期回数は{cycles}回"
    legs = legs_basis or f"thesis {section}: legs {climbers} climb the surmountable obstacle ('乗り越え動作により障害物を回避')"
    ground = legs_basis or f"thesis {section}: legs {grounded} stay on the ground ('脚を地面に接地している')"
    return (
        Check("reached", "==", 1, f"thesis {section}: the robot's CoG reaches the 0.2 m goal circle "
              "('ロボットが目的地まで移動していることが確認できる')", kind="reproduction"),
        Check("collisions", "==", 0, f"thesis {section}: the wall is avoided (no collision)", kind="reproduction"),
        Check("limit_violations", "==", 0, "consistency: thesis §4.1.2 stops a walk at a joint-limit violation "
              "(eq. 11), and so does the executor: a reached walk has none", kind="consistency"),
        Check("min_stability_margin_m", ">", 0.0, MARGIN_BASIS, kind="consistency"),
        Check("final_error_m", "<", 0.2, "consistency: the goal is the 0.2 m circle (thesis §4.1.1), so a reached "
              "walk ends inside it; the thesis's own error is a thesis value, not this bound", kind="consistency"),
        Check("cycles", "<=", cycles, f"thesis {section}: '{cycles_quote}' ({cycles} "
              "walking cycles)", kind="reproduction"),
        Check("climbed_thesis_legs", "==", 2, legs, kind="reproduction"),
        Check("climbed_other_legs", "==", 0, ground, kind="reproduction"),
    )


def weights_path(text: str) -> Path | None:
    """A ``weights`` parameter: empty for the shipped network, else a path."""
    return Path(text) if text else None


def walk(genome: np.ndarray, env: W.Environment, order=None) -> tuple[Episodes, list[R.CycleRecord]]:
    """One recorded episode of the action network ``genome`` in ``env`` (swing orders by ``order``)."""
    ep = T.evaluate(genome, W.EnvBatch.of([env]), order, record=True)
    return ep, ep.records[0]


def passing_x(env: W.Environment, records: list[R.CycleRecord]) -> float | None:
    """Body x [m] (world) at the end of the first cycle whose CoG is past the obstacles' middle line
    in y: negative when the robot passes them shifted left; None if it never gets past."""
    middle = np.mean([o.polygon[:, 1].mean() for o in env.obstacles])
    for r in records:
        if r.body_poses[-1, 1] > middle:
            return float(r.body_poses[-1, 0])
    return None


def walk_metrics(ep: Episodes, env: W.Environment, records: list[R.CycleRecord], climbers=()) -> dict:
    """Outcome of one recorded walk (the quantities the paper reports for §4.2 and §6.2). ``climbers``:
    the legs (1-4) the thesis puts on the surmountable obstacle; ``climbed_thesis_legs`` counts those
    that stood on it, ``climbed_other_legs`` the other legs that did; ``min_step_cycles`` the cycles
    at the smallest forward step of the command range (ΔYr = 150 mm, constants.COMMAND_RANGE)."""
    error = ep.final_error[0]
    on_top = sorted({leg + 1 for r in records for leg in np.flatnonzero(r.stands_on >= 0)})
    surmountable = [k for k, o in enumerate(env.obstacles) if o.surmountable]
    on_low = {leg + 1 for r in records for leg in np.flatnonzero(np.isin(r.stands_on, surmountable))}
    return {
        "reached": int(T.success(ep)[0]),
        "final_error_m": float(np.hypot(*error)),
        "final_error_x_m": float(error[0]),
        "final_error_y_m": float(error[1]),
        "cycles": int(ep.cycles[0]),
        "collisions": int(sum(r.collided for r in records)),
        "limit_violations": int(sum(r.limit for r in records)),
        "unstable_cycles": int(sum(r.unstable for r in records)),
        "min_stability_margin_m": float(min(r.margins.min() for r in records)),
        "body_movement_mm": float(sum(r.br_mm for r in records)),
        "passing_x_m": passing_x(env, records),
        "legs_on_obstacle": "".join(map(str, on_top)) or "none",
        "climbed_surmountable": int(any(np.isin(r.stands_on, surmountable).any() for r in records)),
        "climbed_thesis_legs": len(on_low & set(climbers)),
        "climbed_other_legs": len(on_low - set(climbers)),
        "min_step_cycles": int(sum(r.command[1] <= C.COMMAND_RANGE[0][1] + 1e-9 for r in records)),
    }


def cycle_table(records: list[R.CycleRecord], env: W.Environment) -> list[dict]:
    """Per walking cycle, as the paper's Tables 3-7: action, Zr, Br, swing order, and more."""
    rows = []
    for r in records:
        dx, dy, dth = r.command
        error = np.asarray(env.destination) - r.body_poses[-1, :2]
        rows.append({"k": r.k, "dX_mm": 1000 * dx, "dY_mm": 1000 * dy, "dtheta_deg": float(np.degrees(dth)),
                     "Zr_mm": 1000 * r.zr, "Br_mm": r.br_mm, "order": S.format_order(S.order_index(r.order)),
                     "legs_on_obstacle": [int(o) for o in r.stands_on], "min_margin_m": float(r.margins.min()),
                     "error_after_m": float(np.hypot(*error)), "collided": r.collided, "limit": r.limit,
                     "unstable": r.unstable})
    return rows


CYCLE_COLUMNS = (("k", "k", "{}"), ("ΔXr [mm]", "dX_mm", "{:.1f}"), ("ΔYr [mm]", "dY_mm", "{:.1f}"),
                 ("Δθr [deg]", "dtheta_deg", "{:.2f}"), ("Zr [mm]", "Zr_mm", "{:.0f}"), ("Br [mm]", "Br_mm", "{:.1f}"),
                 ("order", "order", "{}"), ("legs on obstacle", "legs_on_obstacle", "{}"),
                 ("min margin [m]", "min_margin_m", "{:.3f}"), ("error after [m]", "error_after_m", "{:.3f}"))


def write_cycle_table(ctx, key: str, records: list[R.CycleRecord], env: W.Environment) -> None:
    """The per-cycle table (the paper's Tables 3-7) into ``extra[key]`` and ``<key>.md`` in the run's folder."""
    rows = cycle_table(records, env)
    ctx.extra[key] = rows
    lines = ["| " + " | ".join(h for h, _, _ in CYCLE_COLUMNS) + " |", "|" + "---|" * len(CYCLE_COLUMNS)]
    for row in rows:
        legs = ",".join(str(leg + 1) for leg, on in enumerate(row["legs_on_obstacle"]) if on >= 0) or "—"
        cells = [legs if c == "legs_on_obstacle" else f.format(row[c]) for _, c, f in CYCLE_COLUMNS]
        lines.append("| " + " | ".join(cells) + " |")
    (ctx.out / f"{key}.md").write_text(f"# {ctx.scenario.id}: {env.name}, per walking cycle\n\n" + "\n".join(lines) + "\n")


def record_walk(ctx, prefix: str, records: list[R.CycleRecord]) -> None:
    """A walk's per-cycle signals into the run's log (the time axis is the cycle number k)."""
    for r in records:
        ctx.recorder.record(r.k, **{f"{prefix}pose": r.body_poses[-1], f"{prefix}zr": r.zr,
                                    f"{prefix}br_mm": r.br_mm, f"{prefix}command": r.command,
                                    f"{prefix}footholds": r.footholds, f"{prefix}min_margin": r.margins.min()})


def outcome_rates(ep: Episodes) -> dict:
    """Success rate, failure causes (collision; else joint limit or lost stability; else the 50-cycle
    cap) and, over the successful walks, mean cycles and final error."""
    ok = T.success(ep)
    error = np.hypot(*ep.final_error.T)
    return {"success_rate": float(ok.mean()), "collision_rate": float(ep.collided.mean()),
            "limit_rate": float(((ep.limit | ep.unstable) & ~ep.collided).mean()),
            "timeout_rate": float((~ok & ~ep.collided & ~ep.limit & ~ep.unstable).mean()),
            "mean_cycles": float(ep.cycles[ok].mean()) if ok.any() else None,
            "mean_final_error_m": float(error[ok].mean()) if ok.any() else None}


def avoid(ctx, env: W.Environment, climbers: tuple[int, ...]) -> dict:
    """§4.2's walk of the fixed-order action network (``weights``) in ``env``: recorded, tabled,
    drawn and, with ``--video``, filmed; ``climbers`` as :func:`walk_metrics`."""
    genome = T.load_action(weights_path(ctx.params["weights"]))
    ep, records = walk(genome, env)
    ctx.progress(0.5, "walked")
    record_walk(ctx, "", records)
    write_cycle_table(ctx, "cycles", records, env)
    PL.plot_walks(ctx, "walk", {f"{env.name}: fixed order 4→2→3→1, trained action network": (env, records)})
    QV.film_walk(ctx, records, env)
    return walk_metrics(ep, env, records, climbers)
