"""Cla's pictures: ``spine.posture-database`` (seed 003 §5.9: the node graph in a 2-D projection of muscle-length
space, cf. Fig. 5.29, the history replay against the taught history, cf. Fig. 5.30, the push triggers) and the
chapter-5 behaviours (§5.2: the pull, the throw, the levelling, the balance, the pick-and-place, the roll-over)."""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Rectangle

from shintai.spine.robots import CLA_DESK_HEIGHT_M, CLA_OBJECT_HALF_M

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
