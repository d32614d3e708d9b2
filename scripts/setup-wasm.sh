#!/usr/bin/env bash
# Make this machine able to build and test redundant-ik for wasm32-unknown-unknown.
#
# Idempotent: on a ready machine it only checks and takes a few seconds.
# Follows shared/TOOLCHAIN.md: use rustup's wasm32 target when the active
# toolchain has it (or `rustup target add` works); otherwise build the wasm32
# standard library for Debian's rustc-web (1.96) and link it into rustup as
# the `debian-web` toolchain.
#
# SETUP_WASM_FORCE_DEBIAN=1 skips the rustup route (to test the fallback).
#
# Writes the toolchain to use for wasm builds to target/wasm-toolchain, so:
#   RUSTUP_TOOLCHAIN=$(cat target/wasm-toolchain) wasm-pack build --target web --release
#   CHROMEDRIVER=/usr/bin/chromedriver RUSTUP_TOOLCHAIN=$(cat target/wasm-toolchain) \
#       wasm-pack test --headless --chrome
#
# Also installs wasm-bindgen-cli (exactly the version in Cargo.lock), wasm-pack,
# chromium + chromedriver, node and npm, python3's venv (for the Python
# package's tests), and writes webdriver.json (Chromium flags needed as root).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TARGET=wasm32-unknown-unknown
DEBIAN_TOOLCHAIN=debian-web
DEBIAN_RUSTC_VERSION=1.96
DEBIAN_SYSROOT=/usr
DEBIAN_PKGS=(rustc-web cargo-web rust-web-src lld-22)
WASM_PACK_VERSION=0.15.1
# Rust tooling needs ~/.cargo/bin (rustup, cargo installs) on PATH.
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

SECONDS=0
log() { printf '[setup-wasm %3ss] %s\n' "$SECONDS" "$*" >&2; }
die() { log "ERROR: $*"; exit 1; }

if [ "$(id -u)" -eq 0 ]; then SUDO=(); else SUDO=(sudo); fi
APT_UPDATED=0
apt_install() {
    if [ "$APT_UPDATED" -eq 0 ]; then
        log "apt-get update"
        "${SUDO[@]}" apt-get update -qq >&2
        APT_UPDATED=1
    fi
    log "apt-get install $*"
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@" >&2
}
pkgs_installed() {
    local p
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || return 1
    done
}

# True if the given toolchain ("" = whatever is active in $ROOT) can compile
# a std-using crate (plus link libtest, needed by wasm-pack test) for wasm32.
toolchain_has_wasm_std() {
    local tc="$1" tmp rc=0
    tmp="$(mktemp -d)"
    cat > "$tmp/check.rs" <<'EOF'
#![feature(test)]
extern crate test;
pub fn f(n: usize) -> Vec<String> { (0..n).map(|i| format!("{i}")).collect() }
EOF
    if [ -n "$tc" ]; then
        (cd "$tmp" && env -u RUSTC -u RUSTFLAGS RUSTUP_TOOLCHAIN="$tc" RUSTC_BOOTSTRAP=1 \
            rustc --edition 2021 --target "$TARGET" --crate-type lib --emit metadata \
            -o "$tmp/out.rmeta" "$tmp/check.rs") >/dev/null 2>&1 || rc=1
    else
        (cd "$ROOT" && env -u RUSTUP_TOOLCHAIN -u RUSTC -u RUSTFLAGS RUSTC_BOOTSTRAP=1 \
            rustc --edition 2021 --target "$TARGET" --crate-type lib --emit metadata \
            -o "$tmp/out.rmeta" "$tmp/check.rs") >/dev/null 2>&1 || rc=1
    fi
    rm -rf "$tmp"
    return "$rc"
}

active_toolchain() {
    (cd "$ROOT" && env -u RUSTUP_TOOLCHAIN rustup show active-toolchain 2>/dev/null) | awk 'NR==1{print $1}'
}

debian_rustc_ok() {
    [ -x /usr/bin/rustc ] && /usr/bin/rustc --version 2>/dev/null | grep -q "^rustc ${DEBIAN_RUSTC_VERSION}\." \
        && pkgs_installed "${DEBIAN_PKGS[@]}"
}

debian_linked() {
    rustup toolchain list 2>/dev/null | awk '{print $1}' | grep -qx "$DEBIAN_TOOLCHAIN"
}

# Build the wasm32 std/panic_abort/test rlibs from Debian's rust-web-src and
# install them into /usr/lib/rustlib/wasm32-unknown-unknown/lib.
build_debian_wasm_std() {
    local libdir="$DEBIAN_SYSROOT/lib/rustlib/$TARGET/lib" scratch
    scratch="$(mktemp -d /tmp/wasm-std-build.XXXXXX)"
    log "building wasm32 std from /usr/lib/rustlib/src/rust in $scratch (about 1-2 min)"
    mkdir -p "$scratch/src"
    cat > "$scratch/Cargo.toml" <<'EOF'
[package]
name = "wasm_std_scratch"
version = "0.0.0"
edition = "2021"

[lib]
path = "src/lib.rs"

[workspace]
EOF
    : > "$scratch/src/lib.rs"
    # Clean environment: no rustup toolchain override, no project target dir,
    # Debian's cargo and rustc explicitly.
    (cd "$scratch" && env -u RUSTUP_TOOLCHAIN -u CARGO_TARGET_DIR -u CARGO_BUILD_TARGET \
        -u CARGO_BUILD_TARGET_DIR -u RUSTC_WRAPPER -u RUSTC_WORKSPACE_WRAPPER \
        -u CARGO_ENCODED_RUSTFLAGS -u CARGO_BUILD_RUSTFLAGS -u RUSTDOCFLAGS \
        RUSTC=/usr/bin/rustc RUSTDOC=/usr/bin/rustdoc RUSTC_BOOTSTRAP=1 RUSTFLAGS=-Cembed-bitcode=yes \
        /usr/bin/cargo build --release --target "$TARGET" -Zbuild-std=std,panic_abort,test) >&2 \
        || die "building the wasm32 std failed (scratch dir kept: $scratch)"
    local deps="$scratch/target/$TARGET/release/deps"
    ls "$deps"/libstd-*.rlib >/dev/null 2>&1 || die "no libstd rlib in $deps"
    "${SUDO[@]}" mkdir -p "$libdir"
    # Drop any stale rlibs (e.g. from an older rustc-web) before installing.
    "${SUDO[@]}" find "$libdir" -maxdepth 1 -name 'lib*.rlib' -delete
    local f n=0
    for f in "$deps"/lib*.rlib; do
        case "$(basename "$f")" in libwasm_std_scratch-*) continue ;; esac
        "${SUDO[@]}" cp "$f" "$libdir/"
        n=$((n + 1))
    done
    log "installed $n rlibs into $libdir"
    rm -rf "$scratch"
}

setup_debian_toolchain() {
    if debian_rustc_ok; then
        log "Debian rustc-web already installed: $(/usr/bin/rustc --version)"
    else
        apt_install "${DEBIAN_PKGS[@]}"
        debian_rustc_ok || die "/usr/bin/rustc is not ${DEBIAN_RUSTC_VERSION}.x after installing ${DEBIAN_PKGS[*]}: $(/usr/bin/rustc --version 2>&1 || true)"
        log "installed $(/usr/bin/rustc --version)"
    fi
    if debian_linked; then
        log "rustup toolchain $DEBIAN_TOOLCHAIN already linked"
    else
        log "rustup toolchain link $DEBIAN_TOOLCHAIN $DEBIAN_SYSROOT"
        rustup toolchain link "$DEBIAN_TOOLCHAIN" "$DEBIAN_SYSROOT"
    fi
    if toolchain_has_wasm_std "$DEBIAN_TOOLCHAIN"; then
        log "wasm32 std already installed for $DEBIAN_TOOLCHAIN"
    else
        build_debian_wasm_std
        toolchain_has_wasm_std "$DEBIAN_TOOLCHAIN" || die "$DEBIAN_TOOLCHAIN still cannot compile for $TARGET"
    fi
}

# ---------------------------------------------------------------- 1. toolchain
command -v rustup >/dev/null || die "rustup not found (expected rustup with the stable toolchain)"
ACTIVE="$(active_toolchain)"
[ -n "$ACTIVE" ] || die "cannot determine rustup's active toolchain"
WASM_TC=""
if [ "${SETUP_WASM_FORCE_DEBIAN:-0}" = 1 ]; then
    # For testing the fallback on a machine where rustup's route works.
    log "SETUP_WASM_FORCE_DEBIAN=1: using Debian's rustc-web"
    setup_debian_toolchain
    WASM_TC="$DEBIAN_TOOLCHAIN"
elif toolchain_has_wasm_std ""; then
    log "rustup toolchain $ACTIVE already has $TARGET"
    WASM_TC="$ACTIVE"
elif debian_rustc_ok && debian_linked && toolchain_has_wasm_std "$DEBIAN_TOOLCHAIN"; then
    # Already set up by an earlier run: don't spend 20 s re-trying rustup.
    log "using existing $DEBIAN_TOOLCHAIN toolchain ($(/usr/bin/rustc --version))"
    WASM_TC="$DEBIAN_TOOLCHAIN"
else
    log "trying: rustup target add $TARGET (toolchain $ACTIVE, 20 s limit)"
    if (cd "$ROOT" && env -u RUSTUP_TOOLCHAIN timeout 20 rustup target add --toolchain "$ACTIVE" "$TARGET") >&2 2>&1 \
        && toolchain_has_wasm_std ""; then
        log "rustup target add worked"
        WASM_TC="$ACTIVE"
    else
        log "rustup target add failed; falling back to Debian's rustc-web (shared/TOOLCHAIN.md)"
        setup_debian_toolchain
        WASM_TC="$DEBIAN_TOOLCHAIN"
    fi
fi
mkdir -p "$ROOT/target"
printf '%s\n' "$WASM_TC" > "$ROOT/target/wasm-toolchain"
log "wasm toolchain: $WASM_TC ($(RUSTUP_TOOLCHAIN="$WASM_TC" rustc --version)) -> target/wasm-toolchain"

# ------------------------------------------------------------ 2. webdriver.json
WEBDRIVER_JSON='{"goog:chromeOptions": {"args": ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run"]}}'
if [ "$(cat "$ROOT/webdriver.json" 2>/dev/null || true)" != "$WEBDRIVER_JSON" ]; then
    printf '%s\n' "$WEBDRIVER_JSON" > "$ROOT/webdriver.json"
    log "wrote webdriver.json"
fi

# -------------------------------------------------------- 3. wasm-bindgen-cli
wasm_bindgen_version() {
    [ -f "$ROOT/Cargo.lock" ] || return 0
    awk '
        /^\[\[package\]\]/ { name = "" }
        /^name = /         { name = $3 }
        /^version = / && name == "\"wasm-bindgen\"" { gsub(/"/, "", $3); print $3; exit }
    ' "$ROOT/Cargo.lock"
}
WB_VERSION="$(wasm_bindgen_version)"
if [ -z "$WB_VERSION" ]; then
    log "no wasm-bindgen in Cargo.lock yet: cargo generate-lockfile"
    (cd "$ROOT" && env -u RUSTUP_TOOLCHAIN cargo generate-lockfile) >&2 2>&1 \
        || log "cargo generate-lockfile failed"
    WB_VERSION="$(wasm_bindgen_version)"
fi
if [ -z "$WB_VERSION" ]; then
    # Fall back to the exact pin in Cargo.toml (wasm-bindgen = "=X.Y.Z").
    WB_VERSION="$(sed -n 's/^wasm-bindgen *= *.*"=\([0-9][0-9.]*\)".*/\1/p' "$ROOT/Cargo.toml" | head -n1)"
fi
[ -n "$WB_VERSION" ] || die "cannot determine the wasm-bindgen version (Cargo.lock / Cargo.toml)"
if wasm-bindgen --version 2>/dev/null | grep -q "^wasm-bindgen $WB_VERSION\( \|$\)"; then
    log "wasm-bindgen $WB_VERSION already installed"
else
    log "cargo install wasm-bindgen-cli --version $WB_VERSION (5-6 min on 2 cores)"
    (cd / && rustup run stable cargo install wasm-bindgen-cli --version "$WB_VERSION") >&2
    wasm-bindgen --version | grep -q "^wasm-bindgen $WB_VERSION" || die "wasm-bindgen is not $WB_VERSION after install"
fi

# ----------------------------------------------------------------- 4. wasm-pack
if command -v wasm-pack >/dev/null; then
    log "$(wasm-pack --version) already installed"
else
    # The version this project is tested with, with its own lock file, so a new
    # machine gets the same tool whatever crates.io has published since.
    log "cargo install wasm-pack $WASM_PACK_VERSION (about 5 min)"
    (cd / && rustup run stable cargo install wasm-pack --version "$WASM_PACK_VERSION" --locked) >&2
fi

# ------------------------------------------------------- 5. chromium + driver
if [ -x /usr/bin/chromium ] && [ -x /usr/bin/chromedriver ]; then
    log "chromium and chromedriver already installed"
else
    apt_install chromium chromium-driver
fi

# ------------------------------------------------------------------- 6. node
if command -v node >/dev/null && command -v npm >/dev/null; then
    log "node $(node --version), npm $(npm --version)"
else
    log "node/npm missing"
    apt_install nodejs npm
    log "node $(node --version), npm $(npm --version)"
fi

# ------------------------------------------------------------ 7. python venv
# The Python package's tests make their own virtual environment (make
# python-env); Debian's python3 needs python3-venv for that (ensurepip).
if python3 -c 'import ensurepip, venv' 2>/dev/null; then
    log "$(python3 --version) with venv"
else
    apt_install python3-venv
    log "$(python3 --version) with venv"
fi

log "ready: toolchain=$WASM_TC, $(wasm-bindgen --version), $(wasm-pack --version), $(/usr/bin/chromium --version 2>/dev/null), $(/usr/bin/chromedriver --version 2>/dev/null | cut -d' ' -f1-2)"
