#!/usr/bin/env bash
# Downloads the Debian 12 kernel image, its headers (+ kbuild) and the
# matching linux-source, unpacks them into CACHE (not installed), runs depmod
# and builds gpio-sim out of tree. Versions come from apt (the candidate of
# linux-image-amd64), never hard-coded. Idempotent: a finished cache is reused.
# Usage: fetch-kernel.sh CACHE_DIR      prints the kernel release on success.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache=$1
mkdir -p "$cache"
cache=$(cd "$cache" && pwd)
log() { echo "[kernel-vm] $*" >&2; }
die() { echo "[kernel-vm] FAIL: $*" >&2; exit 1; }

# The ABI package linux-image-amd64 points at, e.g. linux-image-6.1.0-56-amd64 (= 6.1.192-2).
meta=$(apt-cache show --no-all-versions linux-image-amd64 2>/dev/null) || true
[[ -n "$meta" ]] || die "apt knows no linux-image-amd64 (run apt-get update?)"
dep=$(sed -n 's/^Depends: *//p' <<<"$meta" | tr ',' '\n' | grep -o 'linux-image-[0-9][^ ]*-amd64' | head -1)
version=$(sed -n 's/^Version: *//p' <<<"$meta" | head -1)
[[ -n "$dep" && -n "$version" ]] || die "cannot read the kernel ABI from linux-image-amd64"
release=${dep#linux-image-}            # 6.1.0-56-amd64
abi=${release%-amd64}                  # 6.1.0-56
series=$(cut -d. -f1,2 <<<"$version")  # 6.1

root="$cache/$release"
if [[ -f "$root/.done" ]]; then
  echo "$release"
  exit 0
fi
rm -rf "$root"
mkdir -p "$root/debs" "$root/rootfs"

# The packages of one kernel, each at a version the archive has.
source "$here/pick-version.sh"
pkgs=("linux-image-${release}=${version}")
for pkg in "linux-headers-${release}" "linux-headers-${abi}-common" "linux-kbuild-${series}" "linux-source-${series}"; do
  picked=$(pick_version "$pkg" "$version") || exit 1
  pkgs+=("${pkg}=${picked}")
done
log "downloading ${pkgs[*]}"
(cd "$root/debs" && apt-get download -q -o APT::Sandbox::User=root "${pkgs[@]}" >&2) || die "apt-get download failed for ${pkgs[*]}"
for deb in "$root"/debs/*.deb; do
  [[ $deb == */linux-source-* ]] && continue   # only three files of it are needed, below
  dpkg-deb -x "$deb" "$root/rootfs"
done
kdir="$root/rootfs/lib/modules/$release"
[[ -d "$kdir" ]] || die "the image package has no lib/modules/$release"

# gpio-sim (+ irq_sim, patched) out of tree against the matching headers.
src_deb=$(ls "$root"/debs/linux-source-"${series}"_*.deb)
mod="$root/gpio-sim"
mkdir -p "$mod"
log "extracting gpio-sim.c, gpiolib.h, irq_sim.c from ${src_deb##*/}"
dpkg-deb --fsys-tarfile "$src_deb" | tar -xO "./usr/src/linux-source-${series}.tar.xz" | xz -dc \
  | tar -x -C "$mod" --strip-components=3 \
      "linux-source-${series}/drivers/gpio/gpio-sim.c" "linux-source-${series}/drivers/gpio/gpiolib.h" \
      "linux-source-${series}/kernel/irq/irq_sim.c" \
  || die "cannot extract gpio-sim.c, gpiolib.h, irq_sim.c from ${src_deb##*/}"
# One module, gpio-sim.ko, from gpio-sim.c + the patched irq_sim.c.
mv "$mod/gpio-sim.c" "$mod/gpio-sim-main.c"
patch -d "$mod" -p3 --no-backup-if-mismatch < "$here/irq_sim-out-of-tree.patch" >&2 \
  || die "irq_sim-out-of-tree.patch does not apply to this kernel's irq_sim.c"
printf 'obj-m := gpio-sim.o\ngpio-sim-y := gpio-sim-main.o irq_sim.o\n' > "$mod/Kbuild"
headers="$root/rootfs/usr/src/linux-headers-${release}"
# Debian's arch Makefile includes the common one by absolute path: point it here.
sed -i "s|^include /usr/src/|include $root/rootfs/usr/src/|" "$headers/Makefile"
log "building gpio-sim.ko against ${headers##*/}"
make -s -C "$headers" M="$mod" modules >"$mod/build.log" 2>&1 || { cat "$mod/build.log" >&2; die "gpio-sim build failed"; }
install -D -m 0644 "$mod/gpio-sim.ko" "$kdir/extra/gpio-sim.ko"
depmod -b "$root/rootfs" "$release" || die "depmod failed"

# The uncompressed vmlinux boots faster under TCG (PVH entry); pull it out of
# the bzImage's xz payload.
vmlinuz="$root/rootfs/boot/vmlinuz-${release}"
offset=$(LC_ALL=C grep -abo -m1 $'\xfd7zXZ' "$vmlinuz" | head -1 | cut -d: -f1) || true
if [[ -n "$offset" ]]; then
  # xz complains about the bzImage bytes after its stream: the payload is whole.
  tail -c +"$((offset + 1))" "$vmlinuz" | xz -dcq > "$root/vmlinux" 2>/dev/null || true
fi
if [[ -s "$root/vmlinux" ]] && [[ $(head -c 4 "$root/vmlinux" | od -An -tx1 | tr -d ' ') == 7f454c46 ]]; then
  log "vmlinux extracted"
else
  rm -f "$root/vmlinux"
  log "no vmlinux (booting vmlinuz instead)"
fi
touch "$root/.done"
echo "$release"
