#!/bin/bash
# `volcomp init` over every configuration LinuxCNC 2.9 installs (issue 45's proof): each INI with a
# [KINS]KINEMATICS line under /usr/share/doc/linuxcnc/examples/sample-configs. An accepted one
# must give a machine file that `volcomp check` passes and a patch that applies (patch -p1
# --dry-run in the sample's own folder: nothing is written there); a refused one must give one
# of the reasons preproc/init/README.md's table lists. At least 180 must be accepted.
# Writes SUMMARY_CSV (sample,result,reason) for the README's counts.
#
#   init_every_sample.sh VOLCOMP SUMMARY_CSV
set -uo pipefail
volcomp=$1; summary=$2
samples=/usr/share/doc/linuxcnc/examples/sample-configs
[ -d "$samples" ] || { echo "LinuxCNC's sample configurations are not installed: $samples"; exit 0; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

# The refusals' reasons: the README's table, as patterns of the messages (first match names it).
reasons=(
  "not a serial chain|maxkins is refused|millturn is refused:kinematics the model cannot express"
  "the model has exactly three linear axes|the model has at most two:axes the model does not have (a lathe, U V W, a third rotary axis)"
  "do not name the same axes|JOINTS = [0-9]+, but:joints the trajectory planner or [KINS]JOINTS does not have ([TRAJ]COORDINATES, JOINTS)"
  "no such file in|is not below MAX_LIMIT|but joint [0-9]+ is [A-Z], a|rtapi_app would refuse:a sample that is itself incomplete or inconsistent (a missing file, MIN_LIMIT = MAX_LIMIT, a wrong TYPE, a parameter the module lacks)"
  "has no MIN_LIMIT|has no MAX_LIMIT:a linear joint without limits (no travel)"
)
echo "sample,result,reason" > "$summary.tmp"
accepted=0; refused=0; failures=0; n=0
while IFS= read -r ini; do
  grep -q '^[[:space:]]*KINEMATICS' "$ini" || continue
  n=$((n + 1)); name=${ini#$samples/}; out="$work/$n"; mkdir "$out"
  message=$(cd "$out" && "$volcomp" init "$ini" -o "$out/machine.toml" --patch "$out/volkins.patch" 2>&1 >/dev/null)
  status=$?
  if [ $status -eq 0 ]; then
    accepted=$((accepted + 1))
    if ! check=$("$volcomp" check "$out/machine.toml" 2>&1); then
      echo "FAIL $name: the machine file does not pass volcomp check: $check" | tail -3; failures=$((failures + 1))
    fi
    if ! applied=$(patch -p1 --dry-run -d "$(dirname "$ini")" -i "$out/volkins.patch" 2>&1); then
      echo "FAIL $name: the patch does not apply: $applied"; failures=$((failures + 1))
    fi
    echo "$name,accepted," >> "$summary.tmp"
    continue
  fi
  refused=$((refused + 1))
  error=$(printf '%s\n' "$message" | grep -m1 'error:')
  reason=""
  for r in "${reasons[@]}"; do
    if printf '%s' "$error" | grep -Eq "${r%:*}"; then reason=${r##*:}; break; fi
  done
  if [ $status -ne 2 ] || [ -z "$reason" ]; then
    echo "FAIL $name: exit $status, a refusal the README does not list: $error"; failures=$((failures + 1))
  fi
  echo "$name,refused,\"$reason\"" >> "$summary.tmp"
done < <(find "$samples" -name '*.ini' | sort)
mv "$summary.tmp" "$summary"
echo "$n sample configurations with a KINEMATICS line: $accepted accepted (each machine file passes volcomp check, each patch applies), $refused refused:"
tail -n +2 "$summary" | grep ',refused,' | cut -d, -f3- | sort | uniq -c | sort -rn
[ $accepted -ge 180 ] || { echo "FAIL: fewer than 180 accepted"; failures=$((failures + 1)); }
[ $failures -eq 0 ]
