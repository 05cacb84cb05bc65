# What the tests on the private Slurm share (sourced, bash; after assert.sh and local_slurm.sh):
#
#   cluster_harness NAME GLINT LIMIT BG_LIMIT
#
# skips (exit 77, CTest's "skipped") without slurm-wlm and munge or when not root; isolates the
# private cluster's jobs from any Slurm job or shell around the test and sets Open MPI up for one
# machine as root; makes the work directory ($work, entered) and a watchdog that ends the whole
# test after LIMIT seconds; and on exit (cluster_cleanup, which a test may also call itself)
# stops the cluster and keeps $work, printing the daemons' logs, unless every check passed and
# the test set finished=1. bg NAME CMD... runs CMD in the background for at most BG_LIMIT
# seconds; collect NAME waits for it and sets RC, OUT and ERR as run does.

now() { date +%s.%N; }
seconds() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

cluster_harness() {
    harness_name=$1 bg_limit=$4
    limit=$3
    local tool
    for tool in munged slurmctld slurmd sbatch squeue scancel sinfo scontrol; do
        if ! command -v "$tool" >/dev/null; then
            echo "$harness_name: skipped: no $tool (Debian slurm-wlm and munge; make deps installs them)"
            exit 77
        fi
    done
    if [ "$(id -u)" != 0 ]; then
        echo "$harness_name: skipped: the private Slurm runs its daemons and jobs as root"
        exit 77
    fi
    [ -x "$2" ] || { echo "$harness_name: error: no glint at $2" >&2; exit 1; }

    # A Slurm job or shell around this test must not leak into the private cluster's jobs.
    unset "${!SBATCH_@}" "${!SLURM_@}" "${!SALLOC_@}" "${!SRUN_@}" GLINT GLINT_MPI GLINT_MPI_LAUNCHER
    # Open MPI as root, on one machine, shared memory only (platform-notes.md); jobs inherit it.
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_pml=ob1 \
        OMPI_MCA_btl=self,vader OMPI_MCA_rmaps_base_oversubscribe=1

    work=$(mktemp -d "${TMPDIR:-/tmp}/glint-$harness_name.XXXXXX")
    chmod 755 "$work"
    cd "$work" || exit 1
    BG=()  # NAME:PID of the background steps (bg)

    # The watchdog ends the test (cleanup included) if a step hangs.
    (
        sleep "$limit" &
        sleeper=$!
        trap 'kill "$sleeper" 2>/dev/null; exit 0' TERM
        wait "$sleeper" && kill -TERM $$
    ) &
    watchdog=$!
    trap cluster_cleanup EXIT
    trap 'echo "$harness_name: error: out of time ($limit s) or interrupted" >&2; exit 1' TERM INT
}

cluster_cleanup() {
    local entry
    for entry in "${BG[@]}"; do  # those still running (a finished one's PID may be reused)
        [ -f "$work/${entry%%:*}.time" ] || kill -TERM "${entry#*:}" 2>/dev/null
    done
    local t0
    t0=$(now)
    local_slurm_stop
    stop_time=$(seconds "$t0" "$(now)")
    kill "$watchdog" 2>/dev/null
    wait "$watchdog" 2>/dev/null
    if [ "$FAILURES" = 0 ] && [ "${finished:-0}" = 1 ]; then
        rm -rf "$work"
    else
        echo "$harness_name: kept $work; the daemons' logs:" >&2
        tail -n 20 "$work"/slurm/log/*.log >&2 2>/dev/null
    fi
}

bg() {
    local name=$1
    shift
    (
        trap '[ -n "${child:-}" ] && kill -TERM "$child" 2>/dev/null; exit 143' TERM
        start=$(now)
        timeout "$bg_limit" "$@" >"$work/$name.out" 2>"$work/$name.err" &
        child=$!
        wait "$child"
        echo $? >"$work/$name.rc"
        seconds "$start" "$(now)" >"$work/$name.time"
    ) &
    BG+=("$name:$!")
}

collect() {
    if [[ " ${BG[*]} " != *" $1:"* ]]; then
        RC="(not started)" OUT="" ERR=""
        return
    fi
    while [ ! -f "$work/$1.time" ]; do wait -n 2>/dev/null || sleep 0.1; done
    RC=$(cat "$work/$1.rc") OUT=$(cat "$work/$1.out") ERR=$(cat "$work/$1.err")
}
