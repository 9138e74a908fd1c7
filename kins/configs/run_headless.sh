#!/bin/bash
# Runs one headless LinuxCNC session of a volkins configuration in a scratch folder and prints
# the driver's result line ("ok N samples" or "error: ...").
#
#   run_headless.sh CONFIG.ini RUN_DIR [--kinematics "volkins machine=... world=tcp"]
#                   [--without-volkins] [--without-update] [--without-comp-files]
#                   [--expect-message TEXT]
#                   [--allow-message TEXT] [--program FILE]
#                   [--compensation on|off|toggle]
#                   [--set SECTION.KEY=VALUE]... [--add SECTION.KEY=VALUE]... [--halfile FILE]...
#                   [--replace-halfile NAME=FILE]...
#
# The configuration folder and kins/configs/common are copied to RUN_DIR/kins/configs, with with the
# machine files and tables (machines/data, tables/data): rtapi_app runs as another user
# (RTAPI_UID, when run as root) and must be able to read them wherever the checkout is. The
# machine= path of [KINS] KINEMATICS is kept relative to the copied configuration, LinuxCNC
# writes its files (parameter file, tool table map via HOME) only inside RUN_DIR, and the trace
# lands in RUN_DIR/kins/configs/<name>/trace.csv (--set DRIVER.TRACE=none: no trace). --halfile
# copies FILE into the configuration folder and adds it to [HAL] after the others (e.g. a
# simulated probe, kins/sim); --replace-halfile copies FILE there in place of the HALFILE NAME
# (a trace with other columns). --add appends KEY = VALUE to [SECTION] (a REMAP, a SUBROUTINE_PATH).
# Exit 0 if the program ran cleanly.
set -euo pipefail

usage() { echo "usage: $0 CONFIG.ini RUN_DIR [--kinematics LINE] [--without-volkins] [--without-update] [--without-comp-files] [--expect-message TEXT] [--allow-message TEXT] [--program FILE] [--compensation on|off|toggle] [--set SECTION.KEY=VALUE]... [--add SECTION.KEY=VALUE]... [--halfile FILE]... [--replace-halfile NAME=FILE]..." >&2; exit 2; }
[ $# -ge 2 ] || usage
ini_src=$(realpath "$1"); run_dir=$2; shift 2
kinematics="" ; without_volkins=0; without_update=0; without_comp_files=0; program=""; compensation=""; settings=(); additions=(); halfiles=(); replacements=()
while [ $# -gt 0 ]; do
  case "$1" in
    --kinematics) kinematics=$2; shift 2 ;;
    --without-volkins) without_volkins=1; shift ;;
    --without-update) without_update=1; shift ;;  # a HAL file that forgot volkins.update
    --without-comp-files) without_comp_files=1; shift ;;  # the joints' [JOINT_n]COMP_FILEs left out
    --expect-message) export VOLKINS_EXPECT_MESSAGE=$2; shift 2 ;;
    --allow-message) export VOLKINS_ALLOW_MESSAGE=$2; shift 2 ;;
    --program) program=$(realpath "$2"); shift 2 ;;
    --compensation) compensation=$2; shift 2 ;;
    --set) settings+=("$2"); shift 2 ;;
    --add) additions+=("$2"); shift 2 ;;
    --halfile) halfiles+=("$(realpath "$2")"); shift 2 ;;
    --replace-halfile) replacements+=("${2%%=*}=$(realpath "${2#*=}")"); shift 2 ;;
    *) usage ;;
  esac
done

configs_src=$(dirname "$(dirname "$ini_src")")   # kins/configs
source_root=$(realpath "$configs_src/../..")
config_name=$(basename "$(dirname "$ini_src")")

rm -rf "$run_dir"
mkdir -p "$run_dir/kins/configs" "$run_dir/machines" "$run_dir/tables"
run_dir=$(realpath "$run_dir")
cp -r "$configs_src/common" "$configs_src/$config_name" "$run_dir/kins/configs/"
cp -r "$source_root/machines/data" "$run_dir/machines/"
cp -r "$source_root/tables/data" "$run_dir/tables/"
ini="$run_dir/kins/configs/$config_name/$(basename "$ini_src")"
if [ -n "$kinematics" ]; then
  sed -i "s|^KINEMATICS = .*|KINEMATICS = $kinematics|" "$ini"
fi
for setting in "${settings[@]}"; do  # SECTION.KEY=VALUE: replaces KEY's line in [SECTION]
  section=${setting%%.*}; rest=${setting#*.}; key=${rest%%=*}; value=${rest#*=}
  awk -v s="[$section]" -v k="$key" -v v="$value" '
    /^\[/ { in_section = ($0 == s) }
    in_section && $1 == k && $2 == "=" { $0 = k " = " v; done = 1 }
    { print }
    END { if (!done) { print "run_headless.sh: no " k " in " s > "/dev/stderr"; exit 1 } }' "$ini" > "$ini.new"
  mv "$ini.new" "$ini"
done
for addition in "${additions[@]}"; do  # SECTION.KEY=VALUE: a new KEY line at the end of [SECTION]
  section=${addition%%.*}; rest=${addition#*.}; key=${rest%%=*}; value=${rest#*=}
  awk -v s="[$section]" -v line="$key = $value" '
    /^\[/ { if (in_section && !done) { print line; done = 1 } in_section = ($0 == s) }
    { print }
    END { if (in_section && !done) { print line; done = 1 } if (!done) { print "run_headless.sh: no " s > "/dev/stderr"; exit 1 } }' "$ini" > "$ini.new"
  mv "$ini.new" "$ini"
done
for halfile in "${halfiles[@]}"; do  # after the [HAL] section's last HALFILE
  cp "$halfile" "$(dirname "$ini")/"
  awk -v f="$(basename "$halfile")" '
    /^\[/ { if (in_hal && !done) { print "HALFILE = " f; done = 1 } in_hal = ($0 == "[HAL]") }
    { if (in_hal && !done && $0 ~ /^[[:space:]]*$/) { print "HALFILE = " f; done = 1 } print }
    END { if (in_hal && !done) print "HALFILE = " f }' "$ini" > "$ini.new"
  mv "$ini.new" "$ini"
done
for replacement in "${replacements[@]}"; do  # NAME=FILE: HALFILE = NAME becomes FILE's copy
  name=${replacement%%=*}; file=${replacement#*=}
  grep -qx "HALFILE = $name" "$ini" || { echo "run_headless.sh: no HALFILE = $name in $ini" >&2; exit 1; }
  cp "$file" "$(dirname "$ini")/"
  sed -i "s|^HALFILE = $name\$|HALFILE = $(basename "$file")|" "$ini"
done
if [ "$without_volkins" = 1 ]; then
  sed -i '/^HALFILE = ..\/common\/volkins.hal/d' "$ini"
fi
if [ "$without_comp_files" = 1 ]; then
  sed -i '/^COMP_FILE\(_TYPE\)\? = /d' "$ini"
fi
if [ "$without_update" = 1 ]; then
  sed -i '/^addf volkins.update/d' "$run_dir/kins/configs/common/volkins.hal"
fi
chmod -R a+rwX "$run_dir"
# rtapi_app refuses to run as root: as root it gets a fallback uid.
[ "$(id -u)" = 0 ] && export RTAPI_UID=${RTAPI_UID:-65534}
export RTAPI_FIFO_PATH=$(mktemp -u /tmp/volkins-rtapi.XXXXXX)
export HOME=$run_dir   # LinuxCNC 2.9 keeps the tool table map in $HOME/.tool.mmap
[ -n "$program" ] && export VOLKINS_PROGRAM=$program
[ -n "$compensation" ] && export VOLKINS_COMPENSATION=$compensation
cd "$(dirname "$ini")"
rm -f result.txt
# Without a terminal LinuxCNC writes its output to $HOME/linuxcnc_print.txt.
timeout 900 linuxcnc "$(basename "$ini")" </dev/null >/dev/null 2>&1 || true
if [ ! -f result.txt ]; then
  echo "error: the session ended without a result; LinuxCNC's output:" >&2
  tail -30 "$HOME/linuxcnc_print.txt" >&2 || true
  exit 1
fi
cat result.txt
grep -q '^ok' result.txt
