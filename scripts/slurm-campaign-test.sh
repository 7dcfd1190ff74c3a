#!/usr/bin/env bash
# A small campaign through a real single-node Slurm on this machine:
# munged, slurmctld and slurmd on localhost (Debian's slurm-wlm and munge),
# the shards as a job array (tools/campaign/engines/slurm-submit.sh,
# sbatch --array ... --wait), then the merge as a job after it; checks the
# merged table's rows and that a run replays bit for bit; then the same
# campaign with one shard file removed must fail to merge, naming it.
# The daemons run from a private directory with their own slurm.conf and
# are stopped at the end (only the ones this script started).
#   scripts/slurm-campaign-test.sh [BUILD_DIR]   (default build/release; needs tnv-hil built)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(realpath "${1:-$root/build/release}")
tnv_hil=$build/tools/tnv-hil
[[ -x $tnv_hil ]] || { echo "[slurm] $tnv_hil: not built" >&2; exit 2; }
"$root/scripts/install-missing.sh" slurm slurm-wlm munge sqlite3

work=$(mktemp -d /tmp/tnv-slurm.XXXXXX)
chmod 755 "$work"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
  for f in "$work"/slurmctld.pid "$work"/slurmd.pid; do
    [[ -s $f ]] && kill "$(cat "$f")" 2> /dev/null || true
  done
  sleep 1
  [[ ${KEEP:-0} == 1 ]] || rm -rf "$work"
}
trap cleanup EXIT
# Two free loopback ports, so two runs on one machine (two clones' CI) do
# not meet; the kernel may hand one out again only after both are closed.
read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')

# munge: its own socket and key in the work directory, run as the munge user.
mkdir -p "$work/munge"
chown munge:munge "$work/munge"
chmod 711 "$work/munge"
if [[ ! -s /etc/munge/munge.key ]]; then
  runuser -u munge -- mungekey --create --keyfile=/etc/munge/munge.key
fi
runuser -u munge -- munged --socket="$work/munge/munge.socket" --pid-file="$work/munge/munged.pid" \
  --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed"
pids+=("$(cat "$work/munge/munged.pid")")

cpus=$(nproc)
mkdir -p "$work/state" "$work/spool"
cat > "$work/slurm.conf" << CONF
ClusterName=tnvtest
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=tnv Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N localhost
for _ in $(seq 1 60); do
  if sinfo -h -o '%T' 2> /dev/null | grep -qE '^(idle|mixed)'; then break; fi
  sleep 1
done
sinfo -h -o '%T' | grep -qE '^(idle|mixed)' || {
  echo "[slurm] the node did not come up" >&2
  tail -20 "$work/slurmctld.log" "$work/slurmd.log" >&2
  exit 1
}

cat > "$work/short.toml" << 'TOML'
name = "short"
[circle]
radius_mm = 2.0
feed_mm_s = 20.0
dwell_s = 0.05
TOML
cat > "$work/study.toml" << 'TOML'
experiment = "circle"
controllers = ["pid", "rdvsc"]
scenario = "short.toml"
runs = 6
seed = 3
[vary]
"plant.x.coulomb_mm_s" = { normal = [1.5, 0.3] }
"x.sliding.gamma" = { uniform = [0.35, 0.45] }
TOML
"$tnv_hil" campaign plan "$work/study.toml" --out "$work/c"
cd "$work"
TNV_HIL=$tnv_hil "$root/tools/campaign/engines/slurm-submit.sh" "$work/c" 3 --wait
rows=$(sqlite3 "$work/c/campaign.sqlite" "SELECT count(*) FROM runs WHERE status = 'ok'")
[[ $rows == 12 ]] || { echo "[slurm] expected 12 ok rows, got $rows" >&2; exit 1; }
"$tnv_hil" campaign replay "$work/c" 7 --json > "$work/replay.json"
# Shard 2 of 3 holds runs 5..8: run 7 is its line 4 (after the header).
[[ $(sed -n 4p "$work/c/shards/shard-0002-of-0003.jsonl") == "$(cat "$work/replay.json")" ]] || {
  echo "[slurm] run 7 did not replay to its row" >&2
  exit 1
}
rm "$work/c/campaign.sqlite" "$work/c/shards/shard-0003-of-0003.jsonl"
if "$tnv_hil" campaign merge "$work/c" 2> "$work/merge.err"; then
  echo "[slurm] merge with a shard missing succeeded" >&2
  exit 1
fi
grep -q "shard-0003-of-0003.jsonl: missing" "$work/merge.err"
[[ ! -e $work/c/campaign.sqlite ]]
echo "[slurm] 12 runs in 3 array tasks on a single-node Slurm, merged; run 7 replays bit for bit; a missing shard is refused"
