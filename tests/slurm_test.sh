#!/usr/bin/env bash
# Brings up a real single-node Slurm (munged, slurmctld and slurmd on this machine, every file in
# a temporary folder, ports above 16000), submits a FlowScape release as a 3-task job array with
# its merge job through scripts/slurm/submit.sh, waits, and checks the result is byte-identical to
# the same release made by one process. Exits 77 (CTest: skipped) with a SKIPPED line only where
# Slurm cannot run here.
set -u
bin=$(cd "$1" && pwd)
scripts=$(cd "$(dirname "$0")/../scripts/slurm" && pwd)
skip() { echo "SKIPPED: $*"; exit 77; }
for command in munged munge slurmctld slurmd sbatch squeue sinfo; do
  command -v "$command" >/dev/null || skip "$command is not installed (Debian: slurm-wlm and munge, which scripts/install_deps.sh installs)"
done
[ "$(id -u)" = 0 ] || skip "starting slurmd needs root"
work=$(mktemp -d)
cleanup() {
  for pid in "$work"/slurmd.pid "$work"/slurmctld.pid "$work"/munge/pid; do
    [ -s "$pid" ] && kill "$(cat "$pid")" 2>/dev/null
  done
  sleep 1
  rm -rf "$work"
}
trap cleanup EXIT
passes=0 failures=0
check() {
  local what=$1; shift
  if "$@"; then echo "ok: $what"; passes=$((passes + 1)); else echo "FAILED: $what"; failures=$((failures + 1)); fi
}

mkdir -p "$work/munge" "$work/state" "$work/spool" && chmod 700 "$work/munge"
head -c 1024 /dev/urandom >"$work/munge/munge.key" && chmod 400 "$work/munge/munge.key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/socket" \
  --pid-file="$work/munge/pid" --log-file="$work/munge/log" --seed-file="$work/munge/seed" ||
  skip "munged does not start here ($(tail -1 "$work/munge/log" 2>/dev/null))"
host=$(hostname -s)
port=$((16000 + RANDOM % 2000))
cat >"$work/slurm.conf" <<CONF
ClusterName=flowscapetest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=flowscape Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
slurmctld -f "$SLURM_CONF" || skip "slurmctld does not start here ($(tail -1 "$work/slurmctld.log" 2>/dev/null))"
slurmd -f "$SLURM_CONF" || skip "slurmd does not start here ($(tail -1 "$work/slurmd.log" 2>/dev/null))"
for _ in $(seq 1 30); do sinfo -h -o %T 2>/dev/null | grep -q idle && break; sleep 1; done
sinfo -h -o %T 2>/dev/null | grep -q idle || skip "the Slurm node did not come up ($(tail -1 "$work/slurmd.log"))"
echo "Slurm is up: $(sinfo -h -o '%P %D %T %c CPUs')"

release=(--maps 1 --frames 3 --resolution 16 --face-size 8 --spp 1 --vehicles 6 --pedestrians 4 --seed 9)
check "submit a 3-task array and its merge" "$scripts/submit.sh" --shards 3 --cpus 1 --bin "$bin" \
  --out "$work/cluster" -- "${release[@]}"
for _ in $(seq 1 300); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 1; done
check "all jobs finished" test -z "$(squeue -h)"
check "the merge wrote the manifest" test -s "$work/cluster/manifest.json"
check "shard manifests were folded in" test ! -e "$work/cluster/manifests"
check "the merge job split the release" test -s "$work/cluster/splits/test.txt"
check "logs beside the release" bash -c "ls '$work/cluster-slurm-logs'/flowscape-*_2.out >/dev/null"

"$bin/gen_flowscape" "${release[@]}" --out "$work/single" >/dev/null 2>&1
"$bin/flowscape_split" "$work/single" >/dev/null
check "byte-identical to one process" diff -r "$work/cluster" "$work/single"

# a lost shard: the merge names it, a resubmission of that task alone completes the release
rm -rf "$work/cluster/manifest.json" "$work/cluster/sequences/map00_seq04"
for k in 0 1 2; do "$bin/gen_flowscape" "${release[@]}" --out "$work/cluster" --shard "$k/3" >/dev/null 2>&1; done
rm "$work/cluster/manifests/shard-1-of-3.json" "$work/cluster/sequences/map00_seq07/erp/color/000002.png"
check "the merge names the missing shard" bash -c "'$bin/flowscape_merge' '$work/cluster' 2>&1 | grep -q 'shard(s) 1 of 3'"
check "resubmit task 1 only" "$scripts/submit.sh" --shards 3 --only 1 --cpus 1 --bin "$bin" --out "$work/cluster" -- "${release[@]}"
for _ in $(seq 1 300); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 1; done
check "identical again after the resubmission" diff -r "$work/cluster" "$work/single"
check "submit.sh rejects a bad option before submitting" bash -c "! '$scripts/submit.sh' --shards 2 --bin '$bin' --out '$work/x' -- --frames 1 2>/dev/null"

echo "$passes passed, $failures failed"
exit $((failures != 0))
