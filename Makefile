# shintai: `make demo` and `make test` work on a fresh machine from nothing but python3 (DESIGN.md).
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
export MUJOCO_GL ?= egl
# one BLAS thread per process: shintai parallelises across processes (see src/shintai/__init__.py)
export OPENBLAS_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1

.PHONY: install test demo reproduce bench clean

# (Re)install when pyproject.toml changes; pinned versions come from pyproject.toml.
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[ray,gym,dev]"
	touch $(STAMP)

install: $(STAMP)

test: $(STAMP)
	$(BIN)/python -m pytest tests -q -n 2 --dist loadfile

demo: $(STAMP)
	$(BIN)/shintai demo --out out/demo

reproduce: $(STAMP)
	$(BIN)/shintai reproduce --out out/reproduce

bench: $(STAMP)
	$(BIN)/shintai bench --out out/bench

clean:
	rm -rf out .pytest_cache
