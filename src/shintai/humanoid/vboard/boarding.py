"""HRP2-JSK boards the V-BOARD, left foot first (seed 000 §5.4.1–5.4.2, Figs. 5.5–5.8).

§5.4.1: the robot's start on the floor and the scooter in front of it are known, and so is the first
footstep onto a board; the left foot steps first and becomes the support on its board while the right
foot reaches the other board; the right foot's target is relative to the landed left foot, so that it
reaches its board even if the scooter has moved meanwhile. The motion is planned offline by the
AutoBalancer (preview control of the ZMP, [84]) — here :class:`~shintai.humanoid.balance.standing.Standing` on
:func:`~shintai.humanoid.balance.standing.platform_steps`, the stack that boards a rigid box, stepping onto the
real scooter (:mod:`~shintai.humanoid.vboard.vehicle`) instead. The right foot's target being relative
to the left holds by construction: the stack's references are the robot's own (the legs' IK from the
waist), not the world's, so a scooter rolling under the left foot carries the whole plan with it.

Foot placement (chosen): the pads are 0.16 × 0.15 m and HRP2's sole 0.24 × 0.136 m, so a sole overhangs
its pad. The thesis's photos (Figs. 5.6–5.7, 6.1) show the feet across the boards' middles, each over its
wheel's axle; here each sole point (under the ankle, where the F/T sensor measures) lands on its pad's
centre, as :func:`~shintai.humanoid.vboard.stand.build_vboard_stand` stands the robot for ch. 6: the sole
overhangs 25 mm behind the pad and 55 mm ahead of it (the sole's centre is 15 mm ahead of the ankle), and
the ankle is over the axle, so the foot's pitch torque is what tilts the board.

Scene (chosen): the scooter's axle at ``BOARD_X`` = :data:`~shintai.humanoid.constants.BOARDING_STEP_X`
ahead of the standing soles, so the boarding is the box's step plan (0.30 m forward, 0.12 m up,
onto y = ±0.1175 m) — its housing's near edge 75 mm ahead of the toes. The unloaded halves rest level (no
drive: the contact switches are off); the left board's drive switches on when the left sole loads it.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.signal import find_peaks

from shintai.humanoid.balance.stabilizer import StabilizerModule
from shintai.humanoid.balance.standing import SoleStep, Standing, platform_steps, settle_on_floor, stand_geometry
from shintai.humanoid.constants import (
    BOARDING_CROUCH,
    BOARDING_STEP_X,
    DAMPING_T,
    DELTA_LIMIT,
    HRP2_LINKS,
    SCENE,
    STANDING_POSTURE,
    SUBSTEPS,
    VBOARD,
    VboardSpec,
)
from shintai.humanoid.learning.slc import SLC, SLCParams, SLCSchedule
from shintai.humanoid.robots.hrp2 import add_hrp2, side_posture
from shintai.humanoid.vboard.constants import BOARDING_ZMP_TRUNCATION, NOSLIP_ITERATIONS, PEAK_GAP_S, PEAK_SMOOTH_S
from shintai.humanoid.vboard.vehicle import BOARD, SIDES, add_vboard, install_firmware
from shintai.sim.body import MujocoBody
from shintai.sim.spec import fill_keyframe, scene_spec, set_joints

BOARD_X = BOARDING_STEP_X  # m, the scooter's axle ahead of the standing sole points (chosen, module docstring)


def boarding_body(x: float = BOARD_X, v: VboardSpec = VBOARD, substeps: int = SUBSTEPS) -> MujocoBody:
    """HRP2 standing on the floor (keyframe ``stand``, as :func:`~shintai.humanoid.robots.hrp2.build_hrp2`)
    with the V-BOARD's axle ``x`` ahead, its halves level and its drives off; ``body.firmware`` is the
    scooter's firmware (run before every physics step)."""
    spec = scene_spec("hrp2-vboard-boarding", *SCENE)
    spec.option.noslip_iterations = NOSLIP_ITERATIONS  # the soles do not creep on the pads (vboard.constants)
    add_vboard(spec, spec.worldbody, pos=(x, 0.0, 0.0), v=v)
    add_hrp2(spec, spec.worldbody, [0.0, 0.0, 1.0])
    spec.add_key(name="stand")
    model = spec.compile()
    qpos = model.qpos0.copy()
    posture = side_posture(STANDING_POSTURE)
    set_joints(model, qpos, posture)
    links = HRP2_LINKS
    hip, knee = posture["l_hip_pitch"], posture["l_knee_pitch"]
    leg = links.thigh * np.cos(hip) + links.shank * np.cos(hip + knee)
    root = model.joint("root").qposadr[0]
    qpos[root:root + 3] = [0.0, 0.0, -links.hip_z + leg + links.ankle_height]
    set_joints(model, qpos, {BOARD[s]: 0.0 for s in SIDES})  # unloaded halves hang level (vboard.py)
    fill_keyframe(model, "stand", qpos)
    body = MujocoBody(model, substeps=substeps, keyframe="stand", spec=spec)
    body.firmware = install_firmware(body, v)
    return body


def boarding_steps(soles: dict, x: float = BOARD_X, v: VboardSpec = VBOARD) -> list[SoleStep]:
    """§5.4.1's two footsteps: the left sole point onto the left pad's centre, then the right onto the
    right pad's (x ahead, on the deck's top, y = ±pad_y)."""
    return platform_steps(soles, x=x, height=v.deck_height, y=v.pad_y)


def boarding_stack(p: SLCParams, T: float = DAMPING_T, learn: bool = True, v: VboardSpec = VBOARD,
                   window: str | None = None, zmp_truncation: bool = BOARDING_ZMP_TRUNCATION) -> tuple[Standing, SLCSchedule]:
    """The boarding of §5.4.1 ready to run: :func:`boarding_body` settled on the floor, the
    :class:`~shintai.humanoid.balance.standing.Standing` stack on :func:`boarding_steps` (crouched by
    :data:`~shintai.humanoid.constants.BOARDING_CROUCH`), D₀ = ``p.D0`` and T on every axis of both feet (Table
    5.2; §5.4.1: the roll stays at D₀), and SLC in its slot after the foot damping — learning (``learn``) or only
    marking the same window (D = D₀ throughout: Fig. 5.6's run). ``humanoid.vboard-boarding`` runs it, and
    ``humanoid.speed-governing`` rides on after it (Fig. 6.16). ``window``: the channel whose state opens and
    closes SLC instead of its own landing guards (:mod:`~shintai.humanoid.vboard.solc` switches it, §7.4.2);
    ``zmp_truncation``: p_d bounded to the stance soles before the distributor (:data:`BOARDING_ZMP_TRUNCATION`)."""
    body = boarding_body(v=v)
    settle_on_floor(body)
    soles, _ = stand_geometry(body)
    sched = SLCSchedule(SLC(p), learn=learn, window=window)
    stabilizer = functools.partial(StabilizerModule, truncate=zmp_truncation)
    st = Standing(steps=boarding_steps(soles, v=v), body=body, crouch=BOARDING_CROUCH, D=p.D0, T=T, learner=sched,
                  stabilizer=stabilizer)
    return st, sched


def j_tau_peaks(t, J):
    """The two highest local maxima of J_τ (smoothed over PEAK_SMOOTH_S) at least PEAK_GAP_S apart, in time order."""
    if len(J) < 3:
        return []
    dt = float(np.median(np.diff(t)))
    n = max(1, round(PEAK_SMOOTH_S / dt))
    smooth = np.convolve(J, np.ones(n) / n, mode="same")
    idx, _ = find_peaks(smooth, distance=max(1, round(PEAK_GAP_S / dt)))
    top = sorted(sorted(idx, key=lambda i: -smooth[i])[:2])
    return [(float(t[i]), float(smooth[i])) for i in top]


def run_summary(run) -> dict:
    """What a ``humanoid.vboard-boarding`` run did (its recorded signals, its schedule ``run.state.sched``,
    its :class:`~shintai.humanoid.balance.standing.Standing` ``run.state.st``): the SLC window (left landing → right
    landing), D in and off it, |δ| and whether it reached the limit, J_τ's peaks in the window, the fall."""
    log, sched, st = run.log, run.state.sched, run.state.st
    t = log.times("J")
    t0 = sched.t_start
    t1 = sched.t_stop if sched.t_stop is not None else float(t[-1])
    window = (t >= t0) & (t <= t1) if t0 is not None else np.zeros_like(t, dtype=bool)
    delta = np.abs(log.values("delta"))
    D = log.values("D_L")
    fell = bool(st.fallen() or not np.all(np.isfinite(st.body.data.qpos)))
    peaks = j_tau_peaks(t[window] - t0, log.values("J")[window]) if window.any() else []
    before, after = (t < t0) if t0 is not None else np.ones_like(window), t > t1
    # D off the window: D₀ before it, the learned value held after it
    off = float(np.abs(D[before] - run.state.params.D0).max()) if before.any() else 0.0
    off += float(np.ptp(D[after])) if after.any() and t0 is not None else 0.0
    return {
        "fell": int(fell), "end_s": float(t[-1]), "t_left_landing_s": t0, "t_right_landing_s": sched.t_stop,
        "window_s": None if sched.duration is None else float(sched.duration),
        "fall_after_start_s": float(t[-1] - t0) if fell and t0 is not None else math.nan,
        "D_final": float(D[window][-1]) if window.any() else float(D[-1]), "D_R_final": float(log.values("D_R")[-1]),
        "D_roll_final": float(log.values("D_L_roll")[-1]),
        "D_changes_outside_window": off,
        "delta_max_window": float(delta[window].max()) if window.any() else math.nan,
        "delta_max": float(delta.max()), "delta_hit_limit": int(delta.max() >= DELTA_LIMIT - 1e-9),
        "delta_hit_limit_window": int(window.any() and delta[window].max() >= DELTA_LIMIT - 1e-9),
        "peaks": peaks, "board_l_min_deg": float(np.degrees(log.values("theta_l").min())),
        "scooter_travel_m": float(np.ptp(log.values("scooter_x"))),
        "unreachable": st.ik.unreachable,
        # the boards' contact switches (pad force > switch_force, vboard.py): the landings as the scooter sees them
        **{f"t_switch_{side}_s": (float(t[on[0]]) if len(on := np.flatnonzero(log.values(f"switch_{side}") > 0.5))
                                  else math.nan) for side in ("l", "r")},
    }
