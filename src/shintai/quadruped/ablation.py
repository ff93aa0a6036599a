"""The sensor-in-the-loop ablation (seed §3, eqs. 3-6): walks of the fixed-order action network with
its obstacle features from a perception (``sensing.SensedObstacles``) instead of the known corners,
and how the sensed features compare with the known ones at the same states.
"""

from __future__ import annotations

import numpy as np

from shintai.quadruped import fitness as F
from shintai.quadruped import sensing as U
from shintai.quadruped import world as W
from shintai.quadruped.episode import SENTINELS, Episodes, GenomePolicy, rollout


def sensed_walks(genome: np.ndarray, envs: W.EnvBatch, perception: U.SensedObstacles | None,
                 record: bool = False) -> Episodes:
    """Episodes of the action network ``genome`` (fixed crawl order) with the known obstacle features
    (``perception=None``) or the perception's."""
    return rollout(envs, GenomePolicy(F.ACTION_NET, np.asarray(genome)[None], len(envs)), record=record,
                   perception=perception)


def feature_metrics(p: U.SensedObstacles) -> dict:
    """How the sensed features of a rollout compare with the known ones at the same states.

    Over the cycles in which both are real features (the obstacle is detected and, by both, not yet
    passed): mean |sensed - known| per group (x: x_max, x_min; y: y_max, y_min; z: z_max; z_min is 0
    in both), the largest |Δz_max| and the largest amount by which the sensed box sticks out of the
    true one (``sensed_box_excess_m``; ≤ 0 means inside). ``sentinel_while_ahead_fraction``: cycles
    whose sensed features are the sentinels while the known obstacle is still ahead (not seen yet or
    "passed" early), over the cycles with a known obstacle ahead. Detection: the first cycle (1-based)
    at which a side's sensors have echoed, the fraction of obstacles ever detected, and the fraction
    of echoes that came from the other side's obstacle."""
    known, sensed = p.known, p.sensed
    valid = np.isfinite(known[..., 0])
    known_ahead = valid & ~np.all(known == SENTINELS, axis=-1)
    both = known_ahead & ~np.all(sensed == SENTINELS, axis=-1)
    d = (sensed - known)[both]
    excess = np.stack([d[:, 0], -d[:, 1], d[:, 2], -d[:, 3]], axis=-1)
    obstacle, cycle = p.obstacle, p.cycle
    echo = obstacle >= 0
    first = np.where(echo, cycle, np.iinfo(int).max).min(axis=-1, initial=np.iinfo(int).max)
    detected = echo.any(axis=-1)
    out = {"feature_error_x_m": float(np.abs(d[:, :2]).mean()) if len(d) else None,
           "feature_error_y_m": float(np.abs(d[:, 2:4]).mean()) if len(d) else None,
           "feature_error_z_m": float(np.abs(d[:, 4]).mean()) if len(d) else None,
           "feature_error_y_max_m": float(np.abs(d[:, 2]).mean()) if len(d) else None,
           "feature_error_z_max_m": float(np.abs(d[:, 4]).max()) if len(d) else None,
           "sensed_box_excess_m": float(excess.max()) if len(d) else None,
           "detected_cycles_fraction": float(both.sum() / max(known_ahead.sum(), 1)),
           "sentinel_while_ahead_fraction": float((known_ahead & ~both).sum() / max(known_ahead.sum(), 1)),
           "first_detection_cycle": float(first[detected].mean() + 1) if detected.any() else None,
           "detected_fraction": float(detected.mean()),
           "cross_side_echo_fraction": float((echo & (obstacle != np.arange(2)[:, None])).sum() / max(echo.sum(), 1)),
           "echoes": int(echo.sum())}
    names = ("x_max", "x_min", "y_max", "y_min", "z_max", "z_min")
    per_feature = {f"{side}_{name}": float(np.abs((sensed - known)[..., i, j][both[..., i]]).mean())
                   for i, side in enumerate(("right", "left")) for j, name in enumerate(names)
                   if both[..., i].any()}
    return out | {"per_feature_error_m": per_feature}
