"""The spine's shared pictures: the 3D spine with its muscle paths coloured by tension (cf. Fig. 4.10,
``general-wire :bodies``), the inverse model's learning curves and errors (cf. Figs. 4.2–4.9, Table 4.2) and the
tracking loops of Cla and Kenta (Figs. 5.12, 5.14)."""

from __future__ import annotations

import numpy as np

from shintai.spine.tracking_loops import tracking_series


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


def tension_sensor(ctx, tension, counts, probes, steps) -> None:
    """Fig. 3.34's analogue: the count against the tension, and the count step's width at the probe tensions."""
    with ctx.figure("tension_sensor", nrows=1, ncols=2, figsize=(11, 4)) as (_fig, (ax_c, ax_s)):
        ax_c.plot(tension, counts, lw=1.2)
        ax_c.set_xlabel("applied tension [N]")
        ax_c.set_ylabel("10-bit ADC count")
        ax_c.set_title("calibration (cf. Fig. 3.34)", fontsize=9)
        ax_s.loglog(probes, steps, "o-")
        ax_s.set_xlabel("tension [N]")
        ax_s.set_ylabel("one count's step [N]")
        ax_s.set_title("resolution: fine at small tensions, coarse at large", fontsize=9)
