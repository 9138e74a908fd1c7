#!/usr/bin/env bash
# Speed of the pre-distorter end to end against LinuxCNC's own interpreter on the same files:
# lines per second and peak memory (max RSS) of `volcomp predistort` and of `rs274 -g`, in one
# run, for a 1,000,000-line 3-axis program (mill3) and a 5-axis program (MC-300).
#
#   tests/bench/predistort_speed.sh [BUILD_DIR] [LINES] [RUNS]     (default build, 1000000, 3)
# Memory that does not grow with the file: the 3-axis program is also run at LINES / 10.
# Each case runs both programs RUNS times, alternating (volcomp, rs274, volcomp, ...), and
# prints every pair's ratio and the ratio of the best times: on a shared machine a run only
# ever gets slower than the program is, and the two do not get slower alike (the
# multi-threaded pre-distorter loses more when the host takes a core away).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
lines=${2:-1000000}
runs=${3:-3}
volcomp="$build/preproc/volcomp"
work=$(mktemp -d /tmp/volcomp-predistort-speed.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/home"

# rs274's standalone machine units are inches: give it the tool table and offsets in inches
# (tests/support/rs274.hpp does the same), so both read the same program the same way.
inches() {  # tool table: Z column to inches
  awk '{ for (i = 1; i <= NF; ++i) if ($i ~ /^Z/) $i = sprintf("Z%.12f", substr($i, 2) / 25.4); print }' "$1"
}
inch_var() {  # .var: linear axes of homes and offsets to inches
  awk '{ r = ($1 - 5160) % 10; if ($1 >= 5161 && $1 <= 5413 && r >= 1 && r <= 3) $2 = $2 / 25.4; printf "%d\t%.12f\n", $1, $2 }' "$1"
}

measure() {  # label, command...: prints "seconds max_rss_kB"
  local label=$1
  shift
  /usr/bin/time -f "%e %M" -o "$work/$label.time" "$@" >/dev/null 2>"$work/$label.err" ||
    { cat "$work/$label.err" >&2; exit 1; }
  cat "$work/$label.time"
}

run_case() {  # name, kind, lines, machine, var, tool table
  local name=$1 kind=$2 n=$3 machine=$4 var=$5 tbl=$6
  python3 tests/bench/make_programs.py "$kind" "$n" "$work/$name.ngc"
  inches "$tbl" > "$work/$name.tbl"
  inch_var "$var" > "$work/$name.var"
  local pairs="" best_vs="" best_rs="" vm=0 rm=0
  for ((run = 1; run <= runs; ++run)); do
    # Each run writes a new file (rs274's output goes to /dev/null): renaming over the last
    # run's file would add ext4's flush of the replacing file (auto_da_alloc), ~30-40 ms of
    # waiting for the disk here, a cost of the file system, not of the pre-distorter.
    rm -f "$work/$name.out.ngc"
    read -r vs m < <(measure "$name-volcomp" "$volcomp" predistort "$machine" "$work/$name.ngc" \
      -o "$work/$name.out.ngc" --var "$var" --tool-table "$tbl" -q)
    ((m > vm)) && vm=$m
    read -r rs m < <(cd "$work" && HOME="$work/home" measure "$name-rs274" rs274 -v "$name.var" -t "$name.tbl" -g "$name.ngc")
    ((m > rm)) && rm=$m
    pairs+="$(awk -v v="$vs" -v r="$rs" 'BEGIN { printf " %.2f/%.2f=%.2fx", r, v, r / v }')"
    best_vs=$(awk -v a="$vs" -v b="${best_vs:-$vs}" 'BEGIN { print (a < b ? a : b) }')
    best_rs=$(awk -v a="$rs" -v b="${best_rs:-$rs}" 'BEGIN { print (a < b ? a : b) }')
  done
  awk -v name="$name" -v n="$n" -v vs="$best_vs" -v vm="$vm" -v rs="$best_rs" -v rm="$rm" -v pairs="$pairs" 'BEGIN {
    printf "%-10s %8d lines  volcomp %6.2f s %9.0f lines/s %7.1f MB   rs274 -g %6.2f s %9.0f lines/s %7.1f MB   speed ratio %.2f\n",
      name, n, vs, n / vs, vm / 1024, rs, n / rs, rm / 1024, rs / vs
    printf "%-10s runs (rs274 s / volcomp s):%s\n", "", pairs }'
}

echo "pre-distorter vs rs274 -g on the same files ($(nproc) cores, $(date -u +%F)): best of $runs alternating runs each"
run_case 3axis-10 3axis $((lines / 10)) machines/data/mill3.toml tests/programs/mill3.var tests/programs/mill3.tbl
run_case 3axis 3axis "$lines" machines/data/mill3.toml tests/programs/mill3.var tests/programs/mill3.tbl
run_case 5axis 5axis "$lines" machines/data/mc300.toml tests/programs/mc300.var tests/programs/mc300.tbl
