#!/usr/bin/env bash
# Runs every cargo-fuzz target of fuzz/ for FUZZ_RUNS executions each
# (default 1 000 000) and prints one line per target: executions, seconds,
# executions per second, corpus size, crashes (always 0 here: a crash stops
# the script with libFuzzer's report and the input in fuzz/artifacts/).
#
#   FUZZ_RUNS=1000000 bash scripts/fuzz.sh            # `make fuzz`: grows fuzz/corpus
#   FUZZ_RUNS=20000 FUZZ_SCRATCH=1 bash scripts/fuzz.sh  # CI: corpus copied, repo untouched
#   FUZZ_TARGETS="weights session" bash scripts/fuzz.sh
#
# cargo-fuzz drives libFuzzer through nightly-only rustc flags for its
# sanitizers, so RUSTC_BOOTSTRAP=1 lets the stable toolchain build them
# (docs/reliability.md). The `weights` target runs under AddressSanitizer:
# it reaches the one piece of unsafe code (the AVX2 kernel of the
# networks). The others are safe Rust, where ASan adds nothing but halves
# the speed, so they run without a sanitizer (debug assertions and
# overflow checks stay on in every build).
set -euo pipefail
cd "$(dirname "$0")/.."
export RUSTC_BOOTSTRAP=1
RUNS=${FUZZ_RUNS:-1000000}
TARGETS=${FUZZ_TARGETS:-weights scene session atlas trainer urdf}
bash scripts/setup-fuzz.sh

sanitizer() {
  case $1 in
    weights) echo address ;;
    *) echo none ;;
  esac
}

scratch=""
if [[ -n ${FUZZ_SCRATCH:-} ]]; then
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
fi

printf '%-8s %12s %8s %9s %7s %7s\n' target executions seconds "exec/s" corpus crashes
for t in $TARGETS; do
  san=$(sanitizer "$t")
  cargo fuzz build -s "$san" "$t" >/dev/null 2>&1 || cargo fuzz build -s "$san" "$t"
  mkdir -p "fuzz/artifacts/$t"
  if [[ -n $scratch ]]; then
    # New inputs go to a scratch directory; the committed corpus is only read.
    dirs=("$scratch/$t" "fuzz/corpus/$t")
    mkdir -p "$scratch/$t"
  else
    dirs=("fuzz/corpus/$t")
  fi
  log=$(mktemp)
  start=$SECONDS
  # libFuzzer reports an input slower than -timeout, but its alarm handler
  # can deadlock when the slow input sits in malloc (seen with a hang in
  # the trainer): the wall-clock guard makes sure the script ends.
  if ! timeout -k 10 "${FUZZ_WALL_SECONDS:-3600}" cargo fuzz run -s "$san" "$t" "${dirs[@]}" -- \
      -runs="$RUNS" -timeout=10 -print_final_stats=1 \
      -artifact_prefix="fuzz/artifacts/$t/" >"$log" 2>&1; then
    tail -60 "$log"
    echo "fuzz target $t FAILED: the input is in fuzz/artifacts/$t/;" \
         "copy it to fuzz/regressions/$t/ once fixed (tests/fuzz.rs replays it)" >&2
    exit 1
  fi
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  corpus=$(find "fuzz/corpus/$t" -type f | wc -l)
  printf '%-8s %12s %8s %9s %7s %7s\n' "$t" "$execs" $((SECONDS - start)) "$rate" "$corpus" 0
  rm -f "$log"
done
