#!/usr/bin/env bash
# Boots the cached Debian kernel under qemu-system-x86_64 (TCG, -smp 1) with
# the test initramfs and the host root over 9p (read-only), runs GUEST_SCRIPT
# inside (chrooted into the host root) and exits with the guest script's exit
# code. The repository is shared a second time and mounted at its own path
# inside the guest, after the guest's tmpfs /tmp and /run: a clone under
# /tmp stays visible. The console goes to LOG and to stdout.
# Usage: run-vm.sh KERNEL_ROOT RELEASE INITRAMFS LOG TIMEOUT_S GUEST_SCRIPT [ARG,ARG...]
set -euo pipefail
kroot=$1 release=$2 initrd=$3 log=$4 timeout_s=$5 script=$6 args=${7:-}
die() { echo "[kernel-vm] FAIL: $*" >&2; exit 1; }
command -v qemu-system-x86_64 >/dev/null || die "qemu-system-x86_64 is missing (install qemu-system-x86)"

kernel="$kroot/../vmlinux"
[[ -f "$kernel" ]] || kernel="$kroot/boot/vmlinuz-$release"
[[ -f "$kernel" ]] || die "no kernel image for $release"
[[ "$args" != *" "* ]] || die "guest args are comma-separated, without spaces"
repo=$(cd "$(dirname "$0")/../.." && pwd)
[[ "$repo" != *" "* && "$repo" != *","* ]] || die "the repository path '$repo' has a space or a comma"

append="console=ttyS0 quiet loglevel=3 panic=-1 oops=panic clocksource=hpet mitigations=off nokaslr"
append+=" tnv.script=$script tnv.repo=$repo"
[[ -n "$args" ]] && append+=" tnv.args=$args"

set +e
timeout --foreground -k 5 "$timeout_s" qemu-system-x86_64 \
  -machine pc,accel=tcg -cpu max -smp 1 -m 768 \
  -nographic -no-reboot -nodefaults -serial stdio \
  -kernel "$kernel" -initrd "$initrd" -append "$append" \
  -device isa-debug-exit,iobase=0xf4,iosize=0x04 \
  -fsdev local,id=hostroot,path=/,security_model=none,readonly=on,multidevs=remap \
  -device virtio-9p-pci,fsdev=hostroot,mount_tag=hostroot \
  -fsdev local,id=repo,path="$repo",security_model=none,readonly=on,multidevs=remap \
  -device virtio-9p-pci,fsdev=repo,mount_tag=repo \
  < /dev/null 2>&1 | tee "$log"
qemu_rc=${PIPESTATUS[0]}
set -e
if ((qemu_rc == 124 || qemu_rc == 137)); then
  die "the VM did not finish within ${timeout_s} s (log: $log)"
fi
done_line=$(grep -a -m1 'TNV-VM: DONE rc=' "$log" | tr -d '\r') || die "the VM ended without its DONE marker (qemu exit $qemu_rc; log: $log)"
guest_rc=${done_line##*rc=}
# isa-debug-exit: qemu's exit code is (value << 1) | 1; both must agree.
(( qemu_rc == ((guest_rc << 1) | 1) )) || die "qemu exit $qemu_rc does not match the guest's rc=$guest_rc"
exit "$guest_rc"
