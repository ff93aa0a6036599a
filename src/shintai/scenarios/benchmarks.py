"""Where the demo's scenarios spend their time (issue 30 item 1): each scenario ``shintai demo`` runs, with its demo
parameters and without films, under the bench's sampling profiler (:mod:`shintai.scenarios.sampling`), one after
another in this process; its wall and CPU time and its profile (layers and top functions) go into ``bench.json``."""

from __future__ import annotations

import sys
import tempfile
import time

from shintai.scenarios import registry
from shintai.scenarios.registry import benchmark
from shintai.scenarios.runner import run_scenario
from shintai.scenarios.sampling import line, sampled


@benchmark("scenarios.demo-profile", "each demo scenario (demo parameters, no film): wall and CPU time, and where it goes")
def demo_profile() -> dict:
    out: dict = {"profiles": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for sid in registry.demo_ids():
            sc = registry.SCENARIOS[sid]
            t0, c0 = time.perf_counter(), time.process_time()
            with sampled() as samples:
                result = run_scenario(sid, f"{tmp}/{sid}", sc.demo_params or None, quiet=True,
                                      demo_variant=bool(sc.demo_params))
            out[f"{sid}.wall_s"] = time.perf_counter() - t0
            out[f"{sid}.cpu_s"] = time.process_time() - c0
            out["profiles"][sid] = profile = samples.summary(top=5)
            if "error" in result:
                profile["error"] = result["error"]
            print(f"    {sid}: wall {out[f'{sid}.wall_s']:.1f} s, CPU {out[f'{sid}.cpu_s']:.1f} s; {line(profile)}", file=sys.stderr)
    return out
