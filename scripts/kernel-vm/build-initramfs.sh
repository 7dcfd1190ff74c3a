#!/usr/bin/env bash
# Builds the test VM's initramfs: static busybox, init.sh as /init, and the
# kernel modules the tests need (with their dependencies, in load order).
# Usage: build-initramfs.sh KERNEL_ROOT RELEASE OUT.cpio.gz
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
kroot=$1 release=$2 out=$3
die() { echo "[kernel-vm] FAIL: $*" >&2; exit 1; }

busybox=/bin/busybox
file -L "$busybox" 2>/dev/null | grep -q "statically linked" || busybox=$(dpkg -L busybox-static 2>/dev/null | grep -m1 '/bin/busybox$') || true
[[ -x "$busybox" ]] || die "no static busybox (install busybox-static)"

# Modules: configfs, CAN (can, can-raw, can-dev, vcan), gpio-sim (out of tree),
# and virtio-pci + 9p for the host root.
wanted=(virtio_pci 9pnet_virtio 9p configfs can can-raw can-dev vcan gpio-sim)
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage"/{bin,proc,sys,dev,modules,host,tmp}
cp "$busybox" "$stage/bin/busybox"
install -m 0755 "$here/init.sh" "$stage/init"
: > "$stage/modules.order"
for m in "${wanted[@]}"; do
  deps=$(modprobe -d "$kroot" -S "$release" --show-depends "$m") || die "module $m not found for $release"
  while read -r verb path _; do
    [[ $verb == insmod ]] || continue
    name=${path##*/}
    grep -qx "$name" "$stage/modules.order" && continue
    case "$name" in
      *.ko) cp "$path" "$stage/modules/$name" ;;
      *.ko.xz) xz -dc "$path" > "$stage/modules/${name%.xz}"; name=${name%.xz} ;;
      *) die "unexpected module file $path" ;;
    esac
    echo "$name" >> "$stage/modules.order"
  done <<<"$deps"
done
(cd "$stage" && find . | cpio -o -H newc --quiet | gzip -1) > "$out"
