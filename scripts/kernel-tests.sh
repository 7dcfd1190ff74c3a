#!/usr/bin/env bash
# The kernel test stage: installs what is missing (the build's packages and
# scripts/kernel-vm/packages.txt), builds tnv-fw, tnv-board-emu and tnvctl
# in build/kernel, and runs the ctest label `kernel` (one test, kernel.vm:
# a Debian 12 kernel under qemu with vcan and gpio-sim; docs/kernel-tests.md).
#   scripts/kernel-tests.sh [BUILD_DIR]     default build/kernel
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/kernel}
t0=$SECONDS
scripts/install-deps.sh
scripts/install-missing.sh kernel-vm $(grep -v '^#' scripts/kernel-vm/packages.txt)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [[ -f $out/CMakeCache.txt ]]; then
  # An existing build (CI passes build/release): keep its settings, add the test.
  cmake -S . -B "$out" -DTNV_KERNEL_TESTS=ON >/dev/null
else
  cmake -S . -B "$out" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTNV_BUILD_BENCHMARKS=OFF -DTNV_KERNEL_TESTS=ON \
    -DCMAKE_UNITY_BUILD=ON "${launcher[@]}" >/dev/null
fi
cmake --build "$out" -j "$(nproc)" --target tnv-fw tnv-board-emu tnvctl
t_test=$SECONDS
ctest --test-dir "$out" -L kernel --output-on-failure --no-tests=error
echo "[kernel-tests] build $((t_test - t0)) s, kernel tests $((SECONDS - t_test)) s"
