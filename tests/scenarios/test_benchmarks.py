"""The benchmarks are too long for the suite (``shintai bench`` runs them), but the names each one imports when
it runs must exist: a benchmark importing inside its function broke silently when a constant moved (spine's
``GENE_HI`` left ``sq43.gaits`` for ``sq43.constants``; found by a bench run)."""

import ast
import importlib
from pathlib import Path

import pytest

import shintai
from shintai.scenarios.registry import BENCHMARKS, load_all

FILES = sorted(Path(shintai.__file__).parent.glob("*/benchmarks.py"))


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.parent.name)
def test_every_import_a_benchmark_makes_resolves(path):
    tree = ast.parse(path.read_text())
    missing = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            module = importlib.import_module(node.module)
            missing += [f"{node.module}.{a.name}" for a in node.names
                        if not hasattr(module, a.name) and not _is_submodule(node.module, a.name)]
        elif isinstance(node, ast.Import):
            for a in node.names:
                importlib.import_module(a.name)
    assert not missing, missing


def _is_submodule(package: str, name: str) -> bool:
    try:
        importlib.import_module(f"{package}.{name}")
        return True
    except ImportError:
        return False


def test_every_benchmark_file_registers_benchmarks():
    load_all()
    assert {b.run.__module__ for b in BENCHMARKS.values()} == {
        f"shintai.{p.parent.name}.benchmarks" for p in FILES}
