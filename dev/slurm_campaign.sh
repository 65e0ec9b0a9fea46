#!/usr/bin/env bash
# A campaign as a Slurm job array on a single-host Slurm cluster set up here and torn down at the
# end (issue 34; docs/datasets.md, "Slurm job array"). Not part of the test command: it needs root
# (munged, slurmctld and slurmd run as root) and Debian's slurm-wlm and munge, which only this
# script needs and which it installs with apt-get when they are missing.
#
#   dev/slurm_campaign.sh [CAMPAIGN.yaml] [RUNS]     (as root; after dev/build.sh)
#
# 1. munge with a new key, slurmctld and slurmd on this host with a generated slurm.conf (the
#    host's sockets, cores and memory from `slurmd -C`; free ports; no cgroups, no accounting), all
#    state, logs and sockets in a temporary directory; the system's own munge/slurm are not touched.
# 2. runs 0..RUNS-1 of the campaign (default config/campaigns/deep_groove_defects.yaml, 400 runs)
#    as `sbatch --array=0-3`: task k runs its --index-range (RUNS/4 runs), with
#    --cpus-per-task=$CPUS_PER_TASK (default 1: `--serial`; more: a LocalCluster of that many workers).
# 3. waits for the array, runs --manifest-only, and checks: every task succeeded and finished its
#    runs (none failed, none found finished before: each run was made once), one data file and one
#    record per run, no temporary files, the data files and the manifest byte-identical to the same
#    runs made --serial outside Slurm.
# 4. prints the figures: wall time of the array, allocated core-seconds, runs per core-hour.
# Everything started here is stopped (and the directory removed) on exit, also on failure or
# Ctrl-C; KEEP=1 keeps the directory (logs, slurm.conf, the runs) for a look.
# Ends with "slurm_campaign: PASSED ..." (exit 0) or "slurm_campaign: FAILED ..." (exit 1).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/../scripts/env.sh"
campaign="$(realpath "${1:-$BEARING_SIM_ROOT/config/campaigns/deep_groove_defects.yaml}")"
runs="${2:-400}"
tasks=4
cpus_per_task="${CPUS_PER_TASK:-1}"
timeout_s="${TIMEOUT_S:-3600}"   # the array's wall time limit, generous: the cores are shared

say() { echo "slurm_campaign: $*"; }
fail() { say "FAILED: $*"; exit 1; }

[ "$(id -u)" -eq 0 ] || fail "run as root (munged, slurmctld and slurmd are started here)"
[ $((runs % tasks)) -eq 0 ] && [ "$runs" -ge "$tasks" ] || fail "RUNS ($runs) must be a multiple of $tasks"
missing=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  say "installing ${missing[*]} (apt-get; the daemons are started by this script only)"
  apt-get update -qq
  # policy-rc.d may start the packages' own services; they use /etc and are left as Debian sets them.
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
set +u  # catkin's setup hooks read unset variables
source "$BEARING_SIM_BUILD/devel/setup.bash"
set -u
tool="$BEARING_SIM_BUILD/devel/lib/bearing_sim/bearing_campaign"
[ -x "$tool" ] || fail "$tool missing: build first (dev/build.sh)"

dir="$(mktemp -d /tmp/slurm_campaign.XXXXXX)"
chmod 700 "$dir"
pids=()      # daemons started here, stopped in this order's reverse
job=""
cleanup() {
  local status=$?
  set +e
  if [ -n "$job" ] && [ -n "${SLURM_CONF:-}" ]; then scancel "$job" 2>/dev/null; fi
  for ((k = ${#pids[@]} - 1; k >= 0; k--)); do
    kill -TERM "${pids[k]}" 2>/dev/null
    for _ in $(seq 100); do kill -0 "${pids[k]}" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "${pids[k]}" 2>/dev/null
    wait "${pids[k]}" 2>/dev/null
  done
  # Job steps slurmd started and left (a task killed by scancel): processes of our job only.
  for p in $(grep -l "^SLURM_CONF=$dir/slurm.conf$" /proc/[0-9]*/environ 2>/dev/null | cut -d/ -f3); do
    kill -KILL "$p" 2>/dev/null
  done
  if [ "${KEEP:-0}" = 1 ]; then say "kept $dir"; else rm -rf "$dir"; fi
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM

free_port() { /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
wait_until() {  # SECONDS WHAT COMMAND...: polls COMMAND until it succeeds
  local limit=$1 what=$2; shift 2
  local end=$((SECONDS + limit))
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $end ] || fail "$what: not within $limit s (logs in $dir; KEEP=1 keeps them)"
    sleep 0.5
  done
}

# --- munge, with a key of its own --------------------------------------------------------------
mkdir -m 700 "$dir/munge"
mungekey --create --keyfile="$dir/munge/munge.key"
munged --foreground --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" \
  >"$dir/munge/munged.out" 2>&1 &
pids+=($!)
wait_until 30 "munged" sh -c "munge --socket='$dir/munge/munge.socket' -n | unmunge --socket='$dir/munge/munge.socket'"

# --- slurm.conf from this host ------------------------------------------------------------------
node="$(hostname -s)"
# NodeName=... CPUs=2 Boards=1 SocketsPerBoard=1 CoresPerSocket=2 ThreadsPerCore=1 RealMemory=24105
hw="$(slurmd -C | head -1)"
cpus="$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<<"$hw")"
memory="$(sed -n 's/.* RealMemory=\([0-9]*\).*/\1/p' <<<"$hw")"
layout="$(grep -o 'Boards=[0-9]* SocketsPerBoard=[0-9]* CoresPerSocket=[0-9]* ThreadsPerCore=[0-9]*' <<<"$hw")"
mkdir -p "$dir/ctld" "$dir/spool" "$dir/log"
export SLURM_CONF="$dir/slurm.conf"
cat >"$SLURM_CONF" <<EOF
# Generated by dev/slurm_campaign.sh: a single-host cluster for one campaign, torn down after.
ClusterName=bearingsim
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/ctld
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups (a container may not delegate them), no accounting database.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
# Cores are the unit: as many 1-core tasks run at once as the host has cores.
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
DefMemPerCPU=1024
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus $layout RealMemory=$((memory * 9 / 10)) State=UNKNOWN
PartitionName=campaign Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
say "cluster in $dir: node $node, $cpus CPUs ($layout), $((memory * 9 / 10)) MB for jobs"

slurmctld -D -i -f "$SLURM_CONF" >"$dir/log/slurmctld.out" 2>&1 &
pids+=($!)
wait_until 60 "slurmctld" scontrol ping
slurmd -D -N "$node" -f "$SLURM_CONF" >"$dir/log/slurmd.out" 2>&1 &
pids+=($!)
wait_until 120 "the node idle" sh -c "sinfo -h -N -n '$node' -o %T | grep -qx idle"

# --- the campaign as a job array ----------------------------------------------------------------
out="$dir/out"
per_task=$((runs / tasks))
cat >"$dir/task.sh" <<EOF
#!/bin/bash
# One array task: runs [A, B) of the campaign with the cores Slurm gave it.
set -eo pipefail
source "$BEARING_SIM_ROOT/scripts/env.sh"
source "$BEARING_SIM_BUILD/devel/setup.bash"
A=\$((SLURM_ARRAY_TASK_ID * $per_task)); B=\$((A + $per_task))
if [ "\${SLURM_CPUS_PER_TASK:-1}" -gt 1 ]; then where="--workers \$SLURM_CPUS_PER_TASK"; else where=--serial; fi
echo "task \$SLURM_ARRAY_TASK_ID start \$(date +%s.%N) runs \$A:\$B \$where"
"$tool" "$campaign" --out "$out" --index-range \$A:\$B \$where
echo "task \$SLURM_ARRAY_TASK_ID end \$(date +%s.%N)"
EOF
say "submitting runs 0..$((runs - 1)) of $(basename "$campaign") as sbatch --array=0-$((tasks - 1)), $per_task runs and $cpus_per_task core(s) per task"
start=$(date +%s.%N)
job="$(sbatch --parsable --array=0-$((tasks - 1)) --job-name=bearing_campaign --cpus-per-task="$cpus_per_task" \
  --mem-per-cpu=1024 --time=$(((timeout_s + 59) / 60)) --output="$dir/task_%a.log" "$dir/task.sh")"
# The array's tasks, until none is pending or running.
wait_until "$timeout_s" "the job array $job" sh -c "[ -z \"\$(squeue -h -j '$job' -o %i)\" ]"
end=$(date +%s.%N)

# --- checks -------------------------------------------------------------------------------------
bad=0
for k in $(seq 0 $((tasks - 1))); do
  log="$dir/task_$k.log"
  if ! grep -q "^task $k end " "$log" 2>/dev/null \
     || ! grep -q "campaign [^ ]*: $per_task finished, 0 failed, 0 skipped" "$log"; then
    say "task $k did not finish its $per_task runs once each:"; sed 's/^/    /' "$log" 2>/dev/null || true
    bad=1
  fi
done
[ $bad -eq 0 ] || fail "a task of the array failed (logs: KEEP=1)"
"$tool" "$campaign" --out "$out" --manifest-only
"$tool" "$campaign" --out "$dir/serial" --index-range "0:$runs" --serial --quiet || fail "the --serial reference run failed"
/usr/bin/python3 - "$out" "$dir/serial" "$runs" <<'EOF' || fail "the array's runs differ from the --serial runs"
import csv, json, os, sys
out, serial, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
expected = sorted([f'run_{i:07d}.npy' for i in range(runs)] + [f'run_{i:07d}.json' for i in range(runs)])
names = sorted(os.listdir(os.path.join(out, 'runs')))
assert names == expected, f'runs/ holds {len(names)} files, expected one data file and one record per run'
for i in range(runs):
    record = json.load(open(os.path.join(out, 'runs', f'run_{i:07d}.json')))
    assert record['status'] == 'ok', f'run {i}: {record}'
    a, b = (open(os.path.join(d, 'runs', f'run_{i:07d}.npy'), 'rb').read() for d in (out, serial))
    assert a == b, f'run {i}: the data file differs from the --serial one'
manifest = open(os.path.join(out, 'manifest.csv'), 'rb').read()
assert manifest == open(os.path.join(serial, 'manifest.csv'), 'rb').read(), 'manifest.csv differs from --serial'
rows = list(csv.DictReader(manifest.decode().splitlines()))
assert [int(r['index']) for r in rows] == list(range(runs)) and {r['status'] for r in rows} == {'ok'}
EOF

# --- figures ------------------------------------------------------------------------------------
/usr/bin/python3 - "$dir" "$out" "$runs" "$tasks" "$cpus_per_task" "$start" "$end" <<'EOF'
import json, os, re, sys
d, out, runs, tasks, cpt, start, end = sys.argv[1], sys.argv[2], *map(int, sys.argv[3:6]), *map(float, sys.argv[6:8])
spans = []
for k in range(tasks):
    log = open(os.path.join(d, f'task_{k}.log')).read()
    t0 = float(re.search(r'start (\S+)', log).group(1)); t1 = float(re.search(r'end (\S+)', log).group(1))
    spans.append(t1 - t0)
records = [json.load(open(os.path.join(out, 'runs', f'run_{i:07d}.json'))) for i in range(runs)]
cpu = sum(r['cpu_s'] for r in records)
wall = end - start
allocated = sum(spans) * cpt
print(f'slurm_campaign: wall time {wall:.1f} s from sbatch to the array\'s end ({tasks} tasks of {runs // tasks} runs, '
      f'task times {", ".join(f"{s:.1f}" for s in spans)} s, {cpt} core(s) each, {os.cpu_count()} cores on the node)')
print(f'slurm_campaign: {runs} runs, {allocated:.1f} allocated core-s: {runs / allocated * 3600:.0f} runs per core-hour '
      f'allocated ({runs / (wall * os.cpu_count()) * 3600:.0f} per core-hour of the node\'s wall time); '
      f'simulation CPU {cpu / runs:.3f} s per run; load average {os.getloadavg()[0]:.2f}')
EOF
say "PASSED: $runs runs as a $tasks-task job array, each run once, byte-identical to --serial, manifest complete"
