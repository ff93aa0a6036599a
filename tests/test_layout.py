"""The layout rules of DESIGN.md and issue 12, read statically from the source: experiment files are short,
nothing imports an experiment file, the package's imports have no cycle, and no experiment hides a dependency
in a function-local import."""

from __future__ import annotations

import ast
from pathlib import Path

import shintai

SRC = Path(shintai.__path__[0])
MAX_EXPERIMENT_LINES = 250  # issue 12: "no file in an experiments/ folder above ~250 lines"


def module_name(path: Path) -> str:
    parts = ("shintai",) + path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports(path: Path) -> list[tuple[str, bool]]:
    """(imported module, at top level) for each import in the file; relative imports resolved."""
    tree = ast.parse(path.read_text(), str(path))
    top = set(map(id, tree.body))
    package = module_name(path) if path.name == "__init__.py" else module_name(path).rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(a.name, id(node) in top) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1] + ([base] if base else []))
            names = [f"{base}.{a.name}" for a in node.names]  # `from pkg import module` imports pkg.module
            found += [(n, id(node) in top) for n in [base] + names]
    return found


FILES = sorted(SRC.rglob("*.py"))
MODULES = {module_name(p): p for p in FILES}


def is_experiment(name: str) -> bool:
    return ".experiments." in name


def test_experiment_files_are_short():
    long = {str(p.relative_to(SRC)): n for p in FILES if "experiments" in p.parts
            and (n := len(p.read_text().splitlines())) > MAX_EXPERIMENT_LINES}
    assert not long, f"experiment files above {MAX_EXPERIMENT_LINES} lines: {long}"


def test_nothing_imports_an_experiment_file():
    offenders = [(module_name(p), m) for p in FILES for m, _ in imports(p) if is_experiment(m) and m in MODULES]
    assert not offenders, offenders


def test_experiments_import_at_top_level():
    local = [(module_name(p), m) for p in FILES if "experiments" in p.parts
             for m, top in imports(p) if not top and m.startswith("shintai")]
    assert not local, f"function-local imports in experiment files: {local}"


def test_no_import_cycles_at_module_level():
    graph = {name: {m for m, top in imports(path) if top and m in MODULES and m != name}
             for name, path in MODULES.items()}
    # a package imports its own submodules through __init__ by design; a cycle through a package's
    # __init__ and its own child is how Python packages work, not a dependency cycle
    for name, deps in graph.items():
        graph[name] = {d for d in deps if not (d.startswith(name + ".") or name.startswith(d + "."))}
    state: dict[str, int] = {}
    cycles = []

    def visit(node: str, stack: list[str]) -> None:
        state[node] = 1
        for dep in sorted(graph[node]):
            if state.get(dep) == 1:
                cycles.append(stack[stack.index(dep):] + [dep])
            elif dep not in state:
                visit(dep, stack + [dep])
        state[node] = 2

    for name in sorted(graph):
        if name not in state:
            visit(name, [name])
    assert not cycles, f"import cycles: {cycles[:5]}"


def test_the_layout_test_sees_imports():
    """The reader above resolves relative and `from pkg import module` imports (else every test passes)."""
    found = dict(imports(SRC / "scenarios" / "registry.py"))
    assert any(m.startswith("shintai.") for m in found)
    assert MODULES and any(is_experiment(m) for m in MODULES)


def test_no_body_keeps_a_scenarios_module():
    """Scenarios live one per file in ``<body>/experiments/`` (issue 12); the old ``*scenarios*.py`` are gone."""
    left = [str(p.relative_to(SRC)) for p in FILES if "scenarios" in p.stem and p.parent.name != "scenarios"]
    assert not left, left
