"""A plain install: `python -m build` makes a wheel that installs into a fresh virtual environment (Python
3.11, and 3.12 where the machine has it) and runs from a folder outside the checkout, with its data files
(notes, trained networks, models) inside."""

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DATA = ("shintai/quadruped/trained/action_fixed.npz", "shintai/core/notes/minjerk.md")
# the installed copy runs without the caller's PYTHONPATH (a worktree's src on it would shadow the wheel)
CLEAN_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("dist")
    done = subprocess.run([sys.executable, "-m", "build", "--wheel", "--outdir", str(out), str(ROOT)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    shutil.rmtree(ROOT / "build", ignore_errors=True)  # setuptools' scratch folder in the checkout
    (path,) = out.glob("shintai-*.whl")
    return path


def install(wheel, python, where):
    venv = where / "venv"
    subprocess.run([python, "-m", "venv", str(venv)], check=True, timeout=300)
    # --no-compile: pip's byte-compiling of every installed dependency is half the install's time and not what
    # this tests (Python compiles what the run imports)
    done = subprocess.run([str(venv / "bin" / "pip"), "install", "--quiet", "--no-compile", str(wheel)],
                          capture_output=True, text=True, timeout=1200, env=CLEAN_ENV)
    assert done.returncode == 0, done.stderr[-3000:]
    return venv / "bin"


def run(bin_dir, *args, cwd):
    return subprocess.run([str(bin_dir / "shintai"), *args], capture_output=True, text=True, timeout=600, cwd=cwd,
                          env=CLEAN_ENV)


def test_the_wheel_carries_the_data_files(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    assert set(DATA) <= names
    assert not any("tests/" in n for n in names)


def test_the_wheel_installs_and_runs_outside_the_checkout(wheel, tmp_path):
    bin_dir = install(wheel, sys.executable, tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    listed = run(bin_dir, "list", cwd=elsewhere)
    assert listed.returncode == 0 and "core.minjerk" in listed.stdout and "quadruped.replay" in listed.stdout
    ran = run(bin_dir, "run", "core.minjerk", "--out", "m", "--quiet", cwd=elsewhere)
    assert ran.returncode == 0, ran.stderr
    assert (elsewhere / "m" / "metrics.json").exists() and "minimum-jerk" in (elsewhere / "m" / "metrics.json").read_text()
    where = subprocess.run([str(bin_dir / "python"), "-c", "import shintai; print(shintai.__file__)"],
                           capture_output=True, text=True, cwd=elsewhere, env=CLEAN_ENV)
    assert str(ROOT) not in where.stdout  # the installed copy, not the checkout


def python312():
    """A working Python 3.12: on PATH, or one of pyenv's versions."""
    candidates = [shutil.which("python3.12"), *sorted(str(p) for p in Path.home().glob(".pyenv/versions/3.12*/bin/python3.12"))]
    for python in filter(None, candidates):
        if subprocess.run([python, "--version"], capture_output=True).returncode == 0:
            return python
    return None


def test_python_312_installs_the_wheel_where_the_machine_has_it(wheel, tmp_path):
    python = python312()
    if python is None:
        pytest.skip("no python3.12 on this machine: the 3.12 install is not tested here")
    bin_dir = install(wheel, python, tmp_path)
    assert run(bin_dir, "list", cwd=tmp_path).returncode == 0
