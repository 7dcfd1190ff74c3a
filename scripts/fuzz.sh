#!/usr/bin/env bash
# scripts/fuzz.sh [--seconds N] [--build-dir DIR]
#
# Builds the libFuzzer targets of tests/fuzz (clang++-14, -O2, -fsanitize=
# fuzzer,address,undefined, -DTNV_FUZZ=ON) in build/fuzz and runs each for
# N seconds (default 60; the decoder-only frame_codec, cheap per input and
# quickly saturated, N/4), two at a time, starting from the checked-in
# corpus (tests/fuzz/corpus/<target>, copied: new inputs stay in the build
# directory). Fails (exit 1) on any crash, broken invariant, sanitizer
# report, timeout or out-of-memory; the input that caused it is left in
# <build>/artifacts/<target>/. Prints executions per target and the wall
# time of the whole run.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
build=build/fuzz
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --build-dir) build="$2"; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "fuzz.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ "${seconds}" =~ ^[0-9]+$ && "${seconds}" -gt 0 ]] || { echo "fuzz.sh: --seconds wants a positive integer" >&2; exit 2; }
"$(dirname "$0")/install-deps.sh"
"$(dirname "$0")/install-missing.sh" fuzz clang-14 libclang-rt-14-dev
command -v clang++-14 >/dev/null || { echo "fuzz.sh: clang++-14 missing after the install" >&2; exit 1; }

start=$(date +%s)
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# -O2 with line tables only: the stacks still name file and line, and the
# can_frames target runs about 40 % more inputs per CPU second than at -O1
# (docs/safety.md "Fuzzing"), for a slightly longer build.
cmake -S . -B "${build}" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_UNITY_BUILD=ON -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only" \
  -DTNV_FUZZ=ON "${launcher[@]}" >/dev/null
cmake --build "${build}" --target fuzz_targets -j 2

targets=(can_frames param_set scenario_toml param_image frame_codec gcode_canon http_routes)
run_one() {
  local t="$1" run_seconds="${seconds}"
  [[ "${t}" == frame_codec ]] && run_seconds=$(( (seconds + 3) / 4 ))
  # can_frames: 32 records an input (more than any seed needs to reach an
  # upload); longer inputs add frames, not states, and cost rate.
  local extra=()
  [[ "${t}" == can_frames ]] && extra=(-max_len=384)
  local corpus="${build}/corpus/${t}" artifacts="${build}/artifacts/${t}"
  rm -rf "${corpus}" "${artifacts}"
  mkdir -p "${corpus}" "${artifacts}"
  cp tests/fuzz/corpus/"${t}"/* "${corpus}/"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: 2 GB is a leak.
  "${build}/tests/fuzz/${t}_fuzz" "${corpus}" -max_total_time="${run_seconds}" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="${artifacts}/" "${extra[@]}" >"${build}/${t}.log" 2>&1
}

status=0
for ((i = 0; i < ${#targets[@]}; i += 2)); do
  pids=()
  for t in "${targets[@]:i:2}"; do
    run_one "${t}" &
    pids+=("$!")
  done
  for p in "${pids[@]}"; do wait "${p}" || status=1; done
done

printf '%-14s %12s %10s %s\n' target executions exec/s result
for t in "${targets[@]}"; do
  log="${build}/${t}.log"
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "${log}" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "${log}" | tail -1)
  result=clean
  if grep -qE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer)|runtime error:|invariant broken' "${log}" ||
     [[ -n "$(ls -A "${build}/artifacts/${t}")" ]]; then
    result="FAILED: see ${log} and ${build}/artifacts/${t}/"
    status=1
  fi
  printf '%-14s %12s %10s %s\n' "${t}" "${execs:-?}" "${rate:-?}" "${result}"
done
echo "fuzz.sh: ${seconds} s per target (frame_codec $(( (seconds + 3) / 4 )) s), wall time $(( $(date +%s) - start )) s"
exit "${status}"
