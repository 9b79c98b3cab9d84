#!/usr/bin/env bash
# A real single-node Slurm on this machine, for tests and for trying `tilekit cluster` locally.
#
#   scripts/slurm/local-slurm.sh install      # Debian packages slurm-wlm and munge (idempotent)
#   scripts/slurm/local-slurm.sh start DIR    # munged + slurmctld + slurmd, all state under DIR
#   source DIR/env                            # SLURM_CONF for sbatch/squeue/scontrol/sinfo
#   scripts/slurm/local-slurm.sh stop DIR     # cancels jobs, stops every daemon by PID
#
# DIR holds everything: the munge key and socket, slurm.conf, StateSaveLocation, the spool,
# pid files and logs (DIR/log/*.log). Nothing under /etc or /var is used or changed, so a
# stale or system-wide Slurm is left alone. The configuration is the smallest that runs jobs:
# SlurmctldHost = short hostname, auth/munge, proctrack/linuxproc, task/none, SlurmUser=root,
# select/cons_tres with CR_Core, one node with CPUs=$(nproc) and RealMemory = memory - 1 GiB,
# one default partition. `start` exits non-zero, with the daemon's log, if any daemon does not
# come up; it never leaves a half-started cluster behind (it stops what it started).
set -euo pipefail

die() { echo "local-slurm: $*" >&2; exit 1; }

install_packages() {
  local pkgs=(slurm-wlm munge) missing=() p
  for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "local-slurm: installing ${missing[*]}" >&2
  local SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get install -y -q "${missing[@]}" >/dev/null 2>&1 || {
    $SUDO apt-get update -q >/dev/null
    $SUDO apt-get install -y -q "${missing[@]}" >/dev/null
  }
  for p in munged slurmctld slurmd sbatch scontrol squeue sinfo; do
    command -v "$p" >/dev/null || [ -x "/usr/sbin/$p" ] || die "$p missing after installing ${missing[*]}"
  done
}

# First TCP port >= $1 that nothing listens on and that is not $2.
free_port() {
  local p=$1
  while ((p < $1 + 200)); do
    if [ "$p" != "${2:-}" ] && [ -z "$(ss -Htln "sport = :$p" 2>/dev/null)" ]; then
      echo "$p"
      return 0
    fi
    p=$((p + 1))
  done
  die "no free TCP port from $1"
}

# Waits up to $2 seconds for command "$3..." to succeed; returns 1 on time-out.
wait_for() {
  local what=$1 secs=$2
  shift 2
  local end=$((SECONDS + secs))
  until "$@" >/dev/null 2>&1; do
    ((SECONDS < end)) || { echo "local-slurm: $what did not come up in ${secs}s" >&2; return 1; }
    sleep 0.5
  done
}

pid_alive() { [ -n "${1:-}" ] && kill -0 "$1" 2>/dev/null; }

# Stops the process whose id is in file $1 (TERM, then KILL after 10 s).
stop_pidfile() {
  local f=$1 pid
  [ -s "$f" ] || return 0
  pid=$(cat "$f")
  pid_alive "$pid" || return 0
  kill -TERM "$pid" 2>/dev/null || true
  local end=$((SECONDS + 10))
  while pid_alive "$pid" && ((SECONDS < end)); do sleep 0.2; done
  if pid_alive "$pid"; then
    echo "local-slurm: pid $pid ($f) ignored TERM; killing" >&2
    kill -KILL "$pid" 2>/dev/null || true
  fi
}

show_log() {
  echo "---- $1 (last 30 lines) ----" >&2
  tail -n 30 "$1" >&2 2>/dev/null || echo "(no log)" >&2
}

start_cluster() {
  local dir=$1
  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  [ ! -e "$dir/run/slurmctld.pid" ] || die "$dir already holds a cluster (stop it first)"
  mkdir -p "$dir"/{munge,state,spool,run,log}
  chmod 0700 "$dir/munge"

  for p in munged slurmctld slurmd sbatch scontrol; do
    command -v "$p" >/dev/null || [ -x "/usr/sbin/$p" ] ||
      die "$p not found: run '$0 install' first"
  done
  export PATH="$PATH:/usr/sbin"

  # If anything below fails, stop what was already started: never a half-started cluster.
  START_OK=0
  trap '[ "$START_OK" = 1 ] || { echo "local-slurm: start failed; stopping what was started" >&2; stop_cluster "$dir"; }' EXIT

  # munge: our own key and socket (the system's /etc/munge is not touched).
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chmod 0400 "$dir/munge/munge.key"
  local sock="$dir/munge/munge.socket"
  munged --force --socket="$sock" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/run/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munged.seed" ||
    { show_log "$dir/log/munged.log"; die "munged did not start"; }
  wait_for munged 10 munge --socket="$sock" -n ||
    { show_log "$dir/log/munged.log"; die "munged does not answer on $sock"; }

  local host cpus mem_mib ctld_port slurmd_port ctld_addr="" node_addr=""
  host=$(hostname -s)
  # A host name that does not resolve gets the loopback address (a single-node cluster).
  if ! getent hosts "$host" >/dev/null 2>&1; then
    ctld_addr="(127.0.0.1)"
    node_addr=" NodeAddr=127.0.0.1"
  fi
  cpus=$(nproc)
  mem_mib=$(($(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 - 1024))
  ((mem_mib > 0)) || die "less than 1 GiB of memory"
  ctld_port=$(free_port "${TILEKIT_SLURMCTLD_PORT:-6817}")
  slurmd_port=$(free_port "${TILEKIT_SLURMD_PORT:-6818}" "$ctld_port")

  cat >"$dir/slurm.conf" <<EOF
# Minimal single-node Slurm written by scripts/slurm/local-slurm.sh.
ClusterName=tilekit
SlurmctldHost=$host$ctld_addr
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
# cred_expire: also how long a requeued job waits before it may start again (default 120 s).
AuthInfo=socket=$sock,cred_expire=${TILEKIT_SLURM_CRED_EXPIRE:-10}
SlurmUser=root
SlurmdUser=root
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
# One line per finished job incarnation (state, exit code) for tests to read.
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ReturnToService=2
# Schedule every few seconds (defaults: 60 s / 30 s) so short test jobs do not wait.
SchedulerParameters=sched_interval=2,bf_interval=5
# Keep finished jobs visible to scontrol for an hour (tests read their exit codes).
MinJobAge=3600
KillWait=10
MailProg=/bin/true
NodeName=$host$node_addr CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$dir/slurm.conf"
  printf 'export SLURM_CONF=%q\nexport PATH="$PATH:/usr/sbin"\n' "$SLURM_CONF" >"$dir/env"

  slurmctld -f "$SLURM_CONF" || { show_log "$dir/log/slurmctld.log"; die "slurmctld did not start"; }
  wait_for slurmctld 30 scontrol ping ||
    { show_log "$dir/log/slurmctld.log"; die "slurmctld does not answer"; }
  slurmd -f "$SLURM_CONF" -N "$host" || { show_log "$dir/log/slurmd.log"; die "slurmd did not start"; }
  wait_for "node $host" 30 node_is_up "$host" ||
    { show_log "$dir/log/slurmd.log"; show_log "$dir/log/slurmctld.log"; die "node $host is not up"; }
  START_OK=1
  echo "local-slurm: up in $dir (slurmctld :$ctld_port, slurmd :$slurmd_port, node $host: $cpus CPUs, ${mem_mib} MiB)" >&2
}

node_is_up() {
  local state
  state=$(sinfo -h -n "$1" -o %T 2>/dev/null | head -n 1)
  [[ "$state" == idle* || "$state" == mixed* || "$state" == allocated* ]]
}

stop_cluster() {
  local dir=$1
  [ -d "$dir" ] || return 0
  set +e  # best effort from here on: every daemon gets its stop even if a step fails
  dir=$(cd "$dir" && pwd)
  export PATH="$PATH:/usr/sbin" SLURM_CONF="$dir/slurm.conf"
  # Jobs first: slurmstepd outlives slurmd by design, so cancel and wait for the steps to end.
  if [ -f "$SLURM_CONF" ] && pid_alive "$(cat "$dir/run/slurmctld.pid" 2>/dev/null)"; then
    scancel --full --quiet --user=root 2>/dev/null || true
    local end=$((SECONDS + 20))
    while [ -n "$(squeue -h -t R,CG,S 2>/dev/null)" ] && ((SECONDS < end)); do sleep 0.5; done
    if pid_alive "$(cat "$dir/run/slurmd.pid" 2>/dev/null)"; then
      # Processes of job steps still on this node (by id, as slurmd reports them).
      local pids
      pids=$(scontrol listpids 2>/dev/null | awk 'NR > 1 && $1 ~ /^[0-9]+$/ {print $1}')
      # shellcheck disable=SC2086
      [ -z "$pids" ] || kill -KILL $pids 2>/dev/null || true
    fi
  fi
  stop_pidfile "$dir/run/slurmd.pid"
  stop_pidfile "$dir/run/slurmctld.pid"
  stop_pidfile "$dir/run/munged.pid"
  rm -f "$dir/run/slurmctld.pid" "$dir/run/slurmd.pid" "$dir/run/munged.pid"
}

case "${1:-}" in
  install) install_packages ;;
  start) [ -n "${2:-}" ] || die "usage: $0 start DIR"; start_cluster "$2" ;;
  stop) [ -n "${2:-}" ] || die "usage: $0 stop DIR"; stop_cluster "$2" ;;
  *) echo "usage: $0 install | start DIR | stop DIR" >&2; exit 2 ;;
esac
