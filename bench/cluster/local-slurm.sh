#!/usr/bin/env bash
# A private single-node Slurm cluster (Debian's slurm-wlm with munge) living in one folder: for
# trying OCPBench's Slurm path on one machine, for its tests and for its throughput benchmark.
# Needs root (munged runs as the munge user) and no systemd. Everything is under STATE: its own
# munge key, its own free ports, pid files, controller state and logs, so it
# never touches a system Slurm or munge and two of them can run side by side. Its Unix sockets
# (munge's, and the job steps' in slurmd's spool) live in a short private folder under /tmp
# (mktemp; its path is in STATE/runtime-dir), since a socket's path may not exceed 107 bytes and
# STATE may be deep in a clone; stop removes it with STATE.
#
#   source bench/cluster/local-slurm.sh
#   local_slurm_start STATE   # exports SLURM_CONF; returns when the node is idle (or fails)
#   sbatch ... / squeue ...
#   local_slurm_stop STATE    # cancels its jobs, stops slurmd, slurmctld, munged, removes STATE
#
# or as a command: bash bench/cluster/local-slurm.sh start|stop STATE (start prints the
# `export SLURM_CONF=...` line to use).
#
# Settings verified on this machine kind (Debian 12, root, cgroup v1 without a usable freezer):
# process tracking by the process tree (proctrack/linuxproc) and no task plugin: the default
# cgroup tracking fails silently here (tasks show COMPLETED although nothing ran), so whoever
# uses this cluster must check what the tasks wrote, never only their states.

# Seconds to wait for each daemon to come up.
LOCAL_SLURM_START_TIMEOUT=${LOCAL_SLURM_START_TIMEOUT:-30}

_local_slurm_log() { echo "local-slurm: $*" >&2; }

# Two free TCP ports on the loopback address (the controller's and slurmd's).
_local_slurm_free_ports() {
  /usr/bin/python3 - <<'EOF'
import socket
socks = [socket.socket() for _ in range(2)]
for s in socks:
    s.bind(("127.0.0.1", 0))
print(" ".join(str(s.getsockname()[1]) for s in socks))
EOF
}

# Polls `$@` every 0.2 s until it succeeds or $1 seconds pass.
_local_slurm_wait_for() {
  local timeout=$1
  shift
  local deadline=$((SECONDS + timeout))
  until "$@" >/dev/null 2>&1; do
    ((SECONDS < deadline)) || return 1
    sleep 0.2
  done
}

_local_slurm_node_idle() { sinfo -h -N -o '%t' | grep -qx idle; }

# Sends SIGTERM to the pid in file $1, then SIGKILL after $2 seconds; waits for it to go.
_local_slurm_stop_pid_file() {
  local file=$1 grace=$2 pid
  [ -s "$file" ] || return 0
  pid=$(cat "$file")
  [ -d "/proc/$pid" ] || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  local deadline=$((SECONDS + grace))
  while [ -d "/proc/$pid" ] && ((SECONDS < deadline)); do sleep 0.1; done
  if [ -d "/proc/$pid" ]; then
    kill -KILL "$pid" 2>/dev/null || true
    while [ -d "/proc/$pid" ]; do sleep 0.1; done
  fi
}

local_slurm_start() {
  local state=$1
  if [ -z "$state" ]; then
    _local_slurm_log "usage: local_slurm_start STATE_FOLDER"
    return 2
  fi
  if [ "$(id -u)" -ne 0 ]; then
    _local_slurm_log "must run as root (munged runs as the munge user, slurmd as root)"
    return 2
  fi
  local tool
  for tool in munged munge unmunge slurmctld slurmd sbatch squeue sinfo scontrol scancel setpriv; do
    if ! command -v "$tool" >/dev/null; then
      _local_slurm_log "$tool not found (Debian packages: munge slurmctld slurmd slurm-client)"
      return 2
    fi
  done
  state=$(realpath -m "$state")
  # A cluster left in STATE by an earlier start: its daemons and its socket folder go first.
  local_slurm_stop "$state"
  rm -rf "$state"
  mkdir -p "$state"/{munge,ctld,tmp}
  chmod 0755 "$state"
  local runtime
  runtime=$(mktemp -d /tmp/ocpb-slurm.XXXXXX) || return 1
  echo "$runtime" >"$state/runtime-dir"
  mkdir -p "$runtime"/{munge-socket,spool}
  chmod 0755 "$runtime"
  # munged refuses a key that others could read and a socket folder that others cannot enter.
  chown munge:munge "$state/munge" "$runtime/munge-socket"
  chmod 0700 "$state/munge"
  chmod 0755 "$runtime/munge-socket"
  dd if=/dev/urandom of="$state/munge/munge.key" bs=1024 count=1 status=none
  chown munge:munge "$state/munge/munge.key"
  chmod 0400 "$state/munge/munge.key"
  local socket="$runtime/munge-socket/munge.socket"
  setpriv --reuid=munge --regid=munge --init-groups \
    munged -F --socket="$socket" --key-file="$state/munge/munge.key" \
    --pid-file="$state/munge/munged.pid" --log-file="$state/munge/munged.log" \
    --seed-file="$state/munge/munged.seed" >"$state/munged.out" 2>&1 &
  echo $! >"$state/munged.pid"
  if ! _local_slurm_wait_for "$LOCAL_SLURM_START_TIMEOUT" \
    bash -c "munge -S '$socket' -n | unmunge -S '$socket'"; then
    _local_slurm_log "munged did not start: $(tail -3 "$state/munged.out" 2>/dev/null)"
    return 1
  fi

  local ports ctld_port slurmd_port
  ports=$(_local_slurm_free_ports) || return 1
  read -r ctld_port slurmd_port <<<"$ports"
  local host cpus
  host=$(hostname -s)
  cpus=$(nproc)
  cat >"$state/slurm.conf" <<EOF
# Written by bench/cluster/local-slurm.sh: a private single-node cluster in $state.
ClusterName=ocpbench
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$runtime/spool
TmpFS=$state/tmp
SlurmctldPidFile=$state/slurmctld.pid.conf
SlurmdPidFile=$state/slurmd.pid.conf
SlurmctldLogFile=$state/slurmctld.log
SlurmdLogFile=$state/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SlurmdParameters=config_overrides
ReturnToService=2
MailProg=/bin/true
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
# Finished jobs stay visible to squeue for 5 minutes; a cancelled task gets 5 s between SIGTERM
# and SIGKILL.
MinJobAge=300
KillWait=5
NodeName=ocpbnode NodeAddr=127.0.0.1 CPUs=$cpus Sockets=1 CoresPerSocket=$cpus ThreadsPerCore=1 RealMemory=1024 State=UNKNOWN
PartitionName=ocpb Nodes=ocpbnode Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$state/slurm.conf"
  slurmctld -D -i >"$state/slurmctld.out" 2>&1 &
  echo $! >"$state/slurmctld.pid"
  if ! _local_slurm_wait_for "$LOCAL_SLURM_START_TIMEOUT" bash -c "scontrol ping | grep -q UP"; then
    _local_slurm_log "slurmctld did not come up: $(tail -3 "$state/slurmctld.log" 2>/dev/null)"
    return 1
  fi
  slurmd -D -N ocpbnode >"$state/slurmd.out" 2>&1 &
  echo $! >"$state/slurmd.pid"
  if ! _local_slurm_wait_for "$LOCAL_SLURM_START_TIMEOUT" _local_slurm_node_idle; then
    _local_slurm_log "the node did not become idle: $(tail -3 "$state/slurmd.log" 2>/dev/null)"
    return 1
  fi
  _local_slurm_log "cluster up in $state (controller port $ctld_port, $cpus CPUs)"
}

# Processes that carry this cluster's SLURM_CONF in their environment: its job steps and the
# tasks they started (they outlive a killed slurmd). Only this cluster's: the folder is unique.
_local_slurm_leftover_pids() {
  local conf=$1 dir pid
  for dir in /proc/[0-9]*; do
    pid=${dir#/proc/}
    [ "$pid" = "$$" ] && continue
    if { tr '\0' '\n' <"$dir/environ"; } 2>/dev/null | grep -qxF "SLURM_CONF=$conf"; then
      echo "$pid"
    fi
  done
}

local_slurm_stop() {
  local state=$1
  [ -n "$state" ] || return 0
  state=$(realpath -m "$state")
  [ -d "$state" ] || return 0
  local conf="$state/slurm.conf"
  if [ -s "$state/slurmctld.pid" ] && [ -d "/proc/$(cat "$state/slurmctld.pid")" ]; then
    SLURM_CONF=$conf scancel --full --quiet -u "$(id -un)" 2>/dev/null || true
    local deadline=$((SECONDS + 10))
    while ((SECONDS < deadline)) && [ -n "$(SLURM_CONF=$conf squeue -h -t R,CG,PD 2>/dev/null)" ]; do
      sleep 0.2
    done
  fi
  # slurmd first (it may ignore SIGTERM when it cannot register), then the controller, munge last.
  _local_slurm_stop_pid_file "$state/slurmd.pid" 5
  _local_slurm_stop_pid_file "$state/slurmctld.pid" 5
  local pid
  for pid in $(_local_slurm_leftover_pids "$conf"); do kill -KILL "$pid" 2>/dev/null || true; done
  _local_slurm_stop_pid_file "$state/munged.pid" 5
  # The private socket folder: only one that start made (its name's pattern, under /tmp).
  local runtime
  runtime=$(cat "$state/runtime-dir" 2>/dev/null || true)
  case "$runtime" in
    /tmp/ocpb-slurm.??????) rm -rf "$runtime" ;;
  esac
  rm -rf "$state"
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
  set -euo pipefail
  case "${1:-}" in
    start)
      local_slurm_start "${2:?usage: local-slurm.sh start STATE}"
      echo "export SLURM_CONF=$(realpath -m "$2")/slurm.conf"
      ;;
    stop) local_slurm_stop "${2:?usage: local-slurm.sh stop STATE}" ;;
    *)
      echo "usage: bash bench/cluster/local-slurm.sh start|stop STATE" >&2
      exit 2
      ;;
  esac
fi
