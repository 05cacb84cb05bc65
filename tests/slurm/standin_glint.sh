#!/bin/bash
# Stands in for glint in tests/slurm/cluster_test.sh, so that the Slurm scripts of
# contrib/slurm/ are tested on a real Slurm with any glint, also one without --part, merge and
# --mpi. Every call appends one line to $STANDIN_LOG: what it was asked, by which Slurm job.
#
#   standin SCENE --part K/N -o PIECE [OPTION...]   renders the whole of SCENE with the real
#        glint ($STANDIN_GLINT SCENE OPTION... -o a .png) and moves that PNG to PIECE; fails
#        (exit 1, no PIECE) when K is $STANDIN_FAIL_PART
#   standin merge -o OUT PIECE...                   checks that every PIECE has the same bytes
#        and copies the first to OUT (atomically)
#   standin --mpi SCENE -o OUT [OPTION...]          one MPI rank: writes OUT.rank-R with its
#        rank and world size as Open MPI (OMPI_COMM_WORLD_*) or Slurm's PMIx (PMIX_RANK,
#        SLURM_NTASKS) told it
set -uo pipefail

log=${STANDIN_LOG:?STANDIN_LOG must name the log file}
say() { echo "$*" >>"$log"; }
die() {
    echo "standin_glint: error: $*" >&2
    say "error $*"
    exit 1
}

if [ "${1:-}" = merge ]; then
    shift
    out="" pieces=()
    while [ $# -gt 0 ]; do
        case $1 in
            -o) out=$2; shift ;;
            *) pieces+=("$1") ;;
        esac
        shift
    done
    { [ -n "$out" ] && [ ${#pieces[@]} -gt 0 ]; } || die "merge: expected -o OUT PIECE..."
    for piece in "${pieces[@]}"; do
        cmp -s "${pieces[0]}" "$piece" || die "merge: $piece differs from ${pieces[0]}"
    done
    { cp "${pieces[0]}" "$out.standin-tmp" && mv "$out.standin-tmp" "$out"; } || die "merge: cannot write $out"
    say "merge job=${SLURM_JOB_ID:-none} pieces=${#pieces[@]} out=$out"
    exit 0
fi

mpi=0 part="" out="" options=()
while [ $# -gt 0 ]; do
    case $1 in
        --mpi) mpi=1 ;;
        --part) part=$2; shift ;;
        -o) out=$2; shift ;;
        *) options+=("$1") ;;
    esac
    shift
done
[ -n "$out" ] || die "expected -o FILE"

if [ "$mpi" = 1 ]; then
    rank=${OMPI_COMM_WORLD_RANK:-${PMIX_RANK:-}}
    size=${OMPI_COMM_WORLD_SIZE:-${SLURM_NTASKS:-}}
    [ -n "$rank" ] || die "--mpi: not started by an MPI launcher (no OMPI_COMM_WORLD_RANK, PMIX_RANK)"
    echo "rank=$rank size=$size ompi=${OMPI_COMM_WORLD_RANK:+yes} pmix=${PMIX_RANK:+yes}" \
        "job=${SLURM_JOB_ID:-none} options=${options[*]}" >"$out.rank-$rank"
    say "mpi rank=$rank size=$size job=${SLURM_JOB_ID:-none}"
    exit 0
fi

[ -n "$part" ] || die "expected --part K/N (or merge, or --mpi)"
k=${part%/*}
say "piece part=$part job=${SLURM_ARRAY_JOB_ID:-none} task=${SLURM_ARRAY_TASK_ID:-none}" \
    "options=${options[*]}"
[ "$k" != "${STANDIN_FAIL_PART:-}" ] || die "piece $part: failing as STANDIN_FAIL_PART asks"
"${STANDIN_GLINT:?}" -q "${options[@]}" -o "$out.standin.png" || die "piece $part: glint failed"
mv "$out.standin.png" "$out" || die "piece $part: cannot write $out"
