#!/usr/bin/env bash
# The kernel test stage's harness (ctest label `kernel`): installs the host
# packages that are missing, fetches the Debian kernel + headers + source
# into the cache, builds gpio-sim and the initramfs, boots the VM and runs
# guest/cases.sh inside against the binaries of BUILD_DIR. Passes only if
# every expected case printed PASS; a missing qemu, kernel package or binary
# is a failure, never a skip.
# Usage: run.sh BUILD_DIR [CASE...]
# Env: TNV_KERNEL_CACHE (default build/kernel-vm-cache in the repo: ignored by git),
#      TNV_KERNEL_VM_TIMEOUT (seconds, default 480), TNV_NO_INSTALL=1 (do not apt-get).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=$(cd "${1:?usage: run.sh BUILD_DIR [CASE...]}" && pwd); shift
cache=${TNV_KERNEL_CACHE:-$repo/build/kernel-vm-cache}
timeout_s=${TNV_KERNEL_VM_TIMEOUT:-480}
die() { echo "[kernel-vm] FAIL: $*" >&2; exit 1; }
t0=$SECONDS

if [[ ${TNV_NO_INSTALL:-0} != 1 ]]; then
  "$repo/scripts/install-missing.sh" kernel-vm $(grep -v '^#' "$here/packages.txt")
fi
for tool in qemu-system-x86_64 candump cansend cangen gpiomon cyclictest depmod cpio; do
  command -v "$tool" >/dev/null || die "$tool is missing (scripts/kernel-vm/packages.txt)"
done

release=$("$here/fetch-kernel.sh" "$cache") || die "could not fetch/prepare the Debian kernel"
kroot="$cache/$release/rootfs"
initrd="$cache/$release/initramfs.cpio.gz"
"$here/build-initramfs.sh" "$kroot" "$release" "$initrd"
echo "[kernel-vm] kernel $release ready after $((SECONDS - t0)) s"

# The tick generator the guest runs (guest/ticker.c), built for the host's libc.
gcc -O2 -Wall -Wextra -Werror -o "$build/kernel-vm-ticker" "$here/guest/ticker.c" || die "cannot build guest/ticker.c"

# The guest sees the host root read-only at the same paths: scripts and
# binaries are used in place.
cases=("$@")
args=$build${cases[*]:+,$(IFS=,; echo "${cases[*]}")}
log=$build/kernel-vm.log
set +e
"$here/run-vm.sh" "$kroot" "$release" "$initrd" "$log" "$timeout_s" "$here/guest/cases.sh" "$args"
vm_rc=$?
set -e
tr -d '\r' < "$log" > "$log.tmp" && mv "$log.tmp" "$log"

# Every case the guest announced must have a PASS line; at least one case.
expected=$(sed -n 's/^TNV-CASES //p' "$log" | head -1)
[[ -n $expected ]] || die "the guest never started its cases (vm exit $vm_rc; log: $log)"
failed=() passed=0
for c in $expected; do
  if grep -q "^TNV-CASE PASS $c " "$log"; then ((++passed)); else failed+=("$c"); fi
done
grep '^TNV-METRIC' "$log" > "$build/kernel-vm-metrics.txt" || true
echo "[kernel-vm] metrics:"; sed 's/^/  /' "$build/kernel-vm-metrics.txt"
echo "[kernel-vm] $passed passed, ${#failed[@]} failed (${failed[*]:-}) in $((SECONDS - t0)) s; log: $log"
((${#failed[@]} == 0 && vm_rc == 0)) || die "kernel tests failed (vm exit $vm_rc)"
