#!/usr/bin/env bash
# Issue 48's proof in LinuxCNC: a true mill3 (its table X and saddle Y position off their file
# by a pitch error each: 4-6 um waves and a lead slope; both axes on the workpiece chain, where
# a reading copied into the file has the wrong sign) measured with the simulated laser
# (preproc/identify/simulate-laser-runs: 5 runs each way, reversal 1.5 um, noise 0.5 um +
# 0.5 um/m) on X and on Y; `identify laser --machine-out` twice -> the identified file; the
# mill3 configuration runs its part (nc/pocket.ngc) headless: volkins with the nominal file,
# volkins with the identified file (and with --with-uncompensated, compensation off); the TRUE
# machine's tool-tip error along each (`volcomp trace` on the true file). Passes if the
# identified file takes the error to within 1.5 um (the laser's noise) and below a third of the
# nominal file's. About 45 s a session.
#
#   tests/session/mill3_laser_loop.sh SOURCE_DIR VOLCOMP [OUT_DIR] [--with-uncompensated]
set -euo pipefail
source_dir=$(realpath "$1") volcomp=$(realpath "$2") out=${3:-$(mktemp -d /tmp/vc-mill3-laser.XXXXXX)}
sessions=(nominal identified); [ "${4:-}" = --with-uncompensated ] && sessions=(off "${sessions[@]}")
cd "$source_dir"
mkdir -p "$out"
runs=$(mktemp -d /tmp/vc-mill3-laser-runs.XXXXXX)  # rtapi_app (another uid) reads the machine files
trap 'rm -rf "$runs"' EXIT
chmod 755 "$runs"
mkdir -p "$runs/src/machines" "$runs/src/tables"
cp -r machines/data "$runs/src/machines/"
cp -r tables/data "$runs/src/tables/"
nominal=$runs/src/machines/data/mill3.toml
awk 'BEGIN { print "x[mm],EXX[um]"; for (x = 0; x <= 500; x += 25) printf "%d,%.4f\n", x, 5 * sin(6.283185307179586 * x / 300) + 0.010 * x
             print "" > "/dev/stderr" }' > "$out/true_x.csv" 2>/dev/null
awk 'BEGIN { print "y[mm],EYY[um]"; for (y = 0; y <= 300; y += 25) printf "%d,%.4f\n", y, 4 * sin(6.283185307179586 * y / 200 + 1) - 0.012 * y }' \
  > "$out/true_y.csv"
"$volcomp" perturb "$nominal" -o "$runs/true" --add-table "$out/true_x.csv" --add-table "$out/true_y.csv" 2> /dev/null
truth=$runs/true/mill3.toml

preproc/identify/simulate-laser-runs "$volcomp" "$truth" EXX x,y,z 0,150,-150 "$(seq 0 10 500)" 1 > "$out/x_runs.csv"
preproc/identify/simulate-laser-runs "$volcomp" "$truth" EYY x,y,z 250,0,-150 "$(seq 0 10 300)" 2 > "$out/y_runs.csv"
"$volcomp" identify laser "$out/x_runs.csv" --error EXX --machine "$nominal" --machine-out "$runs/laser_x" > "$out/identify_x.txt"
"$volcomp" identify laser "$out/y_runs.csv" --error EYY --machine "$runs/laser_x/mill3.toml" --machine-out "$runs/identified" \
  > "$out/identify_y.txt"
chmod -R a+rX "$runs"

config=kins/configs/mill3/mill3.ini
declare -A machine_of=([off]="" [nominal]=$nominal [identified]=$runs/identified/mill3.toml)
declare -A what_of=([off]="no compensation" [nominal]="volkins with the nominal file" [identified]="volkins with the identified file")
for name in "${sessions[@]}"; do
  machine=${machine_of[$name]} what=${what_of[$name]}
  if [ -z "$machine" ]; then
    kins/configs/run_headless.sh "$config" "$runs/session_$name" --compensation off > "$out/session_$name.txt"
  else
    kins/configs/run_headless.sh "$config" "$runs/session_$name" --compensation on \
      --kinematics "volkins machine=$machine coordinates=xyz world=axes" > "$out/session_$name.txt"
  fi
  cp "$runs/session_$name/kins/configs/mill3/trace.csv" "$out/trace_$name.csv"
  "$volcomp" trace "$truth" "$out/trace_$name.csv" > "$out/true_error_$name.txt"
  printf '%-34s %s\n' "$what:" "$(grep -h '^tool tip error' "$out/true_error_$name.txt")"
done
max() { sed -n 's/^tool tip error: max \([0-9.]*\) um.*/\1/p' "$out/true_error_$1.txt"; }
awk -v nominal="$(max nominal)" -v identified="$(max identified)" 'BEGIN {
  ok = identified < 1.5 && identified < nominal / 3 && nominal > 3
  printf "the true mill3 along nc/pocket.ngc, max tool-tip error: nominal file %.2f um, identified %.2f um: %s\n",
         nominal, identified, ok ? "ok" : "FAILED"
  exit !ok }'
