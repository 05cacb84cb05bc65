#!/bin/bash
# Renders a sequence of frames on a Slurm cluster as a job array: by frames, or by pieces of
# frames with a merge job per frame (docs/scale-out.md, "A sequence as a job array"). Run with
# --help for the usage.
set -uo pipefail

me=render-frames.sh
here=$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")

usage() {
    cat <<EOF
Usage: $me [OPTIONS] SCENE OUT FRAMES [GLINT_OPTION...]

Renders frames FRAMES of SCENE (A:B or A:B:STEP, as glint --frames: A to B, every STEP-th) on
a Slurm cluster into the files OUT names: a pattern with the frame's number, as glint's -o
for --frames (out_%04d.png, out_####.png). Prints the job ids.

By frames (the default): a job array whose task K of TASKS renders its share of the frames
with 'glint SCENE --frames ... GLINT_OPTION...' (glint-frames.sbatch), reading the scene's
model files once for all of them.
By pieces of frames (--parts P): a job array of FRAMES x P tasks, task T rendering piece
T % P of the (T / P)-th frame with glint --frame N --part K/P (glint-frame-piece.sbatch), and
a merge job per frame that writes its file once its P pieces have succeeded (glint-merge.sbatch;
cancelled if one fails), for frames too long for one task.

Options:
  --tasks N       Array tasks sharing the frames, at most one per frame (default: one per
                  frame)
  --strided       Task K renders every N-th frame from the K-th (default: a run of consecutive
                  frames each): frames whose cost changes along the sequence spread evenly
  --parts P       Render each frame in P pieces (--part K/P), then merge it (see above)
  --pieces DIR    With --parts: where the pieces go (DIR/frame-N/piece-K.exr); created if
                  needed (default: OUT without its frame number and extension, plus .pieces)
  --logs DIR      Where the jobs' logs go; created if needed (default: the pieces' directory
                  with --parts, else OUT without its frame number and extension, plus .logs)
  --sbatch OPT    Pass OPT to every sbatch call; repeat for more (--sbatch=--partition=render
                  --sbatch=--time=1:00:00 --sbatch=--cpus-per-task=8)
  --wait          Wait for every job; exit 0 only if every frame's file was written
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

positive='^[1-9][0-9]{0,8}$'
tasks="" strided=0 parts="" pieces="" logs="" wait=0 test_only=0 sbatch_opts=()
while [ $# -gt 0 ]; do
    case $1 in
        -h | --help) usage; exit 0 ;;
        --wait) wait=1 ;;
        --test-only) test_only=1 ;;
        --strided) strided=1 ;;
        --tasks=*) tasks=${1#*=} ;;
        --parts=*) parts=${1#*=} ;;
        --pieces=*) pieces=${1#*=} ;;
        --logs=*) logs=${1#*=} ;;
        --sbatch=*) sbatch_opts+=("${1#*=}") ;;
        --tasks | --parts | --pieces | --logs | --sbatch)
            [ $# -ge 2 ] || usage_error "$1 needs a value"
            case $1 in
                --tasks) tasks=$2 ;;
                --parts) parts=$2 ;;
                --pieces) pieces=$2 ;;
                --logs) logs=$2 ;;
                *) sbatch_opts+=("$2") ;;
            esac
            shift ;;
        --) shift; break ;;
        -*) usage_error "unknown option '$1' (glint's options go after SCENE OUT FRAMES)" ;;
        *) break ;;
    esac
    shift
done
[ $# -ge 3 ] || usage_error "expected SCENE OUT FRAMES [GLINT_OPTION...], got $# arguments"
scene=$1 out=$2 frames=$3
shift 3

# FRAMES as glint reads --frames.
int() { if [[ $1 == -* ]]; then echo $((-10#${1#-})); else echo $((10#$1)); fi; }
[[ $frames =~ ^(-?[0-9]{1,8}):(-?[0-9]{1,8})(:([0-9]{1,8}))?$ ]] ||
    usage_error "FRAMES expected A:B or A:B:STEP (frames A to B, every STEP-th), got '$frames'"
first=$(int "${BASH_REMATCH[1]}") last=$(int "${BASH_REMATCH[2]}")
step=$(int "${BASH_REMATCH[4]:-1}")
max=10000000
{ [ "${first#-}" -le $max ] && [ "${last#-}" -le $max ]; } ||
    usage_error "frames must be -$max to $max, got '$frames'"
[ "$last" -ge "$first" ] || usage_error "the last frame comes before the first in '$frames'"
[ "$step" -ge 1 ] || usage_error "the step must be at least 1 in '$frames'"
count=$(((last - first) / step + 1))
frames="$first:$last:$step"

# Where OUT's frame number is, as glint finds it (apps/cli.cpp, frameFileName): the first run
# of #s, or %d, %Wd or %0Wd. Sets field_at and field_len; fails when there is none.
frame_field() {
    local i rest
    for ((i = 0; i < ${#1}; i++)); do
        rest=${1:i}
        if [[ $rest =~ ^#+ ]] || [[ $rest =~ ^%0?[0-9]{0,3}d ]]; then
            field_at=$i field_len=${#BASH_REMATCH[0]}
            return 0
        fi
    done
    return 1
}
# frame_file N: the file of frame N, as glint names it.
frame_file() {
    local field=${out:field_at:field_len} width number
    case $field in
        '#'*) printf -v number '%0*d' "$field_len" "$1" ;;
        %0*) width=${field:2:-1}; printf -v number '%0*d' "$((10#0$width))" "$1" ;;
        *) width=${field:1:-1}; printf -v number '%*d' "$((10#0$width))" "$1" ;;
    esac
    echo "${out:0:field_at}$number${out:field_at+field_len}"
}

[ -n "$out" ] || usage_error "OUT is empty"
frame_field "$out" || usage_error "OUT writes a file per frame: it needs a frame number in its\
 name, as out_%04d.png or out_####.png, got '$out'"
if [ -n "$parts" ]; then
    [[ $parts =~ $positive ]] || usage_error "--parts must be a positive integer, got '$parts'"
    { [ -n "$tasks" ] || [ "$strided" = 1 ]; } && usage_error "--tasks and --strided share out\
 whole frames; with --parts every task renders one piece of one frame"
    tasks=$((count * parts))
else
    [ -n "$pieces" ] && usage_error "--pieces is for --parts: without it no pieces are made"
    [ -n "$tasks" ] || tasks=$count
    [[ $tasks =~ $positive ]] || usage_error "--tasks must be a positive integer, got '$tasks'"
    [ "$tasks" -le "$count" ] ||
        usage_error "--tasks $tasks: the sequence $frames has $count frames, so at most $count tasks"
fi
[ "$wait" = 1 ] && [ "$test_only" = 1 ] && usage_error "--wait and --test-only exclude each other"

{ [ -f "$scene" ] && [ -r "$scene" ]; } || fail "cannot read scene '$scene'"
[ -d "$(dirname "$out")" ] || fail "the directory of OUT '$out' does not exist"
glint=${GLINT:-glint}
resolved=$(command -v "$glint") || fail "glint not found ('$glint'): put it on PATH or set GLINT"
command -v sbatch >/dev/null || fail "sbatch not found: this needs a Slurm client (slurm-client)"

# Absolute paths, so that the jobs and their logs do not depend on a working directory; the
# default directories are named after OUT without its frame number (walk_%04d.png: walk).
scene=$(readlink -f "$scene")
out=$(readlink -m "$out")
frame_field "$out"
stem=${out:0:field_at}
stem=${stem%"${stem##*[!_.-]}"}  # the separators before the number
[[ $stem == */ ]] && stem+=frames
rest=${out:field_at+field_len}
[[ $rest == *.* ]] && rest=${rest%.*}
stem+=$rest
if [ -n "$parts" ]; then
    pieces=$(readlink -m "${pieces:-$stem.pieces}")
    logs=$(readlink -m "${logs:-$pieces}")
else
    logs=$(readlink -m "${logs:-$stem.logs}")
fi
export GLINT
GLINT=$(readlink -f "$resolved")

if [ -n "$parts" ]; then
    array_cmd=(sbatch --parsable "--array=0-$((tasks - 1))" --job-name=glint-frame-piece
        "--output=$logs/slurm-%A_%a.out" "${sbatch_opts[@]}"
        "$here/glint-frame-piece.sbatch" "$scene" "$pieces" "$frames" "$parts" "$@")
else
    split=contiguous
    [ "$strided" = 1 ] && split=strided
    array_cmd=(sbatch --parsable "--array=0-$((tasks - 1))" --job-name=glint-frames
        "--output=$logs/slurm-%A_%a.out" "${sbatch_opts[@]}"
        "$here/glint-frames.sbatch" "$scene" "$out" "$frames" "$tasks" "$split" "$@")
fi
# merge_job I: the sbatch options of the merge job of the sequence's I-th frame, in merge_opts.
merge_job() {
    local frame=$((first + $1 * step))
    merge_opts=(--job-name=glint-merge "--output=$logs/slurm-merge-%j.out" "${sbatch_opts[@]}"
        "$here/glint-merge.sbatch" "$(frame_file "$frame")"
        "$(printf '%s/frame-%04d' "$pieces" "$frame")" "$parts")
}

if [ "$test_only" = 1 ]; then
    # sbatch --test-only names the job id it would get, when and where it would start.
    echo "array: sbatch ${array_cmd[*]:2}"
    sbatch --test-only "${array_cmd[@]:2}" || fail "Slurm would not accept the job array"
    if [ -n "$parts" ]; then
        merge_job 0
        echo "merge (one per frame; the first): sbatch ${merge_opts[*]}"
        sbatch --test-only "${merge_opts[@]}" || fail "Slurm would not accept the merge job"
    fi
    exit 0
fi

mkdir -p "$logs" || fail "cannot create the logs directory '$logs'"
if [ -n "$parts" ]; then mkdir -p "$pieces" || fail "cannot create the pieces directory '$pieces'"; fi
submitted=$(date +%s)
array=$("${array_cmd[@]}") || fail "sbatch did not accept the job array"
array=${array%%;*}
if [ -n "$parts" ]; then
    echo "array job $array: $count frames ($frames) of $scene in $parts pieces each, $tasks" \
        "tasks, into $pieces"
else
    echo "array job $array: $count frames ($frames) of $scene in $tasks tasks" \
        "($([ "$strided" = 1 ] && echo strided || echo contiguous)), into $out"
fi

# A merge job per frame, after that frame's pieces (tasks I*P to I*P+P-1 of the array): a frame
# is written as soon as its pieces are in, and a failed piece cancels its frame's merge alone.
merges=()
if [ -n "$parts" ]; then
    for ((i = 0; i < count; i++)); do
        dependency="afterok"
        for ((k = 0; k < parts; k++)); do dependency+=":${array}_$((i * parts + k))"; done
        merge_job "$i"
        if ! merge=$(sbatch --parsable "--dependency=$dependency" --kill-on-invalid-dep=yes \
            "${merge_opts[@]}"); then
            scancel "$array" "${merges[@]}"
            fail "sbatch did not accept the merge job of frame $((first + i * step)); job array\
 $array and the ${#merges[@]} merge jobs before it cancelled"
        fi
        merges+=("${merge%%;*}")
    done
    echo "merge jobs ${merges[*]}: one per frame, into $out once its pieces have succeeded"
fi
[ "$wait" = 1 ] || exit 0

# Waits until none of the jobs is pending or running (squeue lists those only): every 2 s for a
# minute, then every 15 s. Finished jobs leave the queue. Interrupting the wait leaves the jobs
# running (scancel stops them).
echo "waiting for the jobs (scancel $array${merges[*]:+ ${merges[*]}} stops them)"
ids=" $array ${merges[*]} " failed=0
for ((polls = 0; ; polls++)); do
    if listed=$(squeue -h -o %A -u "$(id -un)" 2>&1); then
        failed=0 live=0
        for id in $listed; do [[ $ids == *" $id "* ]] && live=1 && break; done
        [ "$live" = 0 ] && break
    elif ((++failed == 10)); then
        fail "squeue failed 10 times in a row, the jobs may still run: $listed"
    fi
    sleep $((polls < 30 ? 2 : 15))
done

# Frames written since the jobs were submitted, and for the others what was not rendered.
missing=() why=()
for ((i = 0; i < count; i++)); do
    frame=$((first + i * step))
    file=$(frame_file "$frame")
    [ -f "$file" ] && [ "$(stat -c %Y "$file")" -ge "$submitted" ] && continue
    missing+=("$frame")
    [ -n "$parts" ] || continue
    lost=()
    for ((k = 0; k < parts; k++)); do
        piece=$(printf '%s/frame-%04d/piece-%04d.exr' "$pieces" "$frame" "$k")
        [ -f "$piece" ] && [ "$(stat -c %Y "$piece")" -ge "$submitted" ] || lost+=("$k")
    done
    if [ ${#lost[@]} -gt 0 ]; then
        why+=("frame $frame: pieces ${lost[*]} (tasks $((i * parts)) to $((i * parts + parts - 1)))")
    else
        why+=("frame $frame: its merge job ${merges[i]} failed")
    fi
done
if [ ${#missing[@]} -eq 0 ]; then
    echo "all $count frames written: $out"
    exit 0
fi
echo "$me: error: ${#missing[@]} of $count frames not written: ${missing[*]}" >&2
for line in "${why[@]}"; do echo "  not rendered: $line" >&2; done
echo "  logs: $logs/slurm-${array}_T.out for task T" >&2
exit 1
