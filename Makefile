# Steakhouse Study: `make run` sets up and starts the platform; `make test` sets up and runs every test.
VENV ?= .venv
# Tests run in two worker processes per CPU (pytest-xdist): much of a test's time is spent waiting on a server, a
# browser or a trial's clock, and two per CPU keep the CPUs busy (docs/testing.md measures it); PYTEST_WORKERS=0
# runs them in this process. Work stealing gives each worker a contiguous share and lets an idle one take the tail
# of another's queue; tests/conftest.py puts the slow modules first, so the workers finish together.
PYTEST_WORKERS ?= $(shell echo $$((2 * $$(nproc))))
PYTEST_DIST ?= worksteal
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed-$(shell cat pyproject.toml | cksum | cut -d' ' -f1)
# The example plug-in package (docs/robots.md) is installed for the tests, never by `make run`.
EXAMPLES_STAMP := $(VENV)/.examples-$(shell cat examples/mylab_robots/pyproject.toml | cksum | cut -d' ' -f1)

.PHONY: setup run test lint browser postgres examples flake-hunt

setup: $(STAMP)

examples: $(EXAMPLES_STAMP)

$(EXAMPLES_STAMP): $(STAMP) examples/mylab_robots/pyproject.toml
	$(PY) -m pip install -q --no-deps -e examples/mylab_robots
	rm -f $(VENV)/.examples-*
	touch $@

$(STAMP): pyproject.toml
	test -x $(PY) || python3 -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -e '.[test]'
	rm -f $(VENV)/.installed-*
	touch $@

run: setup
	$(VENV)/bin/steakhouse serve

browser:
	@bash tests/tools/ensure_chromium.sh

postgres:
	@bash tests/tools/ensure_postgres.sh

# The style gates (config in pyproject.toml; also run by pre-commit: .pre-commit-config.yaml).
lint: setup
	$(VENV)/bin/ruff check .
	$(VENV)/bin/mypy

test: setup examples lint browser postgres
	@bash tests/tools/ensure_nginx.sh
	$(PY) -m pytest -n $(PYTEST_WORKERS) --dist $(PYTEST_DIST) --cov --cov-report= --durations=15 $(PYTEST_ARGS)
	$(PY) tests/tools/coverage_floor.py

# The whole suite from a fresh clone with every core kept busy: RUNS times, then RANDOM_RUNS times in a random order
# (docs/testing.md, "Flake hunt").
RUNS ?= 5
RANDOM_RUNS ?= 1
flake-hunt:
	@bash tests/tools/flake_hunt.sh $(RUNS) $(RANDOM_RUNS)
