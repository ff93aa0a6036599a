"""Swing orders (seed §5, Table 2) and the exhaustive-search teacher of the swing-order network (§5.1).

Table 2 numbers the 24 orders of the legs 1..4 (LF, RF, LR, RR) lexicographically, which is exactly
``itertools.permutations((1, 2, 3, 4))``; the crawl order of seed §4 (right rear, right front, left
rear, left front) is number 21.

The teacher labels an action (Zr, ΔXr, ΔYr, Δθr) with the order that minimises the body movement Br
of one walking cycle while keeping static stability (and the joint limits): every order is executed
by the crawl executor from the initial stance on a flat floor and the feasible order with the
smallest Br wins (ties go to the crawl order, then to the lower number).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import world as W

PERMUTATIONS: tuple[tuple[int, int, int, int], ...] = tuple(itertools.permutations((1, 2, 3, 4)))
ORDERS = np.array(PERMUTATIONS)  # (24, 4)
CRAWL = PERMUTATIONS.index(C.CRAWL_ORDER)  # 21
TIE = 1e-9  # [m] body movements closer than this are a tie


def order_index(order) -> int:
    """Table 2 number of a swing order given as legs 1..4, e.g. ``(4, 2, 3, 1) -> 21``."""
    key = tuple(int(leg) for leg in order)
    if key not in PERMUTATIONS:
        raise ValueError(f"not a swing order of the legs 1..4: {order!r}")
    return PERMUTATIONS.index(key)


def format_order(index: int) -> str:
    """``21 -> "4→2→3→1"`` as printed in Table 2."""
    return "→".join(str(leg) for leg in PERMUTATIONS[index])


def actions_to_si(zr_mm, dx_mm, dy_mm, dtheta_deg) -> tuple[np.ndarray, np.ndarray]:
    """Table units (mm, deg) to the executor's (Zr [m], command (n, 3) in m, m, rad)."""
    zr = np.asarray(zr_mm, dtype=float) / 1000
    command = np.stack([np.asarray(dx_mm, float) / 1000, np.asarray(dy_mm, float) / 1000,
                        np.radians(np.asarray(dtheta_deg, float))], axis=-1)
    return zr, command


def body_movement(zr: np.ndarray, command: np.ndarray) -> np.ndarray:
    """Br [m] of one cycle from the initial stance on a flat floor for every order, ``(n, 24)``;
    ``inf`` where the order loses static stability or leaves the joint limits."""
    zr = np.atleast_1d(np.asarray(zr, dtype=float))
    command = np.atleast_2d(np.asarray(command, dtype=float))
    n = len(zr)
    state = R.CrawlState.initial(n * 24)
    out = R.crawl_cycle(state, np.repeat(command, 24, axis=0), np.tile(ORDERS, (n, 1)), np.repeat(zr, 24),
                        W.EnvBatch.flat(n * 24))
    return np.where(out.failed, np.inf, out.br).reshape(n, 24)


def best_orders(zr: np.ndarray, command: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exhaustive search: Table 2 number of the order with minimal Br per action (-1 where no order is
    feasible) and that Br [m]."""
    br = body_movement(zr, command)
    tied = br <= br.min(axis=1, keepdims=True) + TIE
    best = np.where(tied[:, CRAWL], CRAWL, np.argmax(tied, axis=1))
    ok = np.isfinite(br.min(axis=1))
    return np.where(ok, best, -1), np.where(ok, br[np.arange(len(br)), best], np.inf)


@dataclass(frozen=True)
class TeacherSet:
    """Teacher data of seed §5.1: inputs ``x (N, 4)`` = (Zr [m], ΔXr [m], ΔYr [m], Δθr [rad]), the
    optimal order ``label (N,)`` and the one-hot targets ``target (N, 24)``; ``optimal_orders`` lists
    every order that was optimal for some uniform draw (the paper found 19)."""

    x: np.ndarray
    label: np.ndarray
    optimal_orders: tuple[int, ...]

    @property
    def target(self) -> np.ndarray:
        return np.eye(24)[self.label]


TEACHER_LOW = np.array([C.TEACHER_ZR[0], C.TEACHER_DX[0], C.TEACHER_DY[0], C.TEACHER_DTHETA[0]])
TEACHER_HIGH = np.array([C.TEACHER_ZR[1], C.TEACHER_DX[1], C.TEACHER_DY[1], C.TEACHER_DTHETA[1]])


def label(x: np.ndarray) -> np.ndarray:
    """Optimal order of teacher inputs ``x (n, 4)`` (-1 where none is feasible)."""
    return best_orders(x[:, 0], x[:, 1:])[0]


def teacher_set(per_order: int = C.TEACHER_PER_ORDER, draws: int = C.TEACHER_DRAWS,
                seed: int = C.TEACHER_SEED) -> TeacherSet:
    """Build the teacher set: ``draws`` uniform samples of the §5.1 ranges find the optimal orders;
    an order with fewer than ``per_order`` samples gets more by sampling around its own samples
    (±5 % of each range; the paper "shrank the step" for rare orders, §7.18) until it has
    ``per_order``; each order keeps its first ``per_order`` samples."""
    if per_order < 1 or draws < 1:
        raise ValueError(f"teacher_set: per_order and draws must be >= 1, got {per_order}, {draws}")
    rng = np.random.default_rng(seed)
    x = rng.uniform(TEACHER_LOW, TEACHER_HIGH, size=(draws, 4))
    y = label(x)
    optimal = tuple(int(k) for k in np.unique(y[y >= 0]))
    xs, ys = [], []
    for k in optimal:
        mine = x[y == k]
        for _ in range(50):
            if len(mine) >= per_order:
                break
            local = mine[rng.integers(len(mine), size=8 * per_order)]
            local = np.clip(local + rng.uniform(-0.05, 0.05, local.shape) * (TEACHER_HIGH - TEACHER_LOW),
                            TEACHER_LOW, TEACHER_HIGH)
            mine = np.concatenate([mine, local[label(local) == k]])
        xs.append(mine[:per_order])
        ys.append(np.full(len(xs[-1]), k))
    return TeacherSet(np.concatenate(xs), np.concatenate(ys), optimal)


def orders_body_movement(records: list[R.CycleRecord], env: W.Environment) -> np.ndarray:
    """Br [mm] ``(n, 24)`` of every swing order for each executed cycle of a walk, from the state the
    cycle started in and with its action and Zr, in ``env``; ``inf`` where the order fails (a
    collision, a joint limit or no stable body position)."""
    n = len(records)
    feet = [R.CrawlState.initial(1).feet[0]] + [r.footholds for r in records[:-1]]
    state = R.CrawlState(np.repeat([r.body_poses[0] for r in records], 24, axis=0),
                         np.repeat([r.zr for r in records], 24), np.repeat(feet, 24, axis=0))
    out = R.crawl_cycle(state, np.repeat([r.command for r in records], 24, axis=0), np.tile(ORDERS, (n, 1)),
                        state.zr, W.EnvBatch.of([env]).tile(24 * n))
    return 1000 * np.where(out.failed, np.inf, out.br).reshape(n, 24)


def exhaustive_choice(br: np.ndarray) -> np.ndarray:
    """The order of least Br per row (ties go to the crawl order, then the lower number; as
    :func:`best_orders`)."""
    tied = br <= br.min(axis=1, keepdims=True) + 1000 * TIE
    return np.where(tied[:, CRAWL], CRAWL, np.argmax(tied, axis=1))


def strategies(br: np.ndarray, network: np.ndarray) -> dict:
    """ΣBr [mm] and orders of the fixed order, the exhaustive search and the network's choices."""
    rows = np.arange(len(br))
    best = exhaustive_choice(br)
    return {"fixed": br[:, CRAWL], "exhaustive": br[rows, best], "network": br[rows, network],
            "orders": {"fixed": [CRAWL] * len(br), "exhaustive": best.tolist(), "network": network.tolist()}}


def order_names(orders) -> str:
    """Table 2 numbers as ``"4→2→3→1, ..."``."""
    return ", ".join(format_order(int(o)) for o in orders)
