"""``spine.cla-roll-over-ga``: Cla's roll-over keys searched by seed 003's GA, from the back (supine → prone) and
from the front (prone → supine), each best replayed with the spine and with it locked (seed 003 §5.2.8, Fig.
5.9; keys, genes and fitness: :mod:`shintai.spine.cla.roll_over`). A GA, not one loop: a compute experiment."""

from __future__ import annotations

import numpy as np

from shintai.scenarios.experiment import run_rig, variant_metric
from shintai.scenarios.registry import Check, Param, ThesisValue, experiment
from shintai.spine import ga_run
from shintai.spine.cla import roll_over as RO
from shintai.spine.cla.constants import ROLL_GA_GENERATIONS, ROLL_GA_POPULATION

DIRECTIONS = {"supine": False, "prone": True}  # where Cla starts → whether it lies on its front
Q_HALF = ("§5.2.8 '股関節の力・肩の力だけでは体を捻って半身を起こすことができない。脊椎を yaw 軸回りに回転させる動きと"
          "肩・股関節の動きを同時に行うことで … 半身を起こすことができる'")
Q_ROLL = "§5.2.8 'これにより、仰向けからうつぶせ、うつぶせから仰向けと、両方向の寝返りができるようになった'"


def compute(ctx):
    """One GA per direction (seeds seed, seed + 1), the hand-made keys an initial individual; then the best and the
    hand-made keys replayed with the spine and locked."""
    p = ctx.params
    ga = ga_run.ga_of(p)
    out, genomes = {}, {}
    for i, (direction, prone) in enumerate(DIRECTIONS.items()):
        fitness = RO.RollFitness(prone, float(p["fraction"]), float(p["calibration_s"]))
        result = ga_run.evolve(ctx, f"roll_{direction}", fitness, np.zeros(RO.N_GENES), np.ones(RO.N_GENES), ga=ga,
                               initial=RO.HAND_MADE[None], seed=ctx.seed + i,
                               title=f"Cla roll-over keys from {direction} (seed 003 §5.2.8)")
        genomes[direction] = result.best_genome
        out[f"{direction}.best_fitness"] = float(result.best_fitness)
        out[f"{direction}.generations"] = len(result.history)
        for keys, genes in (("ga", result.best_genome), ("hand_made", RO.HAND_MADE)):
            for variant in ("spine", "locked"):
                run = run_rig(RO.roll_rig(variant == "spine", genes, prone, float(p["fraction"]),
                                          float(p["calibration_s"])))
                o = RO.outcome(run.log, prone)
                o["fitness"] = RO.roll_fitness(o)
                out |= {f"{direction}.{keys}.{variant_metric(k, variant)}": v for k, v in o.items()}
                ctx.sim_time_s += run.rig.duration
        # the GA's simulated time, each evaluation counted at the hand-made sequence's length (approximate)
        ctx.sim_time_s += ga_run.evaluations(p["population"], len(result.history)) * RO.sequence_s() * p["fraction"]
    ctx.extra["genomes"] = {d: g.tolist() for d, g in genomes.items()}
    np.savez(ctx.out / "best_genomes.npz", **genomes)
    return out


experiment(
    "spine.cla-roll-over-ga",
    source="seed 003 §5.2.8, Fig. 5.9",
    covers=("003:fig5.9",),
    summary="Cla's roll-over keys (durations, limb angles, the spine's twist and side bend) searched by seed 003's "
            "GA from the back and from the front; each best replayed with the spine and with it locked",
    params=(*ga_run.ga_params(ROLL_GA_GENERATIONS, ROLL_GA_POPULATION),
            Param("fraction", 1.0, "run this fraction of each sequence (tests)", lo=0.05, hi=1.0),
            Param("calibration_s", 1.0, "§4.6.4 encoder zeroing before each run [s]", lo=0.01, hi=5.0)),
    checks=(
        Check("supine.ga.rolled_spine", "==", 1, Q_ROLL + ": from the back, the GA's keys with the spine end on the "
              "front", name="rolls_supine_to_prone", kind="reproduction", row="003:fig5.9"),
        Check("prone.ga.rolled_spine", "==", 1, Q_ROLL + ": from the front, the GA's keys with the spine end on the "
              "back", name="rolls_prone_to_supine", kind="reproduction", row="003:fig5.9"),
        Check("supine.ga.rolled_locked", "==", 0, Q_HALF + ": the same keys with the spine locked do not roll Cla "
              "from the back", name="no_roll_locked_from_supine", kind="reproduction", row="003:fig5.9"),
        Check("prone.ga.rolled_locked", "==", 0, Q_HALF + ": the same keys with the spine locked do not roll Cla "
              "from the front", name="no_roll_locked_from_prone", kind="reproduction", row="003:fig5.9"),
    ),
    thesis={"roll": ThesisValue("rolls over both ways with the spine's yaw (photographs, Fig. 5.9)",
                                "seed 003 " + Q_ROLL, "supine.ga.rolled_spine")},
    compute=compute,
    stochastic=True,
    smoke={"generations": 1, "population": 4, "executor": "serial", "fraction": 0.05, "calibration_s": 0.01},
)
