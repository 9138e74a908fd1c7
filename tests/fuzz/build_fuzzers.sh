#!/usr/bin/env bash
# Configures and builds every fuzzer of tests/fuzz with clang (libFuzzer, ASan, UBSan).
#   tests/fuzz/build_fuzzers.sh SOURCE_DIR BUILD_DIR [JOBS]    (JOBS: default nproc)
set -euo pipefail
src=$1 build=$2 jobs=${3:-$(nproc)}
CXX=clang++ cmake -S "$src/tests/fuzz" -B "$build" -DCMAKE_BUILD_TYPE= >/dev/null
cmake --build "$build" -j "$jobs" >/dev/null
