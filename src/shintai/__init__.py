"""shintai (身体, "body"): one runtime that makes the robot bodies of four theses run, learn and evolve.

See ../shared/DESIGN.md for the architecture: a Body, Modules that add contributions to the command,
a Loop that runs them in parallel and a Switcher that runs exactly one of a set.
"""

import os

# shintai parallelises across processes (GA executors, `reproduce`); multi-threaded BLAS inside each
# process only oversubscribes the cores (measured: an NN training took 19-27 s instead of 1.2 s on a
# loaded 2-core machine). Must be set before numpy is first imported; the user's setting wins.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

__version__ = "0.1.0"
