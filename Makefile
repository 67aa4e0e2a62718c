# Two commands do all set-up on a fresh machine: `make demo` and `make test`; `make docs` builds the site.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
DOCS_STAMP := $(VENV)/.installed-docs

.PHONY: demo test test-quick bench docs clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -e '.[test,mujoco]'
	@# the kernels compiled once, here, in parallel processes: the first throw then starts in seconds
	$(VENV)/bin/throwmap compile
	touch $(STAMP)

# the documentation's tools (the `docs` extra) on top of the package, installed as the package is
$(DOCS_STAMP): $(STAMP) pyproject.toml
	$(PY) -m pip install -q -e '.[docs]'
	touch $(DOCS_STAMP)

demo: $(STAMP)
	$(VENV)/bin/throwmap demo --out out

test: $(STAMP)
	@# the viewer's browser test needs Chromium; installed where we can (Debian, as root), never failing the target
	@{ command -v chromium && command -v chromedriver; } >/dev/null || (command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ] && \
		(apt-get update -qq && apt-get install -y -qq chromium chromium-driver) >/dev/null 2>&1) || true
	@# bytecode caches kept (an environment may ask Python not to write them): every test's subprocess would
	@# otherwise compile the package's sources again
	PYTHONDONTWRITEBYTECODE= $(PY) -m pytest -q -n auto --dist loadgroup --durations=15

# the quick tier for development: everything but the tests marked slow (the full suite above runs them all, as CI does)
test-quick: $(STAMP)
	PYTHONDONTWRITEBYTECODE= $(PY) -m pytest -q -n auto --dist loadgroup -m "not slow"

bench: $(STAMP)
	$(PY) benchmarks/bench_throw.py
	$(PY) benchmarks/bench_rigid_body.py
	$(PY) benchmarks/bench_engine.py
	$(PY) benchmarks/bench_analysis.py

# the documentation site into site/ (MkDocs, strict: any warning fails the build); NO_MKDOCS_2_WARNING silences
# the theme's end-of-life banner, which is not a build warning
docs: $(DOCS_STAMP)
	NO_MKDOCS_2_WARNING=1 $(VENV)/bin/mkdocs build --strict -d site

clean:
	rm -rf $(VENV) out site .pytest_cache .hypothesis
