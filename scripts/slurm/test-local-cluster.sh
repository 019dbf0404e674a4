#!/usr/bin/env bash
# The Slurm test (ctest: SlurmArrayMerge): starts a one-node Slurm cluster on localhost from
# Debian's packages (munged, slurmctld, slurmd; installed by scripts/setup.sh) with a generated
# slurm.conf and munge key in a temporary folder, submits a small suite through
# scripts/slurm/submit.sh as a 2-task job array plus the merge job (--dependency=afterok),
# waits for it (bounded), and checks that the merged folder has the same case ids and
# byte-identical images as an unsharded local sweep of the same suite. It also checks that
# `merge` refuses one shard alone (exit 1, naming the missing shard) and that the comparison
# sees a changed image. The daemons are stopped whatever happens: on exit, on a signal, and
# by a watchdog if this script is killed outright (ctest's timeout).
# Usage: scripts/slurm/test-local-cluster.sh [CLI]    (default: build/strandbench)
# Exit 0 passed, 1 failed (with the reason), 77 skipped. The one skip: not root (slurmd must
# run as root to start jobs; the fresh-machine check and CI run as root). A missing package
# or a daemon that does not start is a failure, not a skip.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
cli=$(realpath "${1:-$root/build/strandbench}")
timeout_s=${SB_SLURM_TIMEOUT:-420}
fail() { echo "SlurmArrayMerge: FAILED: $*" >&2; exit 1; }

if [ "$(id -u)" -ne 0 ]; then
  echo "SlurmArrayMerge: skipped: not root (slurmd starts jobs as their user and needs root)"
  exit 77
fi
for b in munged slurmctld slurmd sbatch squeue scontrol sinfo; do
  command -v "$b" >/dev/null ||
    fail "$b is not installed (Debian packages slurm-wlm and munge: run scripts/setup.sh)"
done
[ -x "$cli" ] || fail "$cli is not an executable"

tmp=$(mktemp -d /tmp/sb-slurm.XXXXXX)
pids=()
stop_all() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  for _ in 1 2 3 4 5 6 7 8 9 10; do
    local alive=0
    for p in "${pids[@]}"; do kill -0 "$p" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.5
  done
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
  # Job steps the daemons left (slurmstepd and the sweeps) carry SLURM_CONF=$tmp/...
  for e in /proc/[0-9]*/environ; do
    p=$(basename "$(dirname "$e")")
    [ "$p" != $$ ] && grep -qz "^SLURM_CONF=$tmp/slurm.conf$" "$e" 2>/dev/null && kill -9 "$p" 2>/dev/null
  done
}
cleanup() {
  local status=$?
  stop_all
  if ((status != 0 && status != 77)); then
    for log in slurmctld slurmd munged; do
      [ -f "$tmp/$log.log" ] && { echo "--- last lines of $log.log"; tail -n 15 "$tmp/$log.log"; }
    done
    for log in "$tmp"/out/logs/*.log; do
      [ -f "$log" ] && { echo "--- $(basename "$log")"; tail -n 15 "$log"; }
    done
  fi
  [ -n "${watchdog:-}" ] && kill -9 "$watchdog" 2>/dev/null
  rm -rf "$tmp"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

# --- munge: a fresh key and a private socket (no system munged is touched) ---
dd if=/dev/urandom of="$tmp/munge.key" bs=1024 count=1 status=none
chmod 600 "$tmp/munge.key"
chmod 700 "$tmp"
socket=$tmp/munge.socket
munged --foreground --force --key-file="$tmp/munge.key" --socket="$socket" \
  --pid-file="$tmp/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munge.seed" \
  >>"$tmp/munged.log" 2>&1 &
pids+=($!)
echo $! >>"$tmp/pids"
# The watchdog: if this script dies without its traps (SIGKILL), it stops the daemons.
(
  trap '' TERM
  while kill -0 $$ 2>/dev/null; do sleep 2; done
  [ -f "$tmp/pids" ] && kill -9 $(cat "$tmp/pids") 2>/dev/null
) >/dev/null 2>&1 &
watchdog=$!
disown "$watchdog"

for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.2; done
[ -S "$socket" ] || fail "munged did not start (no socket $socket)"

# --- slurm.conf: one node (this host's CPUs), ports picked free, state in $tmp ---
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
pick_port() {
  local p
  for _ in $(seq 50); do
    p=$((20000 + RANDOM % 20000))
    port_free "$p" && port_free "$((p + 1))" && { echo "$p"; return; }
  done
  fail "no free TCP port pair found"
}
ctl_port=$(pick_port)
d_port=$(pick_port)
host=$(uname -n)
host=${host%%.*}  # slurmctld compares the short name
cpus=$(nproc)
mkdir -p "$tmp/state" "$tmp/spool"
cat >"$tmp/slurm.conf" <<CONF
ClusterName=sbtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctl_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
SlurmdDebug=info
SlurmctldDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdParameters=config_overrides
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MinJobAge=600
NodeName=sbnode NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$cpus RealMemory=1 State=UNKNOWN
PartitionName=sbtest Nodes=sbnode Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
# Not this shell's own job: a test run inside an allocation would pass these on.
unset SLURM_JOB_ID SLURM_JOBID SLURM_ARRAY_TASK_ID SLURM_ARRAY_TASK_COUNT SLURM_ARRAY_TASK_MIN

slurmctld -D -i -f "$SLURM_CONF" >>"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
echo $! >>"$tmp/pids"
slurmd -D -N sbnode -f "$SLURM_CONF" >>"$tmp/slurmd.out" 2>&1 &
pids+=($!)
echo $! >>"$tmp/pids"

state=""
for _ in $(seq 120); do
  state=$(sinfo -h -n sbnode -o %T 2>/dev/null)
  [[ "$state" == idle* ]] && break
  for p in "${pids[@]}"; do
    kill -0 "$p" 2>/dev/null || { cat "$tmp"/*.out >&2; fail "a daemon exited during startup (pid $p)"; }
  done
  sleep 0.5
done
[[ "$state" == idle* ]] || fail "the node did not become idle in 60 s (state: '${state:-no answer}')"
echo "SlurmArrayMerge: cluster up (slurmctld :$ctl_port, slurmd :$d_port, $cpus CPUs)"

# --- the suite: small, both backends, a reference, so images and metrics both count ---
cat >"$tmp/suite.json" <<'SUITE'
{"name": "slurm-tiny",
 "defaults": {"scene": "straight:strands=40,points=5,head=0", "size": "24x24", "repeat": 1,
              "warmup": 0, "reference": true},
 "groups": [{"name": "shadows", "axes": {"shadow": ["none", "dom:layers=3", "occupancy"]}}]}
SUITE

jobs=$(SB_CLI=$cli "$root/scripts/slurm/submit.sh" "$tmp/suite.json" "$tmp/out" 2) ||
  fail "submit.sh failed"
echo "SlurmArrayMerge: $jobs"
array=$(sed -n 's/^array job \([0-9]*\).*/\1/p' <<<"$jobs")
merge=$(sed -n 's/.*merge job \([0-9]*\).*/\1/p' <<<"$jobs")
[ -n "$array" ] && [ -n "$merge" ] || fail "no job ids in submit.sh's output: $jobs"

# The unsharded local sweep while the cluster works.
"$cli" sweep "$tmp/suite.json" --out "$tmp/local" >"$tmp/local.log" 2>&1 ||
  { cat "$tmp/local.log"; fail "the local sweep failed"; }

deadline=$((SECONDS + timeout_s))
merge_state=""
while ((SECONDS < deadline)); do
  merge_state=$(scontrol show job "$merge" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  case "$merge_state" in
    COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | DEADLINE) break ;;
  esac
  sleep 1
done
if [ "$merge_state" != COMPLETED ]; then
  scontrol show job "$array" 2>/dev/null | grep -E 'JobId|JobState|Reason' >&2
  fail "the merge job $merge ended as '${merge_state:-unknown}' (waited up to $timeout_s s)"
fi
echo "SlurmArrayMerge: array job $array and merge job $merge completed"
[ -d "$tmp/out/shard-0" ] && [ -d "$tmp/out/shard-1" ] || fail "the array did not write shard-0 and shard-1"

# --- same case ids, identical images ---
case_ids() { grep -o '"id": *"[^"]*"' "$1/results.json" | sort; }
same_sweep() {  # same_sweep A B: 0 when the case ids and every image agree, else says why
  local a=$1 b=$2
  [ -f "$a/results.json" ] && [ -f "$b/results.json" ] || { echo "no results.json"; return 1; }
  diff <(case_ids "$a") <(case_ids "$b") >/dev/null || { echo "case ids differ"; return 1; }
  [ "$(case_ids "$a" | wc -l)" -gt 0 ] || { echo "no cases"; return 1; }
  diff <(cd "$a/images" && ls) <(cd "$b/images" && ls) >/dev/null || { echo "image lists differ"; return 1; }
  for f in "$a"/images/*.png; do
    cmp -s "$f" "$b/images/$(basename "$f")" || { echo "image $(basename "$f") differs"; return 1; }
  done
}
why=$(same_sweep "$tmp/out/merged" "$tmp/local") ||
  fail "the merged Slurm sweep and the local sweep differ: $why"
n=$(case_ids "$tmp/local" | wc -l)
[ "$n" -eq 6 ] || fail "expected 6 cases, the sweeps have $n"
grep -q '"shards"' "$tmp/out/merged/context.json" ||
  fail "the merged context.json does not keep the shards' contexts"
grep -q '"source": "SLURM_ARRAY_TASK_ID"' "$tmp/out/shard-1/sweep.json" ||
  fail "shard-1 did not take its shard from SLURM_ARRAY_TASK_ID"
echo "SlurmArrayMerge: merged = local: $n case ids, $(ls "$tmp/local/images" | wc -l) identical images"

# --- the checks can fail: a changed image is seen, a missing shard is refused and named ---
cp -r "$tmp/local" "$tmp/changed"
first=$(ls "$tmp/changed/images"/*.png | head -n 1)
printf 'x' >>"$first"
same_sweep "$tmp/out/merged" "$tmp/changed" >/dev/null && fail "the comparison missed a changed image"
"$cli" merge --out "$tmp/half" "$tmp/out/shard-0" >"$tmp/half.log" 2>&1
status=$?
[ "$status" -eq 1 ] || fail "merge of one shard of 2 exited $status, expected 1"
grep -q "missing shard 2/2" "$tmp/half.log" || { cat "$tmp/half.log"; fail "merge did not name shard 2/2"; }
[ ! -e "$tmp/half" ] || fail "merge with a missing shard wrote $tmp/half"
echo "SlurmArrayMerge: passed"
