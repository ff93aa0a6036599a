"""The spine's benchmarks.

* ``spine.kenta-control-tick``: one L/T/S/LL control tick for all 40 of Kenta's muscles against the
  ~1 ms period (§3.6.1, §4.7.3: "the control period is 1 ms"; §4.6.5: one routine per mode), compared
  with the naive form of the same computation — a Python loop calling the per-mode law for each muscle.
* ``spine.inverse-query``: muscle length → posture on Cla, the NN query against Jacobian integration
  (§4.4.3). Both answer the same question for the same lengths (the thesis compares their errors and
  their time: Jacobian integration took 19–2100 s per posture, Table 4.2). The network is trained once
  (8-40-15, L-BFGS, seeded); its training time is reported separately.
* ``spine.ga-throughput``: one SQ43 trot individual against the thesis's 30 min, and a generation per executor.
* ``spine.control-modes-tick``: ``spine.control-modes``' rig through the Loop against bare ``mj_step`` for the
  same physics steps, on the hardening and on the linear disc, and the disc law's cost per call.
"""

from __future__ import annotations

import time

import numpy as np

from shintai.scenarios.registry import benchmark
from shintai.spine import inverse_model
from shintai.spine.control import Gains, Mode, MuscleControl, law_L, law_LL, law_S, law_T
from shintai.spine.robots import CLA, KENTA


def _inputs(rng, m: int) -> tuple[np.ndarray, np.ndarray]:
    return rng.normal(0.0, 1e-3, m), np.abs(rng.normal(10.0, 3.0, m))


def naive_tick(control: MuscleControl, l, T, dt: float) -> np.ndarray:
    """The same tick muscle by muscle, as a per-muscle firmware routine would run (reference)."""
    g, s = control.gains, control.state
    out = np.zeros(control.m)
    for j in range(control.m):
        dl = (l[j] - s.l_prev[j]) / dt
        dT = (T[j] - s.T_prev[j]) / dt
        mode = s.mode[j]
        if mode == Mode.L or (mode == Mode.LL and T[j] < g.T_l):
            s.integral[j] += (l[j] - control.l_r[j]) * dt
        if mode == Mode.L:
            out[j] = law_L(l[j], control.l_r[j], s.integral[j], dl, g)
        elif mode == Mode.T:
            out[j] = law_T(T[j], control.T_r[j], dT, g)
        elif mode == Mode.S:
            out[j] = law_S(T[j], l[j], control.l_0[j], dT, g)
        else:
            out[j] = law_LL(l[j], control.l_r[j], s.integral[j], dl, T[j], g)
    s.l_prev, s.T_prev = l, T
    return np.clip(out, -1.0, 1.0)


@benchmark("spine.kenta-control-tick", "one L/T/S/LL tick for Kenta's 40 muscles vs the 1 ms control period")
def kenta_control_tick(ticks: int = 20000) -> dict:
    rng = np.random.default_rng(0)
    m = KENTA.m
    period = KENTA.control_period_s
    results = {}
    for name, tick in (("vectorised", lambda c, l, T: c.duty(l, T, period)),
                       ("naive", lambda c, l, T: naive_tick(c, l, T, period))):
        control = MuscleControl(m, Gains(k_s=3000.0), period=period)
        control.set_modes(np.arange(m) % 4)  # 10 muscles in each of L, T, S, LL
        l, T = _inputs(rng, m)
        control.reset({"encoder": l, "tension": T})
        samples = [_inputs(rng, m) for _ in range(64)]
        n = ticks if name == "vectorised" else ticks // 10
        for k in range(200):  # warm-up
            tick(control, *samples[k % 64])
        t0 = time.perf_counter()
        for k in range(n):
            tick(control, *samples[k % 64])
        results[name] = (time.perf_counter() - t0) / n
    return {
        "muscles": m,
        "us_per_tick": 1e6 * results["vectorised"],
        "fraction_of_period": results["vectorised"] / period,
        "naive_us_per_tick": 1e6 * results["naive"],
        "speedup_vs_naive": results["naive"] / results["vectorised"],
        "period_ms": 1e3 * period,
    }


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


@benchmark("spine.ga-throughput", "SQ43 trot GA: one individual's evaluation vs the thesis's 30 min, one generation "
           "serial / process pool / Ray")
def ga_throughput(population: int = 20, repeats: int = 3) -> dict:
    """One SQ43 trot individual (6 s of walking, ``mujoco.rollout``) against §5.6.2's '1 個体の数秒間の運動の解析に
    約 30 分程度', and one generation of ``population`` individuals on each executor (pools started before
    timing: the per-generation cost, not the start-up)."""
    from shintai.evolve import make_executor
    from shintai.spine.sq43.constants import GENE_HI, GENE_LO
    from shintai.spine.sq43.gaits import TrotFitness

    fitness = TrotFitness()
    rng = np.random.default_rng(0)
    genomes = list(GENE_LO + rng.random((population, GENE_LO.size)) * (GENE_HI - GENE_LO))
    fitness(genomes[0])  # warm-up: model build
    t0 = time.perf_counter()
    for k in range(repeats):
        fitness(genomes[k % population])
    one = (time.perf_counter() - t0) / repeats
    out = {"seconds_per_individual": one, "speedup_vs_thesis_30min": 1800.0 / one, "population": population}
    reference = None
    for kind in ("serial", "process", "ray"):
        try:
            with make_executor(kind) as executor:
                executor.map(fitness, genomes[:2])  # workers up and warm
                t0 = time.perf_counter()
                values = executor.map(fitness, genomes)
                out[f"generation_{kind}_s"] = time.perf_counter() - t0
        except Exception as exc:  # Ray may be absent on a machine: report, do not fail the others
            out[f"generation_{kind}_error"] = f"{type(exc).__name__}: {exc}"[:200]
            continue
        reference = values if reference is None else reference
        out[f"generation_{kind}_identical"] = int(np.array_equal(values, reference))
    for kind in ("process", "ray"):
        if f"generation_{kind}_s" in out:
            out[f"speedup_{kind}_over_serial"] = out["generation_serial_s"] / out[f"generation_{kind}_s"]
    return out


@benchmark("spine.control-modes-tick", "Cla's control-modes rig (all-L, pitch, hardening discs, column wrap): its "
           "1 ms tick against bare mj_step for the same physics steps, and the disc law's share")
def control_modes_tick(seconds: float = 3.0) -> dict:
    """The rig of ``spine.control-modes`` (defaults: hardening discs, muscles on the column; all-L on pitch) run
    for ``seconds`` of simulated time through the Loop, against bare ``mj_step`` on the same model for the same
    number of physics steps; the disc law (``discs.HardeningDiscs``, run before every physics step) timed alone
    on the postures the run passed through, and the same rig on the linear disc; the rest of the tick as each
    module's time per tick (the Loop's timing) and the body's snapshot timed alone."""
    import mujoco

    from shintai.scenarios.experiment import run_rig
    from shintai.spine.cla.modes import mode_rig
    from shintai.spine.discs import HardeningDiscs

    def rig(disc):
        r = mode_rig("all_l", "pitch", max_angle_deg=30, hold_s=3.0, move_s=1.0, window_s=1.0, interference=True,
                     k_s={"mid": 100.0, "high": 400.0}, spring_law="counts", T_l_kgf=1.0, T_r_kgf=1.0, disc=disc,
                     wrap="column", log=False)
        r.duration = min(r.duration, seconds)
        return r

    out = {}
    for disc in ("hardening", "linear"):
        r = rig(disc)
        body = r.body
        start = body.t  # after the rig's zeroing prelude, which is not timed
        t0 = time.perf_counter()
        run = run_rig(r)
        wall = time.perf_counter() - t0
        steps = int(round((body.t - start) / body.model.opt.timestep))
        data = mujoco.MjData(body.model)
        data.qpos[:] = body.data.qpos
        t0 = time.perf_counter()
        for _ in range(steps):
            mujoco.mj_step(body.model, data)
        bare = time.perf_counter() - t0
        out |= {f"{disc}_physics_steps": steps, f"{disc}_wall_s": wall, f"{disc}_bare_mj_step_s": bare,
                f"{disc}_overhead_ratio": wall / bare, f"{disc}_step_us": 1e6 * wall / max(steps, 1),
                f"{disc}_bare_step_us": 1e6 * bare / max(steps, 1)}
        ticks = max(run.steps, 1)  # the rest of the tick, per 1 ms tick: each module, and the body's snapshot
        out |= {f"{disc}_{name}_us_per_tick": 1e6 * t.total_s / ticks for name, t in run.loop.timing.items()}
        calls = 2000
        t0 = time.perf_counter()
        for _ in range(calls):
            body.snapshot()
        out[f"{disc}_snapshot_us"] = 1e6 * (time.perf_counter() - t0) / calls
        hooks = [h for h in body.before_physics if isinstance(h, HardeningDiscs)]
        if hooks:
            calls = 2000
            t0 = time.perf_counter()
            for _ in range(calls):
                hooks[0]()
            out["disc_law_us"] = 1e6 * (time.perf_counter() - t0) / calls
        del run
    out["hardening_over_linear"] = out["hardening_wall_s"] / out["linear_wall_s"]
    return out
