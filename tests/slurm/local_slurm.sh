# A private single-node Slurm on localhost, for tests: sourced by tests/slurm/*.sh (bash).
#
#   local_slurm_start DIR   munged, slurmctld and slurmd with every file in DIR (an empty
#                           directory); exports SLURM_CONF; returns once the node is idle
#   local_slurm_stop        cancels every job, then stops the daemons by their PIDs
#
# Nothing outside DIR is written: munged has its own key and socket there, and the
# cluster listens on two ports chosen free at start (retried if one is taken meanwhile), so it
# never meets a Slurm that another test or a person runs on this machine. No systemd, no
# cgroups: proctrack/linuxproc, task/none. The node declares 4 CPUs whatever the machine has
# (SlurmdParameters=config_overrides), so a 4-task job array runs at once, as on 4 nodes.
# Every wait has a deadline; the daemons run in the foreground (-D, -F) as children of this
# shell, so their PIDs are known without trusting a PID file.

LOCAL_SLURM_MUNGED="" LOCAL_SLURM_CTLD="" LOCAL_SLURM_SLURMD=""

# Prints N TCP ports in 20000-32767 (below Linux's ephemeral range) that no socket on this
# machine uses now, IPv4 or IPv6, listening or connected.
_local_slurm_free_ports() {
    local count=$1 used port found=0
    used=$(awk 'NR > 1 { split($2, a, ":"); print a[2] }' /proc/net/tcp /proc/net/tcp6 \
        2>/dev/null | while read -r hex; do [ -n "$hex" ] && echo $((16#$hex)); done)
    while [ "$found" -lt "$count" ]; do
        port=$((20000 + RANDOM % 12768))
        if ! grep -qx "$port" <<<"$used"; then
            echo "$port"
            used+=$'\n'"$port"
            found=$((found + 1))
        fi
    done
}

# Waits until COMMAND succeeds, at most SECONDS (tenths of a second between tries).
_local_slurm_wait_for() {
    local seconds=$1 tries
    shift
    for ((tries = seconds * 10; tries > 0; tries--)); do
        "$@" >/dev/null 2>&1 && return 0
        sleep 0.1
    done
    return 1
}

_local_slurm_write_conf() {
    local dir=$1 ctld_port=$2 slurmd_port=$3
    cat >"$dir/slurm.conf" <<EOF
# Written by tests/slurm/local_slurm.sh: a private single-node Slurm in $dir
ClusterName=glint
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket.2
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
MinJobAge=4
SlurmdParameters=config_overrides
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
NodeName=localhost NodeAddr=127.0.0.1 CPUs=4 RealMemory=2000 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=10 State=UP
EOF
}

_local_slurm_node_idle() {
    [ "$(timeout 5 sinfo -h -n localhost -o %T 2>/dev/null)" = idle ]
}

local_slurm_start() {
    local dir=$1 attempt ports path munged tries
    mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log" || return 1
    chmod 711 "$dir" "$dir/munge" || return 1
    dir=$(readlink -f "$dir")
    # munged refuses a socket below a directory that not everyone may search (o+x).
    path=$dir
    while [ "$path" != / ]; do
        if [ -z "$(find "$path" -maxdepth 0 -perm -o+x)" ]; then
            echo "local_slurm: munged needs $path searchable by all (chmod o+x)" >&2
            return 1
        fi
        path=$(dirname "$path")
    done
    # munged: 1024 random bytes as its key (mode 400), its socket's directory mode 711.
    head -c 1024 /dev/urandom >"$dir/munge/munge.key" && chmod 400 "$dir/munge/munge.key" ||
        return 1
    munged -F --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket.2" \
        --pid-file="$dir/munge/munged.pid" --seed-file="$dir/munge/munged.seed" \
        --log-file="$dir/munge/munged.log" >"$dir/log/munged.out" 2>&1 &
    munged=$!
    LOCAL_SLURM_MUNGED=$munged
    for ((tries = 100; tries > 0; tries--)); do  # until its socket appears or it dies
        [ -S "$dir/munge/munge.socket.2" ] || ! kill -0 "$munged" 2>/dev/null && break
        sleep 0.1
    done
    if [ ! -S "$dir/munge/munge.socket.2" ]; then
        echo "local_slurm: munged did not start:" >&2
        cat "$dir/munge/munged.log" "$dir/log/munged.out" >&2 2>/dev/null
        return 1
    fi
    export SLURM_CONF=$dir/slurm.conf
    for attempt in 1 2 3; do
        mapfile -t ports < <(_local_slurm_free_ports 2)
        _local_slurm_write_conf "$dir" "${ports[0]}" "${ports[1]}"
        slurmctld -D -f "$SLURM_CONF" >"$dir/log/slurmctld.out" 2>&1 &
        LOCAL_SLURM_CTLD=$!
        slurmd -D -f "$SLURM_CONF" -N localhost >"$dir/log/slurmd.out" 2>&1 &
        LOCAL_SLURM_SLURMD=$!
        if _local_slurm_wait_for 20 _local_slurm_node_idle; then
            return 0
        fi
        echo "local_slurm: attempt $attempt: the node did not come up (ports ${ports[*]})" >&2
        tail -n 5 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 2>/dev/null
        _local_slurm_kill "$LOCAL_SLURM_SLURMD" "$LOCAL_SLURM_CTLD"
        LOCAL_SLURM_CTLD="" LOCAL_SLURM_SLURMD=""
        rm -rf "$dir/state" "$dir/spool" && mkdir -p "$dir/state" "$dir/spool"
    done
    return 1
}

# Sends SIGTERM to the PIDs, waits up to 10 s for them to end, then SIGKILLs what is left.
_local_slurm_kill() {
    local pid tries alive
    [ $# -gt 0 ] || return 0
    for pid in "$@"; do kill -TERM "$pid" 2>/dev/null; done
    for ((tries = 100; tries > 0; tries--)); do
        alive=0
        for pid in "$@"; do kill -0 "$pid" 2>/dev/null && alive=1; done
        [ "$alive" = 0 ] && break
        sleep 0.1
    done
    for pid in "$@"; do
        if kill -0 "$pid" 2>/dev/null; then
            echo "local_slurm: PID $pid did not stop on SIGTERM: SIGKILL" >&2
            kill -KILL "$pid" 2>/dev/null
        fi
        wait "$pid" 2>/dev/null
    done
}

_local_slurm_queue_empty() {
    [ -z "$(timeout 5 squeue -h -o %i 2>/dev/null)" ]
}

local_slurm_stop() {
    if [ -n "$LOCAL_SLURM_CTLD" ] && kill -0 "$LOCAL_SLURM_CTLD" 2>/dev/null; then
        # Jobs first, so that no slurmstepd outlives slurmd.
        timeout 5 scancel --full --quiet --user=root >/dev/null 2>&1
        _local_slurm_wait_for 10 _local_slurm_queue_empty
    fi
    # slurmd and slurmctld first, munged last: they talk to it on the way out.
    # shellcheck disable=SC2086 # an empty PID is no argument
    _local_slurm_kill $LOCAL_SLURM_SLURMD $LOCAL_SLURM_CTLD
    # shellcheck disable=SC2086
    _local_slurm_kill $LOCAL_SLURM_MUNGED
    LOCAL_SLURM_MUNGED="" LOCAL_SLURM_CTLD="" LOCAL_SLURM_SLURMD=""
}
