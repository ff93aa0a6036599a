"""shintai (身体, "body"): one runtime that makes the robot bodies of four theses run, learn and evolve.

See ../shared/DESIGN.md for the architecture: a Body, Modules that add contributions to the command,
a Loop that runs them in parallel and a Switcher that runs exactly one of a set.

Modules:

cli — The ``shintai`` command (contract in DESIGN.md): list, run, reproduce, bench, and demo; __main__ runs it
core/ — Shared runtime pieces: Body/Module/Loop/Switcher, the recorder, the online search index, interpolation
gym/ — Gymnasium environments over shintai's bodies and modules (``pip install shintai[gym]``)
humanoid/ — Seed 000 (Kimura 2018): a humanoid drives a tricycle and rides a two-wheeled scooter and a unicycle
nervous/ — nervous — the middle layer between programs and robot bodies (seed 003 ch. 6, App. C)
quadruped/ — Seed 004: the TITAN-VIII quadruped that learns obstacle avoidance and its swing order with Gaussian …
scenarios/ — Scenario registry, runner, reports
sim/ — shintai.sim: the MuJoCo body every MuJoCo-based robot in shintai runs on, and its rendering
snake/ — Wheeled snake robot of seed 001 (Nakajima 2020): constraint switching, two-point control, two planes
spine/ — Variable-flexibility spines of seed 003 (Mizuuchi 2001), ch. 3–5: the shared layers, flat, and one …
"""

import os

# shintai parallelises across processes (GA executors, `reproduce`); multi-threaded BLAS inside each
# process only oversubscribes the cores (measured: an NN training took 19-27 s instead of 1.2 s on a
# loaded 2-core machine). Must be set before numpy is first imported; the user's setting wins.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

__version__ = "0.1.0"


def body_modules(leaf: str) -> list[str]:
    """``shintai.<package>.<leaf>`` for every subpackage that has such a module or package, found on disk
    without importing the subpackages (an optional one, like ``shintai.gym``, may need an extra)."""
    from pathlib import Path

    found = []
    for root in __path__:
        for pkg in sorted(Path(root).iterdir()):
            if (pkg / "__init__.py").is_file() and ((pkg / f"{leaf}.py").is_file() or (pkg / leaf / "__init__.py").is_file()):
                found.append(f"shintai.{pkg.name}.{leaf}")
    return found
