#!/usr/bin/env python3
"""Write the README's reproduction table from a ``shintai reproduce`` folder (the same statuses as its REPORT.md).

    python scripts/readme_table.py out/reproduce [README.md] [--seed 004]

Replaces the block between ``<!-- reproduction:begin ... -->`` and ``<!-- reproduction:end -->``. Rows whose
scenarios are not in the folder keep the status "not run here": reproduce everything before writing it.
With ``--seed S`` only thesis S's rows and summary line are rewritten from the folder (a body re-run on its
own); the other rows are kept as they are, and the commits of both runs are listed. With ``--present`` only
the rows all of whose scenarios are in the folder are rewritten (some scenarios re-run on their own); every
thesis's summary line is recounted from the statuses of its rows.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

from shintai.scenarios.coverage import NOT_COMPARABLE, STATUSES, all_rows
from shintai.scenarios.registry import SCENARIOS, load_all
from shintai.scenarios.report import README_BEGIN, README_END, coverage, load_results, readme_section

COMMITS = re.compile(r"`shintai reproduce` at (.*)\) -->")


def _row_seed(line: str) -> str | None:
    m = re.match(r"\| (\d{3}):\S+ \|", line)
    return m.group(1) if m else None


def _summary_seed(line: str) -> str | None:
    m = re.match(r"\| (\d{3}) [^|]* \|( \d+ \|)+$", line)
    return m.group(1) if m else None


def merge_seed(old: str, new: str, seed: str) -> str:
    """``old``'s block with thesis ``seed``'s rows and summary line taken from ``new``'s (module docstring)."""
    old_lines, new_lines = old.splitlines(), new.splitlines()
    header = next(line for line in old_lines if line.startswith("| thesis |"))
    old_statuses = [c.strip() for c in header.strip("|").split("|")[1:]]
    rows = all_rows()
    commits = sorted(set(COMMITS.search(old_lines[0]).group(1).split(", ")) |
                     set(COMMITS.search(new_lines[0]).group(1).split(", ")))
    out = [COMMITS.sub(f"`shintai reproduce` at {', '.join(commits)}) -->", new_lines[0])]
    for line in old_lines[1:]:
        if line.startswith("| thesis |"):
            out.append(next(li for li in new_lines if li.startswith("| thesis |")))
        elif line.startswith("|---|") and len(line) < 40 and out[-1].startswith("| thesis |"):
            out.append("|---|" + "---|" * len(STATUSES))
        elif _summary_seed(line) == seed:
            out.append(next(li for li in new_lines if _summary_seed(li) == seed))
        elif _summary_seed(line):  # another thesis: its counts under the new columns
            name, *counts = [c.strip() for c in line.strip("|").split("|")]
            by_status = dict(zip(old_statuses, counts))
            for status in STATUSES:
                if status not in by_status:
                    if status != NOT_COMPARABLE:
                        raise ValueError(f"cannot add the column {status!r} to thesis {name!r} without its results")
                    by_status[status] = str(sum(1 for r in rows.values() if r.seed == line[2:5] and r.not_comparable))
            out.append(f"| {name} | " + " | ".join(by_status[s] for s in STATUSES) + " |")
        elif _row_seed(line) == seed:
            continue
        else:
            out.append(line)
    # thesis seed's rows, in registry order, where its first row stood (every old line before it was kept)
    first = next(i for i, li in enumerate(old_lines) if _row_seed(li) == seed)
    return "\n".join(out[:first] + [li for li in new_lines if _row_seed(li) == seed] + out[first:])


def _cells(line: str) -> list[str]:
    return [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]


def _insert_new_rows(out: list[str], new_lines: list[str], fresh: dict[str, str], present: set[str]) -> None:
    """Rows of the registry that ``out`` lacks (a new or a split row), each after the row before it in the fresh
    table, when all their scenarios are in ``present``."""
    key = lambda li: m.group(0) if (m := re.match(r"\| \d{3}:\S+ \|", li)) else None
    have = {key(li) for li in out} - {None}
    previous = None
    for li in new_lines:
        k = key(li)
        if k is None:
            continue
        scenarios = set(re.findall(r"`([^`]+)`", _cells(li)[2]))
        if k not in have and scenarios and scenarios <= present and previous is not None:
            at = next(i for i, o in enumerate(out) if key(o) == previous)
            out.insert(at + 1, li)
            have.add(k)
        if k in have:
            previous = k


def merge_present(old: str, new: str, present: set[str]) -> str:
    """``old``'s block with the rows whose scenarios are all in ``present`` taken from ``new``, the summary lines
    recounted from the rows' statuses and the commits of both runs listed (module docstring)."""
    old_lines, new_lines = old.splitlines(), new.splitlines()
    if not COMMITS.search(old_lines[0]):
        raise ValueError("README: the reproduction table's first line names no `shintai reproduce` commits")
    fresh = {m.group(0): li for li in new_lines if (m := re.match(r"\| \d{3}:\S+ \|", li))}
    commits = sorted(set(COMMITS.search(old_lines[0]).group(1).split(", ")) |
                     set(COMMITS.search(new_lines[0]).group(1).split(", ")))
    out = [COMMITS.sub(f"`shintai reproduce` at {', '.join(commits)}) -->", new_lines[0])]
    for line in old_lines[1:]:
        m = re.match(r"\| \d{3}:\S+ \|", line)
        if m and m.group(0) in fresh:
            scenarios = set(re.findall(r"`([^`]+)`", _cells(fresh[m.group(0)])[2]))
            if scenarios and scenarios <= present:
                line = fresh[m.group(0)]
        elif m and m.group(0) not in fresh:  # a row the registry no longer has (e.g. split in two)
            continue
        out.append(line)
    _insert_new_rows(out, new_lines, fresh, present)
    counts: dict[str, dict[str, int]] = {}
    for line in out:
        if _row_seed(line):
            status = _cells(line)[3]
            if status in STATUSES:  # a row "not run here" is counted nowhere, as in the full table
                counts.setdefault(_row_seed(line), dict.fromkeys(STATUSES, 0))[status] += 1
    for i, line in enumerate(out):
        if _summary_seed(line):
            name = _cells(line)[0]
            seed_counts = counts.get(line[2:5], dict.fromkeys(STATUSES, 0))
            out[i] = f"| {name} | " + " | ".join(str(seed_counts[s]) for s in STATUSES) + " |"
    return "\n".join(out)


def main(folder: str, readme: str = "README.md", *options: str) -> int:
    seed = options[1] if len(options) == 2 and options[0] == "--seed" else None
    present = options == ("--present",)
    if options and seed is None and not present:
        print("usage: readme_table.py FOLDER [README.md] [--seed S | --present]", file=sys.stderr)
        return 2
    load_all()
    out = Path(folder)
    ids = sorted(sid for sid in SCENARIOS if (out / sid / "metrics.json").exists())
    results = load_results(out, ids)
    text = Path(readme).read_text()
    begin, end = text.index(README_BEGIN), text.index(README_END) + len(README_END)
    section = readme_section(results, coverage(results))
    if seed is not None:
        section = merge_seed(text[begin:end], section, seed)
    elif present:
        section = merge_present(text[begin:end], section, set(ids))
    Path(readme).write_text(text[:begin] + section + text[end:])
    print(f"{readme}: reproduction table from {len(ids)} scenarios in {out}" + (f" (thesis {seed} only)" if seed else " (their rows only)" if present else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
