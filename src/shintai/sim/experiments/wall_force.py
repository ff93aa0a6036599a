"""``sim.wall-force``: the online control index on a MuJoCo hand pressing into a wall corner (seed 000
§2.4.1, Eqs. 2.14, 3.17); the rig is :mod:`shintai.sim.corner`. Probe, pressing run and wrong-sign run
are three loops one after another: a compute experiment."""

from __future__ import annotations

import numpy as np

from shintai.core.runtime import is_multiple
from shintai.core.search_index import StabilityMonitor
from shintai.sim.plots import plot_wall_force
from shintai.scenarios.experiment import film
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.sim.corner import AXES, CONTROL_STEP, build_corner, passive_loop, press, probe_sign, shift_wall

@scenario(
    "sim.wall-force",
    source="seed 000 §2.4.1, Eqs. 2.14, 3.17",
    summary="MuJoCo hand in a wall corner: sign matrix probed = −E, force driven to target, escape when pushed",
    params=[
        Param("f_trg_x", -15.0, "target reaction from the x wall [N] (pressing: negative)", lo=-60.0, hi=-1.0),
        Param("f_trg_y", -15.0, "target reaction from the y wall [N]", lo=-60.0, hi=-1.0),
        Param("f_trg_z", 20.0, "target reaction from the floor [N] (pressing: positive)", lo=1.0, hi=60.0),
        Param("step_fraction", 0.5, "a·|∂f/∂ρ|: error fraction removed per update (monotone if < 1)", lo=0.01, hi=3.0),
        Param("update_s", 0.2, "time between updates [s] (the physics settles in between)", lo=0.02, hi=2.0),
        Param("updates", 20, "updates before, and again after, the wall moves", lo=2, hi=500),
        Param("wall_shift_m", 0.01, "how far the x wall moves toward the hand [m]", lo=0.0, hi=0.03),
    ],
    checks=[
        Check("sign_is_minus_identity", "==", 1, "thesis Eq. 3.17: sgn = −E, by probing (spec §5.4 check 2)", kind="consistency"),
        Check("final_force_error_n", "<=", 0.5, "derived: contraction 0.5 per update over 20 updates", kind="consistency"),
        Check("monotone_error", "==", 1, "thesis Eq. 2.22 with a·|∂f/∂ρ| < 1 (spec §2.5 [DERIVED])", kind="consistency"),
        Check("escape_force_error_n", "<=", 0.5, "spec §5.4 check 10: pushed, the passive limb returns to f_trg", kind="consistency"),
        Check("escape_reference_shift_m", "<=", -0.008, "spec §5.4 check 10: the reference retreats with the 10 mm wall", kind="consistency"),
        Check("escape_reference_shift_m", ">=", -0.012, "… by about the wall's 10 mm", name="escape_shift_bounded", kind="consistency"),
        Check("wrong_sign_error_grows", "==", 1, "spec §5.4 check 1: a wrong sign makes the error grow", kind="consistency"),
        Check("ft_vs_contact_max_n", "<=", 0.5, "the compensated wrist sensor agrees with the contact forces", kind="consistency"),
    ],
    thesis={"sgn_passive": ThesisValue("−E = diag(−1, −1, −1) (derived from the sign rule, §3.4.3)", "seed 000 Eq. 3.17",
                                       "sign_is_minus_identity")},
    demo=True,
    estimate_s=8.0,
    video=True,
    constraints=[(lambda p: is_multiple(p["update_s"], CONTROL_STEP),
                  f"update_s must be a whole multiple of the {1000 * CONTROL_STEP:g} ms control step")],
    smoke={"updates": 3},
)
def wall_force_scenario(ctx):
    p = ctx.params
    f_trg = np.array([p["f_trg_x"], p["f_trg_y"], p["f_trg_z"]])
    sgn, slope = probe_sign(settle_s=0.3)
    ctx.progress(0.2, "sign probed")
    errors, refs, f_ft, f_contact, t_end = press(
        sgn, slope, f_trg, p["step_fraction"], p["update_s"], p["updates"], p["wall_shift_m"], ctx.recorder)
    ctx.progress(0.7, "pressed")
    n = p["updates"]
    wrong, _, _, _, _ = press(-sgn, slope, f_trg, p["step_fraction"], p["update_s"], max(3, n // 4), 0.0)
    ctx.progress(0.9, "wrong sign")
    if ctx.video or ctx.view:
        _film(ctx, sgn, slope, f_trg)
    ctx.sim_time_s = float(t_end)
    monitor = StabilityMonitor(tol=1e-3)
    for e in errors[:n]:
        monitor.observe(error=e)
    plot_wall_force(ctx, errors, refs, f_trg, n)
    return {
        "sign_is_minus_identity": int(np.array_equal(sgn, -np.eye(3))),
        "probed_slope_n_per_m": slope.tolist(),
        "final_force_error_n": float(np.abs(errors[n - 1]).max()),
        "monotone_error": int(monitor.error_increases == 0),
        "escape_force_error_n": float(np.abs(errors[-1]).max()),
        "escape_reference_shift_m": float(refs[-1, 0] - refs[n - 1, 0]),
        "wrong_sign_error_grows": int(np.abs(wrong[-1]).max() > np.abs(wrong[0]).max()),
        "ft_vs_contact_max_n": float(np.abs(f_ft[n - 1:] - f_contact[n - 1:]).max()),
    }


def _film(ctx, sgn, slope, f_trg):
    """A shorter run of the same law, filmed (the numbers come from the unfilmed run)."""
    p = ctx.params
    body = build_corner()
    with film(ctx, body, fps=30, track="hand", distance=0.45, azimuth=225, elevation=-30):
        loop, _ = passive_loop(body, sgn, slope, f_trg, p["step_fraction"], p["update_s"])
        loop.run(2.0)
        shift_wall(body, -p["wall_shift_m"])
        loop.run(2.0)
