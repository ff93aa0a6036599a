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
