#!/bin/bash
# Runs inside the test VM (chrooted into the host's root, read-only; /run and
# /tmp are the VM's tmpfs). One line per case on the console:
#   TNV-CASE PASS <name> (seconds)   or   TNV-CASE FAIL <name> (seconds)
# (a failing case prints "  why: ..." lines first) and TNV-METRIC lines with the measured figures. Exit code: the number of
# failed cases (0 = all passed); the host harness checks every expected case.
# Usage (kernel command line, via run-vm.sh): cases.sh BUILD_DIR [CASE...]
set -u
build=${1:?BUILD_DIR}; shift
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$here/lib.sh"

all_cases=(stock_can stock_gpio fw_start heartbeat param_roundtrip malformed circle estop_gpio \
           bus_flood sigterm cyclictest latency_test)
cases=("$@")
((${#cases[@]})) || cases=("${all_cases[@]}")
echo "TNV-CASES ${cases[*]}"

failed=0
for c in "${cases[@]}"; do
  if ! declare -F "case_$c" >/dev/null; then
    echo "TNV-CASE FAIL $c no such case"; ((failed++)); continue
  fi
  started=$EPOCHREALTIME
  "case_$c" && rc=0 || rc=$?
  took=$(awk -v a="$started" -v b="$EPOCHREALTIME" 'BEGIN{printf "%.2f", b-a}')
  if ((rc == 0)); then
    echo "TNV-CASE PASS $c (${took} s)"
  else
    echo "TNV-CASE FAIL $c (${took} s)"
    ((failed++))
  fi
done
stop_everything
echo "TNV-SUMMARY $((${#cases[@]} - failed)) passed, $failed failed"
exit "$failed"
