"""The coverage registry: every experiment and result figure/table of the four theses, and its status.

Each body package lists its thesis's experiments in ``shintai/<body>/coverage.py`` as ``ROWS`` (a tuple of
:class:`Row`); a scenario names the rows it reproduces with ``experiment(..., covers=(key, ...))``, so a new
scenario fills its row. A row's status comes from the results of the scenarios that cover it:

* **not yet built** — no scenario covers it;
* **not reproduced** — a reproduction check about it fails, the run erred, or no reproduction check
  compares with its result at all (only consistency checks: nothing was compared with the thesis);
* **reproduced with a stated difference** — every reproduction check about it holds and the row states a
  difference (``difference``: what we did or got that the thesis did not);
* **reproduced** — every reproduction check about it holds;
* **not comparable** — the thesis's result rests on data the thesis does not print (``not_comparable`` names
  it: a curve, a count, a rate, coordinates), so no reproduction check can be about the row; it is covered
  and its scenarios ran, but nothing of ours can be held against the thesis.

A reproduction check is about a row when it names the row (``Check(..., row=key)``) or, if it names none,
when its scenario covers that row. Only reproduction checks decide (DESIGN.md, ``metrics.json``).
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import shintai

SEEDS = {"000": "Kimura 2018 — humanoid drives and rides vehicles", "001": "Nakajima 2020 — wheeled snake",
         "003": "Mizuuchi 2001 — variable-flexibility spine, nervous", "004": "Yamaguchi — learning quadruped"}

REPRODUCED = "reproduced"
DIFFERENCE = "reproduced with a stated difference"
NOT_REPRODUCED = "not reproduced"
NOT_COMPARABLE = "not comparable"
NOT_BUILT = "not yet built"
STATUSES = (REPRODUCED, DIFFERENCE, NOT_REPRODUCED, NOT_COMPARABLE, NOT_BUILT)


@dataclass(frozen=True)
class Row:
    """One experiment or result figure/table of a thesis.

    ``key``: ``"<seed>:<short name>"``, e.g. ``"000:fig3.22"``; ``where``: section and figure/table;
    ``what``: what the thesis did; ``result``: what it reports, quoted from the seed with its numbers;
    ``difference``: a stated difference of ours (reproduced with a difference); ``why_not``: one line on why
    it does not reproduce (shown when it does not); ``not_built``: for rows without a scenario, why or what
    is missing; ``not_comparable``: the data the thesis's result rests on and does not print (status not
    comparable; the row then has no reproduction check).
    """

    key: str
    where: str
    what: str
    result: str
    difference: str = ""
    why_not: str = ""
    not_built: str = ""
    not_comparable: str = ""

    @property
    def seed(self) -> str:
        return self.key.split(":", 1)[0]


def all_rows() -> dict[str, Row]:
    """Every row of every body's ``coverage.py``, by key (duplicate keys are an error)."""
    rows: dict[str, Row] = {}
    for name in shintai.body_modules("coverage"):
        if name == "shintai.scenarios.coverage":
            continue
        for row in importlib.import_module(name).ROWS:
            if row.key in rows:
                raise ValueError(f"coverage row {row.key!r} is listed twice")
            if row.seed not in SEEDS:
                raise ValueError(f"coverage row {row.key!r}: unknown seed {row.seed!r}")
            rows[row.key] = row
    return rows


@dataclass
class RowStatus:
    row: Row
    status: str
    reason: str
    scenarios: tuple[str, ...]
    checks: list[dict[str, Any]]  # the reproduction checks about this row, as in metrics.json


def row_checks(row: Row, result: Mapping[str, Any], covers: Iterable[str]) -> list[dict[str, Any]]:
    """The reproduction checks of one scenario's result that are about ``row``."""
    covers = tuple(covers)
    return [c for c in result.get("checks", []) if c.get("kind") == "reproduction"
            and (c.get("row") == row.key or (c.get("row") is None and row.key in covers))]


def status_of(row: Row, results: Mapping[str, Mapping[str, Any]], covering: Mapping[str, Iterable[str]]
              ) -> RowStatus:
    """The status of ``row`` given ``results`` (scenario id → metrics.json) and ``covering`` (scenario id →
    the rows it covers) of the scenarios that cover it."""
    ids = tuple(sid for sid, keys in covering.items() if row.key in keys)
    if not ids:
        return RowStatus(row, NOT_BUILT, row.not_built or "no scenario covers it yet", ids, [])
    missing = [sid for sid in ids if sid not in results]
    if missing:
        return RowStatus(row, NOT_REPRODUCED, f"not run: {', '.join(missing)}", ids, [])
    errors = [f"{sid}: {results[sid]['error']}" for sid in ids if results[sid].get("error")]
    checks = [c for sid in ids for c in row_checks(row, results[sid], covering[sid])]
    if errors:
        return RowStatus(row, NOT_REPRODUCED, "run failed — " + "; ".join(errors), ids, checks)
    if row.not_comparable:
        if checks:  # a contradiction the registry test forbids: reported, not hidden
            return RowStatus(row, NOT_REPRODUCED, f"marked not comparable ({row.not_comparable}) but reproduction "
                             f"checks are about it: {', '.join(c['name'] for c in checks)}", ids, checks)
        return RowStatus(row, NOT_COMPARABLE, f"the thesis does not print {row.not_comparable}", ids, checks)
    if not checks:
        return RowStatus(row, NOT_REPRODUCED, row.why_not or "no check compares our result with the thesis's", ids,
                         checks)
    failed = [c["name"] for c in checks if not c.get("ok")]
    if failed:
        return RowStatus(row, NOT_REPRODUCED, row.why_not or f"fails: {', '.join(failed)}", ids, checks)
    if row.difference:
        return RowStatus(row, DIFFERENCE, row.difference, ids, checks)
    return RowStatus(row, REPRODUCED, f"{len(checks)} reproduction check(s) hold", ids, checks)


def summary(statuses: Iterable[RowStatus]) -> dict[str, dict[str, int]]:
    """Counts per status for each thesis: ``{seed: {status: n}}``."""
    out = {seed: dict.fromkeys(STATUSES, 0) for seed in SEEDS}
    for s in statuses:
        out[s.row.seed][s.status] += 1
    return out
