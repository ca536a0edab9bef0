# The two commands of the README: `make book` and `make test`. Needs Python 3.11+ and Node 18+.
PYTHON ?= python3
VENV   := .venv
BIN    := $(CURDIR)/$(VENV)/bin
STAMP  := $(VENV)/.installed
THEME_STAMP := theme/node_modules/.installed
KERNEL := $(VENV)/share/jupyter/kernels/skilllib/kernel.json
CHAPTERS := $(sort $(wildcard notebooks/[0-9][0-9]_*.py))

# Kernels started by nbclient/nbmake/JupyterLab resolve `python` from PATH: make it the project's.
export PATH := $(BIN):$(PATH)
export MPLBACKEND := Agg
export PYDEVD_DISABLE_FILE_VALIDATION := 1

.PHONY: book serve test lab sync bench mutation mutation-sample clean venv theme

# Executes only the chapters whose code (or skilllib/, data/, environment.txt) changed since their last
# execution (cache in _build/cache); a prose-only edit re-renders in seconds.
book: venv theme
	$(BIN)/python scripts/build_site.py
	@echo "The site is in _build/html (open _build/html/index.html)."

# For authors: build, serve on http://127.0.0.1:8000 and rebuild on every save (a chapter's .py included).
serve: venv theme
	$(BIN)/python scripts/serve.py

# Every chapter is executed once: nbmake runs copies in _executed/ and keeps their outputs
# (--overwrite; nbmake skips any path with a _build folder), in the chapters' kernel "skilllib" with
# retina figures as the site build, and the tests of the book's site (marker book_site) render those
# outputs (BOOK_EXECUTED; scripts/build_site.py --executed) instead of executing again; they also fill
# the site's cache. Two lanes use the two cores: (a) nbmake, then the book_site tests and the JupyterLab
# test (marker jupyterlab), then the two longest other tests (LANE_A: the seed survey recomputed, the
# wheel installed in a fresh venv; they balance the lanes), its output kept in _build/test-book.log and
# shown at the end; (b) every other test. Both must pass.
EXECUTED := _executed
LANE_A := tests/cohort/test_cohort.py::test_the_seed_rule_is_recomputed_from_scratch tests/test_install.py
test: venv theme
	rm -rf $(EXECUTED) && mkdir -p $(EXECUTED) _build/ipython/profile_default
	cp notebooks/[0-9][0-9]_*.ipynb $(EXECUTED)/
	echo 'c.InlineBackend.figure_formats = {"retina"}' > _build/ipython/profile_default/ipython_kernel_config.py
	@( IPYTHONDIR=$(CURDIR)/_build/ipython \
	    $(BIN)/python -m pytest -p no:cacheprovider --nbmake --nbmake-timeout=900 --overwrite $(EXECUTED)/[0-9][0-9]_*.ipynb \
	  && BOOK_EXECUTED=$(CURDIR)/$(EXECUTED) $(BIN)/python -m pytest -p no:cacheprovider tests -m "book_site or jupyterlab" \
	  && $(BIN)/python -m pytest -p no:cacheprovider $(LANE_A) \
	) > _build/test-book.log 2>&1 & book=$$!; \
	trap 'kill $$book 2>/dev/null' INT TERM; \
	echo "lane (a): nbmake of the chapters, then the book's site tests, JupyterLab and $(LANE_A) (log: _build/test-book.log)"; \
	echo "lane (b): every other test"; \
	$(BIN)/python -m pytest tests -m "not (book_site or jupyterlab)" $(addprefix --deselect ,$(LANE_A)); other=$$?; \
	wait $$book; lane_a=$$?; \
	echo "==================== lane (a): nbmake and the book's site ===================="; \
	cat _build/test-book.log; \
	echo "make test: lane (a) exit $$lane_a, lane (b) exit $$other"; \
	test $$lane_a -eq 0 -a $$other -eq 0

# JupyterLab on the repository with chapter 1 open, the book's kernel (scripts/kernel.py) and MyST rendering.
lab: venv
	$(BIN)/python scripts/lab.py

# Refresh every chapter's notebook from its percent script, without outputs.
sync: venv
	$(BIN)/jupytext --sync $(CHAPTERS)
	$(BIN)/jupyter nbconvert --clear-output --inplace --log-level=WARN $(CHAPTERS:.py=.ipynb)

bench: venv
	$(BIN)/python benchmarks/bench_sparc.py

# Mutation testing of the library's core modules, outside `make test`. BLAS and OpenMP on one thread, as
# forked test processes can hang on thread pools the parent started. mutmut's configuration is in
# pyproject.toml; the mutants judged equivalent are in tests/mutation_equivalent.toml.
# `make mutation`: every mutant (about 4,700; many hours on two cores).
# `make mutation-sample`: the systematic 10 % sample (benchmarks/README.md "Mutation testing"), every
# mutant whose number ends in 7 (about 450; about an hour on two cores).
SAMPLE = skilllib.*__mutmut_*7
MUTMUT = OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 $(BIN)/mutmut run --max-children 2
mutation: venv
	rm -rf mutants && mkdir -p _build
	$(MUTMUT) > _build/mutmut.log 2>&1 || (tail -c 2000 _build/mutmut.log; exit 1)
	$(BIN)/python scripts/mutation_report.py

mutation-sample: venv
	rm -rf mutants && mkdir -p _build
	$(MUTMUT) '$(SAMPLE)' > _build/mutmut.log 2>&1 || (tail -c 2000 _build/mutmut.log; exit 1)
	$(BIN)/python scripts/mutation_report.py --only '$(SAMPLE)'

venv: $(STAMP) $(KERNEL)
$(STAMP): environment.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r environment.txt
	touch $(STAMP)

# The chapters' kernel, "skilllib": figures inline, MPLBACKEND=Agg for the processes a chapter starts.
$(KERNEL): $(STAMP) scripts/kernel.py
	$(BIN)/python scripts/kernel.py

theme: $(THEME_STAMP)
$(THEME_STAMP): theme/package-lock.json theme/package.json
	npm ci --prefix theme --no-audit --no-fund
	touch $(THEME_STAMP)

clean:
	rm -rf _build _executed .pytest_cache mutants
