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


def test_readme_table_for_one_thesis_keeps_the_other_rows():
    """``scripts/readme_table.py FOLDER README --seed S`` rewrites thesis S's rows and summary line only; the
    other theses keep theirs, counted under the current status columns."""
    import importlib.util

    from shintai.scenarios.coverage import STATUSES

    spec = importlib.util.spec_from_file_location("readme_table", README.parents[0] / "scripts" / "readme_table.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    old = "\n".join([
        "<!-- reproduction:begin (written by scripts/readme_table.py from `shintai reproduce` at aaa) -->", "",
        "| thesis | reproduced | reproduced with a stated difference | not reproduced | not yet built |",
        "|---|---|---|---|---|",
        "| 001 Nakajima 2020 — wheeled snake | 3 | 1 | 0 | 0 |",
        "| 004 Yamaguchi — learning quadruped | 0 | 1 | 9 | 2 |", "",
        "| row | where | scenarios | status | why | our reproduction checks |", "|---|---|---|---|---|---|",
        "| 001:a | §1 | `snake.a` | reproduced | ok | — |", "| 004:a | §2 | `q.a` | not reproduced | old | — |",
        "| 004:b | §3 | — | not yet built | old | — |", "| 005:c | §4 | `x.c` | reproduced | kept | — |", "",
        "<!-- reproduction:end -->"])
    counts = " | ".join(["1", "1", "8", "1", "1"])
    new = "\n".join([
        "<!-- reproduction:begin (written by scripts/readme_table.py from `shintai reproduce` at bbb) -->", "",
        "| thesis | " + " | ".join(STATUSES) + " |", "|---|" + "---|" * len(STATUSES),
        "| 001 Nakajima 2020 — wheeled snake | 0 | 0 | 0 | 0 | 4 |",
        f"| 004 Yamaguchi — learning quadruped | {counts} |", "",
        "| row | where | scenarios | status | why | our reproduction checks |", "|---|---|---|---|---|---|",
        "| 001:a | §1 | `snake.a` | not run here | gone | — |", "| 004:a | §2 | `q.a` | reproduced | new | — |",
        "| 004:b | §3 | `q.b` | not comparable | new | — |", "", "<!-- reproduction:end -->"])
    merged = script.merge_seed(old, new, "004").splitlines()
    assert "aaa, bbb" in merged[0]
    assert merged[2] == new.splitlines()[2] and merged[3] == new.splitlines()[3]
    assert merged[4] == "| 001 Nakajima 2020 — wheeled snake | 3 | 1 | 0 | 0 | 0 |"
    assert merged[5] == f"| 004 Yamaguchi — learning quadruped | {counts} |"
    assert merged[9:13] == ["| 001:a | §1 | `snake.a` | reproduced | ok | — |",
                            "| 004:a | §2 | `q.a` | reproduced | new | — |",
                            "| 004:b | §3 | `q.b` | not comparable | new | — |",
                            "| 005:c | §4 | `x.c` | reproduced | kept | — |"]


def test_readme_table_for_some_scenarios_rewrites_their_rows_and_recounts():
    """``--present``: only rows all of whose scenarios are in the folder are rewritten; a row one of whose
    scenarios did not run keeps its line; the summary lines are recounted from the rows."""
    import importlib.util

    from shintai.scenarios.coverage import STATUSES

    spec = importlib.util.spec_from_file_location("readme_table", README.parents[0] / "scripts" / "readme_table.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    head = ["| thesis | " + " | ".join(STATUSES) + " |", "|---|" + "---|" * len(STATUSES)]
    rows_head = ["| row | where | scenarios | status | why | our reproduction checks |", "|---|---|---|---|---|---|"]
    old = "\n".join([
        "<!-- reproduction:begin (written by scripts/readme_table.py from `shintai reproduce` at aaa) -->", "",
        *head, "| 004 Yamaguchi — learning quadruped | 9 | 9 | 9 | 9 | 9 |", "", *rows_head,
        "| 004:a | §2 | `q.a` | not reproduced | old | — |", "| 004:b | §3 | `q.a`, `q.b` | reproduced | kept | — |",
        "| 004:c | §4 \\| Fig. 1 | — | not yet built | old | — |", "| 004:d | §5 | `q.d` | not run here | old | — |", "",
        "<!-- reproduction:end -->"])
    new = "\n".join([
        "<!-- reproduction:begin (written by scripts/readme_table.py from `shintai reproduce` at bbb) -->", "",
        *head, "| 004 Yamaguchi — learning quadruped | 0 | 0 | 0 | 0 | 0 |", "", *rows_head,
        "| 004:a | §2 | `q.a` | reproduced | new | — |", "| 004:b | §3 | `q.a`, `q.b` | not reproduced | not run: q.b | — |",
        "| 004:c | §4 \\| Fig. 1 | `q.c` | not comparable | new | — |", "", "<!-- reproduction:end -->"])
    merged = script.merge_present(old, new, {"q.a", "q.c"}).splitlines()
    assert "aaa, bbb" in merged[0]
    assert merged[8:11] == ["| 004:a | §2 | `q.a` | reproduced | new | — |",
                            "| 004:b | §3 | `q.a`, `q.b` | reproduced | kept | — |",
                            "| 004:c | §4 \\| Fig. 1 | `q.c` | not comparable | new | — |"]
    counts = {"reproduced": 2, "not comparable": 1}
    assert merged[4] == "| 004 Yamaguchi — learning quadruped | " + " | ".join(
        str(counts.get(s, 0)) for s in STATUSES) + " |"


def test_readme_table_for_some_scenarios_replaces_a_split_row_by_its_halves():
    """``--present``: a row the registry split in two (000:tab6.2 → -v, -omega) is replaced by both, in place."""
    import importlib.util

    from shintai.scenarios.coverage import STATUSES

    spec = importlib.util.spec_from_file_location("readme_table", README.parents[0] / "scripts" / "readme_table.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    head = ["| thesis | " + " | ".join(STATUSES) + " |", "|---|" + "---|" * len(STATUSES)]
    rows_head = ["| row | where | scenarios | status | why | our reproduction checks |", "|---|---|---|---|---|---|"]
    top = "<!-- reproduction:begin (written by scripts/readme_table.py from `shintai reproduce` at {}) -->"
    old = "\n".join([top.format("aaa"), "", *head, "| 004 Y | 9 | 9 | 9 | 9 | 9 |", "", *rows_head,
                     "| 004:a | §2 | `q.a` | reproduced | old | — |", "| 004:b | §3 | `q.b` | reproduced | old | — |",
                     "| 004:c | §4 | `q.c` | reproduced | kept | — |", "", "<!-- reproduction:end -->"])
    new = "\n".join([top.format("bbb"), "", *head, "| 004 Y | 0 | 0 | 0 | 0 | 0 |", "", *rows_head,
                     "| 004:a | §2 | `q.a` | reproduced | new | — |", "| 004:b-1 | §3 | `q.b` | not reproduced | one | — |",
                     "| 004:b-2 | §3 | `q.b` | reproduced | two | — |", "| 004:c | §4 | `q.c` | not run here | — | — |",
                     "", "<!-- reproduction:end -->"])
    merged = script.merge_present(old, new, {"q.a", "q.b"}).splitlines()
    assert merged[8:12] == ["| 004:a | §2 | `q.a` | reproduced | new | — |",
                            "| 004:b-1 | §3 | `q.b` | not reproduced | one | — |",
                            "| 004:b-2 | §3 | `q.b` | reproduced | two | — |",
                            "| 004:c | §4 | `q.c` | reproduced | kept | — |"]
    counts = {"reproduced": 3, "not reproduced": 1}
    assert merged[4] == "| 004 Y | " + " | ".join(str(counts.get(s, 0)) for s in STATUSES) + " |"


def test_readme_rows_say_what_the_coverage_registry_says():
    """A row's 'why' in the README is its registry text for its status (``difference`` or ``why_not``): a row
    whose text changed in coverage.py must have its table line re-written (scripts/readme_table.py)."""
    from shintai.scenarios.coverage import DIFFERENCE, NOT_REPRODUCED, all_rows
    from shintai.scenarios.report import cell

    rows = all_rows()
    stale = []
    for key, cells in readme_rows().items():
        text = {DIFFERENCE: rows[key].difference, NOT_REPRODUCED: rows[key].why_not}.get(cells[3])
        if text and cell(text) != cells[4]:
            stale.append(key)
    assert not stale, f"README rows older than their coverage text: {stale}"
