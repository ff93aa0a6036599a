"""Cla's pictures: E9–E11 (seed 003 §4.2, §4.5.2, §4.7: the teaching replay, the software-spring traces, cf.
Figs. 4.14–4.17, Tables 4.7/4.8 side by side, posture errors and time series, cf. Figs. 4.21–4.27),
``spine.posture-database`` (seed 003 §5.9: the node graph in a 2-D projection of muscle-length
space, cf. Fig. 5.29, the history replay against the taught history, cf. Fig. 5.30, the push triggers) and the
chapter-5 behaviours (§5.2: the pull, the throw, the levelling, the balance, the pick-and-place, the roll-over)."""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Rectangle

from shintai.core.constants import KGF_N
from shintai.spine.cla import crawl as CC
from shintai.spine.cla.constants import COP_BAND_M, ROLLED_DEG
from shintai.spine.robots import CLA_DESK_HALF_M, CLA_DESK_HEIGHT_M, CLA_DESK_NEAR_M, CLA_OBJECT_HALF_M

TAG_COLOUR = {"hold": "tab:gray", "move": "tab:blue", "limp": "tab:red", "play": "tab:green"}
TAG_LABEL = {"hold": "holding", "move": "weak-push nudge", "limp": "strong push: taught limp (T mode)",
             "play": "replay / execution"}
AXES = ("roll", "pitch", "yaw")


def node_graph(ctx, db, log) -> None:
    """Nodes and history edges on the first two principal axes of the session's lengths. The projection is
    orthogonal, so a node's d_len neighbourhood (a sphere) projects to a disc of radius d_len, drawn."""
    from matplotlib.patches import Circle

    enc = 1e3 * np.array(log.encoder)
    mean = enc.mean(axis=0)
    _, _, vt = np.linalg.svd(enc - mean, full_matrices=False)
    P = vt[:2].T
    traj = (enc - mean) @ P
    nodes = (1e3 * db.lengths - mean) @ P
    with ctx.figure("node_graph", 1, 1, figsize=(7.5, 6.5)) as (fig, ax):
        ax.plot(traj[:, 0], traj[:, 1], color="0.8", lw=0.6, zorder=0, label="session (20 ms samples)")
        for a, b in db.edges():
            ax.plot(*nodes[[a, b]].T, color="0.35", lw=0.8, zorder=1)
        r = 1e3 * db.d_len
        for node, (x, y) in zip(db.nodes, nodes):
            ax.add_patch(Circle((x, y), r, fill=False, lw=0.4, color=TAG_COLOUR.get(node.tag, "k"), alpha=0.5))
        for tag, colour in TAG_COLOUR.items():
            idx = [n.id for n in db.nodes if n.tag == tag]
            if idx:
                ax.scatter(nodes[idx, 0], nodes[idx, 1], s=18, color=colour, zorder=2,
                           label=f"{TAG_LABEL[tag]} ({len(idx)})")
        for node, (x, y) in zip(db.nodes, nodes):
            ax.annotate(str(node.id), (x, y), fontsize=6, xytext=(2, 2), textcoords="offset points")
        ax.set_aspect("equal")
        ax.set_xlabel("length-space principal axis 1 [mm]")
        ax.set_ylabel("principal axis 2 [mm]")
        ax.legend(fontsize=7, loc="best")
        ax.set_title(f"posture database: {len(db.nodes)} nodes (circles: d_len = {r:g} mm), edges = history",
                     fontsize=9)


def replay_vs_history(ctx, db, log) -> None:
    """Whole-spine angles while teaching with the history's node postures at their visits (left), and the
    replay at constant length speed with the same nodes at their arrival times (right)."""
    play = next((p for p in log.plays if p["kind"] == "replay"), None)
    if play is None:
        return
    t, whole = np.array(log.t), np.degrees(np.array(log.whole))
    taught = t < play["t0"]
    end = play["arrive"][-1] + 0.5
    replayed = (t >= play["t0"]) & (t <= end)
    nodes = play["nodes"]
    truth = np.degrees(np.array([db.nodes[k].truth for k in nodes]))
    with ctx.figure("replay_vs_history", 1, 2, figsize=(13, 4.5), sharey=True) as (fig, (ax0, ax1)):
        for a, colour in zip(range(3), ("tab:orange", "tab:blue", "tab:green")):
            ax0.plot(t[taught], whole[taught, a], color=colour, lw=0.9, label=AXES[a])
            ax0.plot(db.history_t[:len(nodes)], truth[:, a], "o", ms=3, color=colour)
            ax1.plot(t[replayed] - play["t0"], whole[replayed, a], color=colour, lw=0.9)
            ax1.plot(np.array(play["arrive"]) - play["t0"], truth[:, a], "o", ms=3, color=colour)
        ax0.set_xlabel("teaching session time [s]")
        ax0.set_ylabel("whole-spine angle (true) [deg]")
        ax0.legend(fontsize=8)
        ax0.set_title(f"taught: dots = the {len(nodes)} history entries' node postures", fontsize=9)
        ax1.set_xlabel("replay time [s]")
        ax1.set_title("replayed at constant length speed: dots = the same nodes\n(§5.9.2: the time axis is "
                      "not similar)", fontsize=9)


def triggers(ctx, log, levels) -> None:
    """The push estimate |τ̂| against the two levels, the person's push force, and the triggers that fired."""
    if not log.tau:
        return
    tt, tau = np.array(log.tau).T
    with ctx.figure("triggers", 1, 1, figsize=(12, 4)) as (fig, ax):
        ax.plot(tt, tau, ".", ms=0.6, color="tab:blue", label="|τ̂| = |Jᵀ(T − T_base)| while armed")
        ax.axhline(levels.weak_nm, color="tab:orange", ls="--", lw=1, label=f"weak level {levels.weak_nm:g} N m")
        ax.axhline(levels.strong_nm, color="tab:red", ls="--", lw=1, label=f"strong level {levels.strong_nm:g} N m")
        for fired, _ in log.fired:
            ax.annotate("S" if fired.level == "strong" else "W", (fired.t, fired.peak_nm), color="k", fontsize=9,
                        ha="center", va="bottom")
        t = np.array(log.t)
        limp = np.array([s == "limp" for s in log.state])
        ax.fill_between(t, 0, 1, where=limp, transform=ax.get_xaxis_transform(), color="tab:red", alpha=0.12,
                        label="T mode (limp, taught by hand)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("push moment estimate [N m]")
        if log.force:
            ax2 = ax.twinx()
            ft, f = np.array(log.force).T
            ax2.plot(ft, f, ".", ms=0.8, color="0.4")
            ax2.set_ylabel("person's push on the shoulders [N] (grey)")
        ax.legend(fontsize=7, loc="upper right")
        ax.set_title("push teaching triggers (§5.9.3): W = weak (nudge), S = strong (T mode)", fontsize=9)


def pull(ctx, runs: dict, labels: dict) -> None:
    """Figs. 5.5–5.6: the hand and the object's near face against time, and the hand's path seen from the side."""
    with ctx.figure("pull") as (fig, ax):
        for variant, s in runs.items():
            line, = ax.plot(s["t"], s["hand_x_m"], label=f"hand x, {labels[variant]}")
            ax.plot(s["t"], s["object_x_m"] + s["object_dx_m"] - CLA_OBJECT_HALF_M, ls="--", color=line.get_color(),
                    label=f"object's near face x, {variant}")
        s = runs["with_spine"]
        ax.axhline(s["reach_straight_m"], color="0.6", lw=0.7, ls=":", label="reach at the desk, spine straight")
        ax.axhline(s["reach_leaning_m"], color="0.3", lw=0.7, ls=":", label="reach at the desk, spine leaning")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("x (forward) [m]")
        ax.set_title("Cla pulls an object on the desk (Figs. 5.5–5.6)", fontsize=9)
        ax.legend(fontsize=6)
    with ctx.figure("side_view") as (fig, ax):
        for variant, s in runs.items():
            ax.plot(s["hand_x_m"], s["hand_z_m"], label=f"hand path, {labels[variant]}")
        x0 = runs["with_spine"]["object_x_m"]
        h = CLA_OBJECT_HALF_M
        z = CLA_DESK_HEIGHT_M
        ax.add_patch(Rectangle((x0 - h, z), 2 * h, 2 * h, color="tab:red", alpha=0.4, label="object at start"))
        ax.axhline(z, color="0.5", lw=1.0, label="desk top")
        ax.set_aspect("equal")
        ax.set_xlabel("x (forward) [m]")
        ax.set_ylabel("z [m]")
        ax.legend(fontsize=6)


def throw(ctx, runs: dict, labels: dict) -> None:
    """Figs. 5.3–5.4: the hand's speed of each throw, and the parts' rates of the throw with the spine."""
    with ctx.figure("hand_speed") as (fig, ax):
        for variant, s in runs.items():
            ax.plot(s["t"], s["hand_speed_mps"], label=labels[variant])
        at = s["pattern"].throw_at
        ax.axvline(at, color="0.7", lw=0.6)
        ax.set_xlim(at - 0.2, s["t"][-1])
        ax.set_xlabel("time [s]")
        ax.set_ylabel("hand speed [m/s]")
        ax.set_title("Cla's throw (Figs. 5.3–5.4): hand speed with and without the spine", fontsize=9)
        ax.legend(fontsize=7)
    with ctx.figure("sequence") as (fig, ax):
        s = runs["with_spine"]
        dt = np.gradient(s["t"])
        for key, label in (("spine_yaw_deg", "spine yaw rate [rad/s]"), ("shoulder_rad", "shoulder rate [rad/s]"),
                           ("elbow_rad", "elbow rate [rad/s]")):
            rate = np.gradient(s[key]) / dt
            ax.plot(s["t"], np.abs(np.radians(rate) if key.endswith("deg") else rate), label=label)
        ax.plot(s["t"], s["hand_speed_mps"], "k", lw=1.2, label="hand speed [m/s]")
        ax.set_xlim(s["pattern"].throw_at - 0.1, s["pattern"].throw_at + 0.8)
        ax.set_xlabel("time [s]")
        ax.set_title("with the spine: spine, shoulder, elbow started in that order, their speed peaks together",
                     fontsize=9)
        ax.legend(fontsize=7)


def levelling(ctx, runs: dict) -> None:
    """Fig. 5.2: the shoulders' tilt with and without the levelling against the seat, and the spine's posture."""
    with ctx.figure("shoulder_tilt") as (fig, ax):
        for variant, s in runs.items():
            ax.plot(s["t"], s["roll_deg"], label=f"shoulder roll, {variant} levelling")
            ax.plot(s["t"], s["pitch_deg"], ls="--", label=f"shoulder pitch, {variant} levelling")
        ax.plot(runs["with"]["t"], runs["with"]["seat_roll_deg"], "k:", lw=0.8, label="seat roll")
        ax.plot(runs["with"]["t"], runs["with"]["seat_pitch_deg"], "k-.", lw=0.8, label="seat pitch")
        for e in runs["with"]["events"]:
            ax.axvline(e["t"], color="0.8", lw=0.6)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("tilt [deg] (roll +: right side down; pitch +: forward)")
        ax.set_title("Cla levels its shoulders (Fig. 5.2); grey: sense → compute → move", fontsize=9)
        ax.legend(fontsize=6, ncol=2)
    with ctx.figure("spine_posture") as (fig, ax):
        s = runs["with"]
        for key in ("spine_roll_deg", "spine_pitch_deg"):
            ax.plot(s["t"], s[key], label=f"true {key.split('_')[1]}")
        events = s["events"]
        if events:
            t = [e["t"] for e in events]
            ax.plot(t, [e["nn_whole_deg"][0] for e in events], "o", label="NN estimate, roll")
            ax.plot(t, [e["nn_whole_deg"][1] for e in events], "s", label="NN estimate, pitch")
            ax.plot(t, [e["goal_deg"][0] for e in events], "x", label="goal sent, roll")
            ax.plot(t, [e["goal_deg"][1] for e in events], "+", label="goal sent, pitch")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("whole-spine angle [deg]")
        ax.set_title("the spine's posture: true, the network's estimate from the muscle lengths, the goals",
                     fontsize=9)
        ax.legend(fontsize=7)


def cop_balance(ctx, runs, params):
    """Fig. 5.8: the centre of pressure, the arms' offset and the spine's roll, with and without the swing."""
    colours = {"swing": "tab:blue", "no_swing": "0.4"}
    with ctx.figure("cop_balance", nrows=3, ncols=1, figsize=(9, 8), sharex=True) as (_fig, (ax_x, ax_arm, ax_roll)):
        for v, run in runs.items():
            t = run.log.times("cop")
            err = 1e3 * (run.log.values("cop")[:, 0] - run.log.values("sole_centre_x"))
            ax_x.plot(t, err, color=colours[v], label=v.replace("_", " "))
            ax_arm.plot(t, run.log.values("arm_offset_deg"), color=colours[v])
            ax_roll.plot(t, run.log.values("roll_deg"), color=colours[v])
        for b in (COP_BAND_M, -COP_BAND_M):
            ax_x.axhline(1e3 * b, color="tab:green", lw=0.6, ls="--")
        ax_x.set_ylabel("CoP − sole centre,\nfront–back [mm]")
        ax_x.set_title("centre of pressure (eq. 3.5, 8 FSRs); dashed: the reflex's rest band", fontsize=9)
        ax_x.legend(fontsize=8)
        ax_arm.set_ylabel("arms' pitch offset [deg]\n(+ forward)")
        ax_roll.set_ylabel("whole-spine roll [deg]")
        ax_roll.set_xlabel("t [s]")


def pick_place(ctx, runs, params):
    """Fig. 5.7: the hand and the object seen from the front and from above, and the spine's roll and yaw."""
    colours = {"spine": "tab:blue", "locked": "0.4"}
    with ctx.figure("pick_place", nrows=1, ncols=3, figsize=(14, 4)) as (_fig, (ax_side, ax_top, ax_t)):
        for v, run in runs.items():
            hand, obj, t = run.log.values("hand"), run.log.values("object"), run.log.times("hand")
            scene = run.state["scene"]
            ax_side.plot(hand[:, 1], hand[:, 2], color=colours[v], label=f"hand, {v}")
            ax_side.plot(obj[:, 1], obj[:, 2], "--", color=colours[v], label=f"object, {v}")
            ax_top.plot(hand[:, 0], hand[:, 1], color=colours[v], label=f"hand, {v}")
            ax_top.plot(obj[:, 0], obj[:, 1], "--", color=colours[v])
            ax_t.plot(t, run.log.values("whole_deg")[:, 0], color=colours[v], label=f"roll, {v}")
            ax_t.plot(t, run.log.values("whole_deg")[:, 2], ":", color=colours[v], label=f"yaw, {v}")
        ax_side.axhline(scene["floor_z"], color="k", lw=0.8)
        ax_side.axhline(CLA_DESK_HEIGHT_M, color="tab:brown", lw=0.8)
        ax_side.set_xlabel("y (− = Cla's right) [m]")
        ax_side.set_ylabel("z [m]")
        ax_side.set_title("front view: floor (black) and desk top (brown)", fontsize=9)
        ax_top.add_patch(Rectangle(
            (CLA_DESK_NEAR_M, -CLA_DESK_HALF_M[1]), 2 * CLA_DESK_HALF_M[0], 2 * CLA_DESK_HALF_M[1], color="tab:brown",
            alpha=0.2))
        ax_top.plot(*scene["spot"][:2], "x", color="tab:red", label="place spot")
        ax_top.set_aspect("equal", adjustable="datalim")
        ax_top.set_xlabel("x (forward) [m]")
        ax_top.set_ylabel("y [m]")
        ax_top.set_title("top view: desk and place spot", fontsize=9)
        ax_t.set_xlabel("t [s]")
        ax_t.set_ylabel("whole-spine angle [deg]")
        ax_t.set_title("spine roll (side bend) and yaw (twist) reached", fontsize=9)
        for ax in (ax_side, ax_top, ax_t):
            ax.legend(fontsize=7)


def roll_over(ctx, runs, params):
    """Fig. 5.9: how far each half of Cla turned over, and the spine's yaw."""
    colours = {"spine": "tab:blue", "locked": "0.4"}
    with ctx.figure("roll_over", nrows=2, ncols=1, figsize=(9, 6), sharex=True) as (_fig, (ax_turn, ax_yaw)):
        for v, run in runs.items():
            t = run.log.times("pelvis_turn_deg")
            ax_turn.plot(t, run.log.values("shoulder_turn_deg"), color=colours[v], label=f"shoulders, {v}")
            ax_turn.plot(t, run.log.values("pelvis_turn_deg"), "--", color=colours[v], label=f"pelvis, {v}")
            ax_yaw.plot(t, run.log.values("whole_deg")[:, 2], color=colours[v], label=v)
        ax_turn.axhline(90, color="k", lw=0.6, ls=":")
        ax_turn.axhline(ROLLED_DEG, color="tab:green", lw=0.6, ls="--")
        ax_turn.set_ylabel("turn from lying on the back [deg]\n(90 = on a side, 180 = on the front)")
        ax_turn.set_title("how far each half of Cla turned over; dashed green: 'rolled over'", fontsize=9)
        ax_turn.legend(fontsize=7)
        ax_yaw.set_ylabel("whole-spine yaw [deg]")
        ax_yaw.set_xlabel("t [s]")
        ax_yaw.legend(fontsize=7)


def crawl_ga(ctx, genomes: dict, sensors: dict, metrics: dict, eval_s: float, labels: dict) -> None:
    """Figs. 5.10–5.11: the three crawls' distance, torques and drift, their paths and spine rolls."""
    with ctx.figure("crawl_comparison", nrows=1, ncols=4, figsize=(13, 3.6)) as (_fig, axes):
        for ax, (key, label) in zip(axes, (("distance_m", "forward distance [m]"),
                                           ("torque_integral_nms", "torque integral [N m s]"),
                                           ("peak_torque_nm", "peak torque [N m]"),
                                           ("heading_drift_deg", "heading drift [deg]"))):
            values = [metrics[f"{v}.{key}"] for v in list(labels)]
            ax.bar(range(len(list(labels))), values, color=["0.5", "tab:orange", "tab:blue"])
            if key == "torque_integral_nms":  # the limbs' share
                ax.bar(range(len(list(labels))), [metrics[f"{v}.limb_torque_integral_nms"] for v in list(labels)],
                       color="none", edgecolor="k", hatch="//", label="limbs")
                ax.legend(fontsize=7)
            ax.set_xticks(range(len(list(labels))), ["rigid", "hand-made", "GA"])
            ax.set_title(label, fontsize=9)
    with ctx.figure("crawl_paths", nrows=1, ncols=2, figsize=(11, 4)) as (_fig, (ax_path, ax_roll)):
        t = np.arange(sensors["rigid"].shape[0]) * CC.CRAWL_TIMESTEP_S
        for v in list(labels):
            mid = 0.5 * (sensors[v][:, CC.S_PELVIS] + sensors[v][:, CC.S_CLAVICLE])
            ax_path.plot(mid[:, 0], mid[:, 1], label=labels[v])
            ax_roll.plot(t, np.degrees(CC.schedule(genomes[v], t)["roll"]) * CC.CLA_JOINTS, "--", lw=0.8)
            ax_roll.plot(t, np.degrees(sensors[v][:, CC.ROLL_COLUMNS].sum(axis=1)), label=labels[v],
                         color=ax_roll.lines[-1].get_color())
        ax_path.set_aspect("equal", adjustable="datalim")
        ax_path.set_xlabel("x (start heading) [m]")
        ax_path.set_ylabel("y [m]")
        ax_path.set_title(f"trunk midpoint over {eval_s:g} s (top view)", fontsize=9)
        ax_path.legend(fontsize=7)
        ax_roll.set_xlabel("t [s]")
        ax_roll.set_ylabel("spine roll, 5 joints summed [deg]")
        ax_roll.set_title("roll commanded (dashed) and reached; + = head end to the right", fontsize=9)
        ax_roll.set_xlim(0, min(eval_s, 6.0))


MODE_LABEL = {"all_l": "1. all L", "all_ll": "2. all LL", "all_s_mid": "3. all S (mid)", "all_s_high": "4. all S (high)",
              "l_ll": "5. L + LL", "l_t": "6. L + T", "l_s_mid": "7. L + S (mid)", "l_s_high": "8. L + S (high)",
              "all_l_no_interference": "all L, no interference"}

def _cell(value, digits=2) -> str:
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "—"
    return f"{value:.{digits}f}" if isinstance(value, float) else str(value)

def table_4_8(ctx, ours: dict, thesis: dict, columns) -> None:
    """Table 4.8 side by side: for every mode and column, 'ours / thesis'."""
    headers = ["err θ [°]", "err φ [°]", "held θ [°]", "held φ [°]", "T θ [kgf]", "T φ [kgf]", "I θ [A]", "I φ [A]"]
    cells, labels = [], []
    for mode, row in ours.items():
        labels.append(MODE_LABEL[mode])
        cells.append([f"{_cell(row.get(c), 0 if 'held' in c else 2)} / {_cell(t)}"
                      for c, t in zip(columns, thesis[mode])])
    with ctx.figure("table_4_8", 1, 1, figsize=(13, 0.5 * len(cells) + 1.6)) as (fig, ax):
        ax.axis("off")
        table = ax.table(cellText=cells, rowLabels=labels, colLabels=headers, loc="center", cellLoc="center")
        table.auto_set_font_size(False)
        table.set_fontsize(8)
        table.scale(1.0, 1.4)
        ax.set_title("Table 4.8 side by side — each cell: ours / thesis (held 30 = '30 or more'; — = not held)",
                     fontsize=9)

def posture_errors(ctx, rows_all: dict, names, table_4_7: dict, columns) -> None:
    """Table 4.7 as plots: |error| at each posture of the pitch and roll sequences, per mode —
    ours (top; × = posture lost) and the thesis's (bottom; gaps = "—"; ``table_4_7`` as printed, its
    ``columns`` the modes)."""
    colour = {m: f"C{i % 10}" for i, m in enumerate(MODE_LABEL)}
    with ctx.figure("posture_errors", 2, 2, figsize=(13, 7.5)) as (fig, axes):
        for col, axis_name in enumerate(("pitch", "roll")):
            ax = axes[0, col]
            for mode in list(names) + [n for n in rows_all if n not in names]:
                rows = rows_all.get(mode, {}).get(axis_name)
                if not rows:
                    continue
                ax.plot(np.arange(len(rows)), [r.error_deg if r.held else np.nan for r in rows], "-o", ms=3,
                        color=colour[mode], label=MODE_LABEL[mode])
                lost = [k for k, r in enumerate(rows) if not r.held]
                ax.plot(lost, [20] * len(lost), "x", color=colour[mode], ms=9, mew=2)
            seq = [r.target_deg for r in max((rows_all[m].get(axis_name, []) for m in rows_all), key=len)]
            ax.set_xticks(np.arange(len(seq)), [f"{t:+.0f}" for t in seq], fontsize=7)
            ax.set_title(f"ours — {axis_name} sequence", fontsize=9)
            thesis = axes[1, col]
            rows = table_4_7[axis_name]
            for j, mode in enumerate(columns):
                thesis.plot(np.arange(len(rows)), [np.nan if r[j] is None else r[j] for r in rows], "-o", ms=3,
                            color=colour[mode], label=MODE_LABEL[mode])
            printed = [-10, -20, -30, -20, -10, 0, 10, 20, 30, 20, 10, 0] if axis_name == "pitch" else \
                [10, 20, 30, 20, 10, 0, -10, -20, -30, -20, -10]
            thesis.set_xticks(np.arange(len(printed)), [f"{t:+d}" for t in printed], fontsize=7)
            thesis.set_title(f"thesis Table 4.7 — {axis_name} rows as printed", fontsize=9)
            for a in (ax, thesis):
                a.set_ylim(0, 21)
                a.set_ylabel("|measured − model| [deg]")
                a.set_xlabel(f"commanded whole-spine {axis_name} [deg]")
        axes[0, 0].legend(fontsize=7, ncol=2)

def mode_time_series(ctx, names) -> None:
    """Measured (accelerometers, eq. 3.4) vs reference whole-spine angle for every mode (Figs. 4.21–4.27)."""
    rec = ctx.recorder
    cols = 4
    nrows = int(np.ceil(len(names) / cols))
    with ctx.figure("posture_time_series", nrows, cols, figsize=(15, 3.1 * nrows + 0.6), squeeze=False) as (fig, axes):
        for ax, mode in zip(axes.flat, names):
            offset = 0.0
            for axis_name, color in (("pitch", "C0"), ("roll", "C3")):
                key = f"{mode}.{axis_name}"
                if f"{key}.measured_deg" not in rec:
                    continue
                t = rec.times(f"{key}.measured_deg")
                t = t - t[0] + offset
                ax.plot(t, rec.values(f"{key}.reference_deg"), "--", color=color, lw=1)
                ax.plot(t, rec.values(f"{key}.measured_deg"), color=color, lw=0.8, label=axis_name)
                offset = t[-1] + 1.0
            ax.set_title(MODE_LABEL[mode], fontsize=9)
            ax.set_ylim(-45, 45)
            ax.set_xlabel("time [s] (pitch sequence, then roll)")
            ax.legend(fontsize=7)
        for ax in axes.flat[len(names):]:
            ax.axis("off")
        axes[0, 0].set_ylabel("whole-spine angle [deg] (dashed: model)")

def teach_playback(ctx, recording, results: dict) -> None:
    """Recorded encoder traces and the tracking error / saturation per speed-up factor."""
    samples = 1e3 * recording.samples
    t = np.arange(len(samples)) * recording.period
    factors = sorted(results)
    with ctx.figure("teach_playback", 1, 2, figsize=(12, 4)) as (fig, (ax0, ax1)):
        ax0.plot(t, samples, lw=1)
        ax0.set_xlabel("teaching time [s]")
        ax0.set_ylabel("encoder (wire wound in) [mm]")
        ax0.set_title("taught motion: 8 muscles, 1 kgf tension hold, 20 ms samples", fontsize=9)
        ax1.plot(factors, [results[k]["relative_length_error"] for k in factors], "-o", label="RMS error / RMS motion")
        ax1.plot(factors, [results[k]["saturated_fraction"] for k in factors], "-s", label="fraction of ticks saturated")
        ax1.set_xlabel("speed-up factor (decimation)")
        ax1.set_xticks(factors)
        ax1.axhline(0.1, color="0.5", ls=":", lw=1)
        ax1.legend(fontsize=8)
        ax1.set_title("replay in L mode (§4.2.2: 2–4× follow, 8× exceeds the motors)", fontsize=9)

def software_spring(ctx, k_list, trials: dict) -> None:
    """Per k_s, each muscle's encoder change and tension over time (Figs. 4.14–4.17), and the
    tension change per length change."""
    rec = ctx.recorder
    with ctx.figure("software_spring", 2, len(k_list) + 1, figsize=(4 * (len(k_list) + 1), 6.5),
                    squeeze=False) as (fig, axes):
        for col, k in enumerate(k_list):
            key = f"k{int(k)}."
            t = rec.times(f"{key}length_error_mm")
            axes[0, col].plot(t - t[0], rec.values(f"{key}length_error_mm"), lw=0.8)
            axes[1, col].plot(t - t[0], rec.values(f"{key}tension_n") / KGF_N, lw=0.8)
            axes[0, col].set_title(f"k_s = {k:g}", fontsize=9)
            axes[1, col].set_xlabel("time [s]")
        axes[0, 0].set_ylabel("length from l_0 (encoder) [mm]")
        axes[1, 0].set_ylabel("tension [kgf]")
        ax = axes[0, -1]
        ax.plot(k_list, [trials[k]["tension_change_n"] / KGF_N for k in k_list], "-o")
        ax.set_xscale("log")
        ax.set_xlabel("k_s (thesis units)")
        ax.set_ylabel("Σ|ΔT| while bent [kgf]")
        ax = axes[1, -1]
        ax.plot(k_list, [trials[k]["return_error_deg"] for k in k_list], "-o")
        ax.set_xscale("log")
        ax.set_xlabel("k_s (thesis units)")
        ax.set_ylabel("posture error after release [deg]")


def poses(ctx, runs, poses_deg) -> None:
    """Figs. 3.38 and 5.1: the hands' height against the soles', the spine's roll and yaw, and each pose's hand
    error, with the spine and locked."""
    colours = {"spine": "tab:blue", "locked": "0.4"}
    with ctx.figure("poses", nrows=1, ncols=3, figsize=(15, 4)) as (_fig, (ax_z, ax_a, ax_e)):
        names = list(poses_deg)
        for k, (v, run) in enumerate(runs.items()):
            t, sole = run.log.times("hand_r"), run.state["sole_z"]
            ax_z.plot(t, run.log.values("hand_r")[:, 2] - sole, color=colours[v], label=f"right hand, {v}")
            ax_z.plot(t, run.log.values("hand_l")[:, 2] - sole, "--", color=colours[v], label=f"left hand, {v}")
            whole = run.log.values("whole_deg")
            ax_a.plot(t, whole[:, 0], color=colours[v], label=f"roll, {v}")
            ax_a.plot(t, whole[:, 2], ":", color=colours[v], label=f"yaw, {v}")
            key, labels = run.log.values("key").astype(int), np.array(run.state["labels"])
            errors = []
            for pose in names:
                held = np.flatnonzero(labels[key] == f"{pose}_hold")[-1]
                hand = run.log.values("hand_l" if pose.endswith("_left") else "hand_r")[held]
                errors.append(100 * np.linalg.norm(hand - run.state["targets"][pose][0]))
            ax_e.bar(np.arange(len(names)) + 0.4 * k, errors, 0.4, color=colours[v], label=v)
        ax_z.axhline(0.0, color="k", lw=0.8)
        ax_z.set_xlabel("t [s]")
        ax_z.set_ylabel("hand centre above the soles [m]")
        ax_z.set_title("hands against the soles' height (Fig. 5.1)", fontsize=9)
        ax_a.set_xlabel("t [s]")
        ax_a.set_ylabel("whole-spine angle [deg]")
        ax_a.set_title("side bend (roll) and twist (yaw) reached", fontsize=9)
        ax_e.set_xticks(np.arange(len(names)) + 0.2, names, fontsize=7)
        ax_e.set_ylabel("hand from its target at the end of the hold [cm]")
        ax_e.set_title("poses (Fig. 3.38)", fontsize=9)
        for ax in (ax_z, ax_a, ax_e):
            ax.legend(fontsize=7)


def rpy(ctx, log, postures_deg, each_s) -> None:
    """Fig. 4.42: the whole-spine roll, pitch and yaw reached against the commanded combined postures."""
    t, whole = log.times("whole_deg"), log.values("whole_deg")
    with ctx.figure("rpy", nrows=1, ncols=1, figsize=(9, 4)) as (_fig, ax):
        for i, (axis, colour) in enumerate(zip(AXES, ("tab:blue", "tab:orange", "tab:green"))):
            ax.plot(t, whole[:, i], color=colour, label=f"{axis} reached")
            for k, goal in enumerate(postures_deg):
                ax.plot([t[0] + k * each_s, t[0] + (k + 1) * each_s], [goal[i]] * 2, ":", color=colour)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("whole-spine angle [deg]")
        ax.set_title("combined roll–pitch–yaw commands (dotted) and the spine (cf. Figs. 4.42–4.43)", fontsize=9)
        ax.legend(fontsize=7)
