"""Pictures of ``spine.bvh-retarget`` (seed 003 Fig. 5.28): twist against time, the human as a stick figure and
the robots' shoulder lines against their pelvis lines from above."""

from __future__ import annotations

import numpy as np

from shintai.spine.mocap import retarget as mocap
from shintai.spine.mocap.constants import TILE

COLOURS = {"human": "k", "cla": "tab:blue", "kenta": "tab:green", "hrp2": "tab:orange", "hrp_rigid": "tab:red"}


def twist(ctx, runs) -> None:
    human = runs["human"]
    t = human.times_s
    with ctx.figure("twist", 2, 1, figsize=(7.0, 6.4), sharex=True) as (_fig, (ax, bx)):
        ax.plot(t, human.twist_deg, "k-", lw=2.5, label="human (BVH)")
        for robot in mocap.ROBOTS:
            r = runs[robot]
            ax.plot(t, r.twist_deg, "-", color=COLOURS[robot], label=robot)
            sat = r.saturated
            if sat.any():
                ax.fill_between(t, 0, 1, where=sat, color=COLOURS[robot], alpha=0.12, step="mid",
                                transform=ax.get_xaxis_transform())
        ax.set_ylabel("trunk twist: shoulder line vs pelvis line [deg]")
        ax.legend(fontsize=8, loc="upper right")
        ax.set_title("shaded: a joint target clamped at its limit", fontsize=8)
        for robot, style in (("cla", "-"), ("kenta", "--")):
            r = runs[robot]
            yaw = np.degrees(r.targets[:, 2::3])
            bx.plot(t, yaw, style, color=COLOURS[robot], lw=1)
            bx.axhline(np.degrees(r.upper[2]), color=COLOURS[robot], ls=":", lw=1)
            bx.plot([], [], style, color=COLOURS[robot], label=f"{robot}: yaw of each joint (dotted: limit)")
        r = runs["hrp2"]
        bx.plot(t, np.degrees(r.targets[:, 0]), color=COLOURS["hrp2"], label="hrp2: waist yaw")
        bx.axhline(np.degrees(r.upper[0]), color=COLOURS["hrp2"], ls=":", lw=1)
        bx.set_xlabel("time [s]")
        bx.set_ylabel("joint target [deg]")
        bx.legend(fontsize=8, loc="upper right")


def _bones(bvh):
    return [(j.parent, i) for i, j in enumerate(bvh.joints) if j.parent >= 0]


def figures(ctx, runs) -> None:
    """Left: the human from the front at four frames. Right: from above at the peak twist, each trunk's pelvis
    line (thin) and shoulder line (thick), the human's and the robots', offset for clarity."""
    human, bvh = runs["human"], runs["bvh"]
    peak = int(np.argmax(np.abs(human.twist_deg)))
    picks = sorted({0, peak // 2, peak, len(human.times_s) - 1})
    with ctx.figure("figures", 1, 2, figsize=(11.0, 4.8)) as (_fig, (ax, bx)):
        az = np.radians(35.0)  # seen from the front, 35° to the figure's left
        x = human.positions[..., 0] * np.cos(az) + human.positions[..., 2] * np.sin(az)
        y = human.positions[..., 1]
        span = np.ptp(x[0]) + 1e-9
        for k, f in enumerate(picks):
            dx = k * 1.3 * span - x[f, 0]
            for a, b in _bones(bvh):
                ax.plot([x[f, a] + dx, x[f, b] + dx], [y[f, a], y[f, b]], "k-", lw=1.5)
            ax.text(x[f, 0] + dx, np.max(y[f]) * 1.04, f"t = {human.times_s[f]:.2f} s\ntwist "
                    f"{human.twist_deg[f]:.0f}°", ha="center", fontsize=7)
        ax.set_aspect("equal")
        ax.set_axis_off()
        ax.set_title("the BVH human, seen from the front-left", fontsize=9)
        rows = [("human", None)] + [(r, runs[r]) for r in mocap.ROBOTS]
        for k, (name, r) in enumerate(rows):
            x0 = 2.6 * k
            yaw = np.radians(human.twist_deg[peak] if r is None else r.twist_deg[peak])
            bx.plot([x0, x0], [-1, 1], "-", color="0.6", lw=1)  # pelvis line: left–right, seen from above
            bx.plot([x0 + np.sin(yaw), x0 - np.sin(yaw)], [-np.cos(yaw), np.cos(yaw)], "-", color=COLOURS[name],
                    lw=4)
            bx.text(x0, -1.15, f"{name}\n{round(float(np.degrees(yaw))) + 0:d}°", ha="center", va="top", fontsize=8)
        bx.set_aspect("equal")
        bx.set_xlim(-1.5, 2.6 * (len(rows) - 1) + 1.5)
        bx.set_ylim(-1.9, 1.3)
        bx.set_axis_off()
        bx.set_title(f"from above at t = {human.times_s[peak]:.2f} s: shoulder line (thick),\npelvis line (grey), "
                     "forward to the right", fontsize=9)


# MuJoCo frames: each robot's body posed kinematically at the retargeted joint targets (no dynamics), seen from
# the front-left like the human above; both humanoids with the HRP2 arm targets (mocap.hrp2_arms).
# (robot, body to look at, camera distance [m])
FILMED = (("cla", "link3", 0.55), ("kenta", "link5", 0.75), ("hrp2", "chest", 2.4), ("hrp_rigid", "chest", 2.4))


def _bodies():
    from shintai.humanoid.robots.hrp2 import build_hrp2
    from shintai.spine.bodies_mujoco import SpineBody
    from shintai.spine.robots import CLA, KENTA

    return {"cla": SpineBody(CLA), "kenta": SpineBody(KENTA), "hrp2": build_hrp2(), "hrp_rigid": build_hrp2()}


def _pose(body, robot: str, targets, arms: dict[str, float]) -> None:
    if robot in mocap.SPINE_ROBOTS:
        body.set_theta(targets)
        return
    import mujoco

    body.reset("stand")
    for name, value in {"waist_yaw": targets[0], "waist_pitch": targets[1], **arms}.items():
        body.data.qpos[body.model.joint(name).qposadr[0]] = value
    mujoco.mj_forward(body.model, body.data)


def film(ctx, runs, video: bool) -> None:
    """``mujoco_peak.png``: the four robots at the peak twist; with ``video`` also ``video.mp4``, every frame (in the
    order of :data:`FILMED`: Cla, Kenta, HRP2, the rigid-trunk humanoid)."""
    import imageio

    from shintai.sim.render import make_camera, make_renderer

    human = runs["human"]
    bodies = _bodies()
    peak = int(np.argmax(np.abs(human.twist_deg)))
    frames = range(len(human.times_s)) if video else [peak]
    cams, renderers = {}, {}
    try:
        for robot, look, distance in FILMED:
            cams[robot] = make_camera(bodies[robot], distance=distance, azimuth=215.0, elevation=-12.0)
            renderers[robot] = make_renderer(bodies[robot].model, *TILE)
        writer = imageio.get_writer(ctx.video_path, format="FFMPEG", codec="libx264", macro_block_size=2,
                                    fps=1.0 / float(np.mean(np.diff(human.times_s)))) if video else None
        for f in frames:
            tiles = []
            for robot, look, _ in FILMED:
                body = bodies[robot]
                arms = runs.get("arms")
                _pose(body, robot, runs[robot].targets[f], {} if arms is None else
                      {name: float(v[f]) for name, v in arms.targets.items()})
                cams[robot].lookat[:] = body.data.xpos[body.id("body", look)]
                renderers[robot].update_scene(body.data, cams[robot])
                tiles.append(renderers[robot].render())
            if f == peak:
                _peak_picture(ctx, tiles, runs, peak)
            if writer is not None:
                writer.append_data(np.hstack(tiles))
        if writer is not None:
            writer.close()
    finally:
        for r in renderers.values():
            r.close()


def _peak_picture(ctx, tiles, runs, peak: int) -> None:
    with ctx.figure("mujoco_peak", 1, len(tiles), figsize=(3.0 * len(tiles), 4.3)) as (_fig, axes):
        for ax, image, (robot, _, _) in zip(axes, tiles, FILMED):
            ax.imshow(image)
            ax.set_axis_off()
            ax.set_title(f"{robot}: twist {round(float(runs[robot].twist_deg[peak])) + 0:d}° "
                         f"(human {round(float(runs['human'].twist_deg[peak])):d}°)", fontsize=9)
