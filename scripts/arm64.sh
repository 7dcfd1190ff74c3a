#!/usr/bin/env bash
# The arm64 cross stage: builds the firmware, emulator and driver unit tests
# (and the Linux backend's, when its dependencies exist for arm64) with
# Debian's aarch64 cross compiler and runs them under qemu-user.
#   scripts/arm64.sh [--build-only | --install-only] [BUILD_DIR]     default build/arm64
# --build-only stops after the build (scripts/test.sh starts it early,
# beside another stage's tests; the packages must be installed already:
# scripts/arm64.sh --install-only, which installs and stops).
# GoogleTest is cross-built from Debian's /usr/src/googletest; the
# header-only dependencies (Eigen, toml++, CLI11, nlohmann-json) are used
# from the host's headers through small config shims, so no arm64
# multiarch packages are needed.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
mode=all
case "${1:-}" in
  --build-only) mode=build; shift ;;
  --install-only) mode=install; shift ;;
esac
out=${1:-build/arm64}
mkdir -p "$out"; out=$(cd "$out" && pwd)
t0=$SECONDS
die() { echo "[arm64] FAIL: $*" >&2; exit 1; }

if [[ $mode != build ]]; then
  scripts/install-deps.sh
  scripts/install-missing.sh arm64 g++-aarch64-linux-gnu qemu-user googletest
fi
[[ $mode == install ]] && exit 0
command -v qemu-aarch64 >/dev/null || die "qemu-aarch64 missing (qemu-user)"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)

# 1. GoogleTest for aarch64 (once per build dir).
deps=$out/deps
if [[ ! -f $deps/lib/cmake/GTest/GTestConfig.cmake ]]; then
  echo "[arm64] cross-building GoogleTest from /usr/src/googletest"
  cmake -S /usr/src/googletest -B "$out/gtest-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_TOOLCHAIN_FILE="$repo/scripts/arm64/toolchain.cmake" -DCMAKE_INSTALL_PREFIX="$deps" \
    "${launcher[@]}" >/dev/null
  cmake --build "$out/gtest-build" -j "$(nproc)" >/dev/null
  cmake --install "$out/gtest-build" >/dev/null
fi

# 2. Shims for the header-only packages (scripts/arm64/shims.sh).
shim=$out/shim
shim_args=$(scripts/arm64/shims.sh "$shim")

# 3. Configure and build only the unit-test binaries that matter on the board.
#    No arm64 libgpiod: pkg-config looks only at the (absent) arm64 dir.
echo "[arm64] configure"
PKG_CONFIG_LIBDIR=/usr/lib/aarch64-linux-gnu/pkgconfig PKG_CONFIG_PATH="" \
cmake --preset arm64 -B "$out/tnv" "${launcher[@]}" \
  -DGTest_DIR="$deps/lib/cmake/GTest" $shim_args >/dev/null
suites=(test_firmware test_emulator test_drivers)
if ninja -C "$out/tnv" -t targets all 2>/dev/null | grep -q '^test_linux:'; then suites+=(test_linux); fi
t_build=$SECONDS
echo "[arm64] build ${suites[*]}"
cmake --build "$out/tnv" -j "$(nproc)" --target "${suites[@]}"
t_run=$SECONDS
if [[ $mode == build ]]; then echo "[arm64] built ${suites[*]} in $((t_run - t0)) s"; exit 0; fi

# 4. Run each suite once under qemu-user (one process per suite: far faster
#    than one emulator start per test case).
# The suites run side by side (one per core), each into its own log.
failed=()
declare -A pid_of=()
for s in "${suites[@]}"; do
  exe=$(find "$out/tnv/tests" -maxdepth 1 -name "$s" -type f)
  [[ -x $exe ]] || { failed+=("$s(not built)"); continue; }
  file "$exe" 2>/dev/null | grep -q aarch64 || [[ $(head -c 20 "$exe" | od -An -tx1 | awk '{print $19 $20}') == b700 ]] \
    || die "$exe is not an aarch64 binary"
  while (($(jobs -rp | wc -l) >= $(nproc))); do sleep 0.2; done
  echo "[arm64] qemu-aarch64 $s"
  # The guest's libraries come from the cross sysroot only: where dpkg's
  # arm64 architecture is installed too (scripts/package.sh does that), the
  # guest loader would otherwise take libc from /lib/aarch64-linux-gnu
  # (through the host's ld.so.cache) beside the sysroot's ld.so, and a mix
  # of two glibc builds hangs threads and forked children. A suite that runs
  # over 15 minutes is stopped and fails, not the whole CI run.
  (cd "$repo" && timeout --kill-after=10 900 qemu-aarch64 -L /usr/aarch64-linux-gnu \
    -E LD_LIBRARY_PATH=/usr/aarch64-linux-gnu/lib "$exe" --gtest_brief=1) \
    >"$out/$s.log" 2>&1 &
  pid_of[$s]=$!
done
for s in "${!pid_of[@]}"; do
  wait "${pid_of[$s]}" || failed+=("$s")
  echo "[arm64] --- $s"
  cat "$out/$s.log"
done
echo "[arm64] configure+deps $((t_build - t0)) s, build $((t_run - t_build)) s, run $((SECONDS - t_run)) s"
((${#failed[@]} == 0)) || die "failed under qemu-aarch64: ${failed[*]}"
echo "[arm64] ${#suites[@]} passed, 0 failed (${suites[*]})"
