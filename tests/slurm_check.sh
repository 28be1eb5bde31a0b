#!/bin/sh
# A single-node Slurm (Debian's slurm-wlm and munge) started for this test and stopped after:
# munged, slurmctld and slurmd on this host, each with its own socket, state and log under a
# temp folder (nothing of the system's is used or changed). Submits `shadesim regress --shard
# $SLURM_ARRAY_TASK_ID/2` as a 2-task job array, waits for it and merges the shards; the merge
# must be whole and pass.
#
# Deterministic by construction, each step bounded in time (well inside ctest's 900 s):
# - every daemon is started only once the one it talks to answers: munged (an encode/decode
#   round trip on its socket), then slurmctld (`scontrol ping` UP), then slurmd (the node IDLE);
# - the two ports are free ones (none in /proc/net/tcp*), chosen and taken under a lock shared
#   by every run on this machine: two checkouts' ctest runs at once, or daemons orphaned by a
#   killed run, no longer meet on one port (a slurmctld that cannot bind exits; its clients
#   then talk to the other run's slurmctld, whose munged has another key);
# - names resolve to 127.0.0.1 in slurm.conf, without a resolver;
# - every Slurm client reads this run's slurm.conf (SLURM_CONF; inherited SLURM_*/SBATCH_*
#   variables are dropped), whose AuthInfo names this run's munge socket;
# - the job cannot be requeued or outlive its time limit, sbatch --wait has a deadline;
# - on any exit, signals included, the job's processes and the daemons are stopped.
# munged logs "Unauthorized credential for client UID=0 GID=0" once for each slurmctld, slurmd
# and slurmstepd started: Slurm's auth/munge checks at start that root cannot decode a
# credential meant for another user. Those lines are expected (4 in a passing run).
#
# Usage: slurm_check.sh SHADESIM SOURCE_DIR CACHE
# Exit 77 (ctest: skipped) when not root or slurm-wlm/munge are not installed.
set -eu
shadesim=$1 source_dir=$2 cache=$3

for p in munged munge unmunge slurmctld slurmd sbatch scontrol sinfo squeue flock timeout; do
  if ! command -v "$p" >/dev/null 2>&1; then
    echo "slurm_check: $p not found (Debian packages slurm-wlm, munge, util-linux, coreutils): skipped"
    exit 77
  fi
done
if [ "$(id -u)" -ne 0 ]; then
  echo "slurm_check: needs root (slurmd runs jobs as their user): skipped"
  exit 77
fi

# Only this run's configuration reaches sbatch and the other clients.
for v in $(env | sed -n 's/^\(SLURM_[A-Za-z0-9_]*\|SBATCH_[A-Za-z0-9_]*\|SALLOC_[A-Za-z0-9_]*\)=.*/\1/p'); do
  unset "$v"
done
work=$(mktemp -d /tmp/shadesim_slurm.XXXXXX)
export SLURM_CONF="$work/slurm.conf"
socket=$work/munge/munge.socket
munged_pid="" ctld_pid="" slurmd_pid=""
t0=$(date +%s)
elapsed() { echo "$(($(date +%s) - t0)) s"; }

# Processes of this run: the daemons, the slurmstepds and the job's own (all have this run's
# SLURM_CONF in their environment; this shell exported it, so its own start environment has not).
run_pids() {
  grep -lsxzF "SLURM_CONF=$SLURM_CONF" /proc/[0-9]*/environ | sed -n 's|^/proc/\([0-9]*\)/environ$|\1|p' |
    grep -vx "$$" || true
}
alive() { [ -n "$1" ] && kill -0 "$1" 2>/dev/null; }
# TERM, then up to 5 s, then KILL.
stop_pids() {
  [ -n "$*" ] || return 0
  kill "$@" 2>/dev/null || true
  for _ in 1 2 3 4 5 6 7 8 9 10; do
    left=""
    for p in "$@"; do if alive "$p"; then left="$left $p"; fi; done
    [ -n "$left" ] || return 0
    sleep 0.5
  done
  # shellcheck disable=SC2086
  kill -9 $left 2>/dev/null || true
}
stop() {
  trap - EXIT INT TERM HUP
  # slurmd first (its jobs end with it), then slurmctld, then the rest of the run, munged last.
  stop_pids $slurmd_pid
  stop_pids $ctld_pid
  # shellcheck disable=SC2046
  stop_pids $(run_pids)
  stop_pids $munged_pid
}
trap stop EXIT
interrupted() {
  echo "slurm_check: stopped by SIG$1; the run's folder is kept: $work"
  exit "$2"
}
trap 'interrupted INT 130' INT
trap 'interrupted TERM 143' TERM
trap 'interrupted HUP 129' HUP

fail() {
  echo "slurm_check: FAIL after $(elapsed): $*"
  if alive "$ctld_pid"; then
    echo "--- sinfo"; timeout 10 sinfo -N -l 2>&1 || true
    echo "--- squeue"; timeout 10 squeue -a -l 2>&1 || true
    echo "--- scontrol show job"; timeout 10 scontrol show job 2>&1 | head -60 || true
  fi
  # The daemons' stderr repeats their log; its end still shows an error from before the log opened.
  for f in "$work"/*.log "$work"/*.stderr; do
    [ -f "$f" ] || continue
    n=40
    case $f in *.stderr) n=8 ;; esac
    echo "--- $f (last $n lines)"; tail -n "$n" "$f"
  done
  echo "slurm_check: the run's folder is kept: $work"
  echo "slurm_check: (munged's 'Unauthorized credential for client UID=0' lines are Slurm's own check at"
  echo "  each daemon's start, one per slurmctld, slurmd and slurmstepd: expected, not the failure)"
  exit 1
}
# wait_for SECONDS WHAT CHECK: runs CHECK (a function whose commands are bounded by `timeout`)
# until it succeeds. The daemon in $wait_pid must stay alive meanwhile.
wait_for() {
  secs=$1 what=$2
  shift 2
  end=$(($(date +%s) + secs))
  while :; do
    if "$@" >/dev/null 2>&1; then return 0; fi
    alive "$wait_pid" || fail "$what: its daemon (pid $wait_pid) exited"
    [ "$(date +%s)" -lt "$end" ] || fail "$what: not within $secs s"
    sleep 0.2
  done
}

# munge: its own key, socket and files; ready once a credential made on its socket decodes there.
mkdir -p "$work/munge"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$work/munge/munge.key"
munged --force --foreground --socket="$socket" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --seed-file="$work/munge/munged.seed" \
  >"$work/munged.log" 2>&1 </dev/null &
munged_pid=$!
# shellcheck disable=SC2016
munge_round_trip() { timeout 10 sh -c 'munge -n -S "$1" | unmunge -S "$1"' sh "$socket"; }
wait_pid=$munged_pid
wait_for 20 "munged did not answer on $socket" munge_round_trip

host=$(hostname -s)
# The CPUs slurmd will find (nproc may follow OMP_NUM_THREADS; more than slurmd finds makes the
# node INVAL).
cpus=$(slurmd -C 2>/dev/null | sed -n 's/.* CPUs=\([0-9]*\) .*/\1/p')
[ -n "$cpus" ] || cpus=1

# Two free ports, taken under a machine-wide lock that is held until both daemons listen.
# Daemons must not inherit fd 9 (the lock would live as long as they do).
exec 9>/tmp/shadesim_slurm_ports.lock
flock -w 60 9 || fail "another run held /tmp/shadesim_slurm_ports.lock for 60 s"
port_used() {
  hex=$(printf '%04X' "$1")
  cat /proc/net/tcp /proc/net/tcp6 2>/dev/null | grep -q ":$hex "
}
ctld_port=16817
while port_used "$ctld_port" || port_used $((ctld_port + 1)); do
  ctld_port=$((ctld_port + 2))
  [ "$ctld_port" -lt 17817 ] || fail "no two free ports in 16817-17817"
done
slurmd_port=$((ctld_port + 1))

cat >"$work/slurm.conf" <<EOF
ClusterName=shadesim-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldDebug=debug
SlurmdDebug=debug
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
JobRequeue=0
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
mkdir -p "$work/state" "$work/spool"

slurmctld -D -i >"$work/slurmctld.stderr" 2>&1 </dev/null 9>&- &
ctld_pid=$!
ctld_up() { timeout 10 scontrol ping | grep -q 'is UP'; }
wait_pid=$ctld_pid
wait_for 45 "slurmctld did not answer scontrol ping on port $ctld_port" ctld_up

slurmd -D -N "$host" >"$work/slurmd.stderr" 2>&1 </dev/null 9>&- &
slurmd_pid=$!
node_idle() { [ "$(timeout 10 sinfo -h -N -n "$host" -o %T)" = idle ]; }
wait_pid=$slurmd_pid
wait_for 45 "the node did not come up idle (slurmd on port $slurmd_port)" node_idle
alive "$ctld_pid" || fail "slurmctld exited"
flock -u 9
exec 9>&-
echo "slurm_check: munged, slurmctld (port $ctld_port) and slurmd (port $slurmd_port) ready, node $host idle with $cpus CPU(s), in $(elapsed)"

out=$work/out
cat >"$work/regress.sbatch" <<EOF
#!/bin/sh
#SBATCH --job-name=shadesim-regress
#SBATCH --cpus-per-task=1
#SBATCH --time=10
#SBATCH --output=$work/task-%a.log
cd "$source_dir"
exec "$shadesim" regress scenes/sphere.json scenes/torus.json --backends cpp --cache "$cache" -j 1 \\
  --shard "\$SLURM_ARRAY_TASK_ID/\$SLURM_ARRAY_TASK_COUNT" --out "$out/shard\$SLURM_ARRAY_TASK_ID"
EOF
# The job's time limit (10 min; a first run Verilates both units, maybe after other tests' builds
# in the same cache) ends a stuck task; the deadline here adds Slurm's kill (up to a minute) and
# sbatch --wait's polling (every 32 s at most). Worst case of the whole check: 20 + 45 + 45 + 720
# s and the stops, inside ctest's 900.
# In the background and `wait`ed for, so that a signal stops the run at once.
timeout 720 sbatch --wait --array=1-2 "$work/regress.sbatch" >"$work/sbatch.log" 2>&1 &
sbatch_pid=$!
rc=0
wait "$sbatch_pid" || rc=$?
[ "$rc" != 124 ] || fail "sbatch --wait: no end within 720 s: $(cat "$work/sbatch.log")"
[ "$rc" = 0 ] || fail "sbatch --wait (exit $rc): $(cat "$work/sbatch.log")"
cat "$work/sbatch.log"
for t in 1 2; do
  [ -f "$out/shard$t/plans/shard-$t-of-2.json" ] || fail "task $t wrote no plan (shard-$t-of-2)"
done
"$shadesim" merge "$out/shard1" "$out/shard2" --json "$work/merged.json" || fail "merge failed"
passed=$(sed -n 's/^  "passed": \([0-9]*\),*$/\1/p' "$work/merged.json")
[ "$passed" = 2 ] || fail "merged $passed passed runs, expected 2 (sphere and torus on cpp)"
echo "slurm_check: 2-task array ran both shards; merge whole, 2 passed ($(elapsed))"
stop
rm -rf "$work"
