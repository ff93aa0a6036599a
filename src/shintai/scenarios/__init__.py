"""Scenario registry, runner, reports. Body packages register scenarios with :func:`scenario`."""

from shintai.scenarios.registry import (
    Check,
    Param,
    ParameterError,
    ThesisValue,
    benchmark,
    scenario,
)

__all__ = ["Check", "Param", "ParameterError", "ThesisValue", "benchmark", "scenario"]
