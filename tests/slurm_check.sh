#!/bin/sh
# A single-node Slurm (Debian's slurm-wlm and munge) started for this test and stopped after:
# munged, slurmctld and slurmd on this host, each with its own socket, state and log under a
# temp folder (nothing of the system's is used or changed). Submits `shadesim regress --shard
# $SLURM_ARRAY_TASK_ID/2` as a 2-task job array, waits for it and merges the shards; the merge
# must be whole and pass.
#
# Usage: slurm_check.sh SHADESIM SOURCE_DIR CACHE
# Exit 77 (ctest: skipped) when not root or slurm-wlm/munge are not installed.
set -eu
shadesim=$1 source_dir=$2 cache=$3

for p in munged slurmctld slurmd sbatch scontrol; do
  if ! command -v "$p" >/dev/null 2>&1; then
    echo "slurm_check: $p not found (Debian packages slurm-wlm and munge): skipped"
    exit 77
  fi
done
if [ "$(id -u)" -ne 0 ]; then
  echo "slurm_check: needs root (slurmd runs jobs as their user): skipped"
  exit 77
fi

work=$(mktemp -d /tmp/shadesim_slurm.XXXXXX)
pids=""
stop() {
  for p in $pids; do kill "$p" 2>/dev/null || true; done
  for p in $pids; do
    for _ in 1 2 3 4 5 6 7 8 9 10; do kill -0 "$p" 2>/dev/null || break; sleep 0.5; done
    kill -9 "$p" 2>/dev/null || true
  done
}
trap stop EXIT
fail() {
  echo "slurm_check: FAIL: $*"
  for f in "$work"/*.log; do echo "--- $f"; tail -20 "$f"; done
  exit 1
}

# munge: its own key, socket and files.
mkdir -p "$work/munge"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$work/munge/munge.key"
socket=$work/munge/munge.socket
munged --force --foreground --socket="$socket" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munged.log" \
  --seed-file="$work/munge/munged.seed" >"$work/munged.out.log" 2>&1 &
pids="$pids $!"
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || fail "munged did not start"

host=$(hostname -s)
cpus=$(nproc)
# Ports away from Slurm's defaults, so a system Slurm (if any) is not disturbed.
cat >"$work/slurm.conf" <<EOF
ClusterName=shadesim-test
SlurmctldHost=$host
SlurmUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$socket
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
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
mkdir -p "$work/state" "$work/spool"
export SLURM_CONF=$work/slurm.conf

slurmctld -D -i >"$work/slurmctld.out.log" 2>&1 &
pids="$pids $!"
slurmd -D >"$work/slurmd.out.log" 2>&1 &
pids="$pids $!"
ready=0
for _ in $(seq 60); do
  if sinfo -h -o %T 2>/dev/null | grep -q idle; then ready=1; break; fi
  sleep 0.5
done
[ "$ready" = 1 ] || fail "the node did not come up idle: $(sinfo 2>&1)"

out=$work/out
cat >"$work/regress.sbatch" <<EOF
#!/bin/sh
#SBATCH --job-name=shadesim-regress
#SBATCH --cpus-per-task=1
#SBATCH --output=$work/task-%a.log
cd "$source_dir"
exec "$shadesim" regress scenes/sphere.json scenes/torus.json --backends cpp --cache "$cache" -j 1 \\
  --shard "\$SLURM_ARRAY_TASK_ID/\$SLURM_ARRAY_TASK_COUNT" --out "$out/shard\$SLURM_ARRAY_TASK_ID"
EOF
sbatch --wait --array=1-2 "$work/regress.sbatch" >"$work/sbatch.log" 2>&1 || fail "sbatch --wait: $(cat "$work/sbatch.log")"
cat "$work/sbatch.log"
for t in 1 2; do
  [ -f "$out/shard$t/plans/shard-$t-of-2.json" ] || fail "task $t wrote no plan (shard-$t-of-2)"
done
"$shadesim" merge "$out/shard1" "$out/shard2" --json "$work/merged.json" || fail "merge failed"
passed=$(sed -n 's/^  "passed": \([0-9]*\),*$/\1/p' "$work/merged.json")
[ "$passed" = 2 ] || fail "merged $passed passed runs, expected 2 (sphere and torus on cpp)"
echo "slurm_check: 2-task array ran both shards; merge whole, 2 passed"
rm -rf "$work"
