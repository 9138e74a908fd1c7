#!/usr/bin/env bash
# Runs one built fuzzer for SECONDS from its seeds (seed_corpus.sh) and the corpus earlier runs
# grew (BUILD_DIR/corpus/NAME); exits non-zero on a crash, a hang, a sanitizer report or a
# broken promise, the input kept as BUILD_DIR/artifacts/NAME/crash-* (or timeout-*, oom-*).
# libFuzzer's output goes to BUILD_DIR/NAME.log, its last lines to stdout: they carry the
# figures ("#N DONE cov: C ft: F ..." and stat::number_of_executed_units). Further arguments
# are libFuzzer options (run_long.sh: -fork=1 -ignore_crashes=1 to go on after a crash).
#   tests/fuzz/run_fuzzer.sh SOURCE_DIR BUILD_DIR NAME SECONDS [LIBFUZZER_OPTION...]
set -euo pipefail
src=$1 build=$2 name=$3 seconds=$4
shift 4
fuzzer="$build/${name}_fuzzer"
[ -x "$fuzzer" ] || { echo "run_fuzzer.sh: $fuzzer not built (build_fuzzers.sh)" >&2; exit 2; }
corpus="$build/corpus/$name" artifacts="$build/artifacts/$name/"
mkdir -p "$corpus" "$artifacts"
bash "$src/tests/fuzz/seed_corpus.sh" "$src" "$name" "$corpus"
# The readers read files: the fuzzer writes each input into its own scratch folder under TMPDIR.
scratch="$build/tmp/$name"
rm -rf "$scratch" && mkdir -p "$scratch"
status=0
TMPDIR="$scratch" "$fuzzer" "$corpus" -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$artifacts" "$@" > "$build/$name.log" 2>&1 || status=$?
rm -rf "$scratch"
tail -20 "$build/$name.log"
exit "$status"
