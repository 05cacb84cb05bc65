#!/bin/bash
# Renders a frame on a Slurm cluster as a job array of pieces and a dependent merge job
# (docs/scale-out.md, "Slurm"). Run with --help for the usage.
set -uo pipefail

me=render-array.sh
here=$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")

usage() {
    cat <<EOF
Usage: $me [OPTIONS] SCENE OUT PARTS [GLINT_OPTION...]

Renders SCENE to OUT on a Slurm cluster in PARTS pieces: a job array whose task K runs
'glint SCENE --part K/PARTS GLINT_OPTION...' (glint-piece.sbatch), and a job that runs
'glint merge' into OUT once every task has succeeded (glint-merge.sbatch; it is cancelled
if one fails). Prints the two job ids. OUT's format is any glint writes (.png, .exr, ...).

Options:
  --pieces DIR    Where the pieces (piece-K.exr) and the jobs' logs go; created if needed
                  (default: OUT without its extension, plus .pieces)
  --sbatch OPT    Pass OPT to both sbatch calls; repeat for more (--sbatch=--partition=render
                  --sbatch=--time=1:00:00 --sbatch=--cpus-per-task=8)
  --wait          Wait for the merge job; exit 0 only if it completed (wrote OUT)
  --test-only     Only ask Slurm whether and when the jobs would run (sbatch --test-only)
  -h, --help      Print this help

Environment: GLINT, the glint binary (default: glint on PATH); sbatch's own SBATCH_*
variables. The jobs run in the current directory, so relative paths in GLINT_OPTION work.
EOF
}

usage_error() {
    echo "$me: error: $1" >&2
    echo "Run '$me --help' for usage." >&2
    exit 2
}

fail() {
    echo "$me: error: $1" >&2
    exit 1
}

pieces="" wait=0 test_only=0 sbatch_opts=()
while [ $# -gt 0 ]; do
    case $1 in
        -h | --help) usage; exit 0 ;;
        --wait) wait=1 ;;
        --test-only) test_only=1 ;;
        --pieces=*) pieces=${1#*=} ;;
        --sbatch=*) sbatch_opts+=("${1#*=}") ;;
        --pieces | --sbatch)
            [ $# -ge 2 ] || usage_error "$1 needs a value"
            if [ "$1" = --pieces ]; then pieces=$2; else sbatch_opts+=("$2"); fi
            shift ;;
        --) shift; break ;;
        -*) usage_error "unknown option '$1' (glint's options go after SCENE OUT PARTS)" ;;
        *) break ;;
    esac
    shift
done
[ $# -ge 3 ] || usage_error "expected SCENE OUT PARTS [GLINT_OPTION...], got $# arguments"
scene=$1 out=$2 parts=$3
shift 3
[[ $parts =~ ^[1-9][0-9]{0,8}$ ]] || usage_error "PARTS must be a positive integer, got '$parts'"
[ -n "$out" ] || usage_error "OUT is empty"
[ "$wait" = 1 ] && [ "$test_only" = 1 ] && usage_error "--wait and --test-only exclude each other"

{ [ -f "$scene" ] && [ -r "$scene" ]; } || fail "cannot read scene '$scene'"
[ -d "$out" ] && fail "OUT '$out' is a directory"
[ -d "$(dirname "$out")" ] || fail "the directory of OUT '$out' does not exist"
[ -n "$pieces" ] || pieces=${out%.*}.pieces
glint=${GLINT:-glint}
resolved=$(command -v "$glint") || fail "glint not found ('$glint'): put it on PATH or set GLINT"
command -v sbatch >/dev/null || fail "sbatch not found: this needs a Slurm client (slurm-client)"

# Absolute paths, so that the jobs and their logs do not depend on a working directory.
scene=$(readlink -f "$scene")
out=$(readlink -m "$out")
pieces=$(readlink -m "$pieces")
export GLINT
GLINT=$(readlink -f "$resolved")

array_cmd=(sbatch --parsable "--array=0-$((parts - 1))" --job-name=glint-piece
    "--output=$pieces/slurm-%A_%a.out" "${sbatch_opts[@]}"
    "$here/glint-piece.sbatch" "$scene" "$pieces" "$parts" "$@")
merge_opts=(--job-name=glint-merge "--output=$pieces/slurm-merge-%j.out" "${sbatch_opts[@]}"
    "$here/glint-merge.sbatch" "$out" "$pieces" "$parts")

if [ "$test_only" = 1 ]; then
    # sbatch --test-only names the job id it would get, when and where it would start.
    echo "array: sbatch ${array_cmd[*]:2}"
    sbatch --test-only "${array_cmd[@]:2}" || fail "Slurm would not accept the job array"
    echo "merge: sbatch ${merge_opts[*]}"
    sbatch --test-only "${merge_opts[@]}" || fail "Slurm would not accept the merge job"
    exit 0
fi

mkdir -p "$pieces" || fail "cannot create the pieces directory '$pieces'"
submitted=$(date +%s)
array=$("${array_cmd[@]}") || fail "sbatch did not accept the job array"
array=${array%%;*}
echo "array job $array: $parts pieces of $scene into $pieces"

merge_cmd=(sbatch --parsable "--dependency=afterok:$array" --kill-on-invalid-dep=yes
    "${merge_opts[@]}")
if [ "$wait" = 0 ]; then
    if ! merge=$("${merge_cmd[@]}"); then
        scancel "$array"
        fail "sbatch did not accept the merge job; job array $array cancelled"
    fi
    echo "merge job ${merge%%;*}: $out once every piece has succeeded"
    exit 0
fi

# sbatch --wait prints the job id at once and returns when the job ends, with its exit code;
# a job cancelled before it ran (a piece failed) also returns 0, so the state is checked too.
exec 3< <("${merge_cmd[@]:0:2}" --wait "${merge_cmd[@]:2}"; echo "exit $?")
read -r merge <&3
if [[ $merge == exit* ]]; then
    scancel "$array"
    fail "sbatch did not accept the merge job; job array $array cancelled"
fi
merge=${merge%%;*}
echo "merge job $merge: $out once every piece has succeeded; waiting"
read -r _ status <&3
state=$(scontrol show job -o "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]*')
state=${state#JobState=}
if [ "$status" = 0 ] && [ "${state:-COMPLETED}" = COMPLETED ]; then
    echo "merge job $merge completed: $out"
    exit 0
fi
failed=()
for ((part = 0; part < parts; part++)); do
    file=$(printf '%s/piece-%04d.exr' "$pieces" "$part")
    if [ ! -f "$file" ] || [ "$(stat -c %Y "$file")" -lt "$submitted" ]; then failed+=("$part"); fi
done
if [ ${#failed[@]} -gt 0 ]; then
    fail "merge job $merge ended ${state:-with exit code $status}: pieces not rendered:\
 ${failed[*]} (logs: $pieces/slurm-${array}_K.out)"
fi
fail "merge job $merge ended ${state:-with exit code $status} (log: $pieces/slurm-merge-$merge.out)"
