#!/usr/bin/env bash
# Two LinuxCNC sessions started at once, each isolated (tests/support/isolated_linuxcnc.sh),
# record the same joints as the same session run alone (issue 43): the mill3 configuration's
# part (nc/pocket.ngc) with volkins, run alone, then twice side by side. Compared: the joints
# each trace passes through (a row per servo period; the rows where the joints stand still are
# dropped, since how long a session idles before, between and after moves is the wall clock's), each
# side-by-side run against the one alone, row by row: the count of moving rows and the largest
# difference of a joint. Passes if both runs match the one alone as closely as two runs alone
# match each other (the last run alone, again): LinuxCNC's own run-to-run difference.
#
#   tests/session/parallel_sessions_same_joints.sh SOURCE_DIR [OUT_DIR]
set -euo pipefail
source_dir=$(realpath "$1") out=${2:-$(mktemp -d /tmp/vc-parallel.XXXXXX)}
cd "$source_dir"
mkdir -p "$out"
out=$(realpath "$out")
launcher=tests/support/isolated_linuxcnc.sh
# Inside the launcher /tmp is private: the run folder's trace is copied out before it goes.
run_copy() {
  # (OUT as an argument of its own: the launcher keeps a folder under /tmp that an argument names)
  "$launcher" bash -c 'kins/configs/run_headless.sh kins/configs/mill3/mill3.ini /tmp/run --compensation on > "$1/$2.txt" 2>&1 &&
                       cp /tmp/run/kins/configs/mill3/trace.csv "$1/$2.csv"' _ "$out" "$1"
  # A row moves when a joint differs from the last row kept by more than 1e-9 mm: at rest the
  # inverse kinematics' iteration, seeded with the last joints, wanders within its 1e-10 mm
  # tolerance, for as long as the session idles.
  awk -F, 'function d(a, b) { return a > b ? a - b : b - a }
           NR > 1 && (NR == 2 || d($4, p4) > 1e-9 || d($5, p5) > 1e-9 || d($6, p6) > 1e-9) {
             print $4 "," $5 "," $6; p4 = $4; p5 = $5; p6 = $6 }' "$out/$1.csv" > "$out/$1.joints"
}
run_copy alone
run_copy side_a & a=$!
run_copy side_b & b=$!
wait $a && wait $b
run_copy alone_again
compare() {  # A B: "rows A, rows B, largest joint difference mm"
  paste -d, "$out/$1.joints" "$out/$2.joints" | awk -F, -v na="$(wc -l < "$out/$1.joints")" -v nb="$(wc -l < "$out/$2.joints")" '
    NF == 6 { for (i = 1; i <= 3; ++i) { d = $i - $(i + 3); if (d < 0) d = -d; if (d > m) m = d } }
    END { printf "%d %d %.3g\n", na, nb, m }'
}
read -r n0 n1 alone_diff <<< "$(compare alone alone_again)"
echo "alone vs alone again: $n0 and $n1 moving rows, joints differ by up to $alone_diff mm"
status=0
for side in side_a side_b; do
  read -r na nb diff <<< "$(compare alone "$side")"
  echo "alone vs $side (started at once with the other): $na and $nb moving rows, joints differ by up to $diff mm"
  awk -v d="$diff" -v ref="$alone_diff" -v na="$na" -v nb="$nb" -v n0="$n0" -v n1="$n1" 'BEGIN {
    rows = nb - na; if (rows < 0) rows = -rows; rows0 = n1 - n0; if (rows0 < 0) rows0 = -rows0
    exit !(d <= 1e-9 + 10 * ref && rows <= rows0 + 10) }' || status=1
done
[ $status = 0 ] && echo "ok: side by side, the sessions record the joints they record alone" || echo "FAILED"
exit $status
