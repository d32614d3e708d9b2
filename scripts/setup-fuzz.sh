#!/usr/bin/env bash
# Installs cargo-fuzz (from crates.io) if this machine lacks it; idempotent.
# libFuzzer itself comes with the libfuzzer-sys crate and needs a C++
# compiler (g++, on our machines).
set -euo pipefail
CARGO_FUZZ_VERSION=0.13.2
if cargo fuzz --version 2>/dev/null | grep -q "$CARGO_FUZZ_VERSION"; then
  exit 0
fi
command -v c++ >/dev/null || { echo "cargo-fuzz needs a C++ compiler: apt-get install g++" >&2; exit 1; }
echo "installing cargo-fuzz $CARGO_FUZZ_VERSION (once)" >&2
cargo install cargo-fuzz --locked --version "$CARGO_FUZZ_VERSION"
