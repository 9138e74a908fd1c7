#!/usr/bin/env bash
# Runs every fuzzer long, one after the other, going on after a crash (libFuzzer's fork mode),
# and prints per fuzzer its executions, coverage as fork mode counts it (cov: code points, ft:
# features; not the same count as a plain run's), the crashes, hangs and out-of-memory inputs
# found (kept under BUILD_DIR/artifacts/NAME/; minimise one with
# `NAME_fuzzer -minimize_crash=1 -runs=100000 FILE`, then keep it in tests/fuzz/regressions/NAME/)
# and the inputs of regressions/NAME/ that still fail (run one by one first: fork mode passes
# over a seed that crashes). Exits non-zero if anything was found or still fails.
#   tests/fuzz/run_long.sh [SECONDS_PER_FUZZER]      (default 600)
# Environment: FUZZ_BUILD_DIR (default build-fuzz beside the source tree), FUZZ_JOBS (build
# jobs, default nproc), FUZZERS (names, default every one of fuzzers.txt).
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
seconds=${1:-600}
build=${FUZZ_BUILD_DIR:-$src/../build-fuzz}
read -ra names <<< "${FUZZERS:-$(tr '\n' ' ' < "$src/tests/fuzz/fuzzers.txt")}"
bash "$src/tests/fuzz/build_fuzzers.sh" "$src" "$build" "${FUZZ_JOBS:-$(nproc)}"
summary="$build/long_summary.txt"
printf '%-14s %12s %7s %8s %8s %-20s %s\n' fuzzer executions cov ft found "(crash/timeout/oom)" \
  "regressions failing" | tee "$summary"
found_any=0
for name in "${names[@]}"; do
  failing=0
  for input in "$src/tests/fuzz/regressions/$name"/*; do
    [ -f "$input" ] || continue
    mkdir -p "$build/tmp/replay"
    TMPDIR="$build/tmp/replay" "$build/${name}_fuzzer" "$input" >/dev/null 2>&1 || failing=$((failing + 1))
  done
  rm -rf "$build/tmp/replay"
  bash "$src/tests/fuzz/run_fuzzer.sh" "$src" "$build" "$name" "$seconds" -fork=1 -ignore_crashes=1 \
    -ignore_timeouts=1 -ignore_ooms=1 >/dev/null || true
  # Fork mode's status lines: "#EXECS: cov: C ft: F corp: N exec/s: E oom/timeout/crash: O/T/C time: ..."
  last=$(grep -E '^#[0-9]+: cov: ' "$build/$name.log" | tail -1 || true)
  execs=$(sed -E 's/^#([0-9]+):.*/\1/' <<< "$last")
  cov=$(sed -E 's/.* cov: ([0-9]+) .*/\1/' <<< "$last")
  ft=$(sed -E 's/.* ft: ([0-9]+) .*/\1/' <<< "$last")
  read -r oom timeout crash < <(sed -E 's|.* oom/timeout/crash: ([0-9]+)/([0-9]+)/([0-9]+) .*|\1 \2 \3|' <<< "$last")
  found=$((${crash:-0} + ${timeout:-0} + ${oom:-0}))
  [ "$found" -eq 0 ] && [ "$failing" -eq 0 ] || found_any=1
  printf '%-14s %12s %7s %8s %8s %-20s %s\n' "$name" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$found" \
    "(${crash:-?}/${timeout:-?}/${oom:-?})" "$failing" | tee -a "$summary"
done
echo "(logs: $build/NAME.log; found inputs: $build/artifacts/NAME/; this table: $summary)"
exit "$found_any"
