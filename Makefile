# The two commands of the README are `make demo` and `make test`; both set up
# what they need themselves (scripts/setup-wasm.sh is idempotent).
SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
PORT ?= 8000
WASM_ENV = RUSTUP_TOOLCHAIN=$$(cat target/wasm-toolchain)
# The SIMD build has its own target directory, so neither build evicts the other.
WASM_SIMD_ENV = $(WASM_ENV) CARGO_TARGET_DIR=target/wasm-simd RUSTFLAGS="-C target-feature=+simd128"
WASM_BUILD = wasm-pack build --release --target web --no-typescript
# The page's module is optimised for size (opt-level z: 142 KB gzipped
# against 149 KB at s, measured in docs/web.md), the workers' module for
# size with speed (s: it runs the benchmark, the atlas and the trainer).
# Each has its own target directories, so neither rebuild evicts the other.
PAGE_ENV = CARGO_PROFILE_RELEASE_OPT_LEVEL=z CARGO_TARGET_DIR=target/wasm-page
PAGE_SIMD_ENV = CARGO_PROFILE_RELEASE_OPT_LEVEL=z CARGO_TARGET_DIR=target/wasm-page-simd
WORKER_OPT = CARGO_PROFILE_RELEASE_OPT_LEVEL=s
# Chromium leaves files in TMPDIR when it is stopped (about 40 MB a launch
# in scoped_dir folders); the browser tests keep theirs in one folder under
# target/, emptied at each start, so a long-lived machine's /tmp does not fill.
BROWSER_TMP = rm -rf target/browser-tmp && mkdir -p target/browser-tmp && TMPDIR=$(CURDIR)/target/browser-tmp

.PHONY: setup web dist test-dist offline test-offline npm test-npm demo test lint test-native test-wasm test-e2e test-fuzz fuzz-start fuzz-wait test-soak soak-start soak-wait fuzz soak bench bench-native bench-web figures atlas-figures weights clean-web python-env python-build python-start python-wait python-dev test-python wheel bench-python

## Make this machine able to build and test for wasm32 (idempotent).
setup:
	bash scripts/setup-wasm.sh

## Build the release wasm packages into www/pkg: the page's module (feature
## page: the demo of every arm, planar and in space, and its drawing) and
## the workers' module (feature worker: the atlas, the benchmark, the
## trainer and the figures, which run in Web Workers). Each twice: a
## baseline build and one with wasm SIMD (+simd128) for the networks'
## kernels, four builds in all; the page loads the SIMD ones where the
## browser validates SIMD, else the baseline (some hardened browser modes
## switch SIMD off). Each pair shares its JS glue (checked with cmp).
## Optimised for size (the page's at opt-level z with Talc for allocator,
## feature small-alloc; the workers' at s; 3 is 13 KB gzipped larger),
## then the debug `name` section stripped (cargo's
## strip also drops a section wasm-bindgen needs). The built-in networks'
## weights files go beside the page (www/weights/), which fetches them and
## hands them to its workers: no module embeds them (docs/web.md, "Bytes on
## the wire"). Last, the 3-D view of the arms in space with three.js, one
## module www/pkg/three-view.js (scripts/bundle.sh view). Each module's
## baseline and SIMD builds run at once (their own target directories;
## each link is one LTO code unit, so one core each): on 2 cores that
## takes about a minute off each pair.
PAGE = -- --no-default-features --features page,small-alloc
WORKER = --out-name redundant_ik_worker -- --no-default-features --features worker,small-alloc
web: setup
	( $(WASM_ENV) $(PAGE_ENV) $(WASM_BUILD) --out-dir www/pkg $(PAGE) ) & base=$$!; \
	  $(WASM_SIMD_ENV) $(PAGE_SIMD_ENV) $(WASM_BUILD) --out-dir target/pkg-simd $(PAGE); wait $$base
	cmp www/pkg/redundant_ik.js target/pkg-simd/redundant_ik.js
	cp target/pkg-simd/redundant_ik_bg.wasm www/pkg/redundant_ik_simd_bg.wasm
	( $(WASM_ENV) $(WORKER_OPT) $(WASM_BUILD) --out-dir target/pkg-worker $(WORKER) ) & base=$$!; \
	  $(WASM_SIMD_ENV) $(WORKER_OPT) $(WASM_BUILD) --out-dir target/pkg-worker-simd $(WORKER); wait $$base
	cmp target/pkg-worker/redundant_ik_worker.js target/pkg-worker-simd/redundant_ik_worker.js
	cp target/pkg-worker/redundant_ik_worker.js target/pkg-worker/redundant_ik_worker_bg.wasm www/pkg/
	cp target/pkg-worker-simd/redundant_ik_worker_bg.wasm www/pkg/redundant_ik_worker_simd_bg.wasm
	rm -f www/pkg/redundant_ik_space_bg.wasm www/pkg/redundant_ik_space_simd_bg.wasm www/pkg/redundant_ik_worker_space_bg.wasm www/pkg/redundant_ik_worker_space_simd_bg.wasm www/pkg/space-arms.js
	for f in www/pkg/*.wasm; do python3 scripts/strip-wasm-names.py $$f; done
	mkdir -p www/weights && cp weights/*.json www/weights/
	bash scripts/bundle.sh view
	@for f in www/pkg/*.wasm; do echo "$$f: $$(stat -c %s $$f) B, gzip -9 $$(gzip -9 -c $$f | wc -c) B"; done

## The page as one folder for any static host, dist/ (docs/hosting.md,
## copied in as its README.md), and that folder as an archive in target/:
## what index.html, embed.html and the custom element (redundant-ik-demo.js)
## load, with relative URLs only, so it works from any sub-path, and the
## page in one file (redundant-ik.html, make offline). The list of files is
## this recipe.
VERSION := $(shell sed -n 's/^version = "\(.*\)"$$/\1/p' Cargo.toml | head -n1)
DIST_TAR = target/redundant-ik-$(VERSION).tar.gz
dist: web
	rm -rf dist
	mkdir -p dist/pkg dist/weights
	cp www/*.html www/*.js www/*.css www/bench-native.json dist/
	cp www/pkg/*.js www/pkg/*.wasm dist/pkg/
	cp www/weights/*.json dist/weights/
	cp docs/hosting.md dist/README.md
	cp LICENSE-MIT LICENSE-APACHE dist/
	bash scripts/bundle.sh offline
	tar --sort=name --owner=0 --group=0 --numeric-owner --mtime=@0 \
	  --transform 's,^dist,redundant-ik-$(VERSION),' -czf $(DIST_TAR) dist
	@echo "dist/: $$(find dist -type f | wc -l) files, $$(du -sb dist | cut -f1) B; $(DIST_TAR): $$(stat -c %s $(DIST_TAR)) B"

## dist/ served under a sub-path (/courses/robotics/arm/) on a free port,
## and the page's smoke test there in headless Chromium (scripts/test-dist.sh).
test-dist: dist
	$(BROWSER_TMP) bash scripts/test-dist.sh

## Build, then serve www/ on http://127.0.0.1:$(PORT)/, with CORS, so the
## Embed button's element snippet also runs on a course page served from
## another port or host (docs/embedding.md, "What a host must send").
demo: web
	python3 scripts/serve.py --dir www --port $(PORT) --cors

## The page in one HTML file that opens from file:// with no server
## (dist/redundant-ik.html, under 3 MB): index.html with its styles and its
## one module inline, the SIMD builds of both modules, the shipped network
## sets' weights files and bench-native.json gzipped in base64 inside it
## (tools/bundle.mjs, esbuild pinned in tools/package-lock.json).
offline: web
	bash scripts/bundle.sh offline

## The offline file from file:// in headless Chromium (tests/bundle/offline.mjs).
test-offline: offline
	$(BROWSER_TMP) bash scripts/test-bundle.sh offline

## The npm package: target/npm/redundant-ik/ and its tarball
## target/npm/redundant-ik-VERSION.tgz (npm pack), the version Cargo.toml's:
## the element, the page's module, the compat entry (every file inline) and
## the notebook widget (docs/embedding.md).
npm: web
	bash scripts/bundle.sh npm

## The Python package (python/, docs/python.md). Its virtual environment
## target/py/venv, made here with the build backend, the test runner and
## the optional dependencies the tests use (python/requirements-test.txt,
## pinned, from PyPI).
PY_VENV = target/py/venv
# The machine's setup first (python3's venv; scripts/setup-wasm.sh), but
# not in python-start's background build: make test set it up already.
PY_SETUP ?= setup
python-env: $(PY_SETUP)
	test -x $(PY_VENV)/bin/python || python3 -m venv $(PY_VENV)
	$(PY_VENV)/bin/python -m pip install --quiet --disable-pip-version-check -r python/requirements-test.txt

## The package built as the tests build the crate (the dev profile) and
## installed into target/py/venv (maturin develop, an editable install: the
## package's Python files are read where they are).
python-build: python-env
	VIRTUAL_ENV=$(CURDIR)/$(PY_VENV) $(PY_VENV)/bin/maturin develop --quiet

## make test builds the package in the background beside the bundles'
## browser tests (python-start), which mostly wait, and test-python waits
## for it (python-wait); alone, test-python builds it itself.
PY_LOG = target/python-build.log
python-start:
	@mkdir -p target && rm -f $(PY_LOG) $(PY_LOG).status && touch $(PY_LOG).started
	@echo "python-build: started beside the next tests, its log in $(PY_LOG)"
	@( $(MAKE) --no-print-directory python-build PY_SETUP= > $(PY_LOG) 2>&1; echo $$? > $(PY_LOG).status ) &
python-wait:
	@if [ -f $(PY_LOG).started ]; then \
	  rm -f $(PY_LOG).started; \
	  for i in $$(seq 900); do [ -f $(PY_LOG).status ] && break; sleep 2; done; \
	  cat $(PY_LOG); [ -f $(PY_LOG).status ] || { echo "python-build: no result in 30 min"; exit 1; }; \
	  exit $$(cat $(PY_LOG).status); \
	else $(MAKE) --no-print-directory python-build; fi

## The package with the notebook widget's front end (the npm package's
## widget.js beside its Python files).
python-dev: npm python-wait
	cp target/npm/redundant-ik/widget.js python/redundant_ik/widget.js

## The Python tests (pytest, python/tests): the package against the
## command-line tool (byte for byte), its controller against the runs,
## bad input, pickling, the Dask example on two local workers, and the
## widget in headless Chromium.
test-python: python-dev
	cargo build --quiet --bin redundant-ik
	$(BROWSER_TMP) $(PY_VENV)/bin/python -m pytest -q python/tests

## The wheel (release build, abi3: one wheel for CPython 3.9 and later)
## into target/wheels, the widget's front end inside.
wheel: npm python-env
	cp target/npm/redundant-ik/widget.js python/redundant_ik/widget.js
	rm -f target/wheels/redundant_ik-*.whl
	$(PY_VENV)/bin/maturin build --release --quiet --out target/wheels
	@for w in target/wheels/redundant_ik-*.whl; do echo "$$w: $$(stat -c %s $$w) B"; done

## The peer benchmark (python/bench, not a test): the wheel against mink
## and Robotics Toolbox's NEO on the same Panda task, in target/bench-venv.
bench-python: wheel
	bash python/bench/run.sh

## The tarball installed into a scratch folder, served, and the element loaded
## from it three ways in headless Chromium (tests/bundle/npm.mjs).
test-npm: npm
	$(BROWSER_TMP) bash scripts/test-bundle.sh npm

## Everything CI runs: formatting, lints, native tests, the same core tests in
## headless Chromium, the end-to-end browser test of the page, and the short
## versions of the fuzzing and of the browser soak (docs/reliability.md),
## the page as dist/ builds it, served under a sub-path, the offline file
## from file:// and the npm package installed from its tarball, the Python
## package against the tool (its own virtual environment). The short
## fuzzing (its builds take the cores) runs beside the wasm tests and the
## page's build, whose browser runs mostly wait (fuzz-start, fuzz-wait);
## its report comes last. The Python package builds beside the bundles'
## browser tests (python-start, python-wait), and the short soak plays
## beside them (soak-start, soak-wait).
test: lint test-native fuzz-start test-wasm test-e2e python-start soak-start test-dist test-offline test-npm test-python soak-wait fuzz-wait

FUZZ_LOG = target/test-fuzz.log
fuzz-start:
	@mkdir -p target && rm -f $(FUZZ_LOG) $(FUZZ_LOG).status
	@echo "test-fuzz: started beside the next tests, its report in $(FUZZ_LOG)"
	@( $(MAKE) --no-print-directory test-fuzz > $(FUZZ_LOG) 2>&1; echo $$? > $(FUZZ_LOG).status ) &
fuzz-wait:
	@while [ ! -f $(FUZZ_LOG).status ]; do sleep 2; done
	@cat $(FUZZ_LOG)
	@exit $$(cat $(FUZZ_LOG).status)

lint: setup
	python3 scripts/check-house.py
	python3 scripts/check-docs-paths.py
	python3 scripts/check-page-facts.py
	cargo fmt --check
	cargo clippy --all-targets -- -D warnings
	RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib
	$(WASM_ENV) cargo clippy --target wasm32-unknown-unknown --lib --tests -- -D warnings
	$(WASM_SIMD_ENV) cargo clippy --target wasm32-unknown-unknown --lib --tests -- -D warnings
	$(WASM_ENV) cargo clippy --target wasm32-unknown-unknown --lib --no-default-features --features page,small-alloc -- -D warnings
	$(WASM_ENV) cargo clippy --target wasm32-unknown-unknown --lib --no-default-features --features worker,small-alloc -- -D warnings
	cargo clippy --lib --features python -- -D warnings

test-native:
	cargo test
	# The number reader and the weights files as the page's module is built
	# (without exact-floats; the trainer's options and reports unread).
	cargo test --lib --no-default-features --features page -- arm:: networks::reader

test-wasm: setup
	$(BROWSER_TMP) CHROMEDRIVER=/usr/bin/chromedriver $(WASM_ENV) wasm-pack test --headless --chrome
	$(BROWSER_TMP) CHROMEDRIVER=/usr/bin/chromedriver $(WASM_SIMD_ENV) wasm-pack test --headless --chrome -- --test core --test networks --test alloc --test atlas

test-e2e: web
	$(BROWSER_TMP) bash scripts/e2e.sh

## Every cargo-fuzz target (fuzz/) for FUZZ_RUNS executions (1 000 000 by
## default); new inputs grow the committed corpora in fuzz/corpus/.
FUZZ_RUNS ?= 1000000
fuzz:
	FUZZ_RUNS=$(FUZZ_RUNS) bash scripts/fuzz.sh

## CI's short fuzzing: 20 000 executions per target from the committed
## corpora, which stay untouched (new inputs go to a scratch directory).
test-fuzz:
	FUZZ_RUNS=20000 FUZZ_SCRATCH=1 FUZZ_WALL_SECONDS=600 bash scripts/fuzz.sh

## The browser soak (tests/e2e/soak.mjs) for SOAK_SECONDS (600 by default):
## random drags, methods, tasks, arms, obstacles, atlases, trainings and
## resizes; fails on any error or on memory growing more than 10%.
SOAK_SECONDS ?= 600
soak: web
	$(BROWSER_TMP) SOAK_SECONDS=$(SOAK_SECONDS) E2E_SCRIPT=soak.mjs bash scripts/e2e.sh

## CI's short soak: 60 seconds.
test-soak: web
	$(BROWSER_TMP) SOAK_SECONDS=60 E2E_SCRIPT=soak.mjs bash scripts/e2e.sh

## `make test` runs the short soak beside the tests of dist/, the offline
## file, the npm package and Python: a minute of the page playing whose
## checks are the memory's growth, not its speed. Its browser keeps its
## files in a folder of its own, since each browser test empties
## target/browser-tmp when it starts.
SOAK_LOG = target/test-soak.log
soak-start: web
	@mkdir -p target && rm -f $(SOAK_LOG) $(SOAK_LOG).status
	@echo "test-soak: started beside the next tests, its report in $(SOAK_LOG)"
	@( rm -rf target/browser-tmp-soak && mkdir -p target/browser-tmp-soak && \
	  TMPDIR=$(CURDIR)/target/browser-tmp-soak SOAK_SECONDS=60 E2E_SCRIPT=soak.mjs bash scripts/e2e.sh > $(SOAK_LOG) 2>&1; echo $$? > $(SOAK_LOG).status ) &
soak-wait:
	@while [ ! -f $(SOAK_LOG).status ]; do sleep 2; done
	@cat $(SOAK_LOG)
	@exit $$(cat $(SOAK_LOG).status)

## Criterion benchmarks (for developers; the README quotes `redundant-ik bench`).
bench:
	cargo bench

## `redundant-ik bench`, five runs, the median of each figure into
## www/bench-native.json (shown by the page's benchmark panel; in the README).
bench-native:
	cargo build --release
	python3 scripts/bench-native.py target/release/redundant-ik 5 www/bench-native.json

## The page's benchmark (window.demo.bench(), in a worker) in headless
## Chromium, three runs and their median.
bench-web: web
	bash scripts/bench-web.sh

## The robustness atlases of both tasks (41 x 41 cells, five methods) as SVG
## in docs/img, over the arm's reach and over the v network's trained
## obstacle box, with their tables of success rates (docs/atlas.md).
atlas-figures:
	cargo build --release
	for t in 1 2; do \
	  ./target/release/redundant-ik atlas --task $$t --out docs/img/atlas_task$$t.svg; \
	  ./target/release/redundant-ik atlas --task $$t --region 0.3,0.8,0.3,0.8 --out docs/img/atlas_task$${t}_box.svg; \
	done

## The paper's figures for both tasks and every method, as SVG.
figures:
	cargo run --release -- figure --all --out figures

## Retrain the shipped network weights reproducibly (fixed seeds).
weights:
	bash scripts/train-weights.sh
