#!/usr/bin/env bash
# ThreadSanitizer build and run of the threaded parts: the Linux backend's
# real-time loop (start/stop, the latency-histogram hand-off), the daemon's
# stop path and the two-process rig (tnv-fw and tnv-board-emu built with
# TSan too). Configures build/tsan, builds only test_linux and the two
# binaries it runs, runs test_linux. Exit status: the test binary's.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dir="${TNV_TSAN_DIR:-$root/build/tsan}"
start=$(date +%s)
build_only=0
if [[ "${1:-}" == --build-only ]]; then build_only=1; shift; fi

# -O1 -g1 with assertions on, as the ASan preset: a shorter build than -O2 -g.
# Built with clang, as the asan tree (the release tree keeps GCC, so both
# compilers' warnings stop a build): 139 CPU-s against GCC's 204 for the
# same targets (docs/notes.md "CI time"); clang and its sanitizer runtimes
# are installed if missing.
bash "$root/scripts/install-missing.sh" tsan clang-14 libclang-rt-14-dev
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_UNITY_BUILD=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DTNV_BUILD_BENCHMARKS=OFF -DTNV_CLI_PROCESS_TESTS=OFF -DTNV_BUILD_PYTHON=OFF "${launcher[@]}" \
  -DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" >/dev/null
cmake --build "$dir" -j"${TNV_JOBS:-2}" --target test_linux tnv-fw tnv-board-emu
((build_only)) && exit 0

export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 ${TSAN_OPTIONS:-}"
run() { (cd "$root" && "$dir/tests/test_linux" --gtest_brief=1 "$@"); }
# TSan's runtime (GCC 12's; clang 14's on some kernels) cannot map its
# shadow under the high-entropy ASLR of newer kernels ("unexpected memory
# mapping"); run without ASLR there.
if ! "$dir/tests/test_linux" --gtest_list_tests >/dev/null 2>&1; then
  echo "[tsan] TSan cannot start with ASLR on this kernel: running under setarch -R"
  run() { (cd "$root" && setarch "$(uname -m)" -R "$dir/tests/test_linux" --gtest_brief=1 "$@"); }
fi
status=0
run "$@" || status=$?
echo "[tsan] test_linux exit $status, $(( $(date +%s) - start )) s including the build"
exit $status
