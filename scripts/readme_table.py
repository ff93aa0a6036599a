#!/usr/bin/env python3
"""Write the README's reproduction table from a ``shintai reproduce`` folder (the same statuses as its REPORT.md).

    python scripts/readme_table.py out/reproduce [README.md]

Replaces the block between ``<!-- reproduction:begin ... -->`` and ``<!-- reproduction:end -->``. Rows whose
scenarios are not in the folder keep the status "not run here": reproduce everything before writing it.
"""

from __future__ import annotations

import sys
from pathlib import Path

from shintai.scenarios.registry import SCENARIOS, load_all
from shintai.scenarios.report import README_BEGIN, README_END, coverage, load_results, readme_section


def main(folder: str, readme: str = "README.md") -> int:
    load_all()
    out = Path(folder)
    ids = sorted(sid for sid in SCENARIOS if (out / sid / "metrics.json").exists())
    results = load_results(out, ids)
    text = Path(readme).read_text()
    begin, end = text.index(README_BEGIN), text.index(README_END) + len(README_END)
    Path(readme).write_text(text[:begin] + readme_section(results, coverage(results)) + text[end:])
    print(f"{readme}: reproduction table from {len(ids)} scenarios in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
