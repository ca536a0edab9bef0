# The two commands of the README: `make book` and `make test`. Needs Python 3.11+ and Node 18+.
PYTHON ?= python3
VENV   := .venv
BIN    := $(CURDIR)/$(VENV)/bin
STAMP  := $(VENV)/.installed
THEME_STAMP := theme/node_modules/.installed
CHAPTERS := $(sort $(wildcard notebooks/[0-9][0-9]_*.py))

# Kernels started by nbclient/nbmake/JupyterLab resolve `python` from PATH: make it the project's.
export PATH := $(BIN):$(PATH)
export MPLBACKEND := Agg
export PYDEVD_DISABLE_FILE_VALIDATION := 1

.PHONY: book test lab sync bench mutation clean venv theme

book: venv theme
	$(BIN)/python scripts/build_site.py
	@echo "The site is in _build/html (open _build/html/index.html)."

# Every chapter is executed once: nbmake runs copies in _executed/ and keeps their outputs
# (--overwrite; nbmake skips any path with a _build folder), with the kernel settings of the site build (inline retina figures), and the site tests
# render those outputs (BOOK_EXECUTED; scripts/build_site.py --executed) instead of executing again.
EXECUTED := _executed
test: venv theme
	rm -rf $(EXECUTED) && mkdir -p $(EXECUTED) _build/ipython/profile_default
	cp notebooks/[0-9][0-9]_*.ipynb $(EXECUTED)/
	echo 'c.InlineBackend.figure_formats = {"retina"}' > _build/ipython/profile_default/ipython_kernel_config.py
	IPYTHONDIR=$(CURDIR)/_build/ipython MPLBACKEND=module://matplotlib_inline.backend_inline \
	  $(BIN)/python -m pytest --nbmake --nbmake-timeout=900 --overwrite $(EXECUTED)/[0-9][0-9]_*.ipynb
	BOOK_EXECUTED=$(CURDIR)/$(EXECUTED) $(BIN)/python -m pytest tests

lab: venv
	$(BIN)/jupyter lab --notebook-dir=notebooks $(if $(filter 0,$(shell id -u)),--allow-root)

# Refresh every chapter's notebook from its percent script, without outputs.
sync: venv
	$(BIN)/jupytext --sync $(CHAPTERS)
	$(BIN)/jupyter nbconvert --clear-output --inplace --log-level=WARN $(CHAPTERS:.py=.ipynb)

bench: venv
	$(BIN)/python benchmarks/bench_sparc.py

# Mutation testing of the library's core modules (outside `make test`: about an hour on two cores).
# mutmut's configuration is in pyproject.toml; the equivalent mutants are in tests/mutation_equivalent.toml.
mutation: venv
	rm -rf mutants && mkdir -p _build
	$(BIN)/mutmut run --max-children 2 > _build/mutmut.log 2>&1 || (tail -c 2000 _build/mutmut.log; exit 1)
	$(BIN)/python scripts/mutation_report.py

venv: $(STAMP)
$(STAMP): environment.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r environment.txt
	touch $(STAMP)

theme: $(THEME_STAMP)
$(THEME_STAMP): theme/package-lock.json theme/package.json
	npm ci --prefix theme --no-audit --no-fund
	touch $(THEME_STAMP)

clean:
	rm -rf _build _executed .pytest_cache mutants
