"""``spine.inverse-model``: muscle lengths → posture on Cla (seed 003 §4.4.3, Tables 4.2–4.3): the NNs
8-40-15 and 8-10-10-15 against Jacobian integration (4.26–4.28). Training and integration, no body
and no loop: a compute experiment."""

from __future__ import annotations

import time

import numpy as np

from shintai.scenarios.registry import Check, Param, ThesisValue, scenario
from shintai.spine import inverse_model
from shintai.spine.plots import plot_inverse_errors, plot_learning_curves
from shintai.spine.robots import CLA, PINV_RCOND, TABLE_4_2_DEG

TABLE_4_2_AXES = ("φ", "θ", "ψ")


def timed(fn, *args, **kwargs):
    t0 = time.perf_counter()
    out = fn(*args, **kwargs)
    return out, time.perf_counter() - t0


def nn_query_us(inverse: inverse_model.NeuralInverse, q: np.ndarray, repeat: int = 200) -> float:
    """Mean wall time of one q → θ query (one length vector) [µs]."""
    t0 = time.perf_counter()
    for k in range(repeat):
        inverse.posture(q[k % len(q)])
    return 1e6 * (time.perf_counter() - t0) / repeat


def jacobian_runs(model, theta: np.ndarray, rcond, progress=None) -> list[inverse_model.JacobianIntegration]:
    """Jacobian integration (4.26–4.28) from the straight posture for each posture's lengths."""
    runs = []
    for k, th in enumerate(theta):
        runs.append(inverse_model.jacobian_integration(model, model.lengths(th), rcond=rcond))
        if progress is not None:
            progress((k + 1) / len(theta))
    return runs


def table_4_2(model) -> list[dict]:
    """Table 4.2 analogue: one axis at 1, 5, 10°/joint, n₀ = int|Δq| [mm], 2n₀ and 4n₀ divisions."""
    rows = []
    for deg in TABLE_4_2_DEG:
        for axis, name in enumerate(TABLE_4_2_AXES):
            per_joint = np.zeros(3)
            per_joint[axis] = np.radians(deg)
            truth = inverse_model.uniform_bend(per_joint, model.n)
            q = model.lengths(truth)
            n0 = inverse_model.default_divisions(q, model.lengths(np.zeros_like(truth)))
            for n in (n0, 2 * n0, 4 * n0):
                run = inverse_model.jacobian_integration(model, q, divisions=n)
                err = np.degrees(run.theta - truth).reshape(-1, 3)
                rows.append({"true": f"{name}={deg:g}", "divisions": n, "seconds": run.seconds,
                             "mean_deg": np.degrees(run.theta.reshape(-1, 3).mean(axis=0)).round(3).tolist(),
                             "mean_abs_error_deg": np.abs(err).mean(axis=0).round(3).tolist(),
                             "max_abs_error_deg": np.abs(err).max(axis=0).round(3).tolist(),
                             "error_norm_deg": float(inverse_model.error_norm_deg(run.theta, truth)),
                             "length_residual_mm": 1e3 * run.length_residual_m})
    return rows


@scenario(
    "spine.inverse-model",
    source="seed 003 §4.4.3, Tables 4.2–4.3",
    covers=("003:table4.2", "003:table4.3"),
    summary="muscle lengths → posture on Cla: NN 8-40-15 and 8-10-10-15 vs Jacobian integration (4.26–4.28)",
    params=(
        Param("trainer", "lbfgs", "lbfgs: scipy L-BFGS on the back-propagated loss; backprop: plain eq. 4.30",
              choices=("lbfgs", "backprop")),
        Param("iterations", 2000, "L-BFGS iterations or back-propagation epochs", lo=10, hi=200000),
        Param("eta", 10.0, "back-propagation gain η (trainer=backprop)", lo=1e-3, hi=100.0),
        Param("hidden", 40, "hidden units of the 3-layer network (thesis: 40 chosen of 12–100)", lo=2, hi=200),
        Param("test_postures", 50, "random uniform-bend test postures (thesis: 50)", lo=5, hi=500),
    ),
    checks=(
        Check("nn_test_error_norm_deg", "<=", 2.5,
              "thesis §4.4.3 Table 4.3: 8-40-15 mean error norm 1.95° on 50 random postures (8-10-10-15: 2.51°)", kind="reproduction", row="003:table4.3"),
        Check("nn_train_max_joint_error_deg", "<=", 0.5,
              "thesis §4.4.3: max joint error on uniform-bend inputs 'less than about 0.5°' (8-40-15)", kind="reproduction", row="003:table4.3"),
        Check("jacobian_test_error_norm_deg", ">", "nn_test_error_norm_deg",
              "thesis §4.4.3: Jacobian integration errors are larger than the NN's", name="jacobian_worse_than_nn", kind="reproduction", row="003:table4.2"),
        Check("jacobian_to_nn_time_ratio", ">", 100.0,
              "thesis §4.4.3: Jacobian integration takes 'very large' time (19–2100 s) — two orders over a query", kind="consistency"),
    ),
    thesis={
        "nn_test_error_norm": ThesisValue(1.95, "§4.4.3 Table 4.3 (8-40-15, 50 random inputs)",
                                          "nn_test_error_norm_deg"),
        "nn4_test_error_norm": ThesisValue(2.51, "§4.4.3 Table 4.3 (8-10-10-15)", "nn4_test_error_norm_deg"),
        "nn_min_train_error_norm": ThesisValue(1.26, "§4.4.3 Table 4.3 (8-40-15)", "nn_train_error_norm_deg"),
        "nn4_min_train_error_norm": ThesisValue(1.12, "§4.4.3 Table 4.3 (8-10-10-15)", "nn4_train_error_norm_deg"),
        "nn_max_joint_error": ThesisValue("< about 0.5°", "§4.4.3", "nn_train_max_joint_error_deg"),
        "jacobian_errors": ThesisValue("tens to hundreds of degrees per joint (up to ±360°)", "§4.4.3 Table 4.2",
                                       "jacobian_test_error_norm_deg"),
        "jacobian_time": ThesisValue("19–2100 s per posture", "§4.4.3 Table 4.2", "jacobian_query_s"),
    },
    smoke={"iterations": 300, "test_postures": 10},
)
def inverse_model_scenario(ctx) -> dict:
    p, model = ctx.params, CLA.model
    test = inverse_model.random_postures(model.n, p["test_postures"], ctx.rng)
    nets, fit_s = {}, {}
    for k, hidden in enumerate(((p["hidden"],), (10, 10))):
        inv = inverse_model.NeuralInverse(model, hidden, np.random.default_rng(ctx.rng.integers(2**32)))
        _, fit_s[inv.net.name] = timed(inv.fit, p["trainer"], p["iterations"], p["eta"], test_theta=test)
        nets[inv.net.name] = inv
        ctx.progress(0.3 * (k + 1), f"trained {inv.net.name}")
    nn, nn4 = nets.values()
    jac = jacobian_runs(model, test, PINV_RCOND, lambda f: ctx.progress(0.6 + 0.15 * f, "Jacobian"))
    raw = jacobian_runs(model, test, None, lambda f: ctx.progress(0.75 + 0.15 * f, "Jacobian, raw pinv"))
    table = table_4_2(model)
    ctx.progress(1.0, "Table 4.2")
    ctx.extra["table_4_2"] = table
    jac_err = inverse_model.error_norm_deg(np.array([r.theta for r in jac]), test)
    raw_err = inverse_model.error_norm_deg(np.array([r.theta for r in raw]), test)
    errors = {f"NN {name}": inv.errors_deg(test) for name, inv in nets.items()}
    errors |= {"Jacobian integration (rank threshold)": jac_err, "Jacobian integration (raw pinv)": raw_err}
    plot_learning_curves(ctx, nets)
    plot_inverse_errors(ctx, errors, table)
    query_us = nn_query_us(nn, model.lengths(test))
    jac_s = float(np.mean([r.seconds for r in jac]))
    return {
        "nn_train_error_norm_deg": nn.curve.best_train_deg,
        "nn4_train_error_norm_deg": nn4.curve.best_train_deg,
        "nn_train_max_joint_error_deg": nn.training_max_joint_error_deg(),
        "nn4_train_max_joint_error_deg": nn4.training_max_joint_error_deg(),
        "nn_test_error_norm_deg": float(nn.errors_deg(test).mean()),
        "nn4_test_error_norm_deg": float(nn4.errors_deg(test).mean()),
        "nn_fit_s": fit_s[nn.net.name],
        "nn4_fit_s": fit_s[nn4.net.name],
        "jacobian_test_error_norm_deg": float(jac_err.mean()),
        "jacobian_test_error_norm_max_deg": float(jac_err.max()),
        "jacobian_test_length_residual_mm": 1e3 * float(np.mean([r.length_residual_m for r in jac])),
        "jacobian_raw_test_error_norm_deg": float(raw_err.mean()),
        "jacobian_divisions_mean": float(np.mean([r.divisions for r in jac])),
        "jm_rank": int(np.linalg.matrix_rank(model.jacobian(test[0]), tol=1e-9)),
        "nn_query_us": query_us,
        "jacobian_query_s": jac_s,
        "jacobian_to_nn_time_ratio": jac_s / (1e-6 * query_us),
    }
