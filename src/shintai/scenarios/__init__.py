"""Scenario registry, runner, reports. Body packages register scenarios with :func:`scenario`.

Modules:

benchmarks — Where the demo's scenarios spend their time: each run under the sampling profiler, for ``shintai bench``
coverage — The coverage registry: every experiment and result figure/table of the four theses, and its status
experiment — A scenario as a declaration: its rig, stop rule, recorded signals, metrics, plots and variants
markdown — The small Markdown subset the scenario notes use, as HTML (for the report page)
report — REPORT.md and index.html for ``shintai reproduce``
sampling — Where a benchmark's or a run's CPU time goes: a sampling profiler summarised by layer (physics, control, …)
seeds — Results across seeds: a stochastic scenario (GA, noise, perturbed runs) run with N seeds reports each …
"""

from shintai.scenarios.registry import (
    Check,
    Param,
    ParameterError,
    ThesisValue,
    benchmark,
    scenario,
)

__all__ = ["Check", "Param", "ParameterError", "ThesisValue", "benchmark", "scenario"]
