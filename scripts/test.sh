#!/usr/bin/env bash
# Builds and runs every test stage, stops at the first failure and prints
# how long each stage took and the size of build/ after it (checking first
# that the disk has room for the stages it runs):
#   release  unity build, default generator (tests and benchmarks compiled),
#            every test but the kernel ones, the installed CMake package
#   slurm    a small campaign through a real single-node Slurm (munge,
#            slurmctld, slurmd on localhost; sbatch --array --wait), merged,
#            replayed, and refused with a shard missing, using the release
#            build's tnv-hil                         (scripts/slurm-campaign-test.sh)
#   asan     the suite under AddressSanitizer + UndefinedBehaviorSanitizer,
#            built with clang (the tree the fuzz stage's targets come
#            from), without the tests that run tnv-hil or tnvctl as a process;
#            then every source that the release build's unity batches
#            compiled after their first, compiled on its own, syntax only
#            (what a plain non-unity build needs: scripts/compile-each.py),
#            with this tree's clang flags where it builds the source
#   tsan     the threaded parts under ThreadSanitizer, with clang  (scripts/tsan.sh)
#   fuzz     every libFuzzer target for 45 s, built in the asan tree
#                                                              (scripts/fuzz.sh)
#   kernel   tnv-fw on a Debian kernel booted under qemu, using the release
#            build's binaries                                  (scripts/kernel-tests.sh)
#   arm64    cross-built unit tests under qemu-user            (scripts/arm64.sh)
#   package  the Debian packages for amd64 and lintian; not in the default
#            list (a whole extra build)                        (scripts/package.sh)
# The stages run in this order, one at a time, but for the later
# stages' builds: the asan, tsan and arm64 builds (the arm64 one with its
# tests under qemu-user) run one after another in the background at
# nice 19 from the start of the run, so that they take only the CPU the
# stages in front leave idle (the release build's serial steps, tests
# that wait on real time: the browser test, the Bode experiments, the RT
# loop; the kernel stage's VM, which runs on one core). The asan and
# tsan stages still run their own build in their turn, after waiting for
# the early one: nothing is left to do, or what is left, and a compile
# error shows there; the arm64 stage reports the early run. The early
# build's log is build/<stage>-early-build.log.
# TNV_STAGES="release asan" scripts/test.sh runs a subset (default: all
# but package; TNV_STAGES=package runs the package build alone).
set -euo pipefail
cd "$(dirname "$0")/.."

stages=(${TNV_STAGES:-release slurm asan tsan fuzz kernel arm64})
jobs=$(nproc)
declare -a report=()

# What each stage leaves under build/, in MB, a tenth or so above what a
# clean clone left (2026-11-29; docs/notes.md "Build and CI"): release
# 2,208, asan 1,752 with clang and the fuzz targets in it (3,618 with GCC
# and the test suites' shared precompiled header, 5,094 before it), tsan
# 1,344, the fuzz stage's corpus and logs in the asan tree 20 (alone it
# builds the fuzz targets there: the old fuzz tree's 298), arm64 557, the
# kernel stage's VM cache 737; the package tree is taken as release's.
# ccache's own directory is not counted.
declare -A stage_disk_mb=([release]=2600 [slurm]=50 [asan]=2000 [tsan]=1500 [fuzz]=400 [arm64]=700
                          [kernel]=900 [package]=2600)
# The packages the stages install (chromium, LinuxCNC, clang, the cross
# compiler, qemu and a kernel: 1.5 GB installed and 1.6 GB of downloaded
# archives on a fresh machine) land on the same disk when / holds build/.
installs_mb=3000

# The run needs room for every stage it runs: say so before the first
# build, not as a compiler's "No space left on device" forty minutes in.
check_disk() {
  mkdir -p build
  local need_mb=${installs_mb} stage dir have_mb
  for stage in "${stages[@]}"; do
    # A tree left by an earlier run already holds its share.
    dir=build/${stage}
    [[ "${stage}" == kernel ]] && dir=build/kernel-vm-cache
    [[ "${stage}" == fuzz ]] && dir=build/asan/fuzz
    have_mb=0
    [[ -d "${dir}" ]] && have_mb=$(du -sm "${dir}" | cut -f1)
    ((have_mb < ${stage_disk_mb[${stage}]:-0})) && need_mb=$((need_mb + ${stage_disk_mb[${stage}]:-0} - have_mb))
  done
  local free_mb
  free_mb=$(df -Pm build | awk 'NR == 2 { print $4 }')
  if ((free_mb < need_mb)); then
    echo "test.sh: the stages ${stages[*]} need about ${need_mb} MB free under build/; $(df -Pm build | awk 'NR == 2 { print $6 }') has ${free_mb} MB." >&2
    echo "test.sh: free some space (build trees of other branches, ccache -C) or run fewer stages (TNV_STAGES)." >&2
    exit 1
  fi
}

run_stage() {
  local name=$1
  shift
  local start=$SECONDS
  echo "=== ${name}"
  "$@"
  report+=("$(printf '%-8s %4d s   build/ now %5d MB' "${name}" $((SECONDS - start)) "$(du -sm build | cut -f1)")")
}

# CPU seconds (user + system) of the finished child processes so far, into
# cpu_s: beside other work on the machine a step's wall time says little.
# `times` runs in this shell (in a subshell it would count the subshell's).
cpu_file=$(mktemp)
early_dir=$(mktemp -d)
trap 'rm -f "${cpu_file}"; stop_early_builds; rm -rf "${early_dir}"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
children_cpu_s() {
  times >"${cpu_file}"
  cpu_s=$(awk 'NR == 2 { split($1, u, /[ms]/); split($2, s, /[ms]/); printf "%d", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "${cpu_file}")
}

# A step of a stage, its time reported with the stage's ("release.build"),
# its CPU time beside it.
run_step() {
  local name=$1
  shift
  local start=$SECONDS cpu_s cpu_start
  children_cpu_s
  cpu_start=${cpu_s}
  "$@"
  children_cpu_s
  report+=("$(printf '  %-14s %4d s   CPU %5d s' "${name}" $((SECONDS - start)) $((cpu_s - cpu_start)))")
}

# The later stages' builds (asan, tsan, arm64: those in this run after its
# first stage), started at the beginning of the run in the background at
# nice 19, one after another in the order of the stages: each waits for
# the one before it to end (a file in early_dir), so that the CPU the
# stages in front leave idle goes to the build needed first. Each in its
# own process group (set -m), so that it can be stopped as a group, but
# this session: where the kernel groups processes by session
# (sched_autogroup), nice only ranks processes within one. Their packages
# are installed first, here: two apt-get at once would fail on dpkg's
# lock, and a stage's own install then finds them present.
declare -A early_pid=()
early_builds() {
  local stage prev="" build install
  for stage in "${stages[@]:1}"; do
    case "${stage}" in
      asan) install=${asan_install} build=${asan_build} ;;
      tsan) install=${tsan_install} build=${tsan_build} ;;
      arm64) install=${arm64_install} build=${arm64_early} ;;
      *) continue ;;
    esac
    [[ -z "${early_pid[${stage}]:-}" ]] || continue
    bash -c "${install}"
    echo "=== ${stage} build queued early, at nice 19 (build/${stage}-early-build.log)"
    set -m
    nice -n 19 bash -c "
      if [[ -n '${prev}' ]]; then while [[ ! -e '${early_dir}/${prev}.done' ]]; do sleep 1; done; fi
      date +%s >'${early_dir}/${stage}.start'
      ${build}
      rc=\$?
      echo \${rc} >'${early_dir}/${stage}.done'
      exit \${rc}" >"build/${stage}-early-build.log" 2>&1 &
    early_pid[${stage}]=$!
    set +m
    prev=${stage}
  done
}
# Waits for a stage's early build before the stage's own configure and
# build; a failure there is reported by the stage's own build.
# The report's line: how long the stage waited for it, the early build's
# CPU seconds (all of them: it is reaped here) and when it started.
wait_early_build() {
  local stage=$1 pid=${early_pid[$1]:-} start=$SECONDS cpu_s cpu_start began
  [[ -n "${pid}" ]] || return 0
  children_cpu_s
  cpu_start=${cpu_s}
  early_rc=0
  wait "${pid}" || early_rc=$?
  ((early_rc == 0)) || [[ "${stage}" == arm64 ]] ||
    echo "test.sh: the early ${stage} build failed (build/${stage}-early-build.log); building again"
  children_cpu_s
  unset "early_pid[${stage}]"
  began=?
  [[ -f "${early_dir}/${stage}.start" ]] && began=$((stage_start_epoch - $(cat "${early_dir}/${stage}.start")))
  report+=("$(printf '  %-14s %4d s   CPU %5d s   (started %s s before its stage, nice 19)' "${stage}.early" \
    $((SECONDS - start)) $((cpu_s - cpu_start)) "${began}")")
}
stop_early_builds() {
  local pid
  for pid in "${early_pid[@]}"; do kill -- "-${pid}" 2>/dev/null || true; done
}

# What each stage installs before its build (one place: the early build
# and the stage's own run use the same lines).
asan_install="scripts/install-missing.sh asan clang-14 libclang-rt-14-dev"
asan_build="cmake --preset asan >/dev/null && cmake --build --preset asan -j ${jobs}"
tsan_install="scripts/install-missing.sh tsan clang-14 libclang-rt-14-dev"
tsan_build="scripts/tsan.sh --build-only"
arm64_install="scripts/arm64.sh --install-only"
# The arm64 stage's cross build and its tests under qemu-user need no core
# to themselves (unit tests, no real-time waits): the queue runs the whole
# stage, and the stage reports that run (its log, its exit status).
arm64_early="scripts/arm64.sh"

build_and_test() {
  local preset=$1
  # The asan and tsan trees are clang's (asan's also the fuzz stage's): the
  # release tree keeps GCC, so both compilers' warnings stop a build.
  if [[ "${preset}" == asan ]]; then bash -c "${asan_install}"; fi
  wait_early_build "${preset}"
  cmake --preset "${preset}" >/dev/null
  run_step "${preset}.build" cmake --build --preset "${preset}" -j "${jobs}"
  # The per-source check runs here, after the clang build: clang loads a
  # precompiled header lazily (0.05 s a source) where GCC reads all of it
  # (0.5 to 1.0 s), so the check takes about half the CPU time it took
  # with GCC (docs/notes.md "CI time"). The release tree's batches say
  # what to check; the few sources the asan tree does not compile (the
  # tests that run tnv-hil or tnvctl as a process) keep the release tree's
  # GCC command. Without a release stage in this run, the asan tree's
  # batches.
  if [[ "${preset}" == asan ]]; then
    if [[ " ${stages[*]} " == *" release "* ]]; then
      run_step asan.each scripts/compile-each.py build/release --prefer build/asan -j "${jobs}"
    else
      run_step asan.each scripts/compile-each.py build/asan -j "${jobs}"
    fi
  fi
  run_step "${preset}.tests" ctest --preset "${preset}" -j "${jobs}" -LE kernel
}

tsan_stage() {
  wait_early_build tsan
  run_step tsan.build scripts/tsan.sh --build-only
  run_step tsan.tests scripts/tsan.sh
}

arm64_stage() {
  if [[ -n "${early_pid[arm64]:-}" ]]; then
    wait_early_build arm64
    cat build/arm64-early-build.log
    return "${early_rc}"
  fi
  scripts/arm64.sh
}

check_disk
scripts/install-deps.sh
# LinuxCNC's rs274, the G-code oracle (ctest -L gcode-oracle, docs/gcode.md):
# the tests' alone, so scripts/run-main.sh does not install it.
scripts/install-missing.sh gcode-oracle linuxcnc-uspace
early_builds
for stage_index in "${!stages[@]}"; do
  stage=${stages[stage_index]}
  stage_start_epoch=$(date +%s)
  case "${stage}" in
    release | asan) run_stage "${stage}" build_and_test "${stage}" ;;
    slurm) run_stage slurm scripts/slurm-campaign-test.sh build/release ;;
    tsan) run_stage tsan tsan_stage ;;
    # 45 s: the asan tree's -O1 runs about two thirds of the inputs per
    # second of the -O2 fuzz tree it replaced (docs/notes.md "CI time").
    # (In a run that lists fuzz before asan, the early asan build is
    # waited for first: both build in build/asan.)
    fuzz) wait_early_build asan; run_stage fuzz scripts/fuzz.sh --seconds 45 ;;
    arm64) run_stage arm64 arm64_stage ;;
    # The kernel stage's VM (qemu TCG, -smp 1) needs a whole core: it
    # failed its bus_flood case beside a build at equal priority
    # (docs/notes.md "CI time"). The early builds still running (the
    # arm64 build and tests, in the default order) go on beside it at
    # nice 19 and take the other core, which the VM leaves idle.
    kernel) run_stage kernel scripts/kernel-tests.sh build/release ;;
    package) run_stage package scripts/package.sh --arch amd64 --jobs "${jobs}" ;;
    *) echo "unknown stage '${stage}' (release slurm asan tsan fuzz kernel arm64 package)" >&2; exit 2 ;;
  esac
done

echo "=== all stages passed"
printf '%s\n' "${report[@]}"
