# flexpipe — the two commands a newcomer types are `make straight` and `make test`.
# Every target that needs the environment depends on .venv/.installed (the `setup` target),
# which creates the virtual environment, installs flexpipe with its dependencies and
# compiles its Numba kernels with a few steps of the sample cars, once.

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
	$(PY) -m flexpipe.vehicle.warmup cars/sedan.toml cars/sedan_linkage.toml
	@touch $(STAMP)

straight: setup
	$(PY) -m flexpipe.scenarios straight --out out/straight

slalom: setup
	$(PY) -m flexpipe.scenarios slalom --out out/slalom

sweep: setup
	$(PY) -m flexpipe sweep sweeps/sample.toml --out out/sweep

paper: setup
	$(PY) -m flexpipe.halfcar.paper --out out/paper

# the tests that build Exudyn models, again on Exudyn's range-checked module (flexpipe loads
# its fast module, which has no index checks: an indexing error would not be reported there)
CHECKED_TESTS = tests/test_brackets.py tests/test_exudyn_body.py tests/test_force_laws.py \
	tests/test_inertia_coupling.py tests/test_mounts.py tests/test_node_state.py \
	tests/test_prewarp.py tests/test_linkage_car.py

# the suite runs on TEST_WORKERS pytest-xdist processes (a test file stays on one), each
# held to one BLAS / MKL / Numba thread so that the workers do not oversubscribe the cores
# (a worker that crashes ends the run at once, naming its test: xdist's restart of a
# crashed worker once left a run hanging; tests/conftest.py caps each worker's memory)
TEST_WORKERS ?= 2
PYTEST = OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 NUMBA_NUM_THREADS=1 \
	$(PY) -m pytest -q -n $(TEST_WORKERS) --dist loadfile --max-worker-restart=0

test: setup
	$(PYTEST)
	FLEXPIPE_EXUDYN=checked $(PYTEST) $(CHECKED_TESTS)

bench: setup
	$(PY) -m bench

lint: setup
	$(VENV)/bin/ruff check flexpipe tests bench

clean:
	rm -rf out .pytest_cache
