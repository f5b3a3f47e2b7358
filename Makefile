# flexpipe — the two commands a newcomer types are `make straight` and `make test`.
# Every target that needs the environment depends on .venv/.installed (the `setup` target),
# which creates the virtual environment and installs flexpipe with its dependencies once.

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: setup straight slalom paper sweep test bench lint clean

setup: $(STAMP)

$(STAMP): pyproject.toml
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[dev]"
	@touch $(STAMP)

straight: setup
	$(PY) -m flexpipe.scenarios straight --out out/straight

slalom: setup
	$(PY) -m flexpipe.scenarios slalom --out out/slalom

sweep: setup
	$(PY) -m flexpipe sweep sweeps/sample.toml --out out/sweep

paper: setup
	$(PY) -m flexpipe.halfcar.paper --out out/paper

test: setup
	$(PY) -m pytest -q

bench: setup
	$(PY) -m bench

lint: setup
	$(VENV)/bin/ruff check flexpipe tests bench

clean:
	rm -rf out .pytest_cache
