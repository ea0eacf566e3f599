#!/usr/bin/env bash
# Proves the Slurm path of gridtopo-experiment on a real single-node Slurm cluster started here from Debian's
# slurm-wlm and munge packages, without systemd and with every file (keys, sockets, state, logs, configuration)
# in one temporary folder: submits the quick experiment (config-ini/experiments/quick.ini) as a job array
# (`--emit slurm`), collects it (`--collect`), runs the same experiment locally and compares every run's
# parameters and metrics (not times, host or folders). Stops every daemon it started, by the pids it started them
# with, whatever happens (trap). Works as root or as a normal user.
#
# Usage: scripts/check_slurm.sh [EXPERIMENT.ini]     (needs: apt-get install slurm-wlm munge; a built tree)
# Exit 0 when the Slurm results equal the local ones. GRIDTOPO_BUILD_DIR selects the build folder (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BIN=${GRIDTOPO_BUILD_DIR:-build}/bin
EXP=$(realpath "${1:-config-ini/experiments/quick.ini}")
for t in munged mungekey slurmctld slurmd sbatch sinfo squeue python3; do
  command -v "$t" > /dev/null || [ -x "/usr/sbin/$t" ] ||
    { echo "check_slurm: $t not found (apt-get install slurm-wlm munge python3)" >&2; exit 1; }
done
export PATH=$PATH:/usr/sbin
[ -x "$BIN/gridtopo-experiment" ] || { echo "check_slurm: build gridtopo-experiment first" >&2; exit 1; }
T0=$EPOCHREALTIME
say() { awk -v a="$EPOCHREALTIME" -v b="$T0" -v m="$*" 'BEGIN { printf "check_slurm: %6.1f s  %s\n", a - b, m }'; }

# Short paths: munge's socket path must stay under ~60 characters.
D=$(mktemp -d /tmp/gtslurm.XXXXXX)
chmod 711 "$D"  # munged wants execute permission for all on every folder above its socket
PIDS=()
# Alive: /proc/PID/stat exists and its state (the field after "(comm)") is not Z: exited daemons linger as zombies.
alive() {
  local stat
  stat=$(cat "/proc/$1/stat" 2> /dev/null) || return 1
  stat=${stat##*) }
  [ -n "$stat" ] && [ "${stat%% *}" != Z ]
}
stop_daemons() {
  local p
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do
    p=${PIDS[i]}
    alive "$p" && kill -TERM "$p" 2> /dev/null || true
  done
  for p in "${PIDS[@]}"; do
    for _ in $(seq 50); do alive "$p" || break; sleep 0.1; done
    alive "$p" && { echo "check_slurm: pid $p did not stop on TERM, killing it" >&2; kill -KILL "$p" 2> /dev/null || true; }
    wait "$p" 2> /dev/null || true
  done
  PIDS=()
}
cleanup() {
  local rc=$?
  stop_daemons
  if [ "$rc" = 0 ] && [ -z "${KEEP:-}" ]; then rm -rf "$D"; else echo "check_slurm: files kept in $D" >&2; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

USER_NAME=$(id -un)
HOST=$(hostname -s 2> /dev/null || true)
[ -n "$HOST" ] || HOST=127.0.0.1
CPUS=$(nproc)
read -r CTLD_PORT SLURMD_PORT < <(python3 -c 'import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')

# munge: every path as an option.
mkdir -p "$D/munge" "$D/run" "$D/state" "$D/spool" "$D/log"
chmod 700 "$D/munge"
chmod 755 "$D/run"
mungekey --create --keyfile="$D/munge/munge.key" 2> /dev/null ||
  { dd if=/dev/urandom bs=1 count=1024 of="$D/munge/munge.key" status=none; }
chmod 600 "$D/munge/munge.key"
SOCK=$D/run/munge.sock
munged --foreground --key-file="$D/munge/munge.key" --socket="$SOCK" --pid-file="$D/munge/munged.pid" \
  --log-file="$D/log/munged.log" --seed-file="$D/munge/seed" > "$D/log/munged.out" 2>&1 &
PIDS+=($!)
for _ in $(seq 100); do [ -S "$SOCK" ] && break; sleep 0.05; done
[ -S "$SOCK" ] || { cat "$D/log/munged.out" "$D/log/munged.log" >&2; echo "check_slurm: munged did not start" >&2; exit 1; }
say "munged up (pid ${PIDS[0]})"

cat > "$D/slurm.conf" << CONF
ClusterName=gtcheck
SlurmctldHost=$HOST(127.0.0.1)
SlurmUser=$USER_NAME
SlurmdUser=$USER_NAME
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
AuthType=auth/munge
AuthInfo=socket=$SOCK
CredType=cred/munge
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
PlugStackConfig=/dev/null
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=check Nodes=$HOST Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF
export SLURM_CONF=$D/slurm.conf
slurmctld -D -f "$SLURM_CONF" > "$D/log/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -f "$SLURM_CONF" -N "$HOST" > "$D/log/slurmd.out" 2>&1 &
PIDS+=($!)
state=
for _ in $(seq 200); do
  state=$(sinfo -h -o %T 2> /dev/null | head -1 || true)
  [ "$state" = idle ] && break
  for p in "${PIDS[@]}"; do alive "$p" || { cat "$D"/log/*.out "$D"/log/*.log >&2; echo "check_slurm: daemon $p died" >&2; exit 1; }; done
  sleep 0.05
done
[ "$state" = idle ] || { tail -20 "$D"/log/slurm*.log >&2; echo "check_slurm: node not idle ($state)" >&2; exit 1; }
say "slurmctld (pid ${PIDS[1]}) and slurmd (pid ${PIDS[2]}) up, node $HOST idle with $CPUS CPUs"

# The experiment through Slurm: a job array, then --collect.
OUT_SLURM=$D/slurm-results
OUT_LOCAL=$D/local-results
script=$("$BIN/gridtopo-experiment" "$EXP" -o "$OUT_SLURM" --emit slurm)
runs=$(sed -n 's/^#SBATCH --array=0-\([0-9]*\)$/\1/p' "$script")
job=$(sbatch --parsable "$script")
say "submitted $script as job $job (array 0-$runs)"
for _ in $(seq 6000); do
  [ -z "$(squeue -h -j "$job" 2> /dev/null)" ] && break
  sleep 0.1
done
[ -z "$(squeue -h -j "$job" 2> /dev/null)" ] || { echo "check_slurm: job $job still queued after 10 minutes" >&2; exit 1; }
say "job array $job finished"
"$BIN/gridtopo-experiment" "$EXP" -o "$OUT_SLURM" --collect
stop_daemons
say "daemons stopped"

"$BIN/gridtopo-experiment" "$EXP" -o "$OUT_LOCAL" -q
say "same experiment run locally"
python3 - "$OUT_SLURM/results.jsonl" "$OUT_LOCAL/results.jsonl" << 'PY'
import json, sys
VARYING = {"wall_s", "cpu_s", "peak_rss_mb", "start_time", "host", "dir", "commit"}
def rows(p):
    return [{k: v for k, v in json.loads(l).items() if k not in VARYING} for l in open(p)]
a, b = rows(sys.argv[1]), rows(sys.argv[2])
if len(a) != len(b) or not a:
    sys.exit(f"check_slurm: {len(a)} runs through Slurm, {len(b)} locally")
for x, y in zip(a, b):
    if x != y:
        diff = {k: (x.get(k), y.get(k)) for k in set(x) | set(y) if x.get(k) != y.get(k)}
        sys.exit(f"check_slurm: run {x['index']} differs: {diff}")
    if x["status"] != "ok":
        sys.exit(f"check_slurm: run {x['index']} is {x['status']}: {x['error']}")
print(f"check_slurm: {len(a)} runs, Slurm and local results identical "
      f"(every parameter and metric; trans_mean_m {', '.join('%.6f' % r['trans_mean_m'] for r in a)})")
PY
say "passed"
