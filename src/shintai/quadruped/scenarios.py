"""Scenarios of seed 004 (TITAN-VIII, RBF networks trained by a GA).

* ``quadruped.replay`` replays the paper's executed action tables (Table 3 of §5.2.1, Tables 6 and 7
  of §6.2): open-loop dead reckoning (§5.7, §6.5 check 4), the same rows through the crawl executor
  in their environments (collisions, joint limits, stability, the legs that climb, the body-raise
  rule), and Tables 3-5's comparison of swing-order strategies by body movement Br.
* ``quadruped.train`` trains the networks (training.py); ``quadruped.avoid-known`` (seed §4.2.1),
  ``quadruped.avoid-unseen`` (§4.2.2), ``quadruped.swing-order`` (§5.2), ``quadruped.free-gait``
  (§6.2) and ``quadruped.generalization`` run the trained networks shipped in ``trained/``;
  ``quadruped.sensing-ablation`` runs the fixed-order network with its obstacle features from the
  simulated ultrasonic sensors of the real robot (sensing.py, seed §3) instead of the known corners.

The model is quasi-static: a walking cycle has no duration, so the recorder's time axis is the cycle
number k and ``sim_time_s`` stays 0.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from shintai.evolve import make_executor

from shintai.quadruped import constants as C
from shintai.quadruped import fitness as F
from shintai.quadruped import plots as PL
from shintai.quadruped import replay as P
from shintai.quadruped import robot as R
from shintai.quadruped import sensing as U
from shintai.quadruped import swing_order as S
from shintai.quadruped import training as T
from shintai.quadruped import video as QV
from shintai.quadruped import world as W
from shintai.quadruped.episode import SENTINELS, Episodes, GenomePolicy, rollout
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario

CLIMBERS = {"table3": "legs 2 and 4", "table6": "leg 1 (leg 3 steps over)", "table7": "legs 2 and 4"}


def zr_agreement() -> tuple[int, int]:
    """Cycles of Tables 3, 6, 7 whose printed Zr the body-raise rule reproduces, and their number."""
    agree = total = 0
    for actions, orders, env in P.TABLES.values():
        envs = W.EnvBatch.of([env()])
        zr, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
        state = R.CrawlState.initial(1)
        for z, c, o in zip(zr, command, orders):
            agree += int(np.isclose(R.body_height(state.pose, state.feet, envs)[0], z))
            total += 1
            state = R.crawl_cycle(state, c[None], S.ORDERS[[o]], np.array([z]), envs).state
    return agree, total


def _draw_obstacles(ax, env: W.Environment) -> None:
    for o in env.obstacles:
        poly = np.vstack([o.polygon, o.polygon[:1]])
        ax.fill(poly[:, 0], poly[:, 1], color="0.3" if not o.surmountable else "tab:orange", alpha=0.5)
        ax.annotate(f"{o.height:g} m", o.polygon.mean(0), fontsize=7, ha="center")


def _plot_paths(ctx, replays: dict) -> None:
    from matplotlib.patches import Circle

    with ctx.figure("paths", nrows=1, ncols=3, figsize=(11, 5.0)) as (fig, axes):
        for ax, (name, rep) in zip(axes, replays.items()):
            env = P.TABLES[name][2]()
            _draw_obstacles(ax, env)
            body = np.array([r.body_poses[-1, :2] for r in rep.records])
            ax.plot(np.r_[0, body[:, 0]], np.r_[0, body[:, 1]], "k.-", lw=1, label="CoG after each cycle")
            for leg, color in zip(range(4), ("tab:blue", "tab:red", "tab:cyan", "tab:pink")):
                feet = np.array([r.footholds[leg] for r in rep.records])
                on = feet[:, 2] > 0
                ax.scatter(feet[~on, 0], feet[~on, 1], s=10, color=color, label=f"leg {leg + 1} ({C.LEG_NAMES[leg]})")
                ax.scatter(feet[on, 0], feet[on, 1], s=30, marker="^", color=color, edgecolors="k")
            ax.add_patch(Circle(env.destination, C.GOAL_RADIUS, fill=False, ls="--"))
            ax.set_aspect("equal")
            ax.set_title(f"{name}: climbs with {CLIMBERS[name]} (▲ = on top)", fontsize=8)
            ax.set_xlabel("x [m]")
        axes[0].set_ylabel("y [m]")
        axes[0].legend(fontsize=6, loc="lower left")


def _plot_br(ctx, comparison: P.BodyMovementComparison) -> None:
    k = np.arange(1, 11)
    with ctx.figure("body_movement", nrows=1, ncols=2, figsize=(10, 4)) as (fig, (ax0, ax1)):
        for values, label, style in ((C.TABLE3_BR, "Table 3 fixed", "o-"), (C.TABLE4_BR, "Table 4 all 24", "s-"),
                                     (C.TABLE5_BR, "Table 5 RBFNN", "^-")):
            ax0.plot(k, values, style, ms=4, lw=1, label=label)
        for values, label, style in ((comparison.fixed, "fixed 4→2→3→1", "o-"),
                                     (comparison.exhaustive, "exhaustive", "s-"),
                                     (comparison.rbfnn, "paper's RBFNN orders", "^-")):
            ax1.plot(k, values, style, ms=4, lw=1, label=label)
        ax0.set_title("paper: Br per cycle", fontsize=9)
        ax1.set_title("this executor: Br of the same actions", fontsize=9)
        for ax in (ax0, ax1):
            ax.set_xlabel("walking cycle k")
            ax.set_ylabel("Br [mm]")
            ax.legend(fontsize=7)


@scenario(
    "quadruped.replay",
    source="seed 004 §5.2, §6.2 (Tables 3-7)",
    summary="replay the paper's action tables: dead reckoning, the crawl executor in their environments, Br of "
            "the swing-order strategies",
    checks=tuple(
        Check(f"{t}_final_error_deviation_m", "<=", C.REPLAY_TOLERANCE,
              f"spec §6.5 check 4: dead-reckoned final |e| = {C.DEAD_RECKONED[t][0]} m within about 1 cm")
        for t in P.TABLES) + tuple(
        Check(f"{t}_first_entry_cycle", "==", C.DEAD_RECKONED[t][1],
              "thesis: the walk ends at the first cycle inside the 0.2 m goal circle (Tables 3, 6, 7)")
        for t in P.TABLES) + (
        Check("executor_failed_cycles", "==", 0,
              "thesis §5.2, §6.2: the printed cycles were executed without collision or joint-limit violation"),
        Check("br_exhaustive_mm", "<=", "br_rbfnn_mm", "thesis Tables 4-5: ΣBr all-24 search <= RBFNN orders",
              name="exhaustive_not_worse_than_rbfnn"),
        Check("br_rbfnn_mm", "<", "br_fixed_mm", "thesis Tables 3, 5: RBFNN orders move the body less than fixed",
              name="rbfnn_better_than_fixed"),
    ),
    thesis={
        "table3_final_error_m": ThesisValue(0.073, "seed 004 §6.2.2 ((0.068, -0.027) m, quoted as the §4.2.2 run)",
                                            "table3_final_error_m"),
        "table6_final_error_m": ThesisValue(0.032, "seed 004 §6.2.1 ((-0.017, -0.027) m)", "table6_final_error_m"),
        "table7_final_error_m": ThesisValue(0.023, "seed 004 §6.2.2 ((-0.018, -0.014) m)", "table7_final_error_m"),
        "br_fixed_mm": ThesisValue(4579.794, "seed 004 Table 3 (sum)", "br_fixed_mm"),
        "br_exhaustive_mm": ThesisValue(4284.435, "seed 004 Table 4 (sum)", "br_exhaustive_mm"),
        "br_rbfnn_mm": ThesisValue(4285.733, "seed 004 Table 5 (sum)", "br_rbfnn_mm"),
        "optimal_orders_table4": ThesisValue(
            "2→4→3→1, 4→2→3→1 x3, 2→4→3→1, 4→2→3→1 x2, 3→1→4→2 x3", "seed 004 Table 4", "exhaustive_orders"),
        "rows_as_table4": ThesisValue(10, "seed 004 Table 4 (rows whose optimal order we reproduce)",
                                      "exhaustive_orders_as_table4"),
    },
)
def replay(ctx) -> dict:
    metrics: dict = {}
    replays = {}
    for i, name in enumerate(P.TABLES):
        reck, rep = P.dead_reckon(name), P.replay_executor(name)
        replays[name] = rep
        metrics[f"{name}_final_error_m"] = reck.final_distance
        metrics[f"{name}_final_error_deviation_m"] = abs(reck.final_distance - C.DEAD_RECKONED[name][0])
        metrics[f"{name}_first_entry_cycle"] = reck.first_entry
        metrics[f"{name}_previous_distance_m"] = reck.previous_distance
        metrics[f"{name}_executor_final_error_m"] = rep.reckoning.final_distance
        metrics[f"{name}_climbing_legs"] = "".join(
            str(leg + 1) for leg in sorted({leg for r in rep.records for leg in np.flatnonzero(r.stands_on >= 0)}))
        for r in rep.records:
            ctx.recorder.record(r.k, **{f"{name}.pose": r.body_poses[-1], f"{name}.br_mm": r.br_mm,
                                        f"{name}.zr": r.zr, f"{name}.min_margin": r.margins.min()})
        ctx.progress((i + 1) / 4)
    metrics["executor_failed_cycles"] = sum(r.collided or r.limit or r.unstable
                                            for rep in replays.values() for r in rep.records)
    metrics["executor_min_stability_margin_m"] = min(float(r.margins.min()) for rep in replays.values()
                                                     for r in rep.records)
    comparison = P.body_movement_comparison()
    metrics["br_fixed_mm"], metrics["br_exhaustive_mm"], metrics["br_rbfnn_mm"] = comparison.sums
    metrics["exhaustive_orders"] = ", ".join(S.format_order(int(o)) for o in comparison.exhaustive_orders)
    metrics["exhaustive_orders_as_table4"] = int(np.sum(comparison.exhaustive_orders == np.array(C.TABLE4_ORDERS)))
    agree, total = zr_agreement()
    metrics["zr_rule_agreement"] = agree / total
    ctx.extra["br_per_cycle_mm"] = {"fixed": comparison.fixed, "exhaustive": comparison.exhaustive,
                                    "rbfnn_orders": comparison.rbfnn, "paper_fixed": C.TABLE3_BR,
                                    "paper_exhaustive": C.TABLE4_BR, "paper_rbfnn": C.TABLE5_BR}
    _plot_paths(ctx, replays)
    _plot_br(ctx, comparison)
    ctx.progress(1.0)
    return metrics


# --- Walks of the trained networks ----------------------------------------------------------------

def _path(text: str) -> Path | None:
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


def walk_metrics(ep: Episodes, env: W.Environment, records: list[R.CycleRecord]) -> dict:
    """Outcome of one recorded walk (the quantities the paper reports for §4.2 and §6.2)."""
    error = ep.final_error[0]
    on_top = sorted({leg + 1 for r in records for leg in np.flatnonzero(r.stands_on >= 0)})
    surmountable = [k for k, o in enumerate(env.obstacles) if o.surmountable]
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


def _record_walk(ctx, prefix: str, records: list[R.CycleRecord]) -> None:
    for r in records:
        ctx.recorder.record(r.k, **{f"{prefix}pose": r.body_poses[-1], f"{prefix}zr": r.zr,
                                    f"{prefix}br_mm": r.br_mm, f"{prefix}command": r.command,
                                    f"{prefix}footholds": r.footholds, f"{prefix}min_margin": r.margins.min()})


def _plot_walks(ctx, name: str, walks: dict) -> None:
    """Top views and per-cycle heights of one or more walks ``{title: (env, records)}``."""
    n = len(walks)
    with ctx.figure(f"{name}_path", nrows=1, ncols=n, figsize=(5.2 * n, 6.2), squeeze=False) as (fig, axes):
        for ax, (title, (env, records)) in zip(axes[0], walks.items()):
            PL.draw_walk(ax, env, records)
            ax.set_title(title, fontsize=8)
        axes[0, 0].legend(fontsize=6, loc="best")
    with ctx.figure(f"{name}_legs", nrows=n, ncols=3, figsize=(12, 3.2 * n), squeeze=False) as (fig, axes):
        for row, (title, (_, records)) in zip(axes, walks.items()):
            PL.draw_heights(*row, records)
            row[0].set_title(title, fontsize=8)


AVOID_CHECKS = (
    Check("reached", "==", 1, "thesis §4.2: the robot reaches the 0.2 m goal circle"),
    Check("collisions", "==", 0, "thesis §4.2: the wall is avoided (no collision)"),
    Check("limit_violations", "==", 0, "thesis §4.1.2: joint angles stay within their ranges"),
    Check("min_stability_margin_m", ">", 0.0, "thesis §2.2: the CoG stays inside the support polygon"),
    Check("final_error_m", "<", 0.2, "issue: the CoG ends within the goal circle (paper 0.059 / 0.054 m)"),
    Check("cycles", "<=", 12, "spec §6.5 check 8: about 9 walking cycles (target ≤ 12)"),
    Check("climbed_surmountable", "==", 1, "thesis §4.2: the legs on the low obstacle's side climb over it"),
)

WEIGHTS = Param("weights", "", "action-network .npz (empty: the shipped fixed-order network)")


def _avoid(ctx, env: W.Environment) -> dict:
    genome = T.load_action(_path(ctx.params["weights"]))
    ep, records = walk(genome, env)
    ctx.progress(0.5, "walked")
    _record_walk(ctx, "", records)
    write_cycle_table(ctx, "cycles", records, env)
    _plot_walks(ctx, "walk", {f"{env.name}: fixed order 4→2→3→1, trained action network": (env, records)})
    if ctx.video:
        QV.render(records, env, ctx.video_path)
    return walk_metrics(ep, env, records)


@scenario(
    "quadruped.avoid-known",
    source="seed 004 §4.2.1 (Figs. 18-19)",
    summary="trained action network, fixed crawl order: right wall, left 0.12 m obstacle, destination (-0.15, 2.2)",
    params=[WEIGHTS],
    checks=AVOID_CHECKS + (
        Check("passing_x_m", "<", 0.0, "thesis §4.2.1: the right obstacle is a wall, the robot moves left"),),
    thesis={
        "final_error_m": ThesisValue(0.059, "seed 004 §4.2.1: (x_de, y_de) = (-0.037, 0.046) m", "final_error_m"),
        "cycles": ThesisValue(9, "seed 004 §4.2.1", "cycles"),
        "legs_on_obstacle": ThesisValue("13", "seed 004 §4.2.1: legs 1 and 3 climb, 2 and 4 pass between",
                                        "legs_on_obstacle"),
        "direction": ThesisValue("left", "seed 004 §4.2.1", "passing_x_m"),
    },
    demo=True,
    video=True,
)
def avoid_known(ctx) -> dict:
    """Seed §4.2.1 with the shipped fixed-order action network.

    What reproduces: the robot shifts left (body x ≈ -0.31 m as it passes the obstacles), leg 1
    climbs the 0.12 m obstacle while the right legs pass the wall on the ground in the gap, and it
    reaches the goal circle without collision, joint-limit violation or loss of static stability
    in 12 cycles (paper about 9; check ≤ 12, met on its bound). It walks the first 7 cycles at the
    smallest forward step of seed §5.1's range (ΔYr = 150 mm) and lengthens to 190-230 mm once past
    the obstacles. The final error is 0.139 m (paper 0.059 m, legs 1 and 3 on top). With 180
    generations (``constants.GA_GENERATIONS``) the network walked every cycle at 150 mm (14
    cycles); before the command was kept in that range the GA found only crab walks around the
    obstacles (27 cycles, no climbing)."""
    return _avoid(ctx, W.scenario_421())


@scenario(
    "quadruped.avoid-unseen",
    source="seed 004 §4.2.2 (Figs. 20-21)",
    summary="trained action network in an environment off the training grid: left wall, right 0.07 m obstacle, "
            "destination (0.35, 2.1)",
    params=[WEIGHTS],
    checks=AVOID_CHECKS + (
        Check("passing_x_m", ">", 0.0, "thesis §4.2.2: the left obstacle is a wall, the robot moves right"),),
    thesis={
        "final_error_m": ThesisValue(0.054, "seed 004 §4.2.2: (x_de, y_de) = (-0.048, 0.024) m", "final_error_m"),
        "cycles": ThesisValue(9, "seed 004 §4.2.2", "cycles"),
        "legs_on_obstacle": ThesisValue("24", "seed 004 §4.2.2: legs 2 and 4 climb, 1 and 3 stay on the ground",
                                        "legs_on_obstacle"),
        "direction": ThesisValue("right", "seed 004 §4.2.2", "passing_x_m"),
    },
    video=True,
)
def avoid_unseen(ctx) -> dict:
    """Seed §4.2.2: obstacle corners, the 0.07 m height and the destination are all off the
    training grid (the paper's one generalisation example).

    As in ``quadruped.avoid-known``: the shipped network moves right (body x ≈ 0.44 m past the
    obstacles), legs 2 and 3 land on the 0.07 m obstacle (paper: legs 2 and 4), and it reaches the
    goal without collision, final error 0.026 m (paper 0.054 m), in 12 cycles (paper 9; check
    ≤ 12, met on its bound): 8 cycles at 150 mm, then 205-218 mm."""
    return _avoid(ctx, W.scenario_422())


# --- Swing order (seed §5) ------------------------------------------------------------------------

def orders_body_movement(records: list[R.CycleRecord], env: W.Environment) -> np.ndarray:
    """Br [mm] ``(n, 24)`` of every swing order for each executed cycle of a walk, from the state the
    cycle started in and with its action and Zr, in ``env``; ``inf`` where the order fails (a
    collision, a joint limit or no stable body position)."""
    n = len(records)
    feet = [R.CrawlState.initial(1).feet[0]] + [r.footholds for r in records[:-1]]
    state = R.CrawlState(np.repeat([r.body_poses[0] for r in records], 24, axis=0),
                         np.repeat([r.zr for r in records], 24), np.repeat(feet, 24, axis=0))
    out = R.crawl_cycle(state, np.repeat([r.command for r in records], 24, axis=0), np.tile(S.ORDERS, (n, 1)),
                        state.zr, W.EnvBatch.of([env]).tile(24 * n))
    return 1000 * np.where(out.failed, np.inf, out.br).reshape(n, 24)


def exhaustive_choice(br: np.ndarray) -> np.ndarray:
    """The order of least Br per row (ties go to the crawl order, then the lower number; as
    ``swing_order.best_orders``)."""
    tied = br <= br.min(axis=1, keepdims=True) + 1000 * S.TIE
    return np.where(tied[:, S.CRAWL], S.CRAWL, np.argmax(tied, axis=1))


def strategies(br: np.ndarray, network: np.ndarray) -> dict:
    """ΣBr [mm] and orders of the fixed order, the exhaustive search and the network's choices."""
    rows = np.arange(len(br))
    best = exhaustive_choice(br)
    return {"fixed": br[:, S.CRAWL], "exhaustive": br[rows, best], "network": br[rows, network],
            "orders": {"fixed": [S.CRAWL] * len(br), "exhaustive": best.tolist(), "network": network.tolist()}}


def _order_names(orders) -> str:
    return ", ".join(S.format_order(int(o)) for o in orders)


def _plot_strategies(ctx, ours: dict, table3: dict) -> None:
    with ctx.figure("body_movement", nrows=1, ncols=2, figsize=(11, 4)) as (fig, axes):
        for ax, data, title in ((axes[0], ours, "trained action network, §5.2 environment"),
                                (axes[1], table3, "the paper's Table 3 actions (flat floor, from the stance)")):
            k = np.arange(1, len(data["fixed"]) + 1)
            for key, style in (("fixed", "o-"), ("exhaustive", "s-"), ("network", "^--")):
                ax.plot(k, data[key], style, ms=4, lw=1, label=f"{key}: Σ {np.sum(data[key]):.1f} mm")
            ax.set_xlabel("walking cycle k")
            ax.set_ylabel("Br [mm]")
            ax.set_title(title, fontsize=9)
            ax.legend(fontsize=7)


@scenario(
    "quadruped.swing-order",
    source="seed 004 §5.2 (Tables 3-5, Figs. 30-32)",
    summary="body movement Br of one action sequence under the fixed order, the exhaustive 24-order search "
            "and the trained swing-order network",
    params=[WEIGHTS, Param("order_weights", "", "swing-order network .npz (empty: the shipped one)")],
    checks=(
        Check("body_movement_exhaustive_mm", "<=", "body_movement_network_mm",
              "thesis Tables 4-5: ΣBr of the exhaustive search ≤ the network's (4284.4 ≤ 4285.7 mm)",
              name="exhaustive_not_worse_than_network"),
        Check("body_movement_network_mm", "<", "body_movement_fixed_mm",
              "thesis Tables 3, 5: the network's orders move the body less than the fixed order (4285.7 < 4579.8 mm)",
              name="network_better_than_fixed"),
        Check("network_order_accuracy", ">=", 0.9,
              "spec §6.5 check 7: accuracy on the teacher patterns (the paper gives none; target assumed)"),
    ),
    thesis={
        "body_movement_fixed_mm": ThesisValue(4579.794, "seed 004 Table 3 (sum)", "body_movement_fixed_mm"),
        "body_movement_exhaustive_mm": ThesisValue(4284.435, "seed 004 Table 4 (sum)", "body_movement_exhaustive_mm"),
        "body_movement_network_mm": ThesisValue(4285.733, "seed 004 Table 5 (sum)", "body_movement_network_mm"),
        "optimal_orders_found": ThesisValue(19, "seed 004 §5.1", "optimal_orders_found"),
        "teacher_patterns": ThesisValue(380, "seed 004 §5.1 (19 orders x 20)", "teacher_patterns"),
        "network_matches_exhaustive": ThesisValue(8, "seed 004 Tables 4-5: differs in cycles 1 and 5 of 10",
                                                  "network_matches_exhaustive"),
    },
)
def swing_order(ctx) -> dict:
    """Seed §5.2: the shipped fixed-order action network walks the §5.2 environment under the crawl
    order; every executed cycle is then re-run from its start state with all 24 orders, and the
    fixed order, the exhaustive search (least Br among the orders that keep stability, the limits
    and clear of the obstacles) and the shipped swing-order network's choice are compared on the same
    action sequence, as the paper does. The same comparison on the paper's own Table 3 actions (flat
    floor, from the initial stance, as ``swing_order.best_orders``) is reported as ``table3_*``.
    ``network_matches_exhaustive`` counts the cycles in which the network's order is an optimal one
    (its Br equals the exhaustive minimum; different orders can tie).

    The network only knows the teacher's ranges (ΔYr 150-350 mm, seed §5.1); the shipped action
    network walks near their lower edge (mean ΔYr 168 mm over the 13 cycles). The shipped
    swing-order network (16 hidden units, ``constants.ORDER_HIDDEN``) picks an optimal order in all
    13 cycles: 2529 mm, equal to the exhaustive search and 2.6 % below the fixed order's 2595 mm (the
    paper: 6.4 % below, 4285.7 vs 4579.8 mm). On the paper's own Table 3 actions it matches the
    exhaustive search in 10 of 10 cycles (``table3_*``: 2444 ≤ 2444 < 2575 mm; the paper's network
    differs in 2 of 10). Off its 160 teacher patterns (``network_heldout_accuracy``, ``network_uniform_*``):
    65 % on a second teacher set built the same way; on 1000 uniform draws of the ranges an optimal
    order (ties counted) in 80 % and an infeasible one in 8 %, mean Br 241 mm against the crawl
    order's 245 and the best 234 mm. The earlier 96-unit network fitted the teacher patterns to
    99.4 % but generalised far worse (47 % held out; on the walk 3 of 13 cycles not optimal and a
    total 0.6 % above the fixed order's, so this check failed): a least-squares output layer of
    96 units on 160 patterns overfits. The hidden size was re-chosen on the held-out sets
    (constants), not on this scenario. Only 8 orders are ever optimal in this executor (paper 19),
    so the teacher set has 160 patterns (paper 380).

    Why 8, not 19 (an audit against the Japanese text of §2.2, §3.2, §4, §5.1; nothing in the
    executor departs from it — Br, the body shift and the tie rule are not specified there): with
    the shortest shift into the support triangle the CoG often needs no shift, so different orders
    trace the same body path and tie exactly (48 % of uniform draws,
    ``network_uniform_tied_fraction``; e.g. 4→2→3→1 with 4→3→1→2, 3→1→4→2 with 3→4→2→1); any
    fixed tie rule folds each tied group into one order (5-10 orders for margins 0-50 mm or other
    turn timings, tried). Counting every tied order gives 19-20 only with margin 0 and no joint
    limits, where 97 % of draws tie (tried) — not a usable teacher. The paper's Br is 1.7-2.3× the
    net displacement (ours: median 1.09×, ``network_uniform_br_over_displacement_median``) and
    grows ≈ 19-26 mm per degree of turn (ours is flat), which points to a larger sway in its
    executor; and Table 4 rows 6-7 (4→2→3→1 kept at Zr = 360 mm where 3→1→4→2 would save ≈ 70 mm
    by the trend of rows 8-10) suggest 3→1→4→2 was infeasible there (joint limits): our chosen
    shoulder positions and θ2 zero leave more reach. Exhaustive
    choices agree with Table 4 in 6 of 10 rows.
    """
    env = W.scenario_52()
    genome = T.load_action(_path(ctx.params["weights"]))
    policy = T.load_order(_path(ctx.params["order_weights"]))
    ep, records = walk(genome, env)
    records = [r for r in records if not (r.collided or r.limit or r.unstable)]
    ctx.progress(0.3, "walked")
    zr, command = np.array([r.zr for r in records]), np.array([r.command for r in records])
    ours = strategies(orders_body_movement(records, env), policy(zr, command))
    zr3, command3 = S.actions_to_si(*C.TABLE3_ACTIONS[:, [3, 0, 1, 2]].T)
    table3 = strategies(1000 * S.body_movement(zr3, command3), policy(zr3, command3))
    ctx.progress(0.7, "orders compared")
    teacher = F.default_teacher()
    metrics = {f"{prefix}body_movement_{k}_mm": float(np.sum(data[k]))
               for prefix, data in (("", ours), ("table3_", table3)) for k in ("fixed", "exhaustive", "network")}
    metrics.update({
        "cycles": len(records), "reached": int(T.success(ep)[0]),
        "network_matches_exhaustive": int(np.sum(ours["network"] == ours["exhaustive"])),
        "network_infeasible_cycles": int(np.sum(~np.isfinite(ours["network"]))),
        "network_reduction_percent": float(100 * (1 - np.sum(ours["network"]) / np.sum(ours["fixed"]))),
        "exhaustive_orders": _order_names(ours["orders"]["exhaustive"]),
        "network_orders": _order_names(ours["orders"]["network"]),
        "table3_network_orders": _order_names(table3["orders"]["network"]),
        "table3_network_matches_exhaustive": int(np.sum(table3["network"] == table3["exhaustive"])),
        "optimal_orders_found": len(teacher.optimal_orders), "teacher_patterns": len(teacher.x),
        "network_order_accuracy": T.order_accuracy(policy, teacher),
        **{f"network_{k}": v for k, v in T.order_generalisation(policy).items()},
        "mean_dY_mm": float(1000 * command[:, 1].mean()),
    })
    ctx.extra["br_per_cycle_mm"] = {"ours": {k: ours[k] for k in ("fixed", "exhaustive", "network")},
                                    "table3": {k: table3[k] for k in ("fixed", "exhaustive", "network")},
                                    "orders": ours["orders"], "table3_orders": table3["orders"]}
    write_cycle_table(ctx, "cycles", records, env)
    _plot_strategies(ctx, ours, table3)
    _plot_walks(ctx, "walk", {f"{env.name}: fixed-order walk whose actions are compared": (env, records)})
    return metrics


# --- Free gait (seed §6) --------------------------------------------------------------------------

def _free_walk(ctx, key: str, env: W.Environment, free, fixed, order) -> tuple[dict, list, list]:
    ep, records = walk(free, env, order)
    base_ep, base_records = walk(fixed, env)
    metrics = {f"{key}_{k}": v for k, v in walk_metrics(ep, env, records).items()}
    base = walk_metrics(base_ep, env, base_records)
    orders = [S.order_index(r.order) for r in records]
    metrics.update({f"{key}_baseline_final_error_m": base["final_error_m"], f"{key}_baseline_cycles": base["cycles"],
                    f"{key}_baseline_reached": base["reached"], f"{key}_orders": _order_names(orders),
                    f"{key}_order_changes": int(np.sum(np.diff(orders) != 0))})
    _record_walk(ctx, f"{key}.", records)
    write_cycle_table(ctx, f"{key}_cycles", records, env)
    return metrics, records, base_records


@scenario(
    "quadruped.free-gait",
    source="seed 004 §6.2 (Tables 6-7, Figs. 33-36)",
    summary="action network re-trained with the swing-order network in the loop (free gait), against the "
            "fixed-order network, in the §4.2.1 and §5.2 environments",
    params=[Param("weights", "", "re-trained action-network .npz (empty: the shipped one)"),
            Param("order_weights", "", "swing-order network .npz (empty: the shipped one)"),
            Param("baseline_weights", "", "fixed-order action-network .npz (empty: the shipped one)")],
    checks=tuple(c for key in ("s621", "s622") for c in (
        Check(f"{key}_reached", "==", 1, "thesis §6.2: the free gait reaches the goal circle"),
        Check(f"{key}_collisions", "==", 0, "thesis §6.2: no collision"),
        Check(f"{key}_min_stability_margin_m", ">", 0.0, "thesis §2.2: the CoG stays inside the support polygon"),
        Check(f"{key}_final_error_m", "<=", f"{key}_baseline_final_error_m",
              "thesis §6.2, spec §6.5 check 9: re-training with the free gait does not increase the final error "
              "(paper 0.059 → 0.032 m, 0.073 → 0.023 m)", name=f"{key}_error_not_larger"),
    )) + (Check("order_changes", ">=", 1, "thesis §6.2: the swing order changes with the displacement"),),
    thesis={
        "s621_final_error_m": ThesisValue(0.032, "seed 004 §6.2.1: (-0.017, -0.027) m", "s621_final_error_m"),
        "s621_cycles": ThesisValue(10, "seed 004 §6.2.1 (Table 6)", "s621_cycles"),
        "s621_baseline_final_error_m": ThesisValue(0.059, "seed 004 §6.2.1 (= §4.2.1)",
                                                   "s621_baseline_final_error_m"),
        "s621_baseline_cycles": ThesisValue(9, "seed 004 §6.2.1 (= §4.2.1)", "s621_baseline_cycles"),
        "s622_final_error_m": ThesisValue(0.023, "seed 004 §6.2.2: (-0.018, -0.014) m", "s622_final_error_m"),
        "s622_cycles": ThesisValue(11, "seed 004 §6.2.2 (Table 7)", "s622_cycles"),
        "s622_baseline_final_error_m": ThesisValue(0.073, "seed 004 §6.2.2: (0.068, -0.027) m (Table 3 run)",
                                                   "s622_baseline_final_error_m"),
        "s622_baseline_cycles": ThesisValue(10, "seed 004 §6.2.2 (Table 3 run)", "s622_baseline_cycles"),
        "s621_orders": ThesisValue("3→1→4→2 x5, 4→2→3→1 x5", "seed 004 Table 6", "s621_orders"),
        "s622_orders": ThesisValue("4→2→3→1 x3, 2→4→3→1 x2, 2→4→1→3, 4→2→3→1 x5",
                                   "seed 004 Table 7", "s622_orders"),
    },
    video=True,
)
def free_gait(ctx) -> dict:
    """Seed §6.2: the shipped re-trained action network with the shipped swing-order network choosing
    each cycle's order, in the §6.2.1 (= §4.2.1) and §6.2.2 (= §5.2) environments, against the
    fixed-order network under the fixed order (the paper's baselines). With ``--video`` the §6.2.1 walk
    is ``video.mp4`` and the §6.2.2 walk ``video_s6.2.2.mp4``.

    With the shipped networks both walks reach the goal through the gap, climbing as in the paper,
    in 12 cycles (baselines 12 and 13; the paper: about one more than its baselines). Over the 96
    training environments the re-trained network does what §6.2 reports: eq. (9) 0.121 against
    the fixed-order network's 0.338, final errors 0.059 m against 0.106 m on average, 11.2 cycles
    against 12.1 (``train_*`` against ``train_baseline_*``); on 200 unseen environments
    (``quadruped.generalization --set network=free``) 0.092 m against 0.103 m, reached 82.5 %
    against 83.5 %. In these two walks the error falls in §6.2.2 (0.058 → 0.037 m; paper 0.073 → 0.023 m) but rises in
    §6.2.1 (0.139 → 0.150 m; paper 0.059 → 0.032 m), so that check fails: the GA lowers the sum
    over the 96 environments, and one environment's error can rise while it does. The orders look
    like the paper's: in §6.2.1 3→1→4→2 for the first six cycles, then 4→2→3→1 (paper, Table 6:
    3→1→4→2 x5, 4→2→3→1 x5); in §6.2.2 4→2→3→1, 3→1→4→2 and
    2→4→3→1 (paper, Table 7: 4→2→3→1, 2→4→3→1 and 2→4→1→3). Legs 1 and 4 (§6.2.1) and 2 (§6.2.2)
    land on the obstacle. (With the earlier 96-unit swing-order network, which overfitted its
    teacher patterns, the re-trained network ended at eq. (9) 0.413, above the fixed order's, and
    §6.2.2's error rose to 0.152 m.)"""
    p = ctx.params
    free = T.load_action(_path(p["weights"]), stage="free")
    fixed = T.load_action(_path(p["baseline_weights"]))
    order = T.load_order(_path(p["order_weights"]))
    metrics, walks = {}, {}
    for i, (key, env) in enumerate((("s621", W.scenario_621()), ("s622", W.scenario_622()))):
        m, records, base = _free_walk(ctx, key, env, free, fixed, order)
        metrics.update(m)
        walks[f"{env.name}: free gait, re-trained network"] = (env, records)
        walks[f"{env.name}: fixed order, fixed-order network"] = (env, base)
        if ctx.video:
            QV.render(records, env, ctx.video_path if key == "s621" else ctx.out / "video_s6.2.2.mp4")
        ctx.progress(0.5 * (i + 1))
    metrics["order_changes"] = metrics["s621_order_changes"] + metrics["s622_order_changes"]
    train = F.training_batch()  # the same comparison over the 96 training environments
    for key, ep in (("train", T.evaluate(free, train, order)), ("train_baseline", T.evaluate(fixed, train))):
        rates = outcome_rates(ep)
        metrics.update({f"{key}_{k}": rates[k] for k in ("success_rate", "mean_cycles", "mean_final_error_m")})
    _plot_walks(ctx, "walk", walks)
    return metrics


# --- Generalisation ---------------------------------------------------------------------------------

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


def _plot_generalisation(ctx, envs: list[W.Environment], train: Episodes, unseen: Episodes) -> None:
    ok = T.success(unseen)
    with ctx.figure("generalization", nrows=1, ncols=3, figsize=(14, 4.4)) as (fig, (ax0, ax1, ax2)):
        dest = np.array([e.destination for e in envs])
        wall_left = np.array([not e.left.surmountable for e in envs])
        limit = (unseen.limit | unseen.unstable) & ~unseen.collided
        for mask, label, marker in ((ok, "reached", "o"), (unseen.collided, "collision", "x"),
                                    (limit, "joint limit / stability", "s"),
                                    (~ok & ~unseen.collided & ~limit, "50 cycles", "d")):
            for side, colour in ((wall_left, "tab:blue"), (~wall_left, "tab:red")):
                sel = mask & side
                if not sel.any():
                    continue
                ax0.scatter(dest[sel, 0], dest[sel, 1], marker=marker, s=16, color=colour, alpha=0.7,
                            label=f"{label}, wall {'left' if colour == 'tab:blue' else 'right'}")
        ax0.set_xlabel("destination x [m]")
        ax0.set_ylabel("destination y [m]")
        ax0.legend(fontsize=6)
        ax0.set_title(f"unseen environments: {ok.mean():.0%} reached", fontsize=9)
        bins = np.arange(0.5, C.MAX_CYCLES + 1.5)
        for ep, label in ((train, "training 96"), (unseen, f"unseen {len(envs)}")):
            good = T.success(ep)
            if not good.any():
                continue
            ax1.hist(ep.cycles[good], bins=bins, alpha=0.6, density=True, label=label)
            ax2.hist(np.hypot(*ep.final_error[good].T), bins=np.linspace(0, C.GOAL_RADIUS, 21), alpha=0.6,
                     density=True, label=label)
        ax1.set_xlabel("walking cycles to the goal")
        ax2.set_xlabel("final distance error [m]")
        for ax in (ax1, ax2):
            ax.legend(fontsize=7)


@scenario(
    "quadruped.generalization",
    source="seed 004 §4.2.2, §7 (spec §6.5 check 8)",
    summary="success rate of the trained action network over the 96 training environments and over generated "
            "unseen ones (jittered corners, heights, destinations)",
    params=[Param("unseen", 200, "number of generated unseen environments", lo=1, hi=5000),
            Param("unseen_seed", 1, "seed of the unseen-environment generator", lo=0),
            Param("network", "fixed", "fixed: fixed-order network and order; free: re-trained network with the "
                  "swing-order network", choices=("fixed", "free")),
            WEIGHTS],
    checks=(Check("train_success_rate", ">=", 0.9,
                  "derived: the GA optimised eq. (9) on exactly these environments (the paper reports no rate)"),),
    thesis={"unseen_success_rate": ThesisValue(
        "no rate; 'paths to the destination were obtained in unlearned environments' (one example, §4.2.2)",
        "seed 004 §7", "unseen_success_rate")},
)
def generalization(ctx) -> dict:
    """Spec §6.5 check 8: success (goal reached without collision, joint-limit violation or lost
    stability) over the 96 training environments and over ``unseen`` environments of
    ``world.unseen_environments`` (Table 1 layouts with corners jittered by ±0.05 m, surmountable
    heights 0.05-0.13 m, destinations x ∈ [-0.35, 0.35], y ∈ [1.8, 2.2] m). The paper publishes no
    rate; the unseen rate is a new number, not a reproduction. ``mean_final_error_m`` and the mean
    cycles are over the successful walks (of the unseen environments for ``mean_final_error_m``).
    The shipped network reaches 100 % of the training and 83.5 % of 200 unseen environments, in 12
    cycles on average; the unseen failures are collisions (8 %) and joint limits (8.5 %): it walks
    between the obstacles, through a gap whose place changes with the layout (the crab walk around
    them that the GA found before the displacement range was imposed is history: training.py's
    docstring). With ``network=free`` (re-trained, swing-order network choosing): 100 % and 82.5 %,
    11.2 and 10.8 cycles, final errors 0.059 and 0.092 m. ``shipped_learning_curves.png`` draws the
    learning curves stored with the shipped networks (``quadruped.train`` re-draws them when it
    re-trains)."""
    p = ctx.params
    stage = "action" if p["network"] == "fixed" else "free"
    genome = T.load_action(_path(p["weights"]), stage=stage)
    order = T.load_order() if stage == "free" else None
    train = T.evaluate(genome, F.training_batch(), order)
    ctx.progress(0.3, "training environments")
    envs = list(W.unseen_environments(p["unseen"], p["unseen_seed"]))
    unseen = T.evaluate(genome, W.EnvBatch.of(envs), order)
    ctx.progress(0.9, "unseen environments")
    metrics = {f"train_{k}": v for k, v in outcome_rates(train).items()}
    metrics.update({f"unseen_{k}": v for k, v in outcome_rates(unseen).items()})
    metrics["mean_final_error_m"] = metrics["unseen_mean_final_error_m"]
    ctx.extra["unseen"] = [{"name": e.name, "destination": e.destination, "wall": "left" if not e.left.surmountable
                            else "right", "reached": bool(s), "cycles": int(c)}
                           for e, s, c in zip(envs, T.success(unseen), unseen.cycles)]
    _plot_generalisation(ctx, envs, train, unseen)
    if not p["weights"]:
        with ctx.figure("shipped_learning_curves", nrows=1, ncols=len(T.STAGES), figsize=(15, 4)) as (fig, axes):
            for ax, s in zip(axes, T.STAGES):
                best, mean, _ = T.load_curve(None, s)
                PL.draw_curve(ax, best, mean, CURVE_TITLES[s])
    return metrics


# --- Sensor-in-the-loop ablation (seed §3, eqs. 3-6) -------------------------------------------------------

NOISE_SWEEP = (0.0, 0.005, 0.01, 0.02, 0.05, 0.1)  # range-noise std [m] of the robustness curve (chosen)
INCIDENCE_SWEEP = (5.0, 10.0, 15.0, 25.0, 45.0)  # incidence limits [deg] of the robustness curve (chosen)
POINT_STYLES = {(1, U.FORWARD): ("leg 1 forward", "tab:blue", "o"), (1, U.SIDE): ("leg 1 side", "tab:cyan", "s"),
                (0, U.FORWARD): ("leg 2 forward", "tab:red", "o"), (0, U.SIDE): ("leg 2 side", "tab:orange", "s")}


def sensed_walks(genome: np.ndarray, envs: W.EnvBatch, perception: U.SensedObstacles | None,
                 record: bool = False) -> Episodes:
    """Episodes of the action network ``genome`` (fixed crawl order) with the known obstacle features
    (``perception=None``) or the perception's."""
    return rollout(envs, GenomePolicy(F.ACTION_NET, np.asarray(genome)[None], len(envs)), record=record,
                   perception=perception)


def feature_metrics(p: U.SensedObstacles) -> dict:
    """How the sensed features of a rollout compare with the known ones at the same states.

    Over the cycles in which both are real features (the obstacle is detected and, by both, not yet
    passed): mean |sensed - known| per group (x: x_max, x_min; y: y_max, y_min; z: z_max; z_min is 0
    in both), the largest |Δz_max| and the largest amount by which the sensed box sticks out of the
    true one (``sensed_box_excess_m``; ≤ 0 means inside). ``sentinel_while_ahead_fraction``: cycles
    whose sensed features are the sentinels while the known obstacle is still ahead (not seen yet or
    "passed" early), over the cycles with a known obstacle ahead. Detection: the first cycle (1-based)
    at which a side's sensors have echoed, the fraction of obstacles ever detected, and the fraction
    of echoes that came from the other side's obstacle."""
    known, sensed = p.known, p.sensed
    valid = np.isfinite(known[..., 0])
    known_ahead = valid & ~np.all(known == SENTINELS, axis=-1)
    both = known_ahead & ~np.all(sensed == SENTINELS, axis=-1)
    d = (sensed - known)[both]
    excess = np.stack([d[:, 0], -d[:, 1], d[:, 2], -d[:, 3]], axis=-1)
    obstacle, cycle = p.obstacle, p.cycle
    echo = obstacle >= 0
    first = np.where(echo, cycle, np.iinfo(int).max).min(axis=-1, initial=np.iinfo(int).max)
    detected = echo.any(axis=-1)
    out = {"feature_error_x_m": float(np.abs(d[:, :2]).mean()) if len(d) else None,
           "feature_error_y_m": float(np.abs(d[:, 2:4]).mean()) if len(d) else None,
           "feature_error_z_m": float(np.abs(d[:, 4]).mean()) if len(d) else None,
           "feature_error_y_max_m": float(np.abs(d[:, 2]).mean()) if len(d) else None,
           "feature_error_z_max_m": float(np.abs(d[:, 4]).max()) if len(d) else None,
           "sensed_box_excess_m": float(excess.max()) if len(d) else None,
           "detected_cycles_fraction": float(both.sum() / max(known_ahead.sum(), 1)),
           "sentinel_while_ahead_fraction": float((known_ahead & ~both).sum() / max(known_ahead.sum(), 1)),
           "first_detection_cycle": float(first[detected].mean() + 1) if detected.any() else None,
           "detected_fraction": float(detected.mean()),
           "cross_side_echo_fraction": float((echo & (obstacle != np.arange(2)[:, None])).sum() / max(echo.sum(), 1)),
           "echoes": int(echo.sum())}
    names = ("x_max", "x_min", "y_max", "y_min", "z_max", "z_min")
    per_feature = {f"{side}_{name}": float(np.abs((sensed - known)[..., i, j][both[..., i]]).mean())
                   for i, side in enumerate(("right", "left")) for j, name in enumerate(names)
                   if both[..., i].any()}
    return out | {"per_feature_error_m": per_feature}


def _plot_sensed_walks(ctx, walks: dict) -> None:
    """Top views of sensed walks ``{title: (env, records, perception)}`` with every echo's point."""
    with ctx.figure("sensed_walks", nrows=1, ncols=len(walks), figsize=(6.4 * len(walks), 6.4),
                    squeeze=False) as (fig, axes):
        for ax, (title, (env, records, p)) in zip(axes[0], walks.items()):
            PL.draw_walk(ax, env, records, triangles=False)
            points, beam = p.points[0], p.beam[0]
            for (side, b), (label, colour, marker) in POINT_STYLES.items():
                pts = points[side][beam[side] == b]
                pts = pts[np.isfinite(pts[:, 0])]
                ax.scatter(pts[:, 0], pts[:, 1], s=9, marker=marker, facecolors="none", edgecolors=colour, lw=0.6,
                           label=f"echo: {label} ({len(pts)})")
            ax.set_title(title, fontsize=8)
            ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0))


def _plot_features(ctx, env: W.Environment, p: U.SensedObstacles) -> None:
    """Known and sensed features per cycle of one walk (sentinels shown as gaps)."""
    known, sensed = p.known[0], p.sensed[0]
    k = np.arange(1, len(known) + 1)
    with ctx.figure("sensed_features", nrows=2, ncols=3, figsize=(13, 6.2)) as (fig, axes):
        for row, (i, side) in zip(axes, enumerate(("right", "left"))):
            for ax, (j, group) in zip(row, ((0, "x"), (2, "y"), (4, "z"))):
                for col, (f, style) in enumerate(((known, "-"), (sensed, "--"))):
                    gone = np.all(f[:, i] == SENTINELS[i], axis=-1)
                    for dj, name in ((0, "max"), (1, "min")):
                        if group == "z" and name == "min":
                            continue
                        y = np.where(gone, np.nan, f[:, i, j + dj])
                        ax.plot(k, y, style, color=f"C{dj}", marker="o" if col else "", ms=3, lw=1,
                                label=f"{'sensed' if col else 'known'} {group}_{name}")
                ax.set_title(f"{env.name}: {side} obstacle, {group} (body frame)", fontsize=8)
                ax.set_xlabel("walking cycle k")
                ax.set_ylabel("[m]")
                ax.legend(fontsize=6)


def _plot_success(ctx, rates: dict, noise_curve: list, incidence_curve: list, p: dict) -> None:
    keys = ("success_rate", "collision_rate", "limit_rate", "timeout_rate")
    with ctx.figure("success", nrows=1, ncols=3, figsize=(14, 4.2)) as (fig, (ax0, ax1, ax2)):
        x = np.arange(len(keys))
        for off, name in ((-0.2, "known"), (0.2, "sensed")):
            values = [rates[name][key] for key in keys]
            bars = ax0.bar(x + off, values, width=0.4, label=f"{name} features")
            ax0.bar_label(bars, fmt="%.2f", fontsize=7)
        ax0.set_xticks(x, ["reached", "collision", "joint limit /\nstability", "50 cycles"], fontsize=8)
        ax0.set_ylim(0, 1.1)
        ax0.set_title(f"training environments (noise {p['noise_std']:g} m, incidence ≤ {p['incidence_deg']:g}°)",
                      fontsize=9)
        ax0.legend(fontsize=7)
        for ax, curve, xlabel in ((ax1, noise_curve, "range-noise std [m]"),
                                  (ax2, incidence_curve, "incidence limit [deg]")):
            xs = [c[0] for c in curve]
            ax.plot(xs, [c[1] for c in curve], "o-", label="sensed features")
            ax.axhline(rates["known"]["success_rate"], color="k", ls="--", lw=1, label="known features")
            ax.axhline(rates["blind"]["success_rate"], color="tab:red", ls=":", lw=1,
                       label="no echo at all (sentinels only)")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("success rate")
            ax.set_ylim(0, 1.05)
            ax.legend(fontsize=7)
        ax1.set_title(f"incidence ≤ {p['incidence_deg']:g}°, seed {ctx.seed}", fontsize=9)
        ax2.set_title(f"noise {p['noise_std']:g} m", fontsize=9)


@scenario(
    "quadruped.sensing-ablation",
    source="seed 004 §1.4, eqs. 3–6, §2.2",
    summary="the shipped fixed-order action network with its 12 obstacle features from simulated ultrasonic "
            "sensors (eqs. 3-6 corrected, Figs. 7-8) instead of the known corners",
    params=[Param("noise_std", 0.0, "Gaussian range noise of every reading [m] (seeded by --seed)", lo=0.0, hi=0.5),
            Param("incidence_deg", C.INCIDENCE_LIMIT_DEG, "largest angle of incidence that still echoes [deg] "
                  "(not in the paper: 'nearly perpendicular')", lo=0.0, hi=90.0),
            Param("environments", 96, "training environments walked (evenly spaced over the 96)", lo=1, hi=96),
            WEIGHTS],
    checks=(
        Check("known_success_rate", ">=", 0.9,
              "derived: the GA optimised eq. (9) on these environments with known features (as generalization)"),
        Check("sensed_box_excess_m", "<=", "sensed_box_bound_m",
              "model: every echo point lies on its leg's side's obstacle boundary, so the sensed bounding box lies "
              "inside the true one (noise 0: 1e-6 m; with range noise σ: 1e-6 + 6σ)", name="sensed_box_inside_true"),
        Check("feature_error_z_max_m", "<=", C.HEIGHT_STEP,
              "model (Fig. 8): raising the beam in HEIGHT_STEP steps overestimates a climbable top by less than one "
              "step; an obstacle still echoing at the top of the raise is a wall"),
        Check("detected_fraction", "==", 1.0,
              "thesis §3.2 (Figs. 12, 24): the forward and side sensors measure an edge of each obstacle in front"),
    ),
    thesis={
        "sensed_success_rate": ThesisValue(
            "one real-robot walk with its ultrasonic sensors reached the goal (9 cycles, (0.137, 0.075) m); no rate",
            "seed 004 §4.3", "sensed_success_rate"),
        "s421_known_final_error_m": ThesisValue(0.059, "seed 004 §4.2.1 (known obstacles)",
                                                "s421_known_final_error_m"),
        "s422_known_final_error_m": ThesisValue(0.054, "seed 004 §4.2.2 (known obstacles)",
                                                "s422_known_final_error_m")},
)
def sensing_ablation(ctx) -> dict:
    """Sensor-in-the-loop ablation (issue: "optional sensing"). The paper's simulation — and its GA
    training — gives the action network the known obstacle corners (seed §4, spec §2.2); the real
    robot (seed §3, §4.3) gets them from 3 ultrasonic sensors on each front foot. Here the shipped,
    unchanged fixed-order network walks the training environments and the §4.2.1 and §4.2.2
    environments twice: with the known features, and with features from ``sensing.SensedObstacles``
    (eqs. 3-6 corrected, forward and side beams swept by the shoulder yaw at every four-leg support,
    Fig. 7; heights by raising the leg, Fig. 8; features = the bounding box of the points gathered so
    far, per side, in the body frame). The walk itself (footholds, swing heights, the body-raise rule)
    is the executor's on the true geometry in both. ``feature_*`` compare sensed and known features at
    the same states of the sensed walks. The success curves repeat the sensed walk of the training
    environments for the noise levels ``NOISE_SWEEP`` and the incidence limits ``INCIDENCE_SWEEP``;
    ``blind_*`` is the control without any echo (incidence limit 0: the network sees only sentinels).

    What the numbers are (defaults: noise 0, incidence ≤ 15°, all 96). Every obstacle is detected in
    the first cycle, from the initial stance (``first_detection_cycle`` 1, ``detected_fraction`` 1):
    the front edges are 0.3-0.4 m from the front feet, inside the 0.5 m range, and the ±30° sweep
    always finds a beam within 15° of their normals. No leg's beam meets the other side's obstacle
    (``cross_side_echo_fraction`` 0). The sensed boxes lie inside the true ones (the model's
    guarantee without noise) and the heights are exact (the paper's heights lie on the 10 mm raise
    grid; the wall is "not climbable" and reads 0.3 m). What the sensors miss is depth: the forward
    beams see only the front edge (o2-o3, as the paper says, Fig. 14), so y_max is 0.17 m short on
    average (``feature_error_y_max_m``; about the obstacles' 0.2 m depth) until a side beam meets an
    inner edge, and x is 0.09 m short on average (the outer corners are beyond the range or too
    oblique). Hence the "passed" rule (all points behind the body centre) fires up to a cycle early:
    in 11 % of the cycles with a known obstacle ahead the network gets the sentinels
    (``sentinel_while_ahead_fraction``).

    The network hardly minds: 94 of 96 (97.9 %) reach the goal with sensed features, against 96 of
    96 with known ones, in as many cycles (12.0) and with the same mean final error (0.108 vs
    0.106 m). The two failures (x3y1 and x3y2, right 0.12 m obstacle, left wall, destination 2) are
    that early "passed": at cycle 6 the right obstacle's sensed points are all behind the body
    centre while its back half is still ahead, the network gets the right sentinels and turns the
    other way (Δθr -1.9° instead of +4.3°), and cycle 7 violates a joint limit. §4.2.1 and §4.2.2
    both reach with sensed features, in 12 cycles like the known walks (final error 0.156 vs
    0.139 m, 0.105 vs 0.026 m). The success curves stay at 95-100 % for range noise up to 0.1 m
    and incidence limits of 5-45° (not monotone: noise scatters points and so widens the box
    towards the true one; a 5° limit keeps fewer, more central points and reaches all 96), while
    without any echo only 12.5 % reach and 87.5 % collide (``blind_*``): the features matter, and
    the sensed ones carry what the network needs. This is
    consistent with the network, trained on known corners only and not re-trained here, relying
    on what the foot sensors measure well — z_max (exact), the front edge's y_min (0.01-0.02 m off,
    ``per_feature_error_m`` in the extra output) and the inner x (0.04-0.06 m) — more than on the
    depth (y_max, 0.17 m) and the outer x (0.12-0.13 m); which inputs it uses was not tested further."""
    p = ctx.params
    genome = T.load_action(_path(p["weights"]))
    envs = T.training_envs(p["environments"])

    def perception(noise=p["noise_std"], incidence=p["incidence_deg"]) -> U.SensedObstacles:
        return U.SensedObstacles(noise, incidence, seed=ctx.seed)

    known = sensed_walks(genome, envs, None)
    sense = perception()
    sensed = sensed_walks(genome, envs, sense)
    ctx.progress(0.2, "training environments")
    rates = {"known": outcome_rates(known), "sensed": outcome_rates(sensed)}
    metrics = {f"{name}_{k}": v for name, r in rates.items() for k, v in r.items()}
    features = feature_metrics(sense)
    ctx.extra["per_feature_error_m"] = features.pop("per_feature_error_m")
    metrics.update(features)
    metrics["sensed_box_bound_m"] = 1e-6 + 6 * p["noise_std"]
    names = [e.name for e in W.training_set()]
    picked = np.linspace(0, 95, p["environments"]).round().astype(int)
    ctx.extra["environments"] = [
        {"name": names[i], "known_reached": bool(a), "sensed_reached": bool(b), "known_cycles": int(c),
         "sensed_cycles": int(d)} for i, a, b, c, d in zip(picked, T.success(known), T.success(sensed), known.cycles,
                                                           sensed.cycles)]
    walks = {}
    for key, env in (("s421", W.scenario_421()), ("s422", W.scenario_422())):
        batch = W.EnvBatch.of([env])
        q = perception()
        ep = sensed_walks(genome, batch, q, record=True)
        base = sensed_walks(genome, batch, None)
        metrics.update({f"{key}_sensed_reached": int(T.success(ep)[0]),
                        f"{key}_sensed_final_error_m": float(np.hypot(*ep.final_error[0])),
                        f"{key}_sensed_cycles": int(ep.cycles[0]),
                        f"{key}_known_reached": int(T.success(base)[0]),
                        f"{key}_known_final_error_m": float(np.hypot(*base.final_error[0])),
                        f"{key}_known_cycles": int(base.cycles[0])})
        ctx.extra[f"{key}_features"] = {"known": q.known[0], "sensed": q.sensed[0]}
        _record_walk(ctx, f"{key}.", ep.records[0])
        outcome = "reached" if T.success(ep)[0] else "failed"
        walks[f"{env.name}, sensed features: {outcome} in {ep.cycles[0]} cycles"] = (env, ep.records[0], q)
        if key == "s421":
            _plot_features(ctx, env, q)
    ctx.progress(0.4, "§4.2 walks")
    noise_curve = [(s, float(T.success(sensed_walks(genome, envs, perception(noise=s))).mean())) for s in NOISE_SWEEP]
    ctx.progress(0.7, "noise sweep")
    incidence_curve = [(a, float(T.success(sensed_walks(genome, envs, perception(incidence=a))).mean()))
                       for a in INCIDENCE_SWEEP]
    blind = outcome_rates(sensed_walks(genome, envs, perception(incidence=0.0)))
    metrics["blind_success_rate"], metrics["blind_collision_rate"] = blind["success_rate"], blind["collision_rate"]
    rates["blind"] = blind
    ctx.extra["success_vs_noise"] = noise_curve
    ctx.extra["success_vs_incidence"] = incidence_curve
    _plot_sensed_walks(ctx, walks)
    _plot_success(ctx, rates, noise_curve, incidence_curve, p)
    return metrics


# --- Training -----------------------------------------------------------------------------------------

def _progress(ctx, settings: T.TrainSettings, stages: tuple[str, ...]):
    total = sum(settings.generations_of(s) for s in stages)
    before = {s: sum(settings.generations_of(t) for t in stages[:i]) for i, s in enumerate(stages)}

    def report(stage: str, done: int, generations: int, best: float) -> None:
        ctx.progress((before[stage] + done) / total, f"{stage} generation {done}/{generations}, best {best:.4g}")

    return report


def _shipped_match(settings: T.TrainSettings, results: dict) -> int | None:
    """1 if this run used the shipped set's settings and reproduced its genomes bit for bit, 0 if it
    used them and did not, None for other settings."""
    try:
        shipped = {s: T.load_curve(None, s)[2] for s in results}
    except FileNotFoundError:
        return None
    if any(v != dataclasses.asdict(settings) for v in shipped.values()):
        return None
    same = [np.array_equal(np.load(T.TRAINED_DIR / T.FILES[s])["genome"], r.genome) for s, r in results.items()]
    return int(all(same))


def _train_metrics(settings: T.TrainSettings, results: dict) -> dict:
    envs = T.training_envs(settings.environments)
    action = results["action"]
    ep = T.evaluate(action.genome, envs)
    metrics = {"best_fitness": action.best_fitness, "generations": action.generations,
               **{f"train_{k}": v for k, v in outcome_rates(ep).items()}, "action_wall_s": action.wall_s}
    if "order" in results:
        policy = T.order_policy(results["order"].genome)
        metrics.update(order_best_fitness=results["order"].best_fitness, order_generations=results["order"].generations,
                       order_accuracy=T.order_accuracy(policy), order_wall_s=results["order"].wall_s,
                       **{f"order_{k}": v for k, v in T.order_generalisation(policy).items()})
        free = results["free"]
        free_ep = T.evaluate(free.genome, envs, policy)
        metrics.update(free_best_fitness=free.best_fitness, free_generations=free.generations, free_wall_s=free.wall_s,
                       **{f"free_{k}": v for k, v in outcome_rates(free_ep).items()})
    metrics["reproduces_shipped"] = _shipped_match(settings, results)
    return metrics


@scenario(
    "quadruped.train",
    source="seed 004 §4.1.2, §5.1, §6.1 (eqs. 9-15)",
    summary="GA training of the action network on the 96 environments, of the swing-order network, and the "
            "re-training of the action network with the swing-order network in the loop",
    params=[
        Param("generations", C.GA_GENERATIONS, "GA generations of the action network (fixed order)", lo=1, hi=100000),
        Param("order_generations", C.GA_ORDER_GENERATIONS, "GA generations of the swing-order network",
              lo=1, hi=100000),
        Param("free_generations", C.GA_FREE_GENERATIONS, "GA generations of the re-training with the free gait",
              lo=1, hi=100000),
        Param("mutation_rate", C.GA_MUTATION_RATE, "per-gene mutation probability (not in the paper)", lo=0.0, hi=1.0),
        Param("mutation_sigma", C.GA_MUTATION_SIGMA, "Gaussian mutation, fraction of each gene's range",
              lo=0.0, hi=10.0),
        Param("order_hidden", C.ORDER_HIDDEN, "hidden units of the swing-order network (not printed; chosen by "
              "held-out validation, constants)", lo=1, hi=1000),
        Param("population", C.GA_POPULATION, "GA population (seed §4.1.2: 100)", lo=4, hi=100000),
        Param("environments", 96, "training environments used (evenly spaced over the 96)", lo=1, hi=96),
        Param("init", "data", "initial action-network population: RBF centres on data, or uniform in the gene bounds",
              choices=T.INITS),
        Param("stages", "all", "all: action, order, free; action: the fixed-order action network only",
              choices=("all", "action")),
        Param("executor", "process", "where fitness runs", choices=("serial", "process", "ray")),
        Param("workers", 0, "processes or Ray CPUs (0: all local cores)", lo=0, hi=4096),
        Param("address", "", "Ray cluster address (executor=ray; empty: RAY_ADDRESS or a local Ray)"),
        Param("resume", True, "continue from the GA checkpoints in the output folder"),
    ],
    checks=(
        Check("train_success_rate", ">=", 0.9,
              "derived: the trained network should reach the destinations it was optimised on (the paper shows "
              "§4.2's walks, no rate)"),
        Check("order_accuracy", ">=", 0.9, "spec §6.5 check 7: accuracy on the teacher patterns (target assumed)"),
        Check("free_success_rate", ">=", 0.9, "derived: as train_success_rate, for the re-trained network"),
    ),
    thesis={"generations": ThesisValue("not reported", "seed 004 §4.1.2 (no generation count, no learning curve)",
                                       "generations")},
)
def train_networks(ctx) -> dict:
    """Trains the networks (``training.train``) into the output folder: ``action_fixed.npz``,
    ``swing_order.npz``, ``action_free.npz`` and a GA checkpoint per stage (``<stage>.ga.npz``).
    A killed run continues from its checkpoints when run again (``resume=true``); a finished one
    returns its result at once. The seed is ``--seed`` (default 0, the shipped set)."""
    p = ctx.params
    settings = T.TrainSettings(p["generations"], p["order_generations"], p["free_generations"], p["mutation_rate"],
                               p["mutation_sigma"], p["population"], p["environments"], ctx.seed, p["init"],
                               p["order_hidden"])
    stages = T.STAGES if p["stages"] == "all" else ("action",)
    with make_executor(p["executor"], p["workers"] or None, p["address"] or None) as executor, T.single_threaded_blas():
        results = T.train(ctx.out, settings, executor, p["resume"], stages, _progress(ctx, settings, stages))
    for stage, r in results.items():
        for g, (best, mean) in enumerate(zip(r.best, r.mean)):
            ctx.recorder.record(g, **{f"{stage}.best": best, f"{stage}.mean": mean})
    ctx.extra["learning_curves"] = {s: {"best": r.best, "mean": r.mean} for s, r in results.items()}
    with ctx.figure("learning_curves", nrows=1, ncols=len(results), figsize=(5 * len(results), 4),
                    squeeze=False) as (fig, axes):
        for ax, (stage, r) in zip(axes[0], results.items()):
            PL.draw_curve(ax, r.best, r.mean, CURVE_TITLES[stage])
    return _train_metrics(settings, results)


CURVE_TITLES = {"action": "action network, fixed order: eq. (9)", "order": "swing-order network: eq. (13)",
                "free": "action network re-trained with the free gait: eq. (9)"}
