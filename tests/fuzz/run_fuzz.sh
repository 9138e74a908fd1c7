#!/usr/bin/env bash
# Builds the fuzzers and runs the named ones (default: all) for SECONDS each, one after the
# other; exits non-zero if any of them found something (its input kept under
# BUILD_DIR/artifacts/NAME/).
#   tests/fuzz/run_fuzz.sh SOURCE_DIR BUILD_DIR SECONDS [NAME...]
set -euo pipefail
src=$1 build=$2 seconds=$3
shift 3
names=("$@")
[ ${#names[@]} -gt 0 ] || mapfile -t names < "$src/tests/fuzz/fuzzers.txt"
bash "$src/tests/fuzz/build_fuzzers.sh" "$src" "$build"
failed=()
for name in "${names[@]}"; do
  echo "== $name"
  bash "$src/tests/fuzz/run_fuzzer.sh" "$src" "$build" "$name" "$seconds" || failed+=("$name")
done
[ ${#failed[@]} -eq 0 ] || { echo "found something: ${failed[*]}" >&2; exit 1; }
