#!/usr/bin/env bash
# Copies the seeds of one fuzzer into a corpus folder: the good files of the source tree and
# the golden bad ones for its reader, hand-written seeds (seeds/NAME/) where the tree has no
# good file of that kind, and the inputs that once made it fail (regressions/NAME/).
#   tests/fuzz/seed_corpus.sh SOURCE_DIR NAME CORPUS_DIR
set -euo pipefail
src=$1 name=$2 corpus=$3
mkdir -p "$corpus"
# Copies every file named like $1 under the folders that follow (missing folders skipped),
# each under a name unique to its path: seeds of the same base name would overwrite each other.
seed() {
  local pattern=$1 dir file
  shift
  for dir in "$@"; do
    [ -d "$src/$dir" ] || continue
    find "$src/$dir" -type f -name "$pattern" -print0 | while IFS= read -r -d '' file; do
      cp "$file" "$corpus/seed_$(printf '%s' "${file#"$src"/}" | tr '/' '_')"
    done
  done
}
case $name in
  gcode)
    seed '*.ngc' kins/configs tests
    printf 'G1 X[1+2*3] Y#<a> Z-#5\n#<a>=[atan[1]/[2] mod 3]\n' > "$corpus/expressions.ngc"
    printf 'G2 X1 Y1 R-0.5 P2\nG18 G3 Z1 X0 I0 K1\n' > "$corpus/arcs.ngc"
    printf '/N10 G10 L20 P0 X0 (c) ; x\nO100 sub\n%%\n' > "$corpus/misc.ngc" ;;
  machine) seed '*.toml' machines/data tests/golden/bad_machines tests/unit/machines/data tests/hal/data tests/acceptance ;;
  table) seed '*.csv' tables/data tests/golden/bad_tables tests/golden/bad_machines/tables tests/unit/machines/data ;;
  tool_table) seed '*.tbl' kins/configs tests ;;
  var_file) seed '*.var' kins/configs tests ;;
  cmm_report) seed '*.csv' tests/golden/bad_reports tests/programs/selftune ;;
  laser_runs) seed '*.csv' tests/golden/bad_laser_runs ;;
  circular_test) seed '*.csv' tests/golden/bad_circular_tests ;;
  probe_log) ;;
  acceptance) seed '*.toml' tests/golden/bad_acceptance ; seed '*.csv' tests/golden/bad_acceptance ;;
  init)
    seed '*.ini' tests/golden/bad_inis kins/configs
    # Each golden INI with its HAL file inline (init_fuzzer.cpp: after a "#FUZZ-HAL" line,
    # read as fuzz.hal), so that the fuzzer mutates HAL commands too.
    for ini in "$src"/tests/golden/bad_inis/*.ini "$src"/tests/golden/bad_inis/good/*.ini; do
      hal=${ini%.ini}.hal
      [ -f "$hal" ] || continue
      { sed "s|^HALFILE = $(basename "$hal")\$|HALFILE = fuzz.hal|" "$ini"; printf '#FUZZ-HAL\n'; cat "$hal"; } \
        > "$corpus/inline_hal_$(basename "$ini")"
    done ;;
  *) echo "seed_corpus.sh: no fuzzer '$name'" >&2; exit 2 ;;
esac
seed '*' "tests/fuzz/seeds/$name" "tests/fuzz/regressions/$name"
