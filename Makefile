# The two commands of the README are `make demo` and `make test`; both set up
# what they need themselves (scripts/setup-wasm.sh is idempotent).
SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
PORT ?= 8000
WASM_ENV = RUSTUP_TOOLCHAIN=$$(cat target/wasm-toolchain)

.PHONY: setup web demo test lint test-native test-wasm test-e2e bench figures weights clean-web

## Make this machine able to build and test for wasm32 (idempotent).
setup:
	bash scripts/setup-wasm.sh

## Build the release wasm package into www/pkg: optimised for size for this
## build only (opt-level s; z came out larger), then the debug `name` section
## stripped (cargo's strip also drops a section wasm-bindgen needs).
web: setup
	CARGO_PROFILE_RELEASE_OPT_LEVEL=s $(WASM_ENV) wasm-pack build --release --target web --no-typescript --out-dir www/pkg
	python3 scripts/strip-wasm-names.py www/pkg/redundant_ik_bg.wasm
	@ls -l www/pkg/*.wasm

## Build, then serve www/ on http://127.0.0.1:$(PORT)/.
demo: web
	python3 scripts/serve.py --dir www --port $(PORT)

## Everything CI runs: formatting, lints, native tests, the same core tests in
## headless Chromium, and the end-to-end browser test of the page.
test: lint test-native test-wasm test-e2e

lint:
	cargo fmt --check
	cargo clippy --all-targets -- -D warnings

test-native:
	cargo test

test-wasm: setup
	CHROMEDRIVER=/usr/bin/chromedriver $(WASM_ENV) wasm-pack test --headless --chrome

test-e2e: web
	bash scripts/e2e.sh

## Criterion benchmarks (numbers in the README).
bench:
	cargo bench

## The paper's figures for both tasks and every mode, as SVG.
figures:
	cargo run --release -- figure --all --out figures

## Retrain the shipped network weights reproducibly (fixed seeds).
weights:
	bash scripts/train-weights.sh
