"""Evolution: a genetic algorithm (seed 003 §5.5–5.7, seed 004 §4.1.2) and the executors it runs on.

Modules:

benchmarks — Fitness test functions and the executor benchmark of one GA generation
ga — A real-valued genetic algorithm with pluggable fitness executors, checkpoints and resume
stopping — A GA's stopping rule: stop once the best fitness has stalled
"""

from shintai.evolve.executors import (Executor, ItemError, ProcessExecutor, RayExecutor, SerialExecutor,
                                      make_executor)
from shintai.evolve.ga import (Checkpoint, GAConfig, GAResult, GeneticAlgorithm, History, load_checkpoint,
                               save_checkpoint)
from shintai.evolve.stopping import stalled

__all__ = ["Checkpoint", "Executor", "GAConfig", "GAResult", "GeneticAlgorithm", "History", "ItemError",
           "ProcessExecutor", "RayExecutor", "SerialExecutor", "load_checkpoint", "make_executor",
           "save_checkpoint", "stalled"]
