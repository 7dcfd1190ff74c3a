#!/usr/bin/env bash
# Submits a planned campaign to Slurm: an array of SHARDS tasks (one shard
# each), then the merge, which runs only if every task succeeded.
#   tools/campaign/engines/slurm-submit.sh DIR SHARDS [sbatch options...]
# --wait as an option blocks until the merge has run (used by the test).
# TNV_HIL: the tnv-hil the nodes run (default: tnv-hil on PATH).
set -euo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: $0 DIR SHARDS [sbatch options...]" >&2
  exit 2
fi
dir=$(realpath "$1")
shards=$2
shift 2
here=$(dirname "$(realpath "$0")")
tnv_hil=${TNV_HIL:-tnv-hil}
wait_flag=()
extra=()
for a in "$@"; do
  if [[ $a == --wait ]]; then wait_flag=(--wait); else extra+=("$a"); fi
done
array=$(sbatch --parsable --export=ALL,TNV_HIL="$tnv_hil" --array="1-$shards" "${extra[@]}" \
        "$here/slurm-array.sbatch" "$dir")
array=${array%%;*}
echo "array job $array: $shards shards of $dir"
status=0
merge=$(sbatch --parsable "${wait_flag[@]}" --dependency="afterok:$array" --kill-on-invalid-dep=yes \
        --job-name=tnv-campaign-merge --output="$dir/merge-%j.out" "${extra[@]}" \
        --wrap "'$tnv_hil' campaign merge '$dir'") || status=$?
merge=${merge%%;*}
if [[ ${#wait_flag[@]} -eq 0 ]]; then
  echo "merge job $merge: runs after the array ($dir/merge-$merge.out)"
elif [[ $status -eq 0 ]]; then
  echo "merge job $merge: done ($dir/merge-$merge.out)"
else
  echo "merge job $merge: failed or cancelled (exit $status; a shard failed? see tnv-campaign-${array}_*.out)" >&2
fi
exit "$status"
