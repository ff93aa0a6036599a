"""The README's Python examples run as written (a block fenced ```python no-test is an excerpt and is skipped),
and the commands it shows exist."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"
BLOCKS = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)


def test_the_readme_has_runnable_examples():
    assert len(BLOCKS) >= 2


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_python_block_runs(index):
    pytest.importorskip("gymnasium")
    exec(compile(BLOCKS[index], f"README.md block {index}", "exec"), {"__name__": "readme"})


def test_readme_commands_exist():
    from shintai.cli import build_parser

    commands = set(build_parser()._subparsers._group_actions[0].choices)
    shown = set(re.findall(r"^shintai (\w+)", README.read_text(), flags=re.M))
    assert shown and shown <= commands, shown - commands


def readme_rows() -> dict[str, list[str]]:
    """The README's reproduction table: row key → its cells."""
    from shintai.scenarios.report import README_BEGIN, README_END

    text = README.read_text()
    block = text[text.index(README_BEGIN):text.index(README_END)]
    rows = {}
    for line in block.splitlines():
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        if cells and re.fullmatch(r"\d{3}:\S+", cells[0]):
            assert cells[0] not in rows, f"row {cells[0]} twice in the README"
            rows[cells[0]] = cells
    return rows


def test_readme_table_lists_every_thesis_experiment():
    """The README's table and the coverage registry agree: every row once, with a status; a row no scenario
    covers is 'not yet built' there too, a row whose
    scenarios were left out of the run says 'not run here' (scripts/readme_table.py writes the table from a reproduce folder)."""
    from shintai.scenarios.coverage import NOT_BUILT, STATUSES, all_rows
    from shintai.scenarios.registry import SCENARIOS, load_all
    from shintai.scenarios.report import NOT_RUN_HERE

    load_all()
    rows, table = all_rows(), readme_rows()
    assert set(table) == set(rows), {"missing": sorted(set(rows) - set(table)), "extra": sorted(set(table) - set(rows))}
    covered = {key for sc in SCENARIOS.values() for key in sc.covers}
    for key, cells in table.items():
        assert cells[3] in (*STATUSES, NOT_RUN_HERE), (key, cells[3])
        assert (cells[3] == NOT_BUILT) == (key not in covered), (key, cells[3])


def test_readme_section_is_one_line_per_row():
    from shintai.scenarios.coverage import REPRODUCED, Row, RowStatus
    from shintai.scenarios.report import README_BEGIN, README_END, readme_section

    row = Row("001:x", "§1 | Fig. 2", "what", "result")
    check = {"name": "err_m", "value": 0.001, "op": "<=", "threshold": 0.005, "ok": True}
    text = readme_section([{"commit": "abc1234"}], [RowStatus(row, REPRODUCED, "1 holds", ("snake.x",), [check])])
    assert text.startswith(README_BEGIN) and text.endswith(README_END) and "abc1234" in text
    line = next(li for li in text.splitlines() if li.startswith("| 001:x"))
    assert "§1 \\| Fig. 2" in line and "✓ err_m 0.001 <= 0.005" in line and REPRODUCED in line
