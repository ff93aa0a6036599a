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
