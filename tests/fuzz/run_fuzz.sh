#!/usr/bin/env bash
# Builds the G-code fuzzer with clang and runs it for SECONDS from a corpus of every .ngc in
# the source tree plus hand-written lines; exits non-zero on a crash, hang or sanitizer report.
#   tests/fuzz/run_fuzz.sh SOURCE_DIR BUILD_DIR SECONDS
set -euo pipefail
src=$1 build=$2 seconds=$3
CXX=clang++ cmake -S "$src/tests/fuzz" -B "$build" -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build "$build" -j "$(nproc)" >/dev/null
corpus="$build/corpus"
mkdir -p "$corpus"
find "$src/kins/configs" "$src/tests" -name '*.ngc' -exec cp {} "$corpus/" \;
# (tests/fuzz/regressions: inputs that once crashed it, run first like every corpus file)
printf 'G1 X[1+2*3] Y#<a> Z-#5\n#<a>=[atan[1]/[2] mod 3]\n' > "$corpus/expressions.ngc"
printf 'G2 X1 Y1 R-0.5 P2\nG18 G3 Z1 X0 I0 K1\n' > "$corpus/arcs.ngc"
printf '/N10 G10 L20 P0 X0 (c) ; x\nO100 sub\n%%\n' > "$corpus/misc.ngc"
"$build/gcode_fuzzer" "$corpus" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$build/" 2>&1 | tail -20
