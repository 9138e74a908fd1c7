#!/bin/bash
# Runs one soak session (tests/soak/README.md): a headless LinuxCNC on the MC-300 thermal
# configuration (volkins) for SECONDS, faults injected at random from SEED, every servo period
# recorded. Prints the driver's result line; the trace, event log and memory samples land in
# RUN_DIR/kins/configs/mc300/ (trace.bin, trace.columns, events.csv, memory.csv, result.txt).
# The assertions are tests/soak/soak_session_test.cpp's (it runs this script); to soak long:
#     flock /tmp/vc-linuxcnc.lock env VC_SOAK_SECONDS=3600 build/tests/soak_session_test
#
#   run_soak.sh SECONDS [RUN_DIR] [SEED]
#
# The configuration is derived at run time, nothing in kins/configs changes: kins/configs/mc300
# and common, machines/data and tables/data are copied to RUN_DIR (as kins/configs/run_headless.sh
# does), and soak.ini is mc300_thermal.ini with this folder's driver as DISPLAY, soak_thermal.hal
# and soak_trace.hal for thermal.hal and trace_thermal.hal, no [DRIVER] section, and soak.tbl
# (mc300.tbl plus a 60 mm and a 150 mm tool) as its tool table. Exit 0 if the soak ran cleanly.
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: $0 SECONDS [RUN_DIR] [SEED]" >&2; exit 2; }
seconds=$1; run_dir=${2:-/tmp/volcomp-soak}; seed=${3:-1}
soak_src=$(cd "$(dirname "$0")" && pwd)
source_root=$(realpath "$soak_src/../..")

rm -rf "$run_dir"
mkdir -p "$run_dir/kins/configs" "$run_dir/machines" "$run_dir/tables"
run_dir=$(realpath "$run_dir")
cp -r "$source_root/kins/configs/common" "$source_root/kins/configs/mc300" "$run_dir/kins/configs/"
cp -r "$source_root/machines/data" "$run_dir/machines/"
cp -r "$source_root/tables/data" "$run_dir/tables/"
config=$run_dir/kins/configs/mc300
cp "$soak_src/soak_driver.py" "$soak_src/soak_thermal.hal" "$soak_src/soak_trace.hal" "$config/"
mkdir -p "$config/soak_nc"
cp "$soak_src"/nc/*.ngc "$config/soak_nc/"
{ cat "$config/mc300.tbl"; echo "T2 P2 Z60 D8 ;soak: a shorter tool"; echo "T3 P3 Z150 D12 ;soak: a longer tool"; } > "$config/soak.tbl"
awk '
  /^\[/ { in_driver = ($0 == "[DRIVER]") }
  in_driver { next }
  /^DISPLAY = / { print "DISPLAY = ./soak_driver.py"; next }
  /^HALFILE = thermal.hal/ { print "HALFILE = soak_thermal.hal"; next }
  /^HALFILE = trace_thermal.hal/ { print "HALFILE = soak_trace.hal"; next }
  /^TOOL_TABLE = / { print "TOOL_TABLE = soak.tbl"; next }
  { print }' "$config/mc300_thermal.ini" > "$config/soak.ini"
for f in soak_driver.py soak_thermal.hal soak_trace.hal soak.tbl; do
  grep -q "$f" "$config/soak.ini" || { echo "run_soak.sh: soak.ini does not use $f" >&2; exit 1; }
done
chmod -R a+rwX "$run_dir"
# rtapi_app refuses to run as root: as root it gets a fallback uid.
[ "$(id -u)" = 0 ] && export RTAPI_UID=${RTAPI_UID:-65534}
export RTAPI_FIFO_PATH=$(mktemp -u /tmp/volkins-rtapi.XXXXXX)
export HOME=$run_dir   # LinuxCNC 2.9 keeps the tool table map in $HOME/.tool.mmap
export SOAK_SECONDS=$seconds SOAK_SEED=$seed
cd "$config"
rm -f result.txt
# Without a terminal LinuxCNC writes its output to $HOME/linuxcnc_print.txt.
timeout $((${seconds%.*} + 900)) linuxcnc soak.ini </dev/null >/dev/null 2>&1 || true
if [ ! -f result.txt ]; then
  echo "error: the soak ended without a result; LinuxCNC's output:" >&2
  tail -30 "$HOME/linuxcnc_print.txt" >&2 || true
  exit 1
fi
cat result.txt
grep -q '^ok' result.txt
