"""A parent with a busy process pool that test_executors kills: ``python pool_child.py``.

Prints the pool's worker pids on one line, then maps a slow function until it is killed.
"""

import sys
import time

from shintai.evolve import make_executor


def slow(x):
    time.sleep(0.2)
    return x


if __name__ == "__main__":
    with make_executor("process", workers=2) as ex:
        ex.map(slow, range(2))
        print(" ".join(str(pid) for pid in ex.pool()._processes), flush=True)
        while True:
            ex.map(slow, range(8))
    sys.exit(0)
