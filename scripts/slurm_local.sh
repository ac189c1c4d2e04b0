#!/usr/bin/env bash
# A one-node Slurm on this machine, for CI and for trying the campaign scripts' job arrays for
# real (scripts/diagnosis_campaign.slurm, scripts/fit_campaign.slurm):
#
#   bash scripts/slurm_local.sh start STATEDIR   munged, slurmctld and slurmd, waits for the node
#                                                to be idle; then: export SLURM_CONF=STATEDIR/slurm.conf
#   bash scripts/slurm_local.sh stop STATEDIR    cancels what is queued, stops the three daemons;
#                                                never fails, also when they are already gone
#
# Needs Debian's slurmctld, slurmd, slurm-client and munge (scripts/setup.sh installs them) and
# root; no systemd, no cgroups. Everything it writes is under STATEDIR: its own munge key, socket
# and munged (not the system's /etc/munge or /run/munge), slurm.conf (the daemons and the client
# commands find it through SLURM_CONF, /etc/slurm is not touched), the controller's state, the
# node's spool, pid files and logs (STATEDIR/log/*.log). Each start begins from a clean state (the
# daemons of an earlier start on the same STATEDIR are stopped and its state removed), so it can
# be run twice in a row. The node is `localhost` (127.0.0.1) with the CPUs, sockets, cores and
# memory slurmd measures here; one partition `local`. Ports: SLURM_LOCAL_PORT (default 6817) for
# slurmctld and the next one for slurmd.
#
# Without slurmdbd there is no `sacct`: finished jobs are written to STATEDIR/log/jobcomp.log
# (jobcomp/filetxt) and stay in `scontrol show job` for MinJobAge (10 minutes); a task prolog
# prints "slurm_local: job J array task T ..." at the top of each task's output.
set -euo pipefail

usage() { echo "usage: bash scripts/slurm_local.sh start|stop STATEDIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
mkdir -p "$2"
state=$(cd "$2" && pwd)
conf=$state/slurm.conf
ctld_port=${SLURM_LOCAL_PORT:-6817}
slurmd_port=$((ctld_port + 1))
node=localhost
export SLURM_CONF=$conf

# One line naming what failed and the logs to read (then the end of each log, since a CI scratch
# folder is usually gone by the time anyone reads it), and exit 1. The daemons are left to `stop`.
die() {  # die MESSAGE [LOG...]
  local message=$1 log
  shift
  if [ $# -gt 0 ]; then
    local logs=$1
    [ $# -gt 1 ] && logs="$1 and $2"
    echo "slurm_local.sh: $message: read $logs" >&2
    for log in "$@"; do
      [ -s "$log" ] && tail -n 15 "$log" | sed "s|^|  $(basename "$log") |" >&2
    done
  else
    echo "slurm_local.sh: $message" >&2
  fi
  exit 1
}

# The pid in a pid file if that process is alive and is the daemon named (not a reused pid).
live_pid() {  # live_pid PIDFILE NAME
  local pid
  [ -s "$1" ] || return 1
  pid=$(tr -dc 0-9 < "$1")
  [ -n "$pid" ] && [ -r "/proc/$pid/comm" ] || return 1
  case $(cat "/proc/$pid/comm" 2>/dev/null) in "$2"*) echo "$pid" ;; *) return 1 ;; esac
}

# SIGTERM, up to 10 s for it to go, then SIGKILL. Only the pid of the pid file.
stop_daemon() {  # stop_daemon PIDFILE NAME
  local pid i
  if pid=$(live_pid "$1" "$2"); then
    kill -TERM "$pid" 2>/dev/null || true
    for i in $(seq 1 50); do
      [ -d "/proc/$pid" ] || break
      sleep 0.2
    done
    if [ -d "/proc/$pid" ]; then
      echo "slurm_local.sh: $2 (pid $pid) ignored SIGTERM for 10 s, killing it" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$1"
}

stop() {
  # First the jobs, so that slurmstepd ends their processes (proctrack/linuxproc) and exits.
  if live_pid "$state/run/slurmctld.pid" slurmctld > /dev/null; then
    local jobs i
    jobs=$(timeout 10 squeue -h -o %A 2>/dev/null | sort -u | tr '\n' ' ' || true)
    if [ -n "${jobs// /}" ]; then
      # shellcheck disable=SC2086  # job ids, one word each
      timeout 10 scancel $jobs 2>/dev/null || true
      for i in $(seq 1 30); do
        [ -z "$(timeout 5 squeue -h -o %A 2>/dev/null || true)" ] && break
        sleep 0.5
      done
    fi
  fi
  stop_daemon "$state/run/slurmd.pid" slurmd
  stop_daemon "$state/run/slurmctld.pid" slurmctld
  # A step daemon left behind (a job that would not end) belongs to this node when it carries this
  # SLURM_CONF (slurmd passes its environment on): those only, by pid.
  local p
  for p in $(pgrep -x slurmstepd 2>/dev/null || true); do
    if tr '\0' '\n' < "/proc/$p/environ" 2>/dev/null | grep -qx "SLURM_CONF=$conf"; then
      echo "slurm_local.sh: killing the leftover slurmstepd $p" >&2
      kill -KILL "$p" 2>/dev/null || true
    fi
  done
  stop_daemon "$state/munge/munged.pid" munged
  return 0
}

# True when something listens on 127.0.0.1:PORT.
port_in_use() { (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null; }

start() {
  [ "$(id -u)" -eq 0 ] || die "start needs root (the daemons run as root here)"
  local missing=() tool
  for tool in munged mungekey slurmctld slurmd sbatch sinfo squeue scancel scontrol; do
    command -v "$tool" > /dev/null || PATH=$PATH:/usr/sbin command -v "$tool" > /dev/null ||
      missing+=("$tool")
  done
  [ ${#missing[@]} -eq 0 ] ||
    die "${missing[*]} not found: install slurmctld slurmd slurm-client munge (bash scripts/setup.sh deps)"
  PATH=$PATH:/usr/sbin

  # Whatever an earlier start on this STATEDIR left: its daemons, its state.
  stop 2> /dev/null
  rm -rf "$state/ctld" "$state/spool" "$state/run" "$state/munge"
  mkdir -p "$state/ctld" "$state/spool" "$state/run" "$state/munge" "$state/log"
  # Root's clients only; munged wants the socket's folder searchable (the key itself is 0400).
  chmod 711 "$state/munge"
  : > "$state/log/munged.log"; : > "$state/log/slurmctld.log"; : > "$state/log/slurmd.log"
  : > "$state/log/jobcomp.log"
  # Unix socket paths (munge's, the step daemons' in the spool) must stay under 108 bytes.
  [ ${#state} -le 60 ] || die "STATEDIR $state is too long for Unix socket paths: use a shorter one (60 characters at most)"
  for port in "$ctld_port" "$slurmd_port"; do
    ! port_in_use "$port" ||
      die "port $port on 127.0.0.1 is taken (another Slurm?): set SLURM_LOCAL_PORT to a free pair"
  done

  # munge: a key of our own and munged on a socket under STATEDIR (the system's is left alone).
  mungekey --create --keyfile="$state/munge/munge.key" > "$state/log/munged.log" 2>&1 ||
    die "mungekey could not write a key" "$state/log/munged.log"
  chmod 400 "$state/munge/munge.key"
  munged --force --socket="$state/munge/munge.socket" --key-file="$state/munge/munge.key" \
    --pid-file="$state/munge/munged.pid" --seed-file="$state/munge/munged.seed" \
    --log-file="$state/log/munged.log" >> "$state/log/munged.log" 2>&1 ||
    die "munged did not start" "$state/log/munged.log"
  munge -n -S "$state/munge/munge.socket" | unmunge -S "$state/munge/munge.socket" > /dev/null 2>&1 ||
    die "munged does not answer on $state/munge/munge.socket" "$state/log/munged.log"

  # The node as slurmd measures it (CPUs, sockets, cores, threads, memory), named localhost.
  local hw
  hw=$(slurmd -C 2>/dev/null | head -1 | sed 's/^NodeName=[^ ]* //') ||
    die "slurmd -C could not read this machine's CPUs and memory"
  [ -n "$hw" ] || die "slurmd -C printed nothing"

  # The task prolog's "print" lines go to the top of each task's output.
  cat > "$state/task_prolog.sh" <<'EOF'
#!/bin/sh
echo "print slurm_local: job ${SLURM_JOB_ID:-?} array task ${SLURM_ARRAY_TASK_ID:-none} of ${SLURM_ARRAY_JOB_ID:-none} on ${SLURMD_NODENAME:-?}"
EOF
  chmod 755 "$state/task_prolog.sh"

  cat > "$conf" <<EOF
# Written by scripts/slurm_local.sh: a one-node Slurm for CI, everything under $state.
ClusterName=oscilab-local
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$state/munge/munge.socket
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/run/slurmctld.pid
SlurmdPidFile=$state/run/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No systemd, no cgroups: processes tracked through /proc, tasks not bound.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$state/log/jobcomp.log
TaskProlog=$state/task_prolog.sh
MpiDefault=none
MailProg=/bin/true
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MinJobAge=600
SlurmdTimeout=60
InactiveLimit=0
KillWait=10
NodeName=$node NodeAddr=127.0.0.1 $hw State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF

  slurmctld >> "$state/log/slurmctld.log" 2>&1 || die "slurmctld did not start" "$state/log/slurmctld.log"
  slurmd -N "$node" >> "$state/log/slurmd.log" 2>&1 || die "slurmd did not start" "$state/log/slurmd.log"

  # Up to 60 s for the node to be idle (slurmd registered with slurmctld).
  local i node_state=
  for i in $(seq 1 120); do
    live_pid "$state/run/slurmctld.pid" slurmctld > /dev/null || [ "$i" -lt 6 ] ||
      die "slurmctld exited" "$state/log/slurmctld.log"
    live_pid "$state/run/slurmd.pid" slurmd > /dev/null || [ "$i" -lt 6 ] ||
      die "slurmd exited" "$state/log/slurmd.log"
    node_state=$(timeout 5 sinfo -h -n "$node" -o %T 2>/dev/null || true)
    if [ "$node_state" = idle ]; then
      echo "slurm_local.sh: node $node idle ($hw); export SLURM_CONF=$conf"
      return 0
    fi
    sleep 0.5
  done
  die "node $node not idle after 60 s (state: ${node_state:-no answer from slurmctld})" \
    "$state/log/slurmd.log" "$state/log/slurmctld.log"
}

case $action in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
