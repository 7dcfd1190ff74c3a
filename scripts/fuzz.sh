#!/usr/bin/env bash
# scripts/fuzz.sh [--seconds N] [--build-dir DIR]
#
# Builds the libFuzzer targets of tests/fuzz in the asan preset's tree
# (build/asan: clang++-14, -fsanitize=address,undefined, libFuzzer's
# coverage in the libraries, -DTNV_FUZZ=ON; the asan stage has built them
# already) and runs each for N seconds (default 60; the decoder-only
# frame_codec, cheap per input and quickly saturated, N/4), two at a time,
# starting from the checked-in corpus (tests/fuzz/corpus/<target>, copied:
# new inputs stay in <build>/fuzz). Fails (exit 1) on any crash,
# broken invariant, sanitizer report, timeout or out-of-memory; the input
# that caused it is left in <build>/fuzz/artifacts/<target>/. Prints executions
# per target and the wall time of the whole run.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
build=build/asan
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --build-dir) build="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "fuzz.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ "${seconds}" =~ ^[0-9]+$ && "${seconds}" -gt 0 ]] || { echo "fuzz.sh: --seconds wants a positive integer" >&2; exit 2; }
"$(dirname "$0")/install-deps.sh"
"$(dirname "$0")/install-missing.sh" fuzz clang-14 libclang-rt-14-dev
command -v clang++-14 >/dev/null || { echo "fuzz.sh: clang++-14 missing after the install" >&2; exit 1; }

start=$(date +%s)
# The asan preset as scripts/test.sh configures it (no compiler launcher
# added here: a changed launcher would rebuild the whole tree).
cmake --preset asan -B "${build}" >/dev/null
cmake --build "${build}" --target fuzz_targets -j "$(nproc)"
out="${build}/fuzz"
mkdir -p "${out}"

# Run in pairs: the short frame_codec last, alone, so no pair waits on a
# partner a quarter its length (3 x N + N/4 of wall time, not 4 x N).
targets=(can_frames param_set scenario_toml param_image gcode_canon http_routes frame_codec)
run_one() {
  local t="$1" run_seconds="${seconds}"
  [[ "${t}" == frame_codec ]] && run_seconds=$(( (seconds + 3) / 4 ))
  # can_frames: 32 records an input (more than any seed needs to reach an
  # upload); longer inputs add frames, not states, and cost rate.
  local extra=()
  [[ "${t}" == can_frames ]] && extra=(-max_len=384)
  local corpus="${out}/corpus/${t}" artifacts="${out}/artifacts/${t}"
  rm -rf "${corpus}" "${artifacts}"
  mkdir -p "${corpus}" "${artifacts}"
  cp tests/fuzz/corpus/"${t}"/* "${corpus}/"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: 2 GB is a leak.
  "${build}/tests/fuzz/${t}_fuzz" "${corpus}" -max_total_time="${run_seconds}" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="${artifacts}/" "${extra[@]}" >"${out}/${t}.log" 2>&1
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
  log="${out}/${t}.log"
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "${log}" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "${log}" | tail -1)
  result=clean
  if grep -qE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer)|runtime error:|invariant broken' "${log}" ||
     [[ -n "$(ls -A "${out}/artifacts/${t}")" ]]; then
    result="FAILED: see ${log} and ${out}/artifacts/${t}/"
    status=1
  fi
  printf '%-14s %12s %10s %s\n' "${t}" "${execs:-?}" "${rate:-?}" "${result}"
done
echo "fuzz.sh: ${seconds} s per target (frame_codec $(( (seconds + 3) / 4 )) s), wall time $(( $(date +%s) - start )) s"
exit "${status}"
