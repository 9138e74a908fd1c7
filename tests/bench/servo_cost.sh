#!/usr/bin/env bash
# The cost of volkins in the servo thread: motion-controller.time (CPU clock ticks, it contains
# the kinematics calls: one forward and one inverse per cycle) over the same program with
# trivkins, with LinuxCNC's own 5-axis table kinematics xyzbc-trt-kins (the MC-300's pivot
# geometry, kins/configs/mc300/xyzbc_trt.hal: what a user would run without volkins) and with
# volkins, in alternating sessions (medians vary up to 2x between runs on a shared machine, so
# one run of each is not enough). xyzbc-trt-kins runs the program rewritten for its world (the
# tool tip in the table frame, tests/bench/xyzbc_trt_program.py), so that the joints pass the
# same points. Prints each run's median, p99 and worst, then each kinematics' figures over all
# its samples and the ratios of the medians (the issue 21 target: volkins <= 2 x xyzbc-trt-kins).
# Also the 10th percentile: a shared VM's stalls only add time, and on a noisy host they move
# the medians of the same module by 2x between runs, while the low percentiles stay with the
# computation. And each round's own ratio of the medians, with the median over the rounds.
#
# With --servo-cpu N the servo thread runs alone on CPU N (RTAPI_CPU_NUMBER; the rest of
# LinuxCNC on the other CPUs) and a busy loop at nice 19 keeps CPU N from halting between two
# cycles: what isolcpus=N idle=poll does on a real-time machine (LinuxCNC's latency advice).
# On a VM a halted virtual CPU is given to other guests, and the servo thread then finds its
# code and data evicted at every cycle: the host's noise, not the kinematics' cost.
#
#   tests/bench/servo_cost.sh [--servo-cpu N] [ROUNDS] [PROGRAM]   (default 3 rounds, the 5-axis contour)
# Needs the module installed (cmake --install build --component volkins) and no other session.
set -euo pipefail
cd "$(dirname "$0")/../.."
servo_cpu=
if [ "${1:-}" = --servo-cpu ]; then
  servo_cpu=$2
  shift 2
fi
rounds=${1:-3}
program=${2:-kins/configs/mc300/nc/contour_5axis.ngc}
ini=kins/configs/mc300/mc300.ini
runs=$(mktemp -d /tmp/volcomp-servo-cost.XXXXXX)
chmod 755 "$runs"
# The pivot of xyzbc_trt.hal and mc300.tbl's tool 1 (G43 H1), for the rewritten program.
python3 tests/bench/xyzbc_trt_program.py "$program" "$runs/program_trt.ngc" \
  --rot-point -300 -150 -230 --offset 0 0 --tool-offset 100
chmod 644 "$runs/program_trt.ngc"
pin=()
if [ -n "$servo_cpu" ]; then
  others=$(python3 -c "import os; print(','.join(str(c) for c in sorted(os.sched_getaffinity(0)) if c != $servo_cpu))")
  [ -n "$others" ] || { echo "error: --servo-cpu $servo_cpu leaves no other CPU for the rest of LinuxCNC" >&2; exit 2; }
  printf 'int main(void) { for (;;) __asm__ volatile(""); }\n' > "$runs/busy.c"
  cc -O1 "$runs/busy.c" -o "$runs/busy"
  taskset -c "$servo_cpu" nice -n 19 "$runs/busy" &
  busy=$!
  trap 'kill $busy 2>/dev/null || true' EXIT
  export RTAPI_CPU_NUMBER=$servo_cpu
  pin=(taskset -c "$others")
  echo "servo thread alone on CPU $servo_cpu, kept awake; the rest of LinuxCNC on CPU $others"
fi
ticks() {  # the controller_time column of a trace
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "controller_time") c = i; next } { print $c }' "$1"
}
stats() {  # median, p99, worst and 10th percentile of a column of numbers
  sort -n "$1" | awk '{ v[NR] = $1 } END { printf "%d %d %d %d", v[int(NR * 0.5) + 1], v[int(NR * 0.99) + 1], v[NR], v[int(NR * 0.1) + 1] }'
}
kinematics=(trivkins xyzbc-trt-kins volkins)
declare -A round_median round_p10  # of the current round, by kinematics
for r in $(seq "$rounds"); do
  for kins in "${kinematics[@]}"; do
    case "$kins" in
      trivkins)
        "${pin[@]}" kins/configs/run_headless.sh "$ini" "$runs/$kins-$r" --program "$program" --without-volkins \
          --kinematics "trivkins coordinates=xyzbc kinstype=B" >/dev/null ;;
      xyzbc-trt-kins)
        "${pin[@]}" kins/configs/run_headless.sh "$ini" "$runs/$kins-$r" --program "$runs/program_trt.ngc" --without-volkins \
          --kinematics "xyzbc-trt-kins coordinates=xyzbc" --halfile kins/configs/mc300/xyzbc_trt.hal >/dev/null ;;
      volkins)
        "${pin[@]}" kins/configs/run_headless.sh "$ini" "$runs/$kins-$r" --program "$program" --compensation on >/dev/null ;;
    esac
    ticks "$runs/$kins-$r/kins/configs/mc300/trace.csv" > "$runs/$kins-$r.ticks"
    read -r median p99 worst p10 <<< "$(stats "$runs/$kins-$r.ticks")"
    printf "%-15s run %d: motion-controller.time p10 %6d ticks, median %6d, p99 %6d, worst %7d (%d samples)\n" \
      "$kins" "$r" "$p10" "$median" "$p99" "$worst" "$(wc -l < "$runs/$kins-$r.ticks")"
    cat "$runs/$kins-$r.ticks" >> "$runs/$kins.all"
    round_median[$kins]=$median round_p10[$kins]=$p10
  done
  # The round's own ratios: a host that gets busier between rounds moves every kinematics of
  # one round less than it moves the rounds apart.
  round_ratio=$(awk -v v="${round_median[volkins]}" -v x="${round_median[xyzbc-trt-kins]}" 'BEGIN { printf "%.2f", v / x }')
  printf "round %d: volkins / xyzbc-trt-kins median %s, p10 %s\n" "$r" "$round_ratio" \
    "$(awk -v v="${round_p10[volkins]}" -v x="${round_p10[xyzbc-trt-kins]}" 'BEGIN { printf "%.2f", v / x }')"
  echo "$round_ratio" >> "$runs/round_ratios"
done
ghz=$(awk '/^cpu MHz/ { print $4 / 1000; exit }' /proc/cpuinfo)
echo "all samples (ticks; the CPU's clock is ${ghz:-?} GHz):"
declare -A all
for kins in "${kinematics[@]}"; do
  all[$kins]=$(stats "$runs/$kins.all")
  read -r median p99 worst p10 <<< "${all[$kins]}"
  printf "  %-15s p10 %6d, median %6d, p99 %6d, worst %7d\n" "$kins" "$p10" "$median" "$p99" "$worst"
done
echo "${all[volkins]} ${all[xyzbc-trt-kins]} ${all[trivkins]}" | awk '{
  printf "ratios of the medians: volkins / xyzbc-trt-kins %.2f (target <= 2), volkins / trivkins %.2f, xyzbc-trt-kins / trivkins %.2f\n", $1 / $5, $1 / $9, $5 / $9
  printf "volkins / xyzbc-trt-kins: p10 %.2f, p99 %.2f, worst %.2f\n", $4 / $8, $2 / $6, $3 / $7 }'
echo "the rounds' own median ratios: $(sort -n "$runs/round_ratios" | tr '\n' ' ')(median of the rounds $(sort -n "$runs/round_ratios" | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'))"
rm -rf "$runs"
