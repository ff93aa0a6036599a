"""A GA run that test_ga kills with SIGKILL mid-run: ``python ga_child.py CHECKPOINT``.

The fitness sleeps a little per genome so that generations take long enough for the test to see a
few checkpoints and kill the process well before the run ends; the sleep does not change any value.
"""

import sys
import time

import numpy as np

from shintai.evolve import GAConfig, GeneticAlgorithm
from shintai.evolve.benchmarks import rastrigin

SLEEP_S = 0.005
CONFIG = GAConfig.seed004(population=16, generations=60, elitism=2)
SEED = 11
GENES = 5


def make_ga(fitness, checkpoint) -> GeneticAlgorithm:
    return GeneticAlgorithm(fitness, -5.12 * np.ones(GENES), 5.12 * np.ones(GENES), CONFIG, seed=SEED,
                            checkpoint=checkpoint)


def slow_rastrigin(genome):
    time.sleep(SLEEP_S)
    return rastrigin(genome)


if __name__ == "__main__":
    make_ga(slow_rastrigin, sys.argv[1]).run()
