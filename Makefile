# Steakhouse Study: `make run` sets up and starts the platform; `make test` sets up and runs every test.
VENV ?= .venv
# Tests run in one worker process per CPU (pytest-xdist); PYTEST_WORKERS=0 runs them in this process. Work stealing
# gives each worker a contiguous half and lets an idle one take the tail of the other's queue; tests/conftest.py
# puts the slow modules first, so both finish together (docs/testing.md).
PYTEST_WORKERS ?= auto
PYTEST_DIST ?= worksteal
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed-$(shell cat pyproject.toml | cksum | cut -d' ' -f1)

.PHONY: setup run test lint browser postgres

setup: $(STAMP)

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

test: setup lint browser postgres
	@bash tests/tools/ensure_nginx.sh
	$(PY) -m pytest -n $(PYTEST_WORKERS) --dist $(PYTEST_DIST) $(PYTEST_ARGS)
