"""``core.search-index``: the update rule of the online search index (seed 000 Eqs. 2.13–2.33) on a
scalar and a coupled 2×2 quasi-static plant x = G ρ + c, run in the shared Loop (spec 000-part1 §5.4
check 1). Several small plants, one after another: a compute experiment."""

from __future__ import annotations

import numpy as np

from shintai.core.linear_plant import LinearPlant, run_control_index, run_learning_index
from shintai.core.search_index import estimate_sign_matrix, is_decoupled
from shintai.core.plots import plot_search_index
from shintai.scenarios.registry import Check, Param, scenario

COUPLED_G = np.array([[-2.0, 0.4], [0.3, -1.5]])  # diagonally dominant, decreasing in its own ρ_i
COUPLED_C = np.array([5.0, 4.0])
COUPLED_XD = np.array([1.0, 2.0])


@scenario(
    "core.search-index",
    source="seed 000 §2.4–2.5 (Eqs. 2.13–2.33)",
    summary="online search index update rule: convergence, monotone steps, wrong sign diverges, J decreases",
    params=[
        Param("gain", 0.3, "A for the scalar plant (a·|g| < 1 is monotone, < 2 convergent)", lo=1e-3, hi=2.0),
        Param("plant_slope", -2.0, "g in x = g ρ + c (negative: force against position, Eq. 3.17)", lo=-10.0, hi=10.0),
        Param("steps", 60, "update steps", lo=5, hi=100000),
        Param("learning_rate", 0.05, "A for gain learning (Eq. 2.15)", lo=1e-4, hi=1.0),
    ],
    checks=[
        Check("final_error", "<=", 1e-6, "derived: per-step contraction 0.4 (scalar) and ≈0.67 (coupled, spectral radius) over 60 steps", kind="consistency"),
        Check("monotone_error", "==", 1, "thesis Eq. 2.22 holds for a|g| < 1 (spec §2.5 [DERIVED])", kind="consistency"),
        Check("monotone_step", "==", 1, "thesis Eq. 2.28: the increments of ρ shrink", kind="consistency"),
        Check("wrong_sign_diverges", "==", 1, "spec 000 §5.4 check 1: a wrong sign makes the error grow", kind="consistency"),
        Check("learning_monotone", "==", 1, "thesis Eq. 2.33: J(x_{k+1}) < J(x_k)", kind="consistency"),
        Check("sign_matrix_probed_ok", "==", 1, "thesis §2.4.1: sgn acquired by probing equals the declared one", kind="consistency"),
    ],
    demo=True,
    estimate_s=1.0,
    constraints=[(lambda p: p["plant_slope"] != 0, "plant_slope must be non-zero: x would not depend on ρ")],
    smoke={},
)
def search_index_scenario(ctx):
    p = ctx.params
    g, steps = p["plant_slope"], p["steps"]
    scalar = dict(G=[[g]], c=[5.0], x_d=np.array([1.0]), rho0=[0.0])
    sgn = estimate_sign_matrix(lambda r: LinearPlant(scalar["G"], scalar["c"], r).x, [np.zeros(1), np.ones(1)])
    e1, r1, m1 = run_control_index(**scalar, sgn=sgn, A=[[p["gain"]]], steps=steps)
    e_wrong, _, _ = run_control_index(**scalar, sgn=-sgn, A=[[p["gain"]]], steps=min(steps, 40))

    sgn2 = -np.eye(2)  # decoupled (Eq. 2.24): ρ_i corrected by x_i only, the cross terms are disturbances
    A2 = np.diag([0.25, 0.3])
    e2, r2, m2 = run_control_index(COUPLED_G, COUPLED_C, COUPLED_XD, np.zeros(2), sgn2, A2, steps)
    J, mj = run_learning_index(COUPLED_G, COUPLED_C, COUPLED_XD, np.zeros(2), np.diag([1.0, 2.0]),
                               p["learning_rate"], steps)
    probed2 = estimate_sign_matrix(lambda r: COUPLED_G @ r + COUPLED_C, [np.zeros(2), np.ones(2)])

    for k in range(steps):
        ctx.recorder.record(k, scalar_error=e1[k, 0], scalar_rho=r1[k, 0], coupled_error=e2[k],
                            coupled_rho=r2[k], cost=J[k])
    ctx.sim_time_s = float(steps)
    plot_search_index(ctx, e1, r1, e_wrong, e2, J, scalar)
    return {
        "final_error": float(max(abs(e1[-1, 0]), np.abs(e2[-1]).max())),
        "monotone_error": int(m1.error_increases == 0 and m2.error_increases == 0),
        "monotone_step": int(m1.increment_increases == 0 and m2.increment_increases == 0),
        "wrong_sign_diverges": int(abs(e_wrong[-1, 0]) > 10 * abs(e_wrong[0, 0])),
        "learning_monotone": int(mj.cost_increases == 0),
        "final_cost": float(J[-1]),
        "sign_matrix_probed_ok": int(np.array_equal(sgn, [[np.sign(g)]])),
        "coupled_sign_probed": probed2.tolist(),
        "coupled_decoupling_holds": int(is_decoupled(A2, sgn2)),
        "scalar_contraction": float(abs(1 - p["gain"] * abs(g))),
    }
