# shaftfe — `make demo` and `make test` work on a fresh machine with nothing but Python.
#
# Installs are locked: `make demo`, `make test` and CI (.ci/run) install the exact versions in
# requirements-lock.txt (a pip constraints file; pyproject.toml keeps the loose ranges for
# library users). `make lock` re-resolves the newest allowed versions and rewrites the lock;
# `make test-latest` runs the suite on the newest allowed versions in a separate venv, so that
# drift shows up before users meet it.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
LOCK   := requirements-lock.txt
PIP    := python -m pip --disable-pip-version-check

.PHONY: demo test test-latest lock bench lint clean tables identical

$(STAMP): pyproject.toml $(LOCK)
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/$(PIP) install --quiet -c $(LOCK) pip
	$(BIN)/$(PIP) install --quiet -c $(LOCK) -e '.[dev]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/shaftfe demo --out reports/x2_57
	@echo "open the report: file://$(CURDIR)/reports/x2_57/index.html"

# The suite runs in two worker processes (pytest-xdist), a test file per worker so that a file's
# module fixtures are built once: 314 s against 413-588 s in one process on this 2-core machine.
# Two at most, whatever the core count: the heaviest files take a few GiB each.
PYTEST_PAR := -n auto --maxprocesses 2 --dist loadfile

test: $(STAMP)
	$(BIN)/ruff check shaftfe tests benchmarks
	$(BIN)/python -m pytest $(PYTEST_PAR)

# The newest versions pyproject.toml allows, in .venv-latest (the lock is not used).
test-latest:
	rm -rf .venv-latest
	$(PYTHON) -m venv .venv-latest
	.venv-latest/bin/$(PIP) install --quiet --upgrade pip
	.venv-latest/bin/$(PIP) install --quiet --upgrade --upgrade-strategy eager -e '.[dev]'
	.venv-latest/bin/$(PIP) freeze --all --exclude-editable \
	  | grep -v -E '^(setuptools|wheel)==' > .venv-latest/versions.txt
	@echo "newest allowed versions: .venv-latest/versions.txt"
	@diff -u $(LOCK) .venv-latest/versions.txt | grep '^[-+][A-Za-z]' || echo "same as the lock"
	.venv-latest/bin/ruff check shaftfe tests benchmarks
	.venv-latest/bin/python -m pytest $(PYTEST_PAR)

# Re-resolve the lock: a scratch venv, the newest versions pyproject.toml allows, frozen.
lock:
	rm -rf .venv-lock
	$(PYTHON) -m venv .venv-lock
	.venv-lock/bin/$(PIP) install --quiet --upgrade pip
	.venv-lock/bin/$(PIP) install --quiet '.[dev]'
	{ echo "# Exact versions that make demo / make test / .ci/run install (pip constraints)."; \
	  echo "# Regenerate with: make lock   (then run make test). Resolved on $$(uname -m),"; \
	  echo "# Python $$(.venv-lock/bin/python -c 'import platform; print(platform.python_version())'); a package this platform does not need is ignored."; \
	  .venv-lock/bin/$(PIP) freeze --all --exclude shaftfe | grep -v -E '^(setuptools|wheel)=='; \
	} > $(LOCK).new
	mv $(LOCK).new $(LOCK)
	rm -rf .venv-lock build
	@echo "wrote $(LOCK)"

bench: $(STAMP)
	$(BIN)/python -m benchmarks

lint: $(STAMP)
	$(BIN)/ruff check shaftfe tests benchmarks

clean:
	rm -rf $(VENV) .venv-latest .venv-lock .pytest_cache .ruff_cache build *.egg-info

# The tables the docs quote (docs/VALIDATION.md, STUDIES.md, STRENGTH.md, PERFORMANCE.md; ARCHITECTURE.md's module
# index), recomputed through the API (docs/tables.py; `python docs/tables.py modules` for the index alone).
tables: $(STAMP)
	$(BIN)/python docs/tables.py

# Record the summaries that a no-behaviour-change refactoring must leave byte-identical
# (benchmarks/identical_results.py): make identical BEFORE=<commit> records that commit and this
# tree and compares them (exit 1 on any difference); without BEFORE, records this tree into DIR.
identical: $(STAMP)
	$(if $(BEFORE),$(BIN)/python -m benchmarks.identical_results against $(BEFORE),$(BIN)/python -m benchmarks.identical_results record $(or $(DIR),reports/identical))
