#!/usr/bin/env bash
# A real one-node Slurm cluster on this machine, for `make test-slurm`
# (tests/slurm/test_slurm_cluster.py; docs/CLUSTER.md).
#
#   bash scripts/slurm_local_cluster.sh start   # install if missing, configure, start, wait
#   bash scripts/slurm_local_cluster.sh stop    # stop the daemons, remove config and state
#
# Both are idempotent. Run as root on Debian 12: `start` installs Debian's Slurm 22.05
# (slurmctld, slurmd, slurm-client) and munge when missing, writes
# /etc/slurm/slurm.conf for one node (this host, all its CPUs, one partition), starts
# munged (unless one already answers), slurmctld and slurmd, and waits until `sinfo`
# shows the node idle. Everything Slurm keeps (state, spool, logs, pid files) lives in
# $SLURM_LOCAL_DIR (default /var/lib/ballast-slurm), which `stop` removes.
# It refuses to touch a slurm.conf it did not write: this is for a test machine, not
# for a node of a real cluster.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
dir=${SLURM_LOCAL_DIR:-/var/lib/ballast-slurm}
conf=/etc/slurm/slurm.conf
marker="# Written by Ballast's scripts/slurm_local_cluster.sh: 'stop' removes it."
host=$(hostname -s)

die() { echo "slurm_local_cluster.sh: $*" >&2; exit 1; }

# The pid in FILE if that process is alive, else nothing.
live_pid() {
  local pid
  [ -f "$1" ] || return 0
  pid=$(cat "$1" 2>/dev/null || true)
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then echo "$pid"; fi
}

# Sends SIGTERM to the daemon in pid FILE and waits up to 30 s for it to go.
stop_daemon() {
  local name=$1 pidfile=$2 pid
  pid=$(live_pid "$pidfile")
  [ -n "$pid" ] || return 0
  kill "$pid"
  for _ in $(seq 60); do
    kill -0 "$pid" 2>/dev/null || { echo "stopped $name (pid $pid)"; return 0; }
    sleep 0.5
  done
  echo "slurm_local_cluster.sh: $name (pid $pid) did not stop on SIGTERM within 30 s; killing it" >&2
  kill -9 "$pid" 2>/dev/null || true
}

munge_answers() { munge -n 2>/dev/null | unmunge > /dev/null 2>&1; }

write_conf() {
  local cpus mem_mb
  cpus=$(nproc)
  # slurmd drains a node that has less memory than RealMemory says: claim half of it.
  mem_mb=$(( $(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 / 2 ))
  mkdir -p /etc/slurm
  cat > "$conf" <<EOF
$marker
# One node ($host, $cpus CPUs) in one partition, everything as root.
ClusterName=ballast-local
SlurmctldHost=$host
# The daemons talk over loopback whether or not the host name resolves.
SlurmctldAddr=127.0.0.1
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge

StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log

# No cgroups: track a job's processes through /proc and bind nothing, which works
# in a container as well as on a bare machine.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
# Cores are the resource (not whole nodes), so the tasks of an array share the node;
# memory is not, so jobs need not ask for it.
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
SwitchType=switch/none
# No slurmdbd: the test reads jobs with scontrol, which keeps a finished job for
# MinJobAge seconds.
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MinJobAge=900

# Requeueing: batch jobs may be requeued (scontrol requeue, sbatch --requeue), and a
# node that went down (e.g. slurmd restarted) returns to service when it registers.
JobRequeue=1
ReturnToService=2
# Seconds between SIGTERM and SIGKILL when a job is killed or requeued.
KillWait=10
# Start jobs promptly: the test's jobs are short.
SchedulerType=sched/builtin

NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
  [ "$(id -u)" -eq 0 ] || die "start needs root (it installs packages and runs the daemons as root)"
  if [ -f "$conf" ] && ! grep -qxF "$marker" "$conf"; then
    die "$conf exists and was not written by this script; refusing to replace it"
  fi
  bash "$here/install-packages.sh" slurm-local-cluster slurmctld slurmd slurm-client munge

  # munge authenticates every message between the Slurm commands and daemons.
  if munge_answers; then
    echo "munged already running"
  else
    if [ ! -s /etc/munge/munge.key ]; then
      mkdir -p /etc/munge
      mungekey --create --keyfile=/etc/munge/munge.key
    fi
    # munged insists that its key, state and socket belong to its user, munge.
    chown munge:munge /etc/munge /etc/munge/munge.key
    chmod 0700 /etc/munge
    chmod 0600 /etc/munge/munge.key
    mkdir -p /run/munge /var/lib/munge /var/log/munge
    chown munge:munge /run/munge /var/lib/munge /var/log/munge
    chmod 0755 /run/munge
    runuser -u munge -- /usr/sbin/munged
    mkdir -p "$dir"
    touch "$dir/started-munged"   # so that stop stops only a munged started here
    for _ in $(seq 20); do munge_answers && break; sleep 0.5; done
    munge_answers || die "munged started but 'munge -n | unmunge' fails (see /var/log/munge/munged.log)"
    echo "started munged"
  fi

  mkdir -p "$dir/state" "$dir/spool" "$dir/log"
  write_conf
  if [ -z "$(live_pid "$dir/slurmctld.pid")" ]; then
    slurmctld || die "slurmctld did not start (see $dir/log/slurmctld.log)"
    echo "started slurmctld"
  fi
  if [ -z "$(live_pid "$dir/slurmd.pid")" ]; then
    slurmd || die "slurmd did not start (see $dir/log/slurmd.log)"
    echo "started slurmd"
  fi

  # The node is idle once slurmd has registered with slurmctld.
  local state=""
  for _ in $(seq 120); do
    state=$(sinfo --noheader --nodes="$host" --format=%T 2>/dev/null || true)
    if [ "$state" = idle ]; then
      echo "slurm: node $host idle, $(nproc) CPUs, partition 'local' (config $conf, logs $dir/log)"
      return 0
    fi
    sleep 0.5
  done
  echo "slurm_local_cluster.sh: node $host is '${state:-not reported}', not idle, after 60 s" >&2
  tail -n 20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 2>/dev/null || true
  exit 1
}

stop() {
  if [ -f "$conf" ] && ! grep -qxF "$marker" "$conf"; then
    die "$conf was not written by this script; refusing to stop a cluster it did not start"
  fi
  # Stopping slurmd leaves its jobs running: cancel them first (a test that failed
  # half-way leaves some), and give them KillWait to go.
  if [ -n "$(live_pid "$dir/slurmctld.pid")" ]; then
    local jobs
    mapfile -t jobs < <(squeue --noheader --format=%A 2>/dev/null || true)
    if [ ${#jobs[@]} -gt 0 ]; then
      echo "cancelling jobs ${jobs[*]}"
      scancel "${jobs[@]}" || true
      for _ in $(seq 60); do
        [ -z "$(squeue --noheader --format=%A 2>/dev/null || true)" ] && break
        sleep 0.5
      done
    fi
  fi
  stop_daemon slurmd "$dir/slurmd.pid"
  stop_daemon slurmctld "$dir/slurmctld.pid"
  if pgrep -x slurmstepd > /dev/null; then
    echo "slurm_local_cluster.sh: warning: a job's slurmstepd outlived its cancellation:" >&2
    pgrep -a -x slurmstepd >&2 || true
  fi
  if [ -f "$dir/started-munged" ]; then
    if munged --stop > /dev/null 2>&1; then
      echo "stopped munged"
    else
      echo "slurm_local_cluster.sh: warning: 'munged --stop' failed (was it still running?)" >&2
    fi
  fi
  rm -f "$conf"
  rm -rf "$dir"
  echo "slurm: stopped, $dir and $conf removed"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  *) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2 ;;
esac
