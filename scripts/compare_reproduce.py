#!/usr/bin/env python3
"""Compare two ``shintai reproduce`` folders: does every scenario give the same metrics?

    python scripts/compare_reproduce.py BEFORE AFTER [--rename OLD=NEW ...] [--ignore REGEX] [--rtol R]

For each scenario in either folder: its metrics (keys and values, exactly; NaN equals NaN; with ``--rtol`` floats
within a relative R, for a change declared to differ by rounding; an infinity equals only itself), its checks (value,
threshold, ok) and its error. Wall-clock figures are ignored (``wall_time_s`` and metrics matching
``--ignore``, by default timing names). ``--rename`` maps a metric renamed on purpose. Exit 0 when
everything compared is identical, 1 otherwise; one line per scenario, then the differences.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
from pathlib import Path

TIMING = r"(wall|_us$|_fit_s$|_query_s$|time_ratio|seconds_per_individual|elapsed)"  # wall-clock figures only


def load(folder: Path) -> dict[str, dict]:
    return {p.parent.name: json.loads(p.read_text()) for p in sorted(folder.glob("*/metrics.json"))}


RTOL = [0.0]  # the relative tolerance on floats (--rtol); 0: exactly


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        if math.isnan(a) or math.isnan(b):
            return math.isnan(a) and math.isnan(b)
        if math.isinf(a) or math.isinf(b):  # an infinity equals only itself, whatever the tolerance
            return a == b
        return a == b or abs(a - b) <= RTOL[0] * max(abs(a), abs(b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    return a == b


def compare(before: dict, after: dict, rename: dict[str, str], ignore: re.Pattern) -> list[str]:
    diffs = []
    mb = {rename.get(k, k): v for k, v in before.get("metrics", {}).items() if not ignore.search(k)}
    ma = {k: v for k, v in after.get("metrics", {}).items() if not ignore.search(k)}
    for key in sorted(mb.keys() | ma.keys()):
        if key not in ma:
            diffs.append(f"metric {key}: gone (was {mb[key]!r})")
        elif key not in mb:
            diffs.append(f"metric {key}: new ({ma[key]!r})")
        elif not same(mb[key], ma[key]):
            diffs.append(f"metric {key}: {mb[key]!r} -> {ma[key]!r}")
    cb = {rename.get(c["name"], c["name"]): c for c in before.get("checks", []) if not ignore.search(c["metric"])}
    ca = {c["name"]: c for c in after.get("checks", []) if not ignore.search(c["metric"])}
    for name in sorted(cb.keys() | ca.keys()):
        b, a = cb.get(name), ca.get(name)
        if a is None or b is None:
            diffs.append(f"check {name}: {'gone' if a is None else 'new'}")
        elif not all(same(b.get(k), a.get(k)) for k in ("value", "threshold", "op", "ok")):
            diffs.append(f"check {name}: {b.get('value')!r} {b.get('op')} {b.get('threshold')!r} ({b.get('ok')}) -> "
                         f"{a.get('value')!r} {a.get('op')} {a.get('threshold')!r} ({a.get('ok')})")
    if before.get("error") != after.get("error"):
        diffs.append(f"error: {before.get('error')!r} -> {after.get('error')!r}")
    return diffs


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("before", type=Path)
    ap.add_argument("after", type=Path)
    ap.add_argument("--rename", action="append", default=[], metavar="OLD=NEW")
    ap.add_argument("--ignore", default=TIMING, help="regex of metric names not compared (default: timing)")
    ap.add_argument("--rtol", type=float, default=0.0, help="relative tolerance on floats (default 0: exactly)")
    args = ap.parse_args(argv)
    RTOL[0] = args.rtol
    rename = dict(r.split("=", 1) for r in args.rename)
    before, after = load(args.before), load(args.after)
    ignore = re.compile(args.ignore)
    bad = 0
    for sid in sorted(before.keys() | after.keys()):
        if sid not in after or sid not in before:
            print(f"{sid}: only in {'before' if sid in before else 'after'}")
            bad += 1
            continue
        diffs = compare(before[sid], after[sid], rename, ignore)
        n = len(before[sid].get("metrics", {}))
        verdict = ("identical" if not args.rtol else f"equal within rtol {args.rtol:g}") if not diffs else \
            f"{len(diffs)} differences"
        print(f"{sid}: {verdict} ({n} metrics)")
        for d in diffs:
            print(f"    {d}")
        bad += bool(diffs)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
