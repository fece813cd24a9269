# The two commands of the README. Both build .venv from nothing (Python 3.11 + the registry).
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
STAMP := $(VENV)/.installed

.PHONY: run test venv clean urdf bench install-check docs

# setup.py and the C kernels: an editable install compiles them once, so rebuild on change
$(STAMP): pyproject.toml setup.py $(wildcard csrc/*.c csrc/*.h)
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --upgrade pip
	$(VENV)/bin/python -m pip install --quiet -e ".[test]"
	touch $(STAMP)

venv: $(STAMP)

run: $(STAMP)
	$(VENV)/bin/pollard-pin run

test: $(STAMP)
	$(VENV)/bin/ruff check
	$(VENV)/bin/python -m pytest -q -n auto --dist loadfile --no-loadscope-reorder

urdf: $(STAMP)
	$(VENV)/bin/pollard-pin urdf --out models/pollard.urdf

# A plain `pip install .` (the wheel, no extras) in a fresh venv runs every command
install-check:
	$(PYTHON) scripts/check_install.py

# The site (Sphinx: docs/conf.py) → build/docs/index.html; a warning (a broken reference, a
# tutorial that fails) fails the build. The docs extra is installed once into .venv; where it
# cannot be (offline), scripts/check_docs.py says in one line what to install.
DOCS_STAMP := $(VENV)/.docs-installed
$(DOCS_STAMP): $(STAMP)
	@$(VENV)/bin/python -m pip install --quiet -e ".[docs]" >$(VENV)/docs-install.log 2>&1 \
		&& touch $@ || true

docs: $(DOCS_STAMP)
	@$(VENV)/bin/python scripts/check_docs.py
	MPLBACKEND=Agg $(VENV)/bin/python -m sphinx -E -b html -n -W --keep-going -q docs build/docs
	@echo "site: build/docs/index.html"

bench: $(STAMP)
	$(VENV)/bin/python scripts/benchmark.py

clean:
	rm -rf $(VENV) build *.egg-info pollard_pin/kinematics/_kernels.*.so \
		pollard_pin/painting/spray/_deposit.*.so docs/auto_tutorials \
		docs/sg_execution_times.rst
