# A one-node Slurm on this machine for tests: munged, slurmctld and slurmd with a generated
# slurm.conf, everything (key, state, spool, logs, sockets) in one private folder, free ports
# on 127.0.0.1. Sourced by slurm_arrays_test.sh:
#   slurm_up DIR || skip "$SLURM_WHY"   then sbatch/squeue/scontrol with SLURM_CONF set;
#   slurm_down                          stops what slurm_up started (by pid) and nothing else.

slurm_free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

slurm_up() {
  local d=$1
  SLURM_DIR=$d
  SLURM_WHY=""
  for tool in munged slurmctld slurmd sbatch squeue scontrol sinfo; do
    if ! command -v "$tool" >/dev/null; then
      SLURM_WHY="$tool is not installed (scripts/install-deps.sh --slurm installs slurm-wlm and munge)"
      return 1
    fi
  done
  if [ "$(id -u)" != 0 ]; then
    SLURM_WHY="slurmd must run as root to start jobs (this test runs as $(id -un))"
    return 1
  fi
  mkdir -p "$d"/{state,spool,munge} && chmod 700 "$d" "$d"/munge
  head -c 1024 /dev/urandom > "$d/munge/munge.key" && chmod 400 "$d/munge/munge.key"
  munged --force --socket="$d/munge/munge.socket" --key-file="$d/munge/munge.key" \
    --pid-file="$d/munge/munged.pid" --log-file="$d/munge/munged.log" --seed-file="$d/munge/munge.seed" \
    2>"$d/munge/start.log" || { SLURM_WHY="munged did not start: $(tail -2 "$d/munge/start.log" "$d/munge/munged.log" 2>/dev/null | tr '\n' ' ')"; return 1; }
  local host cpus
  host=$(hostname -s)
  cpus=$(nproc)
  export SLURM_CONF=$d/slurm.conf
  cat > "$SLURM_CONF" <<CONF
ClusterName=pathlettest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$(slurm_free_port)
SlurmdPort=$(slurm_free_port)
AuthType=auth/munge
AuthInfo=socket=$d/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
# Dependent steps start within a second of what they wait for, not at the next 60 s pass.
SchedulerParameters=sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
SlurmdParameters=config_overrides
NodeName=pathletnode NodeHostname=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=pathletnode Default=YES MaxTime=INFINITE State=UP
CONF
  slurmctld -c -f "$SLURM_CONF" 2>"$d/slurmctld.start" || { SLURM_WHY="slurmctld did not start: $(tail -3 "$d/slurmctld.start" "$d/slurmctld.log" 2>/dev/null | tr '\n' ' ')"; return 1; }
  slurmd -f "$SLURM_CONF" -N pathletnode 2>"$d/slurmd.start" || { SLURM_WHY="slurmd did not start: $(tail -3 "$d/slurmd.start" "$d/slurmd.log" 2>/dev/null | tr '\n' ' ')"; return 1; }
  local i state
  for i in $(seq 1 60); do
    state=$(sinfo -h -N -o %t 2>/dev/null | head -1)
    [ "$state" = idle ] && return 0
    sleep 0.5
  done
  SLURM_WHY="the node did not come up (state '${state:-none}'): $(tail -3 "$d/slurmd.log" "$d/slurmctld.log" 2>/dev/null | tr '\n' ' ')"
  return 1
}

slurm_down() {
  [ -n "${SLURM_DIR:-}" ] || return 0
  [ -f "${SLURM_CONF:-}" ] && scancel --quiet --user="$(id -un)" 2>/dev/null || true
  local f pid
  for f in "$SLURM_DIR/slurmd.pid" "$SLURM_DIR/slurmctld.pid" "$SLURM_DIR/munge/munged.pid"; do
    [ -f "$f" ] || continue
    pid=$(cat "$f")
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  done
}

# Waits for every job in "$@" to leave the queue (at most $SLURM_WAIT s); 1 on time-out.
slurm_wait() {
  local i
  for i in $(seq 1 $((${SLURM_WAIT:-180} * 2))); do
    [ -z "$(squeue -h -j "$(IFS=,; echo "$*")" -o %i 2>/dev/null)" ] && return 0
    sleep 0.5
  done
  return 1
}

# Prints "JobState ExitCode" of every task of a job, one line each.
slurm_states() {
  scontrol -o show job "$1" | sed -E 's/.*JobState=([A-Z_]+).* ExitCode=([0-9:]+).*/\1 \2/'
}
