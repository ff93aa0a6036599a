# shintai: `make demo` and `make test` work on a fresh machine from nothing but python3 (DESIGN.md).
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
export MUJOCO_GL ?= egl
# one BLAS thread per process: shintai parallelises across processes (see src/shintai/__init__.py)
export OPENBLAS_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1

.PHONY: install browser test demo reproduce bench clean

# (Re)install when pyproject.toml changes; pinned versions come from pyproject.toml.
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[ray,gym,dev]"
	touch $(STAMP)

install: $(STAMP)

# Debian's chromium for the browser test of the report page (tests/scenarios/test_report_page.py): installed
# when missing, where apt-get runs as root; elsewhere that test skips and says why.
browser:
	@if ! command -v chromium >/dev/null 2>&1; then \
	  if command -v apt-get >/dev/null 2>&1 && [ "$$(id -u)" = 0 ]; then \
	    DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null || \
	    echo "make: chromium could not be installed; the browser test will skip"; \
	  else echo "make: chromium is missing (needs root and apt-get to install); the browser test will skip"; fi; \
	fi

test: $(STAMP) browser
	$(BIN)/python -m pytest tests -q -n 2 --dist loadfile

demo: $(STAMP)
	$(BIN)/shintai demo --out out/demo

reproduce: $(STAMP)
	$(BIN)/shintai reproduce --out out/reproduce

bench: $(STAMP)
	$(BIN)/shintai bench --out out/bench

clean:
	rm -rf out .pytest_cache
