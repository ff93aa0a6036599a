"""``quadruped.sensing-ablation``: the shipped fixed-order action network with its 12 obstacle features from
simulated ultrasonic sensors (seed 004 §3, eqs. 3-6 corrected, Figs. 7-8) instead of the known corners.
Batched rollouts of the crawl executor with a perception: a compute experiment."""

from __future__ import annotations

import numpy as np

from shintai.quadruped import ablation as A
from shintai.quadruped import constants as C
from shintai.quadruped import plots as PL
from shintai.quadruped import sensing as U
from shintai.quadruped import training as T
from shintai.quadruped import world as W
from shintai.quadruped.walks import WEIGHTS, outcome_rates, record_walk, weights_path
from shintai.scenarios.registry import Check, Param, ThesisValue, scenario

@scenario(
    "quadruped.sensing-ablation",
    source="seed 004 §3.1–3.3, eqs. 3–6 (spec §1.4, §2.2)",
    summary="the shipped fixed-order action network with its 12 obstacle features from simulated ultrasonic "
            "sensors (eqs. 3-6 corrected, Figs. 7-8) instead of the known corners",
    params=[Param("noise_std", 0.0, "Gaussian range noise of every reading [m] (seeded by --seed)", lo=0.0, hi=0.5),
            Param("incidence_deg", C.INCIDENCE_LIMIT_DEG, "largest angle of incidence that still echoes [deg] "
                  "(not in the paper: 'nearly perpendicular')", lo=0.0, hi=90.0),
            Param("environments", 96, "training environments walked (evenly spaced over the 96)", lo=1, hi=96),
            WEIGHTS],
    checks=(
        Check("known_success_rate", ">=", 0.9,
              "consistency: the GA optimised eq. (9) on these environments with known features (as generalization)",
              kind="consistency"),
        Check("sensed_box_excess_m", "<=", "sensed_box_bound_m",
              "model: every echo point lies on its leg's side's obstacle boundary, so the sensed bounding box lies "
              "inside the true one (noise 0: 1e-6 m; with range noise σ: 1e-6 + 6σ)", name="sensed_box_inside_true",
              kind="consistency"),
        Check("feature_error_z_max_m", "<=", C.HEIGHT_STEP,
              "model (Fig. 8): raising the beam in HEIGHT_STEP steps overestimates a climbable top by less than one "
              "step; an obstacle still echoing at the top of the raise is a wall", kind="consistency"),
        Check("detected_fraction", "==", 1.0,
              "thesis §3.3 (Fig. 12), §4.3 (Fig. 24): the forward and side sensors measure an edge of each obstacle "
              "in front ('障害物の一辺を計測していることが確認できる')", kind="reproduction"),
    ),
    covers=("004:fig12",),
    stochastic=True,
    thesis={
        "sensed_success_rate": ThesisValue(
            "one real-robot walk with its ultrasonic sensors reached the goal (9 cycles, (0.137, 0.075) m); no rate",
            "seed 004 §4.3", "sensed_success_rate"),
        "s421_known_final_error_m": ThesisValue(0.059, "seed 004 §4.2.1 (known obstacles)",
                                                "s421_known_final_error_m"),
        "s422_known_final_error_m": ThesisValue(0.054, "seed 004 §4.2.2 (known obstacles)",
                                                "s422_known_final_error_m")},
    smoke={"environments": 6},
)
def sensing_ablation(ctx) -> dict:
    p = ctx.params
    genome = T.load_action(weights_path(p["weights"]))
    envs = T.training_envs(p["environments"])

    def perception(noise=p["noise_std"], incidence=p["incidence_deg"]) -> U.SensedObstacles:
        return U.SensedObstacles(noise, incidence, seed=ctx.seed)

    known = A.sensed_walks(genome, envs, None)
    sense = perception()
    sensed = A.sensed_walks(genome, envs, sense)
    ctx.progress(0.2, "training environments")
    rates = {"known": outcome_rates(known), "sensed": outcome_rates(sensed)}
    metrics = {f"{name}_{k}": v for name, r in rates.items() for k, v in r.items()}
    features = A.feature_metrics(sense)
    ctx.extra["per_feature_error_m"] = features.pop("per_feature_error_m")
    metrics.update(features)
    metrics["sensed_box_bound_m"] = 1e-6 + 6 * p["noise_std"]
    names = [e.name for e in W.training_set()]
    picked = np.linspace(0, 95, p["environments"]).round().astype(int)
    ctx.extra["environments"] = [
        {"name": names[i], "known_reached": bool(a), "sensed_reached": bool(b), "known_cycles": int(c),
         "sensed_cycles": int(d)} for i, a, b, c, d in zip(picked, T.success(known), T.success(sensed), known.cycles,
                                                           sensed.cycles)]
    walks = {}
    for key, env in (("s421", W.scenario_421()), ("s422", W.scenario_422())):
        batch = W.EnvBatch.of([env])
        q = perception()
        ep = A.sensed_walks(genome, batch, q, record=True)
        base = A.sensed_walks(genome, batch, None)
        metrics.update({f"{key}_sensed_reached": int(T.success(ep)[0]),
                        f"{key}_sensed_final_error_m": float(np.hypot(*ep.final_error[0])),
                        f"{key}_sensed_cycles": int(ep.cycles[0]),
                        f"{key}_known_reached": int(T.success(base)[0]),
                        f"{key}_known_final_error_m": float(np.hypot(*base.final_error[0])),
                        f"{key}_known_cycles": int(base.cycles[0])})
        ctx.extra[f"{key}_features"] = {"known": q.known[0], "sensed": q.sensed[0]}
        record_walk(ctx, f"{key}.", ep.records[0])
        outcome = "reached" if T.success(ep)[0] else "failed"
        walks[f"{env.name}, sensed features: {outcome} in {ep.cycles[0]} cycles"] = (env, ep.records[0], q)
        if key == "s421":
            PL.plot_features(ctx, env, q)
    ctx.progress(0.4, "§4.2 walks")
    noise_curve = [(s, float(T.success(A.sensed_walks(genome, envs, perception(noise=s))).mean())) for s in C.NOISE_SWEEP]
    ctx.progress(0.7, "noise sweep")
    incidence_curve = [(a, float(T.success(A.sensed_walks(genome, envs, perception(incidence=a))).mean()))
                       for a in C.INCIDENCE_SWEEP]
    blind = outcome_rates(A.sensed_walks(genome, envs, perception(incidence=0.0)))
    metrics["blind_success_rate"], metrics["blind_collision_rate"] = blind["success_rate"], blind["collision_rate"]
    rates["blind"] = blind
    ctx.extra["success_vs_noise"] = noise_curve
    ctx.extra["success_vs_incidence"] = incidence_curve
    PL.plot_sensed_walks(ctx, walks)
    PL.plot_success(ctx, rates, noise_curve, incidence_curve, p)
    return metrics
