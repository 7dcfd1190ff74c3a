#!/bin/busybox sh
# PID 1 of the test VM (busybox, in the initramfs). Loads the modules, mounts
# the host's root read-only over 9p, chroots into it and runs the guest test
# script named on the kernel command line (tnv.script=...), then reports the
# exit code through isa-debug-exit (and on the console) and powers off.
/bin/busybox --install -s /bin
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev

say() { echo "TNV-VM: $*"; }
finish() {
  say "DONE rc=$1"
  # isa-debug-exit at 0xf4: qemu exits with (value << 1) | 1.
  printf "\\$(printf '%03o' "$1")" | dd of=/dev/port bs=1 seek=244 count=1 2>/dev/null
  poweroff -f
}

say "init at $(cut -d" " -f1 /proc/uptime) s"
for m in $(cat /modules.order); do
  insmod "/modules/$m" || { say "ERROR insmod $m"; finish 90; }
done
mount -t configfs configfs /sys/kernel/config || { say "ERROR configfs"; finish 91; }

script=""; args=""; repo=""
for kv in $(cat /proc/cmdline); do
  case "$kv" in
    tnv.script=*) script=${kv#tnv.script=} ;;
    tnv.args=*) args=$(echo "${kv#tnv.args=}" | tr ',' ' ') ;;
    tnv.repo=*) repo=${kv#tnv.repo=} ;;
  esac
done

mkdir -p /host
mount -t 9p -o trans=virtio,version=9p2000.L,ro,cache=loose,msize=262144 hostroot /host \
  || { say "ERROR 9p mount"; finish 92; }
mount -t proc proc /host/proc && mount -t sysfs sysfs /host/sys && mount -t devtmpfs devtmpfs /host/dev \
  && mount -t configfs configfs /host/sys/kernel/config || { say "ERROR mounts in the host root"; finish 93; }
mount -t tmpfs tmpfs /host/tmp
mount -t tmpfs tmpfs /host/run
mkdir -p /host/dev/shm && mount -t tmpfs tmpfs /host/dev/shm
# The repository at its own path, on top of the tmpfs mounts above.
if [ -n "$repo" ]; then
  mkdir -p "/host$repo" && mount -t 9p -o trans=virtio,version=9p2000.L,ro,cache=loose,msize=262144 repo "/host$repo" \
    || { say "ERROR 9p mount of $repo"; finish 95; }
fi
ip link set lo up 2>/dev/null

[ -n "$script" ] || { say "ERROR no tnv.script= on the kernel command line"; finish 94; }
say "running $script $args at $(cut -d" " -f1 /proc/uptime) s"
chroot /host /bin/bash "$script" $args
finish $?
