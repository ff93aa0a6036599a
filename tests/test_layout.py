"""The layout rules of DESIGN.md and issue 12, read statically from the source: experiment files are short,
nothing imports an experiment file, the package's imports have no cycle, and no experiment hides a dependency
in a function-local import."""

from __future__ import annotations

import ast
import re
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


# --- issue 25: one folder per robot or vehicle, stacks from parameters, experiments that only declare -------------
# Each rule names the modules of a body not done yet (the other bodies' experiments and package maps are not yet
# reworked); the humanoid and the spine pass every rule with no exception.

TESTS = Path(__file__).parent
MAX_MODULES_PER_FOLDER = 20  # DESIGN.md: "no folder holds more than about 20 modules"
# a body's shared layers that are folders (its units import them; every other subfolder of a body is a unit)
SHARED_LAYERS = {"shintai.humanoid.robots", "shintai.humanoid.balance", "shintai.humanoid.learning"}
# Kenshiro's model stands on the tricycle's crank (§3.5.5): the one shared layer that builds on a unit's part
SHARED_IMPORTS_UNIT = {("shintai.humanoid.robots.kenshiro", "shintai.humanoid.tricycle.vehicle")}
FOLDERS_NOT_YET_SPLIT = {"snake"}
FLAT_BY_DESIGN = ("experiments",)  # one scenario per file, flat under the body (DESIGN.md)
PRIVATE_IMPORTS_NOT_YET_GONE: set[tuple[str, str]] = set()
PARAMS_READERS_NOT_YET_GONE: set[str] = set()
TESTS_NOT_YET_MIRRORED = {"nervous/test_diagnosis.py", "nervous/test_sequence.py"}  # of nervous/plugins/
PACKAGE_MAPS_NOT_YET_WRITTEN: set[str] = set()
# the calls that draw (matplotlib's Axes and Figure, and the scenario context's ``ctx.figure``)
PLOTTING = {"plot", "scatter", "imshow", "fill_between", "axhline", "axvline", "axvspan", "set_xlabel", "set_ylabel",
            "set_title", "legend", "figure", "subplots", "savefig", "bar", "barh", "hist", "annotate", "contour",
            "contourf", "pcolormesh", "quiver", "errorbar", "semilogy", "loglog", "set_xlim", "set_ylim", "add_patch",
            "colorbar"}


def packages() -> dict[str, Path]:
    return {module_name(p): p.parent for p in FILES if p.name == "__init__.py"}


def subpackage(name: str, of: str) -> str | None:
    """The child package of ``of`` that module ``name`` lies in (None: not below ``of``, or directly in it)."""
    if not name.startswith(of + "."):
        return None
    rest = name[len(of) + 1:].split(".")
    child = f"{of}.{rest[0]}"
    return child if child in packages() else None


def test_unit_folders_do_not_import_their_siblings():
    """A unit (a robot's or vehicle's folder) imports its body's shared layers, never a sibling unit; a shared layer
    imports no unit (named exceptions)."""
    offenders = []
    for parent in packages():  # a body (shintai.<body>) and any folder in it
        if parent == "shintai":
            continue
        kids = {k for k in packages() if k.rpartition(".")[0] == parent and not k.endswith(".experiments")}
        for name, path in MODULES.items():
            own = subpackage(name, parent)
            if own not in kids:
                continue
            for m, _ in imports(path):
                other = subpackage(m, parent)
                if other in kids and other != own and other not in SHARED_LAYERS and m in MODULES:
                    if (name, m) not in SHARED_IMPORTS_UNIT:
                        offenders.append((name, m))
    assert not offenders, f"units importing a sibling unit: {sorted(set(offenders))}"


def test_at_most_20_modules_per_folder():
    counts = {}
    for p in FILES:
        if p.name != "__init__.py":
            key = str(p.parent.relative_to(SRC))
            counts[key] = counts.get(key, 0) + 1
    big = {k: n for k, n in counts.items() if n > MAX_MODULES_PER_FOLDER and k not in FOLDERS_NOT_YET_SPLIT
           and Path(k).name not in FLAT_BY_DESIGN}
    assert not big, f"folders above {MAX_MODULES_PER_FOLDER} modules: {big}"


def test_every_module_is_on_its_package_map():
    """A package's ``__init__`` docstring names every module and subpackage of its folder (by its dotted name, or
    by its bare name as a word)."""
    missing = {}
    for pkg, folder in packages().items():
        if pkg.endswith(".experiments") or pkg in PACKAGE_MAPS_NOT_YET_WRITTEN:
            continue
        doc = ast.get_docstring(ast.parse((folder / "__init__.py").read_text())) or ""
        kids = [q.stem for q in folder.iterdir()
                if (q.suffix == ".py" and q.name != "__init__.py") or (q / "__init__.py").exists()]
        if lost := sorted(k for k in kids if f"{pkg}.{k}" not in doc and not re.search(rf"(?<![\w.]){k}\b", doc)):
            missing[pkg] = lost
    assert not missing, f"modules missing from their package map: {missing}"


def test_no_private_imports_across_files():
    found = {(module_name(p), f"{n.module}.{a.name}") for p in FILES for n in ast.walk(ast.parse(p.read_text()))
             if isinstance(n, ast.ImportFrom) and (n.module or "").startswith("shintai")
             for a in n.names if a.name.startswith("_")}
    assert not found - PRIVATE_IMPORTS_NOT_YET_GONE, sorted(found - PRIVATE_IMPORTS_NOT_YET_GONE)


def reads_params(tree: ast.AST) -> bool:
    """``params["key"]`` or ``params.get(...)``: a read of the experiment's parameter dict."""
    for n in ast.walk(tree):
        if (isinstance(n, ast.Subscript) and isinstance(n.value, ast.Name) and n.value.id == "params"
                and isinstance(n.slice, ast.Constant) and isinstance(n.slice.value, str)):
            return True
        if (isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute) and n.func.attr == "get"
                and isinstance(n.func.value, ast.Name) and n.func.value.id == "params"):
            return True
    return False


def test_only_experiments_read_the_params_dict():
    readers = {module_name(p) for p in FILES if "experiments" not in p.parts and reads_params(ast.parse(p.read_text()))}
    assert not readers - PARAMS_READERS_NOT_YET_GONE, sorted(readers - PARAMS_READERS_NOT_YET_GONE)


def test_experiments_draw_nothing():
    """Figures are the unit's ``plots.py``; an experiment's ``plots=`` names one."""
    drawing = set()
    for p in FILES:
        if "experiments" not in p.parts:
            continue
        for n in ast.walk(ast.parse(p.read_text())):
            if (isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute) and n.func.attr in PLOTTING) or (
                    isinstance(n, (ast.Import, ast.ImportFrom))
                    and any("matplotlib" in (a.name + (getattr(n, "module", "") or "")) for a in n.names)):
                drawing.add(module_name(p))
    assert not drawing, sorted(drawing)


def test_tests_mirror_src():
    """``tests/<path>/test_*.py`` tests the package ``shintai/<path>``; a test named after a module sits in the
    mirror of that module's folder."""
    where: dict[str, set[Path]] = {}
    for p in FILES:
        where.setdefault(p.stem, set()).add(p.parent.relative_to(SRC))
    wrong = []
    for t in TESTS.rglob("test_*.py"):
        folder = t.parent.relative_to(TESTS)
        if folder == Path("."):
            continue
        if not (SRC / folder / "__init__.py").exists():
            wrong.append((str(t.relative_to(TESTS)), "no such package"))
            continue
        homes = {h for h in where.get(t.stem[5:], set()) if h.parts[:1] == folder.parts[:1]}
        if homes and folder not in homes and str(t.relative_to(TESTS)) not in TESTS_NOT_YET_MIRRORED:
            wrong.append((str(t.relative_to(TESTS)), f"its module is in {sorted(map(str, homes))}"))
    assert not wrong, wrong


# --- the spine's layout (issue 25): one folder per robot beside the flat shared layers ---------------------------

SPINE = SRC / "spine"
SPINE_UNITS = ("cla", "kenta", "sq43", "hanzous", "bebe", "mocap", "rabbit")
FLAT_FOLDERS = ("experiments", "notes")  # one scenario per file, flat by design


def spine_folders() -> list[Path]:
    return [SPINE, *(SPINE / u for u in SPINE_UNITS)]


def test_spine_units_exist_and_nothing_else_is_a_folder():
    folders = {p.name for p in SPINE.iterdir() if p.is_dir() and p.name != "__pycache__"}
    assert folders == set(SPINE_UNITS) | set(FLAT_FOLDERS), folders


def test_spine_modules_are_on_their_package_map():
    """Each spine folder's ``__init__`` docstring names every module of the folder, one line each
    (``name — ...``), and no module that is gone."""
    missing = {}
    for folder in spine_folders():
        doc = ast.get_docstring(ast.parse((folder / "__init__.py").read_text())) or ""
        named = {line.split(" — ")[0].strip() for line in doc.splitlines() if " — " in line}
        modules = {p.stem for p in folder.glob("*.py") if p.name != "__init__.py"}
        if modules - named:
            missing[str(folder.relative_to(SRC))] = sorted(modules - named)
        stale = {n for n in named - modules if not n.endswith("/")}
        if stale:
            missing[f"{folder.relative_to(SRC)} (stale)"] = sorted(stale)
    assert not missing, missing


def test_spine_unit_tests_sit_in_their_unit_folder():
    flat = [p.name for p in (TESTS / "spine").glob("test_*.py")
            if any(p.stem == f"test_{u}" or p.stem.startswith(f"test_{u}_") for u in SPINE_UNITS)]
    assert not flat, f"spine unit tests outside their unit's folder: {flat}"


# who may build a Loop: the runner builds every rig's (scenarios.experiment), the gym envs and nervous run their own;
# these named owners run a loop a rig or a compute needs inside it
LOOP_OWNERS = {
    "shintai.scenarios.experiment": "the runner",
    "shintai.gym.loop_env": "the Gymnasium environments' episodes",
    "shintai.nervous.nerve": "the nervous server's control loop (seed 003 ch. 6)",
    "shintai.nervous.bodies": "the nervous server's simulated robot",
    "shintai.core.linear_plant": "core.search-index's compute: Eq. 2.14 on a linear plant, one loop per gain",
    "shintai.sim.corner": "sim.wall-force's settle between search-index updates (a compute)",
    "shintai.humanoid.tricycle.kenshiro": "the rig's settle on the pedals before the pedalling, no module running",
    "shintai.humanoid.balance.standing": "the standing stack run on its own (tests, benchmarks), built on first use",
    "shintai.quadruped.episode": "the crawl of one GA individual (a compute's fitness rollout)",
    "shintai.quadruped.video": "the film of a recorded walk (a replay body, no control)",
    "shintai.spine.teaching": "§4.6.4's encoder zeroing, the prelude every spine rig runs when it is built",
    "shintai.spine.kenta.body": "Kenta's zeroing prelude (calibrated_kenta)",
    "shintai.spine.kenta.postures": "the teaching prelude of its rigs: each posture held by the hands, one loop each",
    "shintai.spine.cla.teach_runs": "E9's teaching, then replays of its recording: a chain of loops (a compute)",
    "shintai.spine.bebe.body": "BeBe's calibration settles and tracking runs: a chain of loops (a compute)",
}


def builds_loop(tree: ast.AST) -> bool:
    return any(isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "Loop" for n in ast.walk(tree))


def test_only_the_runner_and_named_owners_build_a_loop():
    builders = {module_name(p) for p in FILES if builds_loop(ast.parse(p.read_text()))
                and not p.stem == "benchmarks"}  # a benchmark times a loop against bare mj_step
    owners = set(LOOP_OWNERS)
    assert builders <= owners, f"Loop built outside the runner: {sorted(builders - owners)}"
    assert owners <= builders, f"owners that no longer build one: {sorted(owners - builders)}"


# --- one place per constant (DESIGN.md): a body's numbers live in its constants file or its units' ---------------
# Bodies brought to the rule, each with its constants files (relative to the body's folder). The spine's robots'
# parameter sets are ``spine/robots.py``; its shared layers' protocol numbers ``spine/constants.py``.
CONSTANTS_FILES = {"humanoid": ("constants.py", "tricycle/constants.py", "unicycle/constants.py", "vboard/constants.py"),
                   "spine": ("robots.py", "constants.py", "bebe/constants.py", "cla/constants.py",
                             "hanzous/constants.py", "kenta/constants.py", "mocap/constants.py", "sq43/constants.py")}
# (module, name) that stay where they are, with the reason
CONSTANTS_KEPT_IN_PLACE = {
    ("shintai.humanoid.learning.slc", "PITCH"): "an index into FootDamping's (roll, pitch), not a parameter",
    ("shintai.humanoid.tricycle.hrp2_limbs", "BAR_IN_HAND"): "a frame's axis (the grasp site's x), not a parameter",
    ("shintai.humanoid.tricycle.hrp2_limbs", "CRANK_AXIS_IN_SOLE"): "a frame's axis (the sole's y), not a parameter",
    ("shintai.humanoid.tricycle.hrp2_limbs", "_GRIP_Y"): "a frame's axis (the grip site's y), private to the IK",
    ("shintai.humanoid.tricycle.hrp2_limbs", "_ORIGIN"): "the waist frame's own pose, private to the IK",
    ("shintai.humanoid.tricycle.hrp2_limbs", "_EYE"): "the waist frame's own pose, private to the IK",
    ("shintai.humanoid.tricycle.switching", "Y_AXIS"): "a frame's axis, not a parameter",
    ("shintai.spine.mocap.retarget", "TO_ROBOT"): "the BVH-to-robot axis permutation (frames' axes), not a parameter",
    **{("shintai.humanoid.balance.stabilizer_tick", n): "a slot of the LIP kernel's state or output array, not a parameter"
       for n in ("COM", "COM_VEL", "REF", "HAS_REF", "READ", "READ_VEL", "HAS_READ", "READ_SUPPORT", "STATE_SIZE",
                 "OUT_SIZE")},
}
LITERAL_CALLS = {"array", "diag", "radians", "deg2rad", "asarray"}  # np.array([...]) of numbers is a number too


def is_number(v: ast.AST) -> bool:
    """A literal number, or arithmetic, a tuple or list, ``math.pi`` or ``np.array(...)`` of literal numbers (a
    derived constant, which names another, is not one)."""
    if isinstance(v, ast.Constant):
        return isinstance(v.value, (int, float)) and not isinstance(v.value, bool)
    if isinstance(v, ast.UnaryOp):
        return is_number(v.operand)
    if isinstance(v, ast.BinOp):
        return is_number(v.left) and is_number(v.right)
    if isinstance(v, (ast.Tuple, ast.List)):
        return bool(v.elts) and all(map(is_number, v.elts))
    if isinstance(v, ast.Attribute):
        return v.attr == "pi" and isinstance(v.value, ast.Name) and v.value.id in ("math", "np")
    if isinstance(v, ast.Call):
        return (isinstance(v.func, ast.Attribute) and v.func.attr in LITERAL_CALLS and len(v.args) == 1
                and not v.keywords and is_number(v.args[0]))
    return False


def numeric_constants(tree: ast.Module) -> list[str]:
    """The module-level UPPER_CASE names bound to a number (``X = 1.0``, ``X, Y = 1.0, 2.0``, ``X: float = 1.0``)."""
    found = []
    for n in tree.body:
        if isinstance(n, ast.Assign) and len(n.targets) == 1:
            target, value = n.targets[0], n.value
        elif isinstance(n, ast.AnnAssign) and n.value is not None:
            target, value = n.target, n.value
        else:
            continue
        names = [target] if isinstance(target, ast.Name) else list(getattr(target, "elts", []))
        if names and all(isinstance(t, ast.Name) and t.id.isupper() for t in names) and is_number(value):
            found += [t.id for t in names]
    return found


def test_numbers_live_in_the_constants_files():
    stray = []
    for body, files in CONSTANTS_FILES.items():
        own = {SRC / body / f for f in files}
        for p in sorted((SRC / body).rglob("*.py")):
            if p not in own:
                stray += [(module_name(p), n) for n in numeric_constants(ast.parse(p.read_text()))
                          if (module_name(p), n) not in CONSTANTS_KEPT_IN_PLACE]
    assert not stray, f"numbers outside the constants files: {stray}"
    kept = {m for m, _ in CONSTANTS_KEPT_IN_PLACE}
    assert kept <= set(MODULES), sorted(kept - set(MODULES))


def test_the_constants_rule_sees_numbers():
    found = numeric_constants(ast.parse("A = 1.0\nB, C = 2, -3e-4\nD = (1, 2.5)\nE = np.array([[1.0, 0.0]])\n"
                                        "F = 10 * math.pi / 180\nG = A * 2\nH = 'x'\nJ = True\nk = 1\n"))
    assert found == ["A", "B", "C", "D", "E", "F"], found


BODIES = ("humanoid", "snake", "spine", "nervous", "quadruped")
# a body that imports another, with the reason (issue 25: "no body imports another body; name any exception")
BODY_IMPORTS = {
    ("nervous", "spine"): "nervous serves the spine robots (seed 003 ch. 6): it runs their models, laws and teaching",
    ("nervous", "snake"): "nervous's robot table also offers the snake's MuJoCo model",
    ("nervous", "humanoid"): "nervous's robot table also offers HRP2's model",
    ("spine", "humanoid"): "§5.8.2's motion capture compares the spined robots with the rigid-trunk HRP2",
}


def test_no_body_imports_another_body():
    found = set()
    for name, path in MODULES.items():
        own = name.split(".")[1] if name.count(".") else ""
        if own not in BODIES:
            continue
        for m, _ in imports(path):
            other = m.split(".")[1] if m.startswith("shintai.") else ""
            if other in BODIES and other != own and m in MODULES:
                found.add((own, other))
    assert found <= set(BODY_IMPORTS), f"bodies importing another body: {sorted(found - set(BODY_IMPORTS))}"
    assert set(BODY_IMPORTS) <= found, f"named exceptions that no longer hold: {sorted(set(BODY_IMPORTS) - found)}"
