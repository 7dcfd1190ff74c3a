#!/usr/bin/env bash
# The Debian packages, into out/deb/:
#   tnv-fw_<ver>_<arch>.deb       the board daemon, config, units, udev, sysusers
#   tnv-tools_<ver>_<arch>.deb    tnvctl, tnv-hil, tnv-board-emu, the Python module tnv
#   tnv-fw-dbgsym_<ver>_<arch>.deb, tnv-tools-dbgsym_<ver>_<arch>.deb   (debug symbols)
# built by dpkg-buildpackage + debhelper (debian/) with the `package`
# preset, for amd64 natively and for arm64 with the aarch64 cross
# toolchain (scripts/arm64/), then checked with lintian.
#   scripts/package.sh [--arch amd64|arm64|all] [--jobs N] [--no-lintian]
# Default: --arch all, --jobs 1. The CMake build directories stay in
# build/deb/<arch>/ between runs, so a second run rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
arch=all
jobs=1
lintian=1
while (($#)); do
  case $1 in
    --arch) arch=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --no-lintian) lintian=0; shift ;;
    -h | --help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "[package] unknown argument '$1'" >&2; exit 2 ;;
  esac
done
case $arch in
  all) arches=(amd64 arm64) ;;
  amd64 | arm64) arches=("$arch") ;;
  *) echo "[package] --arch amd64, arm64 or all (got '$arch')" >&2; exit 2 ;;
esac
die() { echo "[package] FAIL: $*" >&2; exit 1; }
[[ $(dpkg --print-architecture) == amd64 ]] || die "builds on an amd64 host only"

scripts/install-deps.sh
scripts/install-missing.sh package debhelper dh-python dpkg-dev fakeroot lintian help2man rsync
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-/work} CCACHE_NOHASHDIR=1
mkdir -p out/deb
declare -a report=()

# The arm64 build: the cross compiler, qemu-user (help2man runs the tools
# for their --help), and for dpkg-shlibdeps the arm64 runtime libraries the
# programs link (libgpiod2, libstdc++6, libc6; multiarch, no -dev package).
# The header-only dependencies (and the Python module's headers: pybind11,
# the shared Python headers, libpython3-dev:arm64's pyconfig.h) come from
# scripts/arm64/shims.sh, libgpiod's
# header from the host's libgpiod-dev (same version), its library through
# a pkg-config file and a libgpiod.so link written here.
prepare_arm64() {
  local dir=$1
  scripts/install-missing.sh package g++-aarch64-linux-gnu qemu-user
  if ! dpkg --print-foreign-architectures | grep -qx arm64; then
    echo "[package] dpkg --add-architecture arm64"
    dpkg --add-architecture arm64 2>/dev/null || sudo dpkg --add-architecture arm64
  fi
  scripts/install-missing.sh package libgpiod2:arm64 libstdc++6:arm64 libpython3-dev:arm64
  local gpiod_version
  gpiod_version=$(dpkg-query -W -f='${Version}' libgpiod2:arm64)
  [[ $gpiod_version == $(dpkg-query -W -f='${Version}' libgpiod-dev:amd64) ]] \
    || die "libgpiod2:arm64 $gpiod_version differs from the host's libgpiod-dev (gpiod.h)"
  mkdir -p "$dir/gpiod/lib" "$dir/gpiod/pkgconfig"
  ln -sfn /usr/lib/aarch64-linux-gnu/libgpiod.so.2 "$dir/gpiod/lib/libgpiod.so"
  cat > "$dir/gpiod/pkgconfig/libgpiod.pc" <<EOP
Name: libgpiod
Description: libgpiod (arm64 runtime library, host header)
Version: ${gpiod_version%%-*}
Libs: -lgpiod
Cflags:
EOP
  export PKG_CONFIG_LIBDIR=$dir/gpiod/pkgconfig PKG_CONFIG_PATH=""
  export DEB_LDFLAGS_MAINT_APPEND="-L$dir/gpiod/lib"
  TNV_DEB_CMAKE_ARGS=$(scripts/arm64/shims.sh "$dir/shim" --python)
  export TNV_DEB_CMAKE_ARGS
}

# The Python module as packaged: amd64 imports it from the unpacked
# tnv-tools and reads a parameter of an emulated node; arm64 (no arm64
# python3 on this host) checks it is an aarch64 module with the target's
# suffix that needs no libpython (Debian's extensions never link it).
check_python_module() {
  local a=$1 dir=$2 root=$2/unpacked
  rm -rf "$root"
  dpkg-deb -x "$dir"/tnv-tools_*_"$a".deb "$root"
  local so
  so=$(find "$root/usr/lib/python3/dist-packages/tnv" -name '_tnv.cpython-*.so' -print -quit)
  [[ -n $so ]] || die "tnv-tools ($a) holds no _tnv module"
  if [[ $a == amd64 ]]; then
    PYTHONPATH=$root/usr/lib/python3/dist-packages /usr/bin/python3 -c '
import sys, tempfile, tnv
with tempfile.TemporaryDirectory() as d, tnv.Node.emulated(storage=d + "/params.bin") as node:
    gamma = node.params["x.sliding.gamma"]
    assert 0.0 < gamma < 1.0, gamma
print("[package] import tnv from the package: x.sliding.gamma =", gamma)' || die "import tnv from tnv-tools ($a)"
  else
    [[ $so == *-aarch64-linux-gnu.so ]] || die "arm64 module suffix: $so"
    aarch64-linux-gnu-readelf -h "$so" | grep -q 'Machine:.*AArch64' || die "$so is not an AArch64 object"
    ! aarch64-linux-gnu-readelf -d "$so" | grep -q 'NEEDED.*libpython' || die "$so links libpython"
    echo "[package] $(basename "$so"): AArch64, no libpython"
  fi
}

build_arch() {
  local a=$1 t0=$SECONDS
  local dir=$repo/build/deb/$a
  local src=$dir/src
  echo "=== [package] $a"
  mkdir -p "$src"
  # A copy of the tracked (and new, not ignored) files: dpkg-buildpackage
  # writes its results next to the tree it builds, here build/deb/<arch>/.
  # rsync keeps the times, so the kept build directory rebuilds only what changed.
  git ls-files -z --cached --others --exclude-standard \
    | rsync -a --delete --ignore-missing-args --from0 --files-from=- ./ "$src/.tmp-new/"
  rsync -a --delete --exclude=.tmp-new "$src/.tmp-new/" "$src/"
  rm -rf "$src/.tmp-new"
  rm -f "$dir"/*.deb "$dir"/*.ddeb "$dir"/*.changes "$dir"/*.buildinfo
  (
    export TNV_DEB_BUILDDIR=$dir/obj
    export DEB_BUILD_OPTIONS="parallel=$jobs${DEB_BUILD_OPTIONS:+ $DEB_BUILD_OPTIONS}"
    cross=()
    if [[ $a != amd64 ]]; then
      prepare_arm64 "$dir"
      # -d: the build dependencies are the host's (header-only shims, libgpiod above), not :arm64 packages.
      cross=(-a "$a" -d -Pcross,nocheck)
      export DEB_BUILD_OPTIONS="$DEB_BUILD_OPTIONS nocheck"
      export CC=aarch64-linux-gnu-gcc CXX=aarch64-linux-gnu-g++
    fi
    cd "$src"
    dpkg-buildpackage -b -us -uc -nc --no-sign "${cross[@]}" >"$dir/build.log" 2>&1 \
      || { tail -40 "$dir/build.log" >&2; die "dpkg-buildpackage for $a (log: $dir/build.log)"; }
  )
  local files
  files=$(shopt -s nullglob; echo "$dir"/*.deb "$dir"/*.ddeb)
  [[ -n $files ]] || die "no packages in $dir"
  rm -f out/deb/*_"$a".deb out/deb/*_"$a".ddeb out/deb/*_"$a".changes
  cp $files out/deb/
  report+=("$(printf '%-6s %4d s  %s' "$a" $((SECONDS - t0)) "$(cd out/deb && ls -- *_"$a".*deb | tr '\n' ' ')")")
  check_python_module "$a" "$dir"
  if ((lintian)); then
    echo "[package] lintian $a"
    # Errors and warnings fail the run; info and pedantic tags are listed.
    lintian --fail-on error,warning --info --display-info --pedantic \
      "$dir"/*.changes | tee "$dir/lintian.log" || die "lintian: errors or warnings for $a ($dir/lintian.log)"
  fi
}

for a in "${arches[@]}"; do build_arch "$a"; done
echo "=== [package] done"
printf '%s\n' "${report[@]}"
ls -l out/deb/
