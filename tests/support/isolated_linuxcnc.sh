#!/usr/bin/env bash
# Runs COMMAND (a test that starts LinuxCNC or halrun) where it cannot meet another one, so that
# CTest may run several at once (issue 43):
# - as root, where the kernel allows it: in private IPC, PID and mount namespaces (unshare):
#   HAL's and NML's shared memory (fixed SysV keys) and semaphores, the process list (the soak
#   test samples "the" rtapi_app), and a private /tmp (LinuxCNC's /tmp/linuxcnc.lock, its
#   print and debug files, the default rtapi FIFO) are the command's own; the source and build
#   folders stay where they are even when they live under /tmp; the modules VC_MODULES names
#   (this build's volkins.so, simsphere.so) are bound over the installed ones;
# - otherwise: one at a time, under flock /tmp/vc-linuxcnc.lock (the developer's lock, as
#   the READMEs use it).
# A GoogleTest listing (--gtest_list_tests: CTest's discovery at build time) runs as it is.
#
#   isolated_linuxcnc.sh COMMAND [ARGS...]
#   VC_ISOLATION=lock isolated_linuxcnc.sh ...   # the lock even where namespaces work
set -euo pipefail
for arg in "$@"; do
  [ "$arg" = --gtest_list_tests ] && exec "$@"
done
can_unshare() {
  [ "$(id -u)" = 0 ] && [ "${VC_ISOLATION:-}" != lock ] &&
    unshare --ipc --pid --mount --fork --mount-proc true 2>/dev/null
}
if [ -z "${VC_ISOLATED_INSIDE:-}" ]; then
  if can_unshare; then
    exec env VC_ISOLATED_INSIDE=1 unshare --ipc --pid --mount --propagation private --fork --mount-proc "$0" "$@"
  fi
  exec flock /tmp/vc-linuxcnc.lock "$@"
fi

# Inside the namespaces: a fresh folder of the real /tmp becomes /tmp; the real /tmp stays
# reachable at $real, and each of its top folders that holds the working directory or a path
# in the command (a checkout or build under /tmp) is bound back into the new /tmp.
real=$(mktemp -d /run/vc-real-tmp.XXXXXX)
mount --bind /tmp "$real"
private=$(mktemp -d /tmp/vc-isolated.XXXXXX)
chmod 1777 "$private"
mount --bind "$private" /tmp
rebind() {
  local path=$1 top
  case "$path" in /tmp/?*) ;; *) return 0 ;; esac
  top=${path#/tmp/}; top=${top%%/*}
  [ -e "$real/$top" ] && [ ! -e "/tmp/$top" ] || return 0
  if [ -d "$real/$top" ]; then mkdir "/tmp/$top"; else touch "/tmp/$top"; fi
  mount --bind "$real/$top" "/tmp/$top"
  bound+=("/tmp/$top")
}
bound=() modules=()
rebind "$(pwd -P)"
for arg in "$@"; do rebind "$(realpath -m -- "$arg" 2>/dev/null || echo "$arg")"; done
# The modules of this build (VC_MODULES: .so files, set by tests/CMakeLists.txt) in place of the
# installed ones, in this namespace only: two checkouts testing side by side each run their own.
for module in ${VC_MODULES:-}; do
  rebind "$module"
  target=/usr/lib/linuxcnc/modules/$(basename "$module")
  if [ -f "$module" ] && [ -f "$target" ]; then mount --bind "$module" "$target" && modules+=("$target"); fi
done
set +e
"$@"
status=$?
set -e
cd /
for m in "${modules[@]}"; do umount "$m" 2>/dev/null || true; done  # gone with the namespace anyway
for b in "${bound[@]}"; do umount "$b"; done  # the checkout is not under what is removed next
if ! findmnt -rn -o TARGET | grep -q "^/tmp/"; then rm -rf "${real:?}/$(basename "$private")"; fi
umount "$real" && rmdir "$real"
exit $status
