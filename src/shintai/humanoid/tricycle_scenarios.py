"""HRP2-JSK drives the tricycle in MuJoCo (seed 000 §3.5.1–3.5.3, E1, E2, E4).

The robot (:mod:`~shintai.humanoid.riding`) plugs into the operation algorithm of Fig. 3.16
(:mod:`~shintai.humanoid.operation`) through :class:`~shintai.humanoid.hrp2_limbs.Hrp2Limb`:
the active limb follows its plan from the tricycle's *nominal* kinematic model (Eq. 3.7 for a foot,
the grip at θ_h for a hand, §3.4.2) under the active impedance, the passive limb runs the passive
impedance (Eq. 3.13) and acquires its reference once per passive phase (Eq. 3.14), and the roles
swap when the angle measured from the robot's own FK (method (a), §3.4.4) passes a switching angle
(Eq. 3.19). Gains and force targets are Table 3.4's; Δθ_h = 5°, Δθ_c = 10°, Δt = 0.8 s (§3.5.1).

Model errors (the reason for the passive function, §3.3.2): the simulated tricycle differs from the
nominal model all the controllers use — the crank centre by ``crank_error_mm`` (E2/E4); for E1 the
grips sit ``grip_error_mm`` farther out from the steering axis (a handlebar half-width error, the
default), and optionally the steering axis is shifted (``handle_error_mm``) or inclined
(``rake_error_deg``). The same error is in the active/passive run and in the comparison run with
two active limbs, so the two configurations meet the same tricycle.

``time_scale`` multiplies Δt (1 = the thesis's 0.8 s); the defaults run the thesis's timing.
"""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import Loop
from shintai.humanoid import riding
from shintai.humanoid.riding import PEDAL
from scipy.stats import spearmanr

from shintai.humanoid.constants import (CONTROL_PERIOD, D_THETA_C, D_THETA_H, DEG, DELTA_C, DELTA_T, IMPEDANCE,
                                        PEDAL_FORCE_BAND, SWITCH_HYSTERESIS, TRICYCLE)
from shintai.humanoid.active import grip_plan
from shintai.humanoid.hrp2_limbs import riding_limbs
from shintai.humanoid.operation import SIDES, LimbPair, OperationSchedule, role_switcher, travel_distance
from shintai.humanoid.switching import (SwitchingDiagnostic, active_arm, active_leg, estimate_crank_angle,
                                        estimate_handle_angle)
from shintai.humanoid.vehicles.tricycle import crank_centre, pedal_position
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.sim.render import VideoRecorder

LEG_GAINS = {"active": IMPEDANCE["active_leg"], "passive": IMPEDANCE["passive_leg"]}
ARM_GAINS = {"active": IMPEDANCE["active_arm"], "passive": IMPEDANCE["passive_arm"]}
F_TRG = IMPEDANCE["passive_leg"].f_trg[2]  # 150 N (Table 3.4)
PEDAL_HALF_THICKNESS = TRICYCLE.pedal_size[2] / 2


# --- the limbs' plans and the measured angles (vehicle frame) -------------------------------------


def foot_plan(leg: str):
    """X_active^ref of a foot: Eq. 3.7's pedal point at the target crank angle, on the nominal crank
    circle (the sole on the level platform top, :func:`~shintai.humanoid.vehicles.tricycle.pedal_position`)."""
    return lambda theta_c: pedal_position(theta_c, leg[0])


def hand_plan(arm: str):
    """X_active^ref of a hand: its grip at the target θ_h on the nominal handle (§3.4.2)."""
    return lambda theta_h: grip_plan(theta_h, arm)


def pedal_axles(feet: dict, snapshot) -> dict:
    """Each foot's pedal-axle point: the sole point less the platform's half thickness along the
    sole normal (vehicle frame), so that method (a) sees points on the crank circle."""
    axles = {}
    for leg, limb in feet.items():
        site = getattr(limb, "_site_id", None)  # an Hrp2Limb's cached site id: read the data in place
        xmat = limb.body.site_xmat(limb.site) if site is None else limb.body.data.site_xmat[site].reshape(3, 3)
        normal = limb.frame.rotate_to_vehicle(xmat[:, 2])
        axles[leg] = limb.point(snapshot) - PEDAL_HALF_THICKNESS * normal
    return axles


def crank_diagnostic(feet: dict) -> SwitchingDiagnostic:
    """Fig. 3.14 for the legs: θ_c by method (a) from both feet about the nominal crank centre."""
    centre = crank_centre()  # the nominal model's (constant)
    return SwitchingDiagnostic(lambda s: estimate_crank_angle(pedal_axles(feet, s), centre),
                               lambda a: active_leg(a, DELTA_C), SWITCH_HYSTERESIS)


def handle_diagnostic(hands: dict) -> SwitchingDiagnostic:
    """Fig. 3.14 for the arms: θ_h by method (a) from both hands about the nominal steering axis."""
    return SwitchingDiagnostic(lambda s: estimate_handle_angle({k: h.point(s) for k, h in hands.items()}),
                               active_arm, SWITCH_HYSTERESIS)


# --- running ---------------------------------------------------------------------------------------


def drive(body, modules, seconds: float, log, progress=None) -> None:
    """Run ``modules`` on the body for ``seconds``, calling ``log(snapshot)`` every control tick."""
    loop = Loop(body, modules)
    n = int(round(seconds / body.dt))
    for k in range(n):
        log(loop.step())
        if progress is not None and k % 250 == 0:
            progress(k / n)


def video_of(ctx, body, **view):
    """The scenario's video recorder (``None`` unless ``--video``): a three-quarter view of the rider."""
    if not ctx.video:
        return None
    return VideoRecorder(body, ctx.video_path, fps=15, width=480, height=360, track="waist",
                         **{"distance": 2.6, "azimuth": 140.0, "elevation": -15.0, **view})


def crank_schedule(revolutions: float, dt_transition: float) -> OperationSchedule:
    """Fig. 3.16 samples turning the crank forward from θ_c = 0 by ``revolutions`` (handle straight)."""
    return OperationSchedule(0.0, 0.0, [(0.0, 2 * np.pi * revolutions)], dt_transition, D_THETA_H, D_THETA_C)


def pedal_run(rec, prefix: str, body, module, feet, schedule, active_of, diag=None, progress=None) -> None:
    """Pedal through ``schedule`` (plus one sample to settle), logging under ``prefix``: crank angle
    (true and estimated), each foot's f_z and f_x (vehicle frame) and whether it is active
    (``active_of(side)``)."""
    start = body.body_pos("tricycle")
    # ids, data views and the logged names, looked up once (the log runs every control tick)
    vehicle_xy = body.data.xpos[body.id("body", "tricycle")][:2]
    start_xy = start[:2]
    pedal_xpos = {side: body.data.site_xpos[body.id("site", PEDAL[side[0]])] for side in feet}
    keys = {k: f"{prefix}{k}" for k in ("crank_true", "crank_est", "travel")}
    side_keys = {side: tuple(f"{prefix}{k}_{side}" for k in ("fz", "fx", "active", "on_pedal")) for side in feet}
    centre = crank_centre()

    def log(snap):
        est = diag.angle if diag is not None and diag.angle is not None else estimate_crank_angle(
            pedal_axles(feet, snap), centre)
        travel = vehicle_xy - start_xy
        signals = {keys["crank_true"]: snap["q:crank"], keys["crank_est"]: est,
                   keys["travel"]: np.sqrt(travel.dot(travel))}  # = np.linalg.norm of the 2-vector
        for side, limb in feet.items():
            k_fz, k_fx, k_active, k_on = side_keys[side]
            force = limb.force(snap)
            signals[k_fz] = force[2]
            signals[k_fx] = force[0]  # along the crank tangent at the dead centres
            signals[k_active] = float(active_of(side))
            # evaluation only: where the sole sits on its pedal (the pedal's top site, vehicle frame)
            signals[k_on] = limb.point(snap) - limb.frame.to_vehicle(pedal_xpos[side])
        rec.record(snap["t"], **signals)

    drive(body, [module], schedule.duration + 2 * schedule.phase, log, progress)


def settled(t: np.ndarray, active: np.ndarray, wait: float) -> np.ndarray:
    """Ticks at least ``wait`` after the start and after the limb's last role change (transients)."""
    change = np.concatenate([[t[0]], t[1:][np.diff(active) != 0]])
    last = change[np.searchsorted(change, t, side="right") - 1]
    return (t - t[0] >= wait) & (t - last >= wait)


def force_errors(rec, prefix: str, wait: float, role: float) -> np.ndarray:
    """f_z of every foot while its role flag equals ``role`` (1 active, 0 passive), after transients."""
    t = rec.times(f"{prefix}fz_left")
    parts = []
    for side in SIDES:
        active = rec.values(f"{prefix}active_{side}")
        parts.append(rec.values(f"{prefix}fz_{side}")[settled(t, active, wait) & (active == role)])
    return np.concatenate(parts)


def unwrap_from(angle: np.ndarray, start: float) -> np.ndarray:
    return np.unwrap(angle) - np.unwrap(angle)[0] + start


# --- E2 + E4: pedalling ----------------------------------------------------------------------------


@scenario(
    "humanoid.tricycle-pedaling",
    source="seed 000 §3.5.2–3.5.3, Eqs. 3.7, 3.13–3.14, 3.19–3.20, Fig. 3.18, Fig. 3.22",
    summary="E2/E4: HRP2 pedals one crank revolution with active/passive legs (150 N), vs. two active legs",
    params=[
        Param("time_scale", 1.0, "Δt = 0.8 s × time_scale (1 = the thesis's lab setting)", lo=0.1, hi=1.0),
        Param("revolutions", 1.0, "crank revolutions of the active/passive run", lo=0.1, hi=2.0),
        Param("both_active_revolutions", 1.0, "crank revolutions of the both-active comparison run", lo=0.0, hi=2.0),
        Param("crank_error_mm", 10.0, "true crank centre ahead of the nominal model [mm] (spec §5.4 check 8)",
              lo=0.0, hi=30.0),
    ],
    checks=[
        Check("passive_force_mean_n", ">=", 0.9 * F_TRG, "spec §5.4 check 8 [PROPOSAL]: mean within −10 % of f^trg"),
        Check("passive_force_mean_n", "<=", 1.1 * F_TRG, "spec §5.4 check 8: within +10 %", name="passive_force_upper"),
        Check("passive_force_min_n", ">", 0.0, "thesis §3.5.3 (E4): the passive foot keeps contact with its pedal"),
        Check("both_active_force_rms_error_n", ">", "passive_force_rms_error_n",
              "thesis claim §3.5.3 / Fig. 3.22: two active legs track 150 N worse than the passive leg"),
        Check("active_force_cos_corr", ">=", 0.5,
              "thesis claim §3.5.3: the active leg's f_z grows roughly as 1/|cos θ_c| (threshold: ours, 'strong')"),
        Check("role_swaps", "==", "revolutions_x2", "thesis §3.5.2 / Eq. 3.19: two swaps per revolution"),
        Check("swap_angle_error_deg", "<=", 1.0,
              "Eq. 3.19 at 110°/290°; derived: hysteresis 0.5° plus method (a) error"),
        Check("revolution_time_ratio", ">=", 0.97, "thesis Eq. 3.20: T_2π = 2π · 2Δt / Δθ_c (−3 %)"),
        Check("revolution_time_ratio", "<=", 1.03, "Eq. 3.20 (+3 %); derived: the crank reaches its last target "
              "(within 1°) as the last sample's passive phase ends, up to a servo lag", name="revolution_time_upper"),
        Check("travel_per_rev_m", ">=", 0.98 * TRICYCLE.travel_per_rev, "thesis App. A.1.1: D_c = 2.45 m (−2 %)"),
        Check("travel_per_rev_m", "<=", 1.02 * TRICYCLE.travel_per_rev, "App. A.1.1 (+2 %)", name="travel_upper"),
    ],
    thesis={
        "revolution_time_s": ThesisValue(57.6, "seed 000 Eq. 3.20 (Δt = 0.8 s, Δθ_c = 10°)", "revolution_time_s"),
        "travel_per_rev_m": ThesisValue(2.45, "seed 000 App. A.1.1", "travel_per_rev_m"),
        "both_active_force_centre_n": ThesisValue(160.0, "seed 000 §3.5.3 (Fig. 3.22-(I), ≈160 N)",
                                                  "both_active_force_mean_n"),
        "passive_force_target_n": ThesisValue(150.0, "seed 000 Table 3.4, Fig. 3.22-(II)", "passive_force_mean_n"),
        "swap_angles_deg": ThesisValue([110.0, 290.0], "seed 000 Eq. 3.19, §3.5.2", "swap_angles_deg"),
    },
    demo=True,
    video=True,
)
def tricycle_pedaling(ctx):
    """E2 (one revolution, Fig. 3.18) and E4 (contact force, Fig. 3.22).

    Active/passive: the left leg starts active at θ_c = 0 and the roles swap at 110° and 290°
    (§3.5.2). Both-active comparison: the same samples with both feet on the nominal circle under
    the active impedance and no switching. Forces are compared after transients: from one command
    sample (2Δt) after the start and after each role swap.

    What happens (default run, crank centre 10 mm off): one revolution in 57.3 s (Eq. 3.20:
    57.6 s), swaps at 110.5° and 290.5° (estimated), 2.44 m travelled; the passive foot holds
    153 N mean, 7.2 N RMS error, against 13.5 N RMS with two active legs (Fig. 3.22's contrast
    reproduces). Root cause of the earlier failure (the passive foot lost its pedal at θ_c ≈ 200°):
    the soles' pitch was left free in the IK (line contact, Table 3.1), the DLS let it drift to
    ±30°, the free pedal tilted with the sole, and the vertical f^trg then had a 40 % component
    along the tilted pedal — the sole crept down it (MuJoCo's soft friction) until it fell off;
    the feet now stay level (``PEDAL_SOLE_PITCH`` in constants); the passive f_z stays above
    129 N and the soles move at most 22 mm on their pedals (the active one, under its x force).
    **Not reproduced**: the active foot's f_z does not grow as 1/|cos θ_c| (§3.5.3, Fig. 3.22-(II):
    it rises near TDC/BDC, "near the black switching lines", and approaches 150 N at the crank-
    horizontal instants 3, 30, 63 s; θ_c = 0 is the crank horizontal, :mod:`~shintai.humanoid.active`).
    Ours: Pearson correlation with 1/|cos θ_c| −0.08 (rank correlation −0.19); 160 N within 30° of
    the horizontal, 151 N within 30° of the dead centres — the opposite trend, with a dip to
    ≈145 N as the active pedal passes BDC. Checked against the thesis's measurement: f_z is the
    vertical component of the ankle F/T force (vehicle z = vertical here, as in §3.5.3), θ_c our
    role-table angle; taking every active tick, the swap transients included (the thesis plots the
    raw series), gives −0.08 too. Cause: the thesis explains its trend by a conjecture made in its
    own contact model — the foot acts on the pedal only along the pedal normal (Table 3.1 / §3.3.4:
    line contact, z unilateral, "sole–pedal static friction not considered"), so the tangential
    drive must come from a vertical force and f_z − 150 N ≈ (tangential demand)/|cos θ_c|. Our
    sole–pedal contact has friction (μ = 1), and the stiff active impedance (K = 3000 N/m, Table 3.4)
    tracks the crank tangent in x as well as z: near the dead centres it pushes the pedal along the
    tangent with |f_x| ≈ 12 N (``active_fx_dead_centre_n``; at most 20 % of f_z, inside the cone),
    where pressing alone would need f_z 23 N (30° off) to 67 N (10° off) above the passive foot's
    150 N. The model cannot drop that friction: the passive foot (f^trg_x = 0) follows its pedal
    round the circle only because friction displaces it (Eq. 3.14). Probes (one revolution, active/
    passive run): sole–pedal μ = 0.1 — the soles slide 62 mm, f_z reaches 220–230 N just after
    each swap (the active pedal 20–40° past TDC, the thesis's mechanism) but drops to ≈130 N
    through BDC, where Eq. 3.6's active range (δ_c to δ_c + π) runs the active pedal 20° past BDC
    and a vertical push opposes the crank (Table 3.1's model itself predicts f_z < 150 N there,
    not 1/|cos θ_c|): correlation −0.12 (rank −0.34); 8× the crank load (8 N m + 8 N m s/rad; our
    1 N m + 1 N m s/rad is not in the thesis, spec §6 item 14): 166 N near the horizontal, 150 N
    near the dead centres, |f_x| 15 N, −0.11. What does give Fig. 3.22-(II)'s shape here is a
    *vertical* model error: the true crank 10 mm higher than the nominal one (instead of 10 mm
    ahead) preloads the active foot radially at both dead centres (vertical part K·Δz·cos²φ, up
    to 30 N) — 176 N near them, 161 N near
    the horizontal — yet correlation only 0.11 (rank 0.47), because the ±20 N per-sample ripple
    (the impedance transient of each 10° step) and 1/|cos θ_c|'s pole (Pearson is dominated by the
    ticks within ~1° of the dead centres) swamp a 15 N trend; the error direction is not in the
    thesis (spec §5.4 check 8: "crank centre or radius ~1 cm"), so the scenario keeps its 10 mm
    forward error and the check fails. Run time ≈ 15–60 s (118 s simulated, both runs).
    """
    p = ctx.params
    dt = DELTA_T * p["time_scale"]
    error = (p["crank_error_mm"] / 1000, 0.0)
    schedule = crank_schedule(p["revolutions"], dt)
    body = riding.build_riding(crank_error=error)
    feet = riding_limbs(body, "foot")
    diag = crank_diagnostic(feet)
    legs = role_switcher("legs", "crank", feet, {leg: foot_plan(leg) for leg in SIDES}, diag,
                         active_leg(0.0, DELTA_C), schedule, LEG_GAINS, CONTROL_PERIOD,
                         {leg: limb.reachable for leg, limb in feet.items()})
    video = video_of(ctx, body)
    try:
        pedal_run(ctx.recorder, "", body, legs, feet, schedule, lambda s: legs.active == f"legs:{s}-active", diag,
                  lambda f: ctx.progress(0.6 * f, "active/passive"))
    finally:
        if video is not None:
            video.close()
    metrics = pedal_metrics(ctx.recorder, "", body, schedule, diag, dt)
    metrics["unreachable_ticks"] = sum(limb.unreachable for limb in feet.values())
    if p["both_active_revolutions"] > 0:
        metrics.update(both_active_run(ctx, p["both_active_revolutions"], dt, error))
    ctx.sim_time_s = float(ctx.recorder.times("crank_true")[-1] + ctx.recorder.times("both_crank_true")[-1]
                           if "both_crank_true" in ctx.recorder else ctx.recorder.times("crank_true")[-1])
    _plot_pedaling(ctx, diag)
    return metrics


def both_active_run(ctx, revolutions: float, dt: float, error) -> dict:
    """E4's only-active configuration: both feet follow Eq. 3.7 on the nominal crank, active impedance."""
    schedule = crank_schedule(revolutions, dt)
    body = riding.build_riding(crank_error=error)
    feet = riding_limbs(body, "foot")
    both = LimbPair("legs:both-active", "crank", feet, {leg: "active" for leg in SIDES},
                    {leg: foot_plan(leg) for leg in SIDES}, schedule, LEG_GAINS, CONTROL_PERIOD)
    pedal_run(ctx.recorder, "both_", body, both, feet, schedule, lambda s: True, None,
              lambda f: ctx.progress(0.6 + 0.35 * f, "both active"))
    fz = force_errors(ctx.recorder, "both_", 2 * dt, 1.0)
    return {"both_active_force_mean_n": float(fz.mean()),
            "both_active_force_rms_error_n": float(np.sqrt(np.mean((fz - F_TRG) ** 2))),
            "both_active_force_std_n": float(fz.std())}


def pedal_metrics(rec, prefix: str, body, schedule: OperationSchedule, diag, dt: float) -> dict:
    t = rec.times(f"{prefix}crank_true")
    true = rec.values(f"{prefix}crank_true")
    advance = true - true[0]
    goal = schedule.samples[-1].theta_c - schedule.theta_c0
    done = np.flatnonzero(advance >= goal - 1 * DEG)
    passive = force_errors(rec, prefix, 2 * dt, 0.0)
    active_fz, cos_term = active_samples(rec, prefix, 2 * dt)
    active_fx, _ = active_samples(rec, prefix, 2 * dt, "fx")
    swaps = np.mod([a for _, a, _ in diag.log], 2 * np.pi) / DEG
    expected = np.where(np.abs(swaps - 110) < np.abs(swaps - 290), 110.0, 290.0)
    travel = rec.values(f"{prefix}travel")[-1]
    slip = max(np.linalg.norm(rec.values(f"{prefix}on_pedal_{side}") - rec.values(f"{prefix}on_pedal_{side}")[0],
                              axis=1).max() for side in SIDES)
    horizontal = 1 / cos_term >= np.cos(PEDAL_FORCE_BAND)  # |cos θ_c|: near the crank horizontal
    dead = 1 / cos_term <= np.sin(PEDAL_FORCE_BAND)  # near TDC/BDC
    return {
        "passive_force_mean_n": float(passive.mean()),
        "passive_force_rms_error_n": float(np.sqrt(np.mean((passive - F_TRG) ** 2))),
        "passive_force_min_n": float(passive.min()),
        "max_sole_slip_mm": float(1000 * slip),
        "active_force_mean_n": float(active_fz.mean()),
        "active_force_cos_corr": float(np.corrcoef(active_fz, cos_term)[0, 1]),
        "active_force_horizontal_n": float(active_fz[horizontal].mean()) if horizontal.any() else float("nan"),
        "active_force_dead_centre_n": float(active_fz[dead].mean()) if dead.any() else float("nan"),
        # diagnostics of §3.5.3's claim (not checked): the rank correlation is blind to how far
        # 1/|cos θ_c| shoots up at the dead centres (Pearson's is dominated by the ticks within ~1°
        # of them); |f_x| near the dead centres is the tangential force the active foot gives the
        # pedal through friction there, and its ratio to f_z the friction coefficient that needs —
        # the force Table 3.1's contact model (sole–pedal static friction ignored) does not have.
        "active_force_cos_rank_corr": float(spearmanr(active_fz, cos_term)[0]),
        "active_fx_dead_centre_n": float(np.abs(active_fx[dead]).mean()) if dead.any() else float("nan"),
        "active_friction_use_dead_centre": float((np.abs(active_fx) / active_fz)[dead].max()) if dead.any()
        else float("nan"),
        "role_swaps": len(diag.log),
        "revolutions_x2": int(round(2 * goal / (2 * np.pi))),
        "swap_angles_deg": swaps.tolist(),
        "swap_angle_error_deg": float(np.abs(swaps - expected).max()) if len(swaps) else float("nan"),
        "crank_advance_deg": float(advance[-1] / DEG),
        "crank_estimate_error_deg": float(np.abs(unwrap_from(rec.values(f"{prefix}crank_est"), true[0])
                                                 - true).max() / DEG),
        "revolution_time_s": float(t[done[0]]) if done.size else float("nan"),
        "eq_3_20_time_s": goal / D_THETA_C * 2 * dt,
        "revolution_time_ratio": float(t[done[0]] / (goal / D_THETA_C * 2 * dt)) if done.size else float("nan"),
        "travel_m": float(travel),
        "travel_per_rev_m": float(travel / advance[-1] * 2 * np.pi),
        "travel_nominal_m": travel_distance(advance[-1], TRICYCLE.travel_per_rev),
    }


def active_samples(rec, prefix: str, wait: float, axis: str = "fz") -> tuple[np.ndarray, np.ndarray]:
    """The active foot's f_z (``axis="fx"``: f_x) after transients and 1/|cos θ_c| at the same ticks
    (true θ_c, §3.5.3)."""
    t = rec.times(f"{prefix}crank_true")
    inv_cos = 1 / np.maximum(np.abs(np.cos(rec.values(f"{prefix}crank_true"))), 1e-3)
    fz, term = [], []
    for side in SIDES:
        active = rec.values(f"{prefix}active_{side}")
        keep = settled(t, active, wait) & (active == 1.0)
        fz.append(rec.values(f"{prefix}{axis}_{side}")[keep])
        term.append(inv_cos[keep])
    return np.concatenate(fz), np.concatenate(term)


def _plot_pedaling(ctx, diag) -> None:
    """Fig. 3.22 (foot f_z against the 150 N target, active phases shaded) and the crank angle."""
    rec = ctx.recorder
    runs = [("", "active/passive (Fig. 3.22-(II))")]
    if "both_crank_true" in rec:
        runs.append(("both_", "both active, crank model off (Fig. 3.22-(I))"))
    with ctx.figure("foot_forces", len(runs) + 1, 1, figsize=(10, 3.2 * (len(runs) + 1)), sharex=True) as (fig, ax):
        for axis, (prefix, title) in zip(ax, runs):
            t = rec.times(f"{prefix}crank_true")
            for side, color in (("left", "C0"), ("right", "C3")):
                axis.plot(t, rec.values(f"{prefix}fz_{side}"), color=color, lw=0.8, label=f"{side} foot f_z")
                if prefix == "":
                    axis.fill_between(t, 0, 1, where=rec.values(f"active_{side}") > 0.5, color=color, alpha=0.08,
                                      transform=axis.get_xaxis_transform(), label=f"{side} leg active")
            axis.axhline(F_TRG, color="k", ls="--", lw=1, label="f^trg_z = 150 N")
            axis.set_ylabel("f_z from pedal [N]")
            axis.set_title(title, fontsize=9)
            axis.legend(fontsize=7, loc="upper right", ncol=3)
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


# --- E1: steering ----------------------------------------------------------------------------------


def hand_forces(hands: dict, snapshot) -> dict:
    """The two-hand grasp's forces (vehicle frame, N): ``internal`` ‖(f_L − f_R)/2‖, the classic
    internal force of a two-hand grasp; ``squeeze``, its part along the hand-to-hand line, positive
    when the hands press the handle together (the environment pushes each hand outward); ``net``
    ‖f_L + f_R‖, the force the hands put on the handle, which its bearing takes except for the part
    that turns it. f are the environment's forces on the hands (f^trg = 0 for both arms, Table 3.4)."""
    f_l, f_r = hands["left"].force(snapshot), hands["right"].force(snapshot)
    u = hands["left"].point(snapshot) - hands["right"].point(snapshot)
    half, net = (f_l - f_r) / 2, f_l + f_r
    # ‖x‖ as np.linalg.norm forms it for a vector (√(x·x)), without its dispatch
    return {"internal": float(np.sqrt(half.dot(half))), "squeeze": float(half @ u / np.sqrt(u.dot(u))),
            "net": float(np.sqrt(net.dot(net)))}


def steer_schedule(dt_transition: float, limit: float) -> OperationSchedule:
    """E1's command: θ_h from 0 to −limit, then to +limit, by Δθ_h (§3.5.2)."""
    return OperationSchedule(0.0, 0.0, [(-limit, 0.0), (limit, 0.0)], dt_transition, D_THETA_H, D_THETA_C)


def steer_run(rec, prefix: str, body, module, hands, schedule, active_of, diag=None, progress=None) -> None:
    """Steer through ``schedule`` (plus one sample to settle), logging under ``prefix``: handle angle
    (true and estimated), the squeeze between the hands, and which arm is active."""

    def log(snap):
        est = diag.angle if diag is not None and diag.angle is not None else estimate_handle_angle(
            {k: h.point(snap) for k, h in hands.items()})
        signals = {"handle_true": snap["q:handle"], "handle_est": est, **hand_forces(hands, snap)}
        signals.update({f"active_{side}": float(active_of(side)) for side in SIDES})
        signals.update({f"f_{side}": float(np.linalg.norm(hands[side].force(snap))) for side in SIDES})
        rec.record(snap["t"], **{f"{prefix}{k}": v for k, v in signals.items()})

    drive(body, [module], schedule.duration + 2 * schedule.phase, log, progress)


def sample_end_errors(rec, prefix: str, schedule: OperationSchedule) -> np.ndarray:
    """True θ_h minus the commanded θ_h at the end of each sample (after its passive phase)."""
    t, true = rec.times(f"{prefix}handle_true"), rec.values(f"{prefix}handle_true")
    ends = np.searchsorted(t, [s.t0 + 2 * schedule.phase - 1e-9 for s in schedule.samples])
    return true[np.minimum(ends, len(t) - 1)] - np.array([s.theta_h for s in schedule.samples])


@scenario(
    "humanoid.tricycle-steering",
    source="seed 000 §3.5.2, Eqs. 3.2, 3.13–3.14, 3.19, Fig. 3.17",
    summary="E1: HRP2 steers −25° → +25° with active/passive arms (swap at 0°), vs. two active arms",
    params=[
        Param("time_scale", 1.0, "Δt = 0.8 s × time_scale (1 = the thesis's lab setting)", lo=0.1, hi=1.0),
        Param("limit_deg", 25.0, "steering amplitude Θ_H [deg] (Table 3.4: 25°)", lo=5.0, hi=25.0),
        Param("grip_error_mm", 10.0, "true grips farther out from the steering axis than the nominal model, "
              "each side [mm] (handlebar half-width error; spec §5.4 check 9)", lo=-30.0, hi=30.0),
        Param("handle_error_mm", 0.0, "true steering axis ahead of the nominal model [mm]", lo=0.0, hi=30.0),
        Param("rake_error_deg", 0.0, "true steering axis inclined this much more than the nominal rake [deg]",
              lo=-5.0, hi=5.0),
        Param("grasp", "grip", "hand hold: grip (position + bar direction, turns about the bar), weld "
              "(6-DoF, Table 3.1), connect (point)", choices=("grip", "weld", "connect")),
        Param("both_active", 1, "also run the both-active comparison (1) or not (0)", choices=(0, 1)),
    ],
    checks=[
        Check("max_handle_error_deg", "<=", D_THETA_H / DEG,
              "spec §5.4 check 7: each commanded θ_h reached within one Δθ_h step (5°)"),
        Check("role_swaps", "==", 1, "thesis §3.5.2 / Eq. 3.19: one swap, at θ_h^init = 0"),
        Check("swap_angle_deg", "<=", 1.0, "Eq. 3.19 at 0°; derived: hysteresis 0.5° plus method (a) error"),
        Check("internal_force_rms_n", "<", "internal_force_both_active_rms_n",
              "thesis claim §3.3.2 (spec §5.4 check 9): the passive arm relieves the squeeze two active arms build"),
        Check("squeeze_rms_n", "<", "squeeze_both_active_rms_n",
              "spec §5.4 check 9: the squeeze along the hand-to-hand line (the internal force of a two-point "
              "grasp) is smaller with active/passive arms than with both active, on the same mismodelled handle"),
        Check("passive_hand_force_rms_n", "<", "hand_force_both_active_rms_n",
              "spec §5.4 check 9 ('near f^trg = 0'): the passive hand carries less force than a hand of the "
              "both-active pair (RMS of ‖f‖; the thesis gives no number)"),
    ],
    thesis={
        "steering_range_deg": ThesisValue([-25.0, 25.0], "seed 000 §3.5.2, Table 3.4", "handle_range_deg"),
        "switch_angle_deg": ThesisValue(0.0, "seed 000 Eq. 3.19 (θ_h^init = 0)", "swap_angle_deg"),
    },
    video=True,
)
def tricycle_steering(ctx):
    """E1 (Fig. 3.17): the left arm active from 0 to −25° and back, the right arm active after the
    measured handle passes 0°, up to +25° (§3.5.2). The comparison runs the same command with both
    arms active on the nominal grip plans. Forces are counted after the first sample (2Δt).

    The model error (default): the true grips 10 mm farther out from the steering axis than the
    nominal model, each side. Unlike a shifted steering axis (``handle_error_mm``: a rigid turn
    about any axis keeps the grips' distance, so two active arms on the nominal plans barely
    squeeze — 0.8 N RMS along the hand line with the grip grasp, 3 N with the weld) a wrong
    half-width makes the nominal grip plans 20 mm closer together than the true grips, which two
    position-controlled arms can only meet by squeezing. The grasp (default ``grip``, see
    ``GRIP_BAR_OFFSET``): the hand holds the round grip at two points on the bar, free to turn
    about it. The 6-DoF weld of Table 3.1 (``grasp=weld``) also locks that roll and turns the
    orientation mismatch between the IK's hand and the true handle into wrist loads that the
    position-only impedance cannot relieve: with it the active hand carries 45 N RMS instead of
    24 N, and the internal force is 22.2 N active/passive vs 30.6 N both active (22.5 vs 23.6 N
    with no model error at all, 23.4 vs 23.6 N with the axis 10 mm off — the earlier default).

    What happens (default run, 51 s simulated): the handle follows every 5° command within 1.6°
    (±25.9° reached), the roles swap once at +0.5°. The squeeze along the hand line is 9.2 N RMS
    with active/passive against 20.1 N with both arms active (internal ‖(f_L − f_R)/2‖ 11.2 vs
    20.8 N) and the passive hand carries 10.3 N RMS against 24.3 N per hand when both are active —
    spec §5.4 check 9 holds in direction and by about a factor of two, not to "near zero": the
    passive hand's ≈10 N is the same without any model error (10.3 N, measured), i.e. it is not
    the model error but the passive law's lag while the handle moves (16.8 N RMS during the active
    half of each sample, 5 N at its end, from the damping D_v = 500 N s/m of Table 3.4 on a grip
    moving ≈3 cm/s), and the active hand alone pushes the 10 mm error into the steering bearing
    (24 N), half of which the two-hand decomposition ‖(f_L − f_R)/2‖ counts as internal. With an
    error that keeps the grip distance the comparison reverses: axis 10 mm ahead
    (``handle_error_mm=10 grip_error_mm=0``) gives 9.7 N internal active/passive against 4.7 N both
    active, and no error at all 8.7 vs 5.4 N — there the passive arm's lag is the larger force.
    A steering axis inclined 2° more than the model (``rake_error_deg=2 grip_error_mm=0``) is worse
    for active/passive on every count: 21.3 vs 9.6 N internal, and the single active arm leaves the
    handle 7.0° from its command (check 7 fails), while two active arms hold 1.5° and push 110 N
    into the bearing. Smaller or opposite half-width errors keep the ordering (5 mm: squeeze 6.3 vs
    10.5 N; −10 mm: 7.0 vs 18.2 N).
    """
    p = ctx.params
    dt, limit = DELTA_T * p["time_scale"], p["limit_deg"] * DEG
    errors = {"handle_error": (p["handle_error_mm"] / 1000, 0.0, 0.0), "grip_error": p["grip_error_mm"] / 1000,
              "rake_error": p["rake_error_deg"] * DEG, "grasp": p["grasp"]}
    schedule = steer_schedule(dt, limit)
    body = riding.build_riding(**errors)
    hands = riding_limbs(body, "hand")
    diag = handle_diagnostic(hands)
    arms = role_switcher("arms", "handle", hands, {arm: hand_plan(arm) for arm in SIDES}, diag,
                         active_arm(0.0, heading=-1.0), schedule, ARM_GAINS, CONTROL_PERIOD,
                         {arm: limb.reachable for arm, limb in hands.items()})
    video = video_of(ctx, body, azimuth=160.0, elevation=-30.0, distance=2.0)
    try:
        steer_run(ctx.recorder, "", body, arms, hands, schedule, lambda s: arms.active == f"arms:{s}-active", diag,
                  lambda f: ctx.progress(0.6 * f, "active/passive"))
    finally:
        if video is not None:
            video.close()
    metrics = steer_metrics(ctx.recorder, "", schedule, dt)
    swaps = [a for _, a, _ in diag.log]
    metrics.update(role_swaps=len(swaps), swap_angle_deg=float(np.abs(swaps).max() / DEG) if swaps else float("nan"),
                   unreachable_ticks=sum(limb.unreachable for limb in hands.values()))
    if p["both_active"]:
        body = riding.build_riding(**errors)
        hands = riding_limbs(body, "hand")
        both = LimbPair("arms:both-active", "handle", hands, {arm: "active" for arm in SIDES},
                        {arm: hand_plan(arm) for arm in SIDES}, schedule, ARM_GAINS, CONTROL_PERIOD)
        steer_run(ctx.recorder, "both_", body, both, hands, schedule, lambda s: True, None,
                  lambda f: ctx.progress(0.6 + 0.35 * f, "both active"))
        both_metrics = steer_metrics(ctx.recorder, "both_", schedule, dt)
        metrics.update(internal_force_both_active_rms_n=both_metrics["internal_force_rms_n"],
                       squeeze_both_active_rms_n=both_metrics["squeeze_rms_n"],
                       net_force_both_active_rms_n=both_metrics["net_force_rms_n"],
                       max_handle_error_both_active_deg=both_metrics["max_handle_error_deg"],
                       hand_force_both_active_rms_n=both_metrics["active_hand_force_rms_n"])
    ctx.sim_time_s = float(sum(ctx.recorder.times(f"{pre}handle_true")[-1] for pre in ("", "both_")
                               if f"{pre}handle_true" in ctx.recorder))
    _plot_steering(ctx, schedule, diag)
    return metrics


def steer_metrics(rec, prefix: str, schedule: OperationSchedule, dt: float) -> dict:
    t = rec.times(f"{prefix}handle_true")
    late = t >= 2 * dt
    true = rec.values(f"{prefix}handle_true")

    def rms(name):
        return float(np.sqrt(np.mean(rec.values(f"{prefix}{name}")[late] ** 2)))

    passive = np.concatenate([rec.values(f"{prefix}f_{side}")[late & (rec.values(f"{prefix}active_{side}") == 0.0)]
                              for side in SIDES])
    active = np.concatenate([rec.values(f"{prefix}f_{side}")[late & (rec.values(f"{prefix}active_{side}") == 1.0)]
                             for side in SIDES])
    return {"max_handle_error_deg": float(np.abs(sample_end_errors(rec, prefix, schedule)).max() / DEG),
            "handle_range_deg": [float(true.min() / DEG), float(true.max() / DEG)],
            "internal_force_rms_n": rms("internal"), "squeeze_rms_n": rms("squeeze"), "net_force_rms_n": rms("net"),
            "passive_hand_force_rms_n": float(np.sqrt(np.mean(passive**2))) if passive.size else float("nan"),
            "active_hand_force_rms_n": float(np.sqrt(np.mean(active**2))) if active.size else float("nan")}


def _plot_steering(ctx, schedule: OperationSchedule, diag) -> None:
    """Handle angle (commanded, true, estimated) and the squeeze between the hands, both configurations."""
    rec = ctx.recorder
    with ctx.figure("steering", 2, 1, figsize=(10, 6.4), sharex=True) as (fig, ax):
        t = rec.times("handle_true")
        ax[0].step([s.t0 for s in schedule.samples], [s.theta_h / DEG for s in schedule.samples], where="post",
                   color="0.5", label="commanded θ_h (Δθ_h = 5°)")
        ax[0].plot(t, rec.values("handle_true") / DEG, label="true handle joint (evaluation only)")
        ax[0].plot(t, rec.values("handle_est") / DEG, "--", label="estimated from the hands (method (a))")
        if "both_handle_true" in rec:
            ax[0].plot(rec.times("both_handle_true"), rec.values("both_handle_true") / DEG, ":",
                       label="true, both arms active")
        ax[0].set_ylabel("θ_h [deg]")
        ax[1].plot(t, rec.values("internal"), color="C0", label="internal ‖(f_L − f_R)/2‖, active/passive")
        ax[1].plot(t, rec.values("squeeze"), color="C0", lw=0.7, ls="--", label="squeeze, active/passive")
        if "both_internal" in rec:
            tb = rec.times("both_internal")
            ax[1].plot(tb, rec.values("both_internal"), color="C1", label="internal, both active")
            ax[1].plot(tb, rec.values("both_squeeze"), color="C1", lw=0.7, ls="--", label="squeeze, both active")
        ax[1].axhline(0.0, color="k", lw=0.8, ls=":")
        ax[1].set_ylabel("force between the hands [N]")
        for axis in ax:
            axis.fill_between(t, 0, 1, where=rec.values("active_right") > 0.5, color="C3", alpha=0.08,
                              transform=axis.get_xaxis_transform(), label="right arm active")
            for ts, _, _ in diag.log:
                axis.axvline(ts, color="k", lw=0.8, ls=":")
            axis.legend(fontsize=7, loc="upper left")
        ax[1].set_xlabel("time [s] (dotted: role swap, Eq. 3.19)")
