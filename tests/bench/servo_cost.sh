#!/usr/bin/env bash
# The cost of volkins in the servo thread: motion-controller.time (CPU clock ticks, it contains
# the kinematics calls) over the same program with trivkins and with volkins, in alternating
# sessions (medians vary up to 2x between runs on a shared machine, so one run of each is not
# enough). Prints each run's median and p99 and the ratio of the medians of all samples.
#
#   tests/bench/servo_cost.sh [ROUNDS] [PROGRAM]     (default 3 rounds, the 5-axis contour)
# Needs the module installed (cmake --install build --component volkins) and no other session.
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-3}
program=${2:-kins/configs/mc300/nc/contour_5axis.ngc}
ini=kins/configs/mc300/mc300.ini
runs=$(mktemp -d /tmp/volcomp-servo-cost.XXXXXX)
chmod 755 "$runs"
ticks() {  # the controller_time column of a trace
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "controller_time") c = i; next } { print $c }' "$1"
}
stats() {  # median and p99 of a column of numbers
  sort -n "$1" | awk '{ v[NR] = $1 } END { printf "%d %d", v[int(NR * 0.5) + 1], v[int(NR * 0.99) + 1] }'
}
for r in $(seq "$rounds"); do
  for kins in trivkins volkins; do
    if [ "$kins" = trivkins ]; then
      kins/configs/run_headless.sh "$ini" "$runs/$kins-$r" --program "$program" --without-volkins \
        --kinematics "trivkins coordinates=xyzbc kinstype=B" >/dev/null
    else
      kins/configs/run_headless.sh "$ini" "$runs/$kins-$r" --program "$program" --compensation on >/dev/null
    fi
    ticks "$runs/$kins-$r/kins/configs/mc300/trace.csv" > "$runs/$kins-$r.ticks"
    read -r median p99 <<< "$(stats "$runs/$kins-$r.ticks")"
    echo "$kins run $r: motion-controller.time median $median ticks, p99 $p99 ticks"
    cat "$runs/$kins-$r.ticks" >> "$runs/$kins.all"
  done
done
read -r m_triv _ <<< "$(stats "$runs/trivkins.all")"
read -r m_vol _ <<< "$(stats "$runs/volkins.all")"
awk -v a="$m_vol" -v b="$m_triv" 'BEGIN { printf "median over all samples: volkins %d ticks, trivkins %d ticks, ratio %.2f\n", a, b, a / b }'
rm -rf "$runs"
