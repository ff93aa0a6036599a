"""Candidate rules for the body movement Br of seed 004 Tables 3-5 (§5.1-5.2; Br is not defined there).

Each rule gives one cycle's Br [mm] from the initial stance on a flat floor (as the teacher of §5.1), for
the printed (Zr, ΔXr, ΔYr, Δθr) and swing order of a table row, from the same executed cycle
(``robot.crawl_cycle``: its support triangles, footholds and final pose). :func:`printed_rows` are the
distinct (action, order, Br) rows of Tables 3-5; :func:`rule_errors` the RMS error [mm] of every rule
against them, raw and with the best single scale factor (a rule right up to a unit or a constant factor).
"""

from __future__ import annotations

import numpy as np

from shintai.quadruped import constants as C
from shintai.quadruped import robot as R
from shintai.quadruped import swing_order as S
from shintai.quadruped import world as W


def printed_rows() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The distinct rows of Tables 3-5: actions ``(n, 4)`` (ΔXr, ΔYr [mm], Δθr [deg], Zr [mm]), Table 2
    order numbers ``(n,)`` and printed Br [mm] ``(n,)``."""
    rows = {}
    for orders, br in ((C.TABLE3_ORDERS, C.TABLE3_BR), (C.TABLE4_ORDERS, C.TABLE4_BR),
                       (C.TABLE5_ORDERS, C.TABLE5_BR)):
        for k, (order, value) in enumerate(zip(orders, br)):
            rows.setdefault((k, order), value)
    keys = sorted(rows)
    return (C.TABLE3_ACTIONS[[k for k, _ in keys]], np.array([o for _, o in keys]),
            np.array([rows[key] for key in keys]))


def _path(points: list[np.ndarray]) -> np.ndarray:
    return sum(W.length(b - a) for a, b in zip(points[:-1], points[1:]))


def _centre(triangle: np.ndarray, kind: str) -> np.ndarray:
    if kind == "centroid":
        return triangle.mean(axis=-2)
    a, b, c = triangle[..., 0, :], triangle[..., 1, :], triangle[..., 2, :]
    la, lb, lc = W.length(b - c), W.length(c - a), W.length(a - b)
    return (la[..., None] * a + lb[..., None] * b + lc[..., None] * c) / (la + lb + lc)[..., None]


def rules(actions: np.ndarray, orders: np.ndarray) -> dict[str, np.ndarray]:
    """Every candidate rule's Br [mm] for ``actions (n, 4)`` and Table 2 ``orders (n,)``."""
    zr, command = S.actions_to_si(actions[:, 3], actions[:, 0], actions[:, 1], actions[:, 2])
    n = len(zr)
    start = R.CrawlState.initial(n)
    out = R.crawl_cycle(start, command, S.ORDERS[orders], zr, W.EnvBatch.flat(n))
    begin, end = start.pose[:, :2], out.state.pose[:, :2]
    tri = out.triangles  # (n, 4, 3, 2)
    feet0 = start.feet[..., :2]
    swing = W.length(out.footholds[..., :2] - feet0)  # (n, 4) each foot's travel
    found = {
        "shortest shift into the triangle, 10 mm margin (ours)": out.br,
        "shortest shift, then straight to the end": W.length(out.poses[:, 1, :2] - begin) + _path(
            [out.poses[:, s, :2] for s in range(1, 6)]),
        "centroid of each support triangle": _path([begin] + [_centre(tri[:, s], "centroid") for s in range(4)]
                                                   + [end]),
        "incentre of each support triangle": _path([begin] + [_centre(tri[:, s], "incentre") for s in range(4)]
                                                   + [end]),
        "net displacement": W.length(end - begin),
        "sum of the four feet's travel": swing.sum(axis=1),
        "half the feet's travel plus the body's": swing.sum(axis=1) / 2 + W.length(end - begin),
    }
    for margin in (0.03, 0.05, 0.08):  # the shortest shift with a larger margin (the shrunk triangle)
        inc = _centre(tri, "incentre")
        scale = []
        pts = [begin]
        for s in range(4):
            t = W.ccw(tri[:, s])
            a, b, c = t[:, 0], t[:, 1], t[:, 2]
            area = 0.5 * np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
            r = 2 * area / (W.length(b - c) + W.length(c - a) + W.length(a - b))
            f = np.clip((r - margin) / r, 0.0, 1.0)
            scale.append(f)
            shrunk = inc[:, s, None] + f[:, None, None] * (t - inc[:, s, None])
            pts.append(W.nearest_inside(pts[-1], shrunk))
        found[f"shortest shift, {1000 * margin:.0f} mm margin"] = _path(pts + [end])
    return {name: 1000 * np.asarray(v, dtype=float) for name, v in found.items()}


def rule_errors() -> dict[str, dict[str, float]]:
    """RMS error [mm] of every rule on :func:`printed_rows`, raw and after the best scale factor, and that factor."""
    actions, orders, printed = printed_rows()
    out = {}
    for name, br in rules(actions, orders).items():
        scale = float(br @ printed / (br @ br)) if np.any(br) else 0.0
        out[name] = {"rms_mm": float(np.sqrt(np.mean((br - printed) ** 2))),
                     "scaled_rms_mm": float(np.sqrt(np.mean((scale * br - printed) ** 2))), "scale": scale}
    return out
