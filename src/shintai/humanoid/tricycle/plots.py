"""The humanoid experiments' pictures (seed 000 Figs. 3.17–3.35, 4.19–4.22, 7.2, 7.15): each draws from
the recorded signals of one or more runs (:class:`~shintai.scenarios.experiment.Run`)."""

from __future__ import annotations

import math

import matplotlib.patches
import numpy as np

from shintai.core.geometry import unwrap_from
from shintai.humanoid.constants import DEG, NAVIGATION, TRICYCLE
from shintai.humanoid.tricycle.kenshiro import active_leg_plan, contact_of, crank_centre, sole_normal
from shintai.humanoid.tricycle.rig import F_TRG

# --- ch. 3: the tricycle ------------------------------------------------------------------------------


def pedaling(ctx, runs: list[tuple], diag) -> None:
    """Fig. 3.22 (foot f_z against the 150 N target, active phases shaded) and the crank angle.
    ``runs``: (log, title, shade the active phases) per run, the first the active/passive one."""
    with ctx.figure("foot_forces", len(runs) + 1, 1, figsize=(10, 3.2 * (len(runs) + 1)), sharex=True) as (fig, ax):
        for axis, (rec, title, shade) in zip(ax, runs):
            t = rec.times("crank_true")
            for side, color in (("left", "C0"), ("right", "C3")):
                axis.plot(t, rec.values(f"fz_{side}"), color=color, lw=0.8, label=f"{side} foot f_z")
                if shade:
                    axis.fill_between(t, 0, 1, where=rec.values(f"active_{side}") > 0.5, color=color, alpha=0.08,
                                      transform=axis.get_xaxis_transform(), label=f"{side} leg active")
            axis.axhline(F_TRG, color="k", ls="--", lw=1, label="f^trg_z = 150 N")
            axis.set_ylabel("f_z from pedal [N]")
            axis.set_title(title, fontsize=9)
            axis.legend(fontsize=7, loc="upper right", ncol=3)
        rec = runs[0][0]
        t = rec.times("crank_true")
        true = rec.values("crank_true")
        ax[-1].plot(t, true / DEG, label="true crank joint (evaluation only)")
        ax[-1].plot(t, unwrap_from(rec.values("crank_est"), true[0]) / DEG, "--", label="estimated from the feet (method (a))")
        for ts, _, _ in diag.log:
            for axis in ax:
                axis.axvline(ts, color="k", lw=0.8, ls=":")
        ax[-1].set_ylabel("θ_c [deg]")
        ax[-1].set_xlabel("time [s] (dotted: role swaps, Eq. 3.19)")
        ax[-1].legend(fontsize=8)


def steering(ctx, rec, both, schedule, diag) -> None:
    """Handle angle (commanded, true, estimated) and the squeeze between the hands, both configurations
    (``both``: the both-active run's log, or None)."""
    with ctx.figure("steering", 2, 1, figsize=(10, 6.4), sharex=True) as (fig, ax):
        t = rec.times("handle_true")
        ax[0].step([s.t0 for s in schedule.samples], [s.theta_h / DEG for s in schedule.samples], where="post",
                   color="0.5", label="commanded θ_h (Δθ_h = 5°)")
        ax[0].plot(t, rec.values("handle_true") / DEG, label="true handle joint (evaluation only)")
        ax[0].plot(t, rec.values("handle_est") / DEG, "--", label="estimated from the hands (method (a))")
        if both is not None:
            ax[0].plot(both.times("handle_true"), both.values("handle_true") / DEG, ":", label="true, both arms active")
        ax[0].set_ylabel("θ_h [deg]")
        ax[1].plot(t, rec.values("internal"), color="C0", label="internal ‖(f_L − f_R)/2‖, active/passive")
        ax[1].plot(t, rec.values("squeeze"), color="C0", lw=0.7, ls="--", label="squeeze, active/passive")
        if both is not None:
            tb = both.times("internal")
            ax[1].plot(tb, both.values("internal"), color="C1", label="internal, both active")
            ax[1].plot(tb, both.values("squeeze"), color="C1", lw=0.7, ls="--", label="squeeze, both active")
        ax[1].axhline(0.0, color="k", lw=0.8, ls=":")
        ax[1].set_ylabel("force between the hands [N]")
        for axis in ax:
            axis.fill_between(t, 0, 1, where=rec.values("active_right") > 0.5, color="C3", alpha=0.08,
                              transform=axis.get_xaxis_transform(), label="right arm active")
            for ts, _, _ in diag.log:
                axis.axvline(ts, color="k", lw=0.8, ls=":")
            axis.legend(fontsize=7, loc="upper left")
        ax[1].set_xlabel("time [s] (dotted: role swap, Eq. 3.19)")


def ride(ctx, runs: list[tuple], name: str = "ride") -> None:
    """Per ride (log, title, passive f^trg_z): handle and crank angles (commanded, true, estimated), foot
    forces with the legs' active phases shaded, against the force targets."""
    with ctx.figure(name, 2 * len(runs), 1, figsize=(11, 3.0 * 2 * len(runs))) as (fig, ax):
        ax = np.atleast_1d(ax)
        for i, (rec, title, passive) in enumerate(runs):
            t = rec.times("x")
            a, b = ax[2 * i], ax[2 * i + 1]
            a.plot(t, rec.values("handle_cmd") / DEG, color="0.5", lw=1, drawstyle="steps-post", label="θ_h commanded")
            a.plot(t, rec.values("handle_true") / DEG, color="C0", label="θ_h true (evaluation only)")
            a.plot(t, rec.values("handle_est") / DEG, "--", color="C0", lw=0.8, label="θ_h from the hands")
            a.set_ylabel("θ_h [deg]")
            twin = a.twinx()
            twin.plot(t, rec.values("crank_cmd") / DEG, color="0.7", lw=1, drawstyle="steps-post")
            twin.plot(t, rec.values("crank_true") / DEG, color="C2", label="θ_c true")
            twin.set_ylabel("θ_c [deg]", color="C2")
            a.fill_between(t, 0, 1, where=rec.values("arm_active_right") > 0.5, color="C3", alpha=0.08,
                           transform=a.get_xaxis_transform(), label="right arm active")
            a.set_title(title, fontsize=9)
            a.legend(fontsize=7, loc="upper left", ncol=2)
            for side, color in (("left", "C0"), ("right", "C3")):
                b.plot(t, rec.values(f"fz_{side}"), color=color, lw=0.7, label=f"{side} foot f_z")
                b.fill_between(t, 0, 1, where=rec.values(f"leg_active_{side}") > 0.5, color=color, alpha=0.08,
                               transform=b.get_xaxis_transform(), label=f"{side} leg active")
            b.axhline(F_TRG, color="k", ls="--", lw=1, label="f^trg_z = 150 N")
            if passive != F_TRG:
                b.axhline(passive, color="k", ls=":", lw=1, label=f"passive f^trg_z = {passive:g} N")
            b.plot(t, rec.values("internal"), color="C4", lw=0.6, label="hands ‖(f_L − f_R)/2‖")
            b.set_ylabel("force [N]")
            b.set_ylim(-20, 400)
            b.legend(fontsize=7, loc="upper right", ncol=3)
        ax[-1].set_xlabel("time [s]")


def paths(ctx, runs: list[tuple]) -> None:
    """The vehicle path on the floor (vehicle-frame origin, under the crank), with its heading;
    ``runs``: (log, label)."""
    with ctx.figure("path", 1, 1, figsize=(7, 6)) as (fig, ax):
        for i, (rec, label) in enumerate(runs):
            x, y, yaw = (rec.values(k) for k in ("x", "y", "yaw"))
            ax.plot(x, y, color=f"C{i}", label=label)
            picks = np.linspace(0, len(x) - 1, 12).astype(int)
            ax.quiver(x[picks], y[picks], np.cos(yaw[picks]), np.sin(yaw[picks]), color=f"C{i}", scale=25, width=0.004)
            ax.plot(x[0], y[0], "ko", ms=4)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)


# --- ch. 3: Kenshiro ----------------------------------------------------------------------------------


def kenshiro_forces(ctx, rec, t0: float, swaps: list) -> None:
    """Fig. 3.35: the crank angle (top) and the vertical sole forces (bottom), active phases shaded."""
    t = rec.times("crank_true") - t0
    true = rec.values("crank_true")
    est = unwrap_from(rec.values("crank_est"), true[0])
    right_active = rec.values("right_active") > 0.5
    with ctx.figure("force_trace", 2, 1, figsize=(9, 6), sharex=True) as (fig, ax):
        ax[0].plot(t, true / DEG, label="crank joint θ_c")
        ax[0].plot(t, est / DEG, "--", label="estimated from the feet (method (a))")
        ax[0].set_ylabel("crank angle [deg]")
        for leg, color in (("right", "C3"), ("left", "C0")):
            ax[1].plot(t, rec.values(f"fz_{leg}"), color=color, label=f"{leg} foot F_z")
            mask = right_active if leg == "right" else ~right_active
            ax[1].fill_between(t, 0, 1, where=mask, color=color, alpha=0.08, transform=ax[1].get_xaxis_transform(),
                               label=f"{leg} leg active")
        for axis in ax:
            for ts, _, _ in swaps:
                axis.axvline(ts - t0, color="k", lw=0.8, ls=":")
            axis.legend(fontsize=8, loc="upper left")
        ax[1].set_ylabel("vertical force from the pedal [N]")
        ax[1].set_xlabel("time from the start of pedalling [s] (dotted: role swaps, Eq. 3.19)")


def kenshiro_plan(ctx, k) -> None:
    """The active leg's plan (Eq. 3.7) with the chosen sole orientation and the Eq. 3.21 margin."""
    with ctx.figure("active_plan", 1, 2, figsize=(11, 4.5)) as (fig, ax):
        c = crank_centre(k)
        circle = c[:, None] + k.crank_radius * np.array([np.sin(np.linspace(0, 2 * np.pi, 200)),
                                                         np.cos(np.linspace(0, 2 * np.pi, 200))])
        ax[0].plot(*circle, color="0.7", lw=1)
        steps = active_leg_plan("right", k)
        for i, s in enumerate(steps):
            color = "0.5" if i == len(steps) - 1 else "C2" if s.margin > 0 else "C3"  # p_T has no step
            contact = contact_of(s.p, s.psi)
            sole = np.array([math.cos(s.psi), -math.sin(s.psi)]) * 0.04
            ax[0].plot(*np.array([contact - sole, contact + sole]).T, color=color, lw=2)
            ax[0].arrow(*contact, *(0.03 * sole_normal(s.psi)), width=0.0008, color="0.4")
        ax[0].plot(*np.array([s.p for s in steps]).T, "k.", ms=4)
        ax[0].set_aspect("equal")
        ax[0].set_title("right leg's active plan p_i, soles (green: Eq. 3.21 holds)", fontsize=9)
        ax[0].set_xlabel("x from the hip [m]")
        ax[0].set_ylabel("z from the hip [m]")
        margins = [s.margin + k.d_th for s in steps[:-1]]
        ax[1].bar(range(len(margins)), margins, color=["C2" if s.margin > 0 else "C3" for s in steps[:-1]])
        ax[1].axhline(k.d_th, color="k", ls="--", lw=1, label=f"D_th = {k.d_th * 1000:.2f} mm")
        ax[1].set_xlabel("sample i")
        ax[1].set_ylabel("−(p_{i+1} − p_i)·u_i [m]")
        ax[1].legend(fontsize=8)


# --- ch. 4 / ch. 7: corrections while driving -----------------------------------------------------------


def navigation(ctx, rec, nav, path: np.ndarray, goal, wall) -> None:
    """The vehicle path on the floor with the wall, the costmap and the last global path (Fig. 4.19)."""
    cm = nav.costmap
    with ctx.figure("navigation_path", 1, 1, figsize=(9, 5.5)) as (fig, ax):
        extent = [cm.origin[0], cm.origin[0] + cm.shape[0] * cm.res, cm.origin[1], cm.origin[1] + cm.shape[1] * cm.res]
        inflated = np.where(cm.occupied, 1.0, np.where(cm.distance <= NAVIGATION.footprint_r, 0.45, 0.0))
        ax.imshow(inflated.T, origin="lower", extent=extent, cmap="Greys", vmin=0, vmax=1, alpha=0.8)
        hx, hy = wall.half[0], wall.half[1]
        ax.add_patch(matplotlib.patches.Rectangle((wall.pos[0] - hx, wall.pos[1] - hy), 2 * hx, 2 * hy,
                                                  fill=False, ec="C3", lw=1.5, label="wall (true)"))
        if nav.path is not None:
            ax.plot(*nav.path.T, "m--", lw=1, label="global path (last)")
        ax.plot(path[:, 0], path[:, 1], "C0", lw=2, label="vehicle (crank origin)")
        ax.plot(*goal, "g*", ms=14, label="goal")
        ax.plot(0, 0, "ko", ms=5)
        ax.set_aspect("equal")
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title("costmap from the head depth sensor (black: occupied, grey: inflated by the footprint)", fontsize=9)
        ax.legend(fontsize=8, loc="lower right")
    with ctx.figure("navigation_commands", 2, 1, figsize=(9, 5), sharex=True) as (fig, ax):
        t = rec.times("x")
        ax[0].plot(t, rec.values("theta_h_ref") / DEG, label="θ_h^ref (Eq. 4.21)")
        ax[0].plot(t, rec.values("handle") / DEG, label="handle joint (evaluation)")
        ax[0].set_ylabel("deg")
        ax[0].legend(fontsize=8)
        ax[1].plot(t, np.minimum(rec.values("clearance"), 2.0))
        ax[1].set_ylabel("clearance to wall [m]")
        ax[1].set_xlabel("time [s]")


def posture(ctx, runs: dict, steps) -> None:
    """Trunk (chest IMU) and vehicle roll against the distance driven, with and without the control."""
    with ctx.figure("trunk_roll", 2, 1, figsize=(9, 6), sharex=True) as (fig, ax):
        for name, color in (("with", "C0"), ("without", "C3")):
            rec = runs[name].log
            x = rec.values("x")
            ax[0].plot(x, rec.values("trunk_roll") / DEG, color=color, label=f"trunk roll, {name} posture control")
            ax[0].plot(x, rec.values("vehicle_roll") / DEG, color=color, ls=":", lw=1, label=f"vehicle roll, {name}")
        ax[1].plot(runs["with"].log.values("x"), runs["with"].log.values("chest_roll_ref") / DEG, color="C0")
        ax[1].set_ylabel("Δφ_C (Eq. 4.8) [deg]")
        ax[0].set_ylabel("roll [deg]")
        ax[0].legend(fontsize=7)
        for axis in ax:
            for ob in steps:
                for edge in (ob.pos[0] - ob.half[0], ob.pos[0] + ob.half[0]):
                    axis.axvline(edge + TRICYCLE.crank_to_back, color="0.6", lw=0.8, ls="--")
        ax[1].set_xlabel("vehicle x [m] (dashed: the back wheels at the step edges)")


def recovery(ctx, runs: dict) -> None:
    """Fig. 7.15: trunk roll, feet force, hip slip and the recovery phases, with and without."""
    with ctx.figure("sitting_recovery", 3, 1, figsize=(9, 8), sharex=True) as (fig, ax):
        for name, color in (("with", "C0"), ("without", "C3")):
            rec = runs[name].log
            t = rec.times("roll")
            label = name + " recovery"
            ax[0].plot(t, np.clip(rec.values("roll") / DEG, -20, 20), color=color, label=f"θ_roll, {label}")
            ax[0].plot(t, np.clip(rec.values("vehicle_roll") / DEG, -20, 20), color=color, ls=":", lw=1,
                       label=f"vehicle roll, {label}")
            ax[1].plot(t, rec.values("fz_feet"), color=color, label=f"Σ foot f_z, {label}")
            ax[2].plot(t, rec.values("hip_y") * 100, color=color, label=f"hip y on the saddle, {label}")
        rec = runs["with"].log
        t = rec.times("roll")
        for axis in ax:
            axis.fill_between(t, 0, 1, where=rec.values("recovering") > 0.5, color="C0", alpha=0.12,
                              transform=axis.get_xaxis_transform(), label="recovering (with)")
            axis.legend(fontsize=7, loc="upper left")
        ax[0].set_ylabel("roll [deg] (clipped ±20)")
        ax[1].set_ylabel("feet vertical force [N]")
        ax[2].set_ylabel("hip slip [cm]")
        ax[2].set_xlabel("time [s]")


def small_obstacle(ctx, runs: dict, board) -> None:
    """Foot forces, crank angle and vehicle position, with and without the detection method (Fig. 4.22)."""
    with ctx.figure("small_obstacle", 3, 1, figsize=(9, 8), sharex=True) as (fig, ax):
        for name, color in (("with", "C0"), ("without", "C3")):
            rec = runs[name].log
            t = rec.times("x")
            lab = name + " detection"
            ax[0].plot(t, rec.values("x"), color=color, label=f"vehicle x, {lab}")
            ax[1].plot(t, rec.values("crank") / DEG, color=color, label=f"θ_c (method (a)), {lab}")
            ax[2].plot(t, rec.values("fz_l"), color=color, label=f"left f_z, {lab}")
            ax[2].plot(t, rec.values("fz_r"), color=color, ls="--", label=f"right f_z, {lab}")
        rec = runs["with"].log
        t = rec.times("x")
        for axis in ax:
            axis.fill_between(t, 0, 1, where=rec.values("state") == 1, color="C1", alpha=0.15,
                              transform=axis.get_xaxis_transform(), label="back-pedalling")
            axis.fill_between(t, 0, 1, where=rec.values("state") == 2, color="C2", alpha=0.15,
                              transform=axis.get_xaxis_transform(), label="pushing harder")
            axis.legend(fontsize=7, loc="upper left")
        ax[0].axhline(board.pos[0] - board.half[0] - TRICYCLE.crank_to_front, color="0.5", ls=":", lw=1)
        ax[0].set_ylabel("x [m]")
        ax[1].set_ylabel("crank [deg]")
        ax[2].set_ylabel("ankle f_z [N]")
        ax[2].set_xlabel("time [s]")


# --- ch. 7: self-localisation -------------------------------------------------------------------------


def odometry(ctx, tracks: dict, obstacles, handle_deg: float) -> None:
    """Fig. 7.4: the truth, wheel odometry, visual odometry and the localisation on the X–Y plane (the
    room's obstacles, the map, drawn as boxes), and each estimate's position error over the run."""
    styles = {"truth": ("k", "-", "ground truth (simulator)"), "wheel": ("C0", "--", "wheel odometry (Eq. 4.15, FK)"),
              "visual": ("C1", "-.", "visual odometry (head camera, drift)"),
              "localisation": ("C3", "-", "localisation (MCL on depth rays + map)")}
    with ctx.figure("odometry_tracks", 1, 3, figsize=(16, 5.2)) as (fig, ax):
        for ob in obstacles:
            ax[0].add_patch(matplotlib.patches.Rectangle((ob.pos[0] - ob.half[0], ob.pos[1] - ob.half[1]),
                                                         2 * ob.half[0], 2 * ob.half[1], angle=math.degrees(ob.yaw),
                                                         rotation_point="center", fc="0.7", ec="0.4"))
        for axis in ax[:2]:
            for name, (color, ls, label) in styles.items():
                xy = tracks[name]
                axis.plot(xy[:, 0], xy[:, 1], color=color, ls=ls, lw=2 if name in ("truth", "localisation") else 1.5,
                          label=label)
                axis.plot(xy[-1, 0], xy[-1, 1], "o", color=color, ms=5)
            axis.plot(1.3, -0.6, "x", color="m", ms=10, mew=2, label="thesis's end point ≈(1.3, −0.6) m")
            axis.set_aspect("equal")
            axis.set_xlabel("X [m]")
            axis.set_ylabel("Y [m]")
        ax[0].set_title(f"the room (the map) and the tracks, θ_h = {handle_deg:g}° (Fig. 7.4)", fontsize=9)
        ax[0].legend(fontsize=7, loc="upper left")
        end = tracks["truth"][-1]
        ax[1].set_xlim(end[0] - 0.35, end[0] + 0.25)
        ax[1].set_ylim(end[1] - 0.3, end[1] + 0.3)
        ax[1].set_title("near the end point (dots: where each ends)", fontsize=9)
        for name in ("wheel", "visual", "localisation"):
            color, ls, label = styles[name]
            err = np.hypot(*(tracks[name][:, :2] - tracks["truth"][:, :2]).T)
            ax[2].plot(tracks["t"], err, color=color, ls=ls, label=label.split(" (")[0])
        ax[2].set_xlabel("time [s]")
        ax[2].set_ylabel("position error [m]")
        ax[2].set_title("distance of each estimate from the truth", fontsize=9)
        ax[2].legend(fontsize=8)


def navigation_estimated(ctx, runs: dict, wall) -> None:
    """§7.3.2 / Fig. 7.5 with the self-localisation in the loop: the true path of the run on the estimated
    pose, the pose the navigator believed, the true-pose run's path, and the estimate's error over time."""
    est = runs["estimated"]
    hist = est.state.loc.history
    t = np.array([h[0] for h in hist])
    truth, mcl = np.array([h[1] for h in hist]), np.array([h[4] for h in hist])
    with ctx.figure("navigation_estimated", 2, 1, figsize=(9, 7.5), gridspec_kw={"height_ratios": [3, 1.4]}) \
            as (fig, ax):
        hx, hy = wall.half[0], wall.half[1]
        ax[0].add_patch(matplotlib.patches.Rectangle((wall.pos[0] - hx, wall.pos[1] - hy), 2 * hx, 2 * hy,
                                                     fc="0.6", ec="C3", lw=1.5, label="wall (the map)"))
        if "run" in runs:
            path = np.array(runs["run"].state.path)
            ax[0].plot(path[:, 0], path[:, 1], color="0.5", lw=1.5, ls=":", label="true-pose run (truth)")
        ax[0].plot(truth[:, 0], truth[:, 1], "k", lw=2, label="estimated-pose run: truth")
        ax[0].plot(mcl[:, 0], mcl[:, 1], "C3--", lw=1.5, label="estimated-pose run: the navigator's pose (MCL)")
        ax[0].plot(*est.state.goal, "g*", ms=14, label="goal")
        ax[0].set_aspect("equal")
        ax[0].set_xlabel("x [m]")
        ax[0].set_ylabel("y [m]")
        ax[0].set_title("navigation on the estimated pose (§7.3.2, Fig. 7.3's self-localisation loop)", fontsize=9)
        ax[0].legend(fontsize=8, loc="lower right")
        ax[1].plot(t, np.hypot(*(mcl[:, :2] - truth[:, :2]).T), "C3")
        ax[1].set_xlabel("time [s]")
        ax[1].set_ylabel("|estimate − truth| [m]")


def load_monitor(ctx, rec, windows) -> None:
    """Fig. 7.16 over time: force and joint-torque norms, the CoM's offset on the saddle, and model A
    against model B (hands, waist), the recovery shaded and the before/after windows marked."""
    t = rec.times("load.force_norm")
    with ctx.figure("load_monitor", 4, 1, figsize=(10, 10), sharex=True) as (fig, ax):
        series = [
            (0, "load.force_norm", "‖f‖ hands and feet", "C0"), (0, "load.hand_force_norm", "‖f‖ hands", "C1"),
            (1, "load.torque_norm", "‖τ‖ joint servos", "C2"),
            (3, "load.hand_ab", "hands: |A − B| (mean)", "C4"), (3, "load.waist_ab", "waist: |A − B|", "C5")]
        for k, key, label, color in series:
            ax[k].plot(t, rec.values(key), color=color, lw=1, label=label)
        ax[2].plot(t, rec.values("load.com_y") * 100, "C3", lw=1, label="CoM y − saddle top (vehicle frame)")
        for axis, ylabel in zip(ax, ("force [N]", "torque [N m]", "CoM offset [cm]", "A vs B [m]")):
            axis.fill_between(t, 0, 1, where=rec.values("recovering") > 0.5, color="k", alpha=0.08,
                              transform=axis.get_xaxis_transform(), label="sitting recovery")
            if windows:
                for (a, b), color in zip(windows, ("C3", "C2")):
                    axis.axvspan(a, b, color=color, alpha=0.12)
            axis.set_ylabel(ylabel)
            axis.legend(fontsize=7, loc="upper left")
        ax[0].set_title("load monitor (Fig. 7.16): before (red band) and after (green band) the recovery", fontsize=9)
        ax[-1].set_xlabel("time [s]")
