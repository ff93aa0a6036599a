"""Benchmark: muscle length → posture on Cla, the NN query against Jacobian integration (§4.4.3).

Both answer the same question for the same lengths (the thesis compares their errors and their
time: Jacobian integration took 19–2100 s per posture, Table 4.2). The network is trained once
(8-40-15, L-BFGS, seeded); its training time is reported separately.
"""

from __future__ import annotations

import time

import numpy as np

from shintai.scenarios.registry import benchmark
from shintai.spine import inverse_model
from shintai.spine.robots import CLA


@benchmark("spine.inverse-query", "Cla q → θ: NN 8-40-15 query vs Jacobian integration (4.26–4.28), same 20 postures")
def inverse_query() -> dict:
    model = CLA.model
    rng = np.random.default_rng(0)
    theta = inverse_model.random_postures(model.n, 20, rng)
    q = model.lengths(theta)
    t0 = time.perf_counter()
    nn = inverse_model.NeuralInverse(model, (40,), np.random.default_rng(1))
    nn.fit(iterations=1000, record_every=100)
    train_s = time.perf_counter() - t0
    repeat = 50
    t0 = time.perf_counter()
    for _ in range(repeat):
        for qk in q:
            nn.posture(qk)
    nn_s = (time.perf_counter() - t0) / (repeat * len(q))
    runs = [inverse_model.jacobian_integration(model, qk) for qk in q]
    jac_s = float(np.mean([r.seconds for r in runs]))
    return {
        "nn_query_us": 1e6 * nn_s,
        "jacobian_query_ms": 1e3 * jac_s,
        "jacobian_over_nn": jac_s / nn_s,
        "jacobian_divisions_mean": float(np.mean([r.divisions for r in runs])),
        "nn_train_s": train_s,
        "nn_error_norm_deg": float(inverse_model.error_norm_deg(nn.posture(q), theta).mean()),
        "jacobian_error_norm_deg": float(inverse_model.error_norm_deg(np.array([r.theta for r in runs]), theta).mean()),
    }
