"""Pictures of the spine scenarios: the 3D spine with its muscle paths coloured by tension (cf.
Fig. 4.10, ``general-wire :bodies``), Tables 4.7/4.8 side by side, posture errors and time series
(cf. Figs. 4.21–4.27), the teaching replay and the software-spring traces (cf. Figs. 4.14–4.17).
"""

from __future__ import annotations

import numpy as np

from shintai.core.constants import KGF_N
from shintai.spine.tracking_loops import tracking_series

MODE_LABEL = {"all_l": "1. all L", "all_ll": "2. all LL", "all_s_mid": "3. all S (mid)", "all_s_high": "4. all S (high)",
              "l_ll": "5. L + LL", "l_t": "6. L + T", "l_s_mid": "7. L + S (mid)", "l_s_high": "8. L + S (high)",
              "all_l_no_interference": "all L, no interference"}


def spine_state(body) -> dict:
    """What the 3D picture needs from a :class:`~shintai.spine.bodies_mujoco.SpineBody` now: link
    origins, each muscle's path as MuJoCo wrapped it (without the reel inside the block), its
    tension, the wrap sphere and the posture."""
    m, d = body.model, body.data
    links = np.array([d.xpos[body.id("body", f"link{i}")] for i in range(body.robot.n + 1)])
    points = d.wrap_xpos.reshape(-1, 3)  # MuJoCo stores the wrap points in rows of two
    paths = [points[d.ten_wrapadr[t] + 1:d.ten_wrapadr[t] + d.ten_wrapnum[t]].copy() for t in body.tendon_ids]
    wrap = None
    if "wrap" in body.ids["geom"]:
        g = body.id("geom", "wrap")
        wrap = (d.geom_xpos[g].copy(), float(m.geom_size[g, 0]))
    return {"links": links, "paths": paths, "tension": body.wire_tension(), "names": body.robot.muscle_names,
            "wrap": wrap, "theta": body.theta()}


def _sphere(ax, centre, radius, color, alpha):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 18), np.linspace(0, np.pi, 10))
    ax.plot_surface(centre[0] + radius * np.cos(u) * np.sin(v), centre[1] + radius * np.sin(u) * np.sin(v),
                    centre[2] + radius * np.cos(v), color=color, alpha=alpha, linewidth=0)


def spine_3d(ctx, states: dict) -> None:
    """One 3D panel per captured state: vertebrae, wrap sphere, muscles coloured by tension."""
    from matplotlib import cm, colors

    vmax = max(float(s["tension"].max()) for s in states.values()) or 1.0
    norm = colors.Normalize(0.0, vmax)
    with ctx.figure("spine_3d", 1, len(states), figsize=(5.6 * len(states), 5.4),
                    subplot_kw={"projection": "3d"}) as (fig, axes):
        axes = np.atleast_1d(axes)
        for ax, (label, s) in zip(axes, states.items()):
            links = s["links"]
            ax.plot(*links.T, "-o", color="0.35", lw=4, ms=7)
            if s["wrap"] is not None:
                _sphere(ax, *s["wrap"], color="orange", alpha=0.25)
            for path, tension, name in zip(s["paths"], s["tension"], s["names"]):
                ax.plot(*path.T, color=cm.plasma(norm(tension)), lw=2.5, label=f"{name} {tension:.1f} N")
            ax.legend(fontsize=6, loc="upper left", title=f"tension (colour: 0–{vmax:.0f} N)", title_fontsize=6)
            whole = np.degrees(s["theta"].reshape(-1, 3).sum(axis=0))
            ax.set_title(f"{label}: whole spine roll {whole[0]:.1f}°, pitch {whole[1]:.1f}°", fontsize=9)
            centre = links.mean(axis=0)
            span = 0.09
            ax.set_xlim(centre[0] - span, centre[0] + span)
            ax.set_ylim(centre[1] - span, centre[1] + span)
            ax.set_zlim(centre[2] - span, centre[2] + span)
            ax.set_xlabel("x (front) [m]")
            ax.set_ylabel("y (left) [m]")
            ax.view_init(elev=12, azim=-60)


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


def rabbit(ctx, levels, curves: dict) -> None:
    with ctx.figure("rabbit_stiffness", 1, 1, figsize=(6.4, 4.2)) as (fig, ax):
        for label, stiff in curves.items():
            ax.plot(levels, stiff, "-o", label=label.rstrip(".").replace("_", " "))
        ax.set_xlabel("disc pre-compression the muscle lengths are computed for [mm]")
        ax.set_ylabel("lateral stiffness at the top [N/mm]")
        ax.set_yscale("log")
        ax.legend(fontsize=8)


def plot_learning_curves(ctx, nets: dict) -> None:
    """Figs. 4.2–4.9 analogue: mean error norm on the 343 teacher postures (and the test set)."""
    with ctx.figure("inverse_learning_curves", figsize=(7.5, 4.2)) as (fig, ax):
        for (label, inv), color in zip(nets.items(), ("tab:blue", "tab:orange")):
            c = inv.curve
            ax.semilogy(c.iterations, c.train_deg, color=color, lw=1.2, label=f"{label}: 343 teacher postures")
            ax.semilogy(c.iterations, c.test_deg, color=color, lw=1, ls="--", label=f"{label}: 50 random postures")
            ax.plot(c.best_iteration, c.best_train_deg, "o", color=color, ms=5)
        ax.axhline(1.26, color="tab:blue", ls=":", lw=0.8, label="thesis 8-40-15 min 1.26° (Table 4.3)")
        ax.axhline(1.12, color="tab:orange", ls=":", lw=0.8, label="thesis 8-10-10-15 min 1.12°")
        ax.set_xlabel("iteration")
        ax.set_ylabel("mean error norm over 15 joints [deg]")
        ax.legend(fontsize=7)
        ax.set_title("learning curves on Cla's geometric model (dot: the kept network)", fontsize=9)


def plot_inverse_errors(ctx, errors: dict, table: list[dict]) -> None:
    """Per-posture error norms of the three inverses, and Table 4.2's Jacobian runs against n."""
    with ctx.figure("inverse_errors", nrows=1, ncols=2, figsize=(11.0, 4.2)) as (fig, ax):
        for label, e in errors.items():
            ax[0].semilogy(np.arange(1, len(e) + 1), np.maximum(e, 1e-3), "o-", ms=3, lw=0.8, label=label)
        ax[0].axhline(1.95, color="k", ls=":", lw=0.8, label="thesis NN 8-40-15: 1.95°")
        ax[0].set_xlabel("random uniform-bend test posture")
        ax[0].set_ylabel("error norm over 15 joints [deg]")
        ax[0].legend(fontsize=7)
        for name in sorted({r["true"] for r in table}, key=lambda s: (float(s.split("=")[1]), s)):
            rows = [r for r in table if r["true"] == name]
            ax[1].loglog([r["divisions"] for r in rows], [r["error_norm_deg"] for r in rows], "o-", ms=3, lw=0.8,
                         label=name)
        ax[1].set_xlabel("divisions n (n₀ = int|Δq| mm, 2n₀, 4n₀)")
        ax[1].set_ylabel("error norm [deg]")
        ax[1].set_title("Table 4.2 analogue (Jacobian integration)", fontsize=9)
        ax[1].legend(fontsize=6, ncol=3)


def tracking(ctx, runs: dict) -> None:
    """Per robot: the target's angle from the optical axis, and each part's share of the gaze's pan."""
    with ctx.figure("tracking", len(runs), 2, figsize=(13, 3.6 * len(runs)), squeeze=False) as (fig, axes):
        for row, (robot, run) in enumerate(runs.items()):
            s = tracking_series(run.log, run.state)
            ax = axes[row, 0]
            ax.plot(s["t"], np.degrees(s["image"][:, 0]), label="horizontal")
            ax.plot(s["t"], np.degrees(s["image"][:, 1]), label="vertical")
            ax.set_ylabel(f"{robot}: target off axis [deg]")
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
            ax = axes[row, 1]
            names = ("spine", "neck", "eyes")[:s["gaze"].shape[1]]
            for k, name in enumerate(names):
                ax.plot(s["t"], np.degrees(s["gaze"][:, k, 0]), label=f"{name} pan")
            ax.plot(s["t"], np.degrees(s["gaze"][:, :, 0].sum(axis=1)), "k--", lw=1, label="sum")
            ax.set_ylabel("pan [deg]")
            ax.legend(fontsize=8)
            ax.grid(alpha=0.3)
        axes[-1, 0].set_xlabel("time [s]")
        axes[-1, 1].set_xlabel("time [s]")
