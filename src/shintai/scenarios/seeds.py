"""Results across seeds: a stochastic scenario (GA, noise, perturbed runs) run with N seeds reports each
metric as mean ± std over the seeds, and each check on the mean together with the seeds it held in.

``shintai reproduce --seeds N`` runs a scenario declared ``stochastic=True`` into ``<out>/<id>/seed-<s>/``
for each seed and writes the combined ``<out>/<id>/metrics.json`` with :func:`combine`.
"""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path
from typing import Any

import numpy as np

from shintai.scenarios.registry import Scenario
from shintai.scenarios.runner import jsonable


def combine(sc: Scenario, per_seed: list[dict[str, Any]]) -> dict[str, Any]:
    """One metrics.json from the metrics.json of each seed's run.

    ``metrics``: the mean over the seeds of each numeric metric (a non-numeric one: the first seed's);
    ``metrics_std``: the standard deviation (population, ``ddof=0``); ``per_seed``: every seed's metrics.
    ``checks``: evaluated on the means, each with ``held_in`` — the number of seeds whose own check held.
    """
    first = per_seed[0]
    seeds = [r["seed"] for r in per_seed]
    ok_runs = [r for r in per_seed if "error" not in r]
    keys = list(first.get("metrics", {}))
    mean, std = {}, {}
    for key in keys:
        values = [r["metrics"].get(key) for r in ok_runs]
        if values and all(isinstance(v, (int, float)) and math.isfinite(float(v)) for v in values):
            arr = np.asarray(values, dtype=float)
            mean[key], std[key] = float(arr.mean()), float(arr.std())
        else:
            mean[key] = first["metrics"].get(key)
    checks = []
    for check in sc.checks:
        c = check.evaluate(mean)
        c["held_in"] = sum(any(rc["name"] == c["name"] and rc["ok"] for rc in r.get("checks", [])) for r in per_seed)
        checks.append(c)
    errors = [f"seed {r['seed']}: {r['error']}" for r in per_seed if "error" in r]
    out = {**{k: v for k, v in first.items() if k not in ("metrics", "checks", "error", "seed")},
           "seed": seeds[0], "seeds": seeds, "metrics": mean, "metrics_std": std,
           "per_seed": [{"seed": r["seed"], "metrics": r.get("metrics", {}), **({"error": r["error"]} if "error" in r
                                                                                 else {})} for r in per_seed],
           "checks": checks, "sim_time_s": sum(r.get("sim_time_s", 0.0) for r in per_seed),
           "wall_time_s": sum(r.get("wall_time_s", 0.0) for r in per_seed)}
    if errors:
        out["error"] = "; ".join(errors)
    out["ok"] = not errors and all(c["ok"] for c in checks)
    return out


def write_combined(sc: Scenario, folder: Path, seeds: list[int]) -> dict[str, Any]:
    """Combine ``folder/seed-<s>/metrics.json`` into ``folder/metrics.json``; the first seed's pictures
    and video are copied up so the report shows them."""
    per_seed = [json.loads((folder / f"seed-{s}" / "metrics.json").read_text()) for s in seeds
                if (folder / f"seed-{s}" / "metrics.json").exists()]
    if not per_seed:
        raise FileNotFoundError(f"{sc.id}: no seed finished")
    combined = combine(sc, per_seed)
    for item in (folder / f"seed-{seeds[0]}").glob("*"):
        if item.suffix in (".png", ".mp4"):
            shutil.copy2(item, folder / item.name)
    (folder / "metrics.json").write_text(json.dumps(jsonable(combined), indent=2) + "\n")
    return combined
