#!/usr/bin/env bash
# Runs a planned campaign's shards with GNU parallel on this machine, then
# merges them: tools/campaign/engines/parallel.sh DIR SHARDS [JOBS]
#   DIR     the campaign directory (tnv-hil campaign plan FILE --out DIR)
#   SHARDS  how many shards to cut the runs into (more shards than jobs
#           balance better; a shard is the unit that is resumed)
#   JOBS    shards at a time (default: the number of cores)
# TNV_HIL: the tnv-hil to run (default: tnv-hil on PATH). Run it again after
# an interruption: finished shards are kept, a cut one continues.
set -euo pipefail
if [[ $# -lt 2 || $# -gt 3 ]]; then
  echo "usage: $0 DIR SHARDS [JOBS]" >&2
  exit 2
fi
dir=$1
shards=$2
jobs=${3:-$(nproc)}
tnv_hil=${TNV_HIL:-tnv-hil}
command -v parallel > /dev/null || { echo "$0: GNU parallel is missing (Debian: apt-get install parallel)" >&2; exit 2; }
# --halt now,fail=1: a failing shard stops the rest (they resume later).
seq 1 "$shards" | parallel --will-cite --halt now,fail=1 -j "$jobs" "$tnv_hil" campaign run "$dir" --shard "{}/$shards"
"$tnv_hil" campaign merge "$dir"
