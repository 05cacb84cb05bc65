#!/bin/bash
# The argument handling of contrib/slurm/ without a Slurm: render-array.sh's usage errors and the
# sbatch commands it builds, and the commands the job scripts run, with stand-ins for sbatch,
# scancel, mpirun, srun and glint that record their arguments (cluster_test.sh runs the same
# scripts on a real Slurm).
#
#   args_test.sh SOURCE_DIR
set -uo pipefail
source_dir=$(readlink -f "${1:?usage: args_test.sh SOURCE_DIR}")
here=$source_dir/tests/slurm
contrib=$source_dir/contrib/slurm
# shellcheck source=tests/slurm/assert.sh
. "$here/assert.sh"

work=$(mktemp -d "${TMPDIR:-/tmp}/glint-slurm-args.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
unset "${!SBATCH_@}" "${!SLURM_@}" GLINT

# A recorder: every stand-in appends "NAME ARG..." (one argument per line after the first) to
# $work/calls; the sbatch stand-in prints job ids 100, 101, ... and fails when asked to submit
# the script named in $FAIL_SCRIPT (its $FAIL_AT-th such call, when set); the squeue stand-in
# runs $ON_SQUEUE (what the jobs would have written meanwhile) and lists no job.
mkdir bin
cat >bin/recorder <<'EOF'
#!/bin/bash
name=$(basename "$0")
{ echo "== $name"; printf '%s\n' "$@"; echo "GLINT=${GLINT:-}"; } >>"$CALLS"
if [ "$name" = squeue ] && [ -n "${ON_SQUEUE:-}" ]; then eval "$ON_SQUEUE"; fi
if [ "$name" = sbatch ]; then
    for arg in "$@"; do
        if [ -n "${FAIL_SCRIPT:-}" ] && [[ $arg == *"$FAIL_SCRIPT" ]]; then
            seen=$(($(cat "$CALLS.fail" 2>/dev/null || echo 0) + 1))
            echo "$seen" >"$CALLS.fail"
            [ "$seen" = "${FAIL_AT:-$seen}" ] && { echo "sbatch: error: no" >&2; exit 1; }
        fi
    done
    id=$(($(cat "$CALLS.id" 2>/dev/null || echo 99) + 1))
    echo "$id" >"$CALLS.id"
    echo "$id"
fi
exit 0
EOF
chmod +x bin/recorder
for tool in sbatch scancel squeue mpirun srun glint glint-mpi; do ln -s recorder "bin/$tool"; done
export CALLS=$work/calls PATH=$work/bin:$PATH
echo "size 8 6" >scene.test
mkdir out

calls() { cat "$CALLS" 2>/dev/null; }
reset_calls() { rm -f "$CALLS" "$CALLS.id" "$CALLS.fail"; }
# The arguments of call number N (from 1) of stand-in NAME, one per line.
call_args() {
    awk -v name="$1" -v n="$2" '/^== / { i += ($2 == name); on = ($2 == name && i == n); next }
        on && !/^GLINT=/' "$CALLS"
}
lines() { printf '%s\n' "$@"; }

## render-array.sh: usage errors exit 2 and say what is wrong, before anything is submitted.
ra=$contrib/render-array.sh
run "$ra"
check_rc "no arguments" 2
check_contains "no arguments: message" "$ERR" "expected SCENE OUT PARTS"
run "$ra" --help
check_rc "--help" 0
check_contains "--help prints the usage" "$OUT" "Usage: render-array.sh [OPTIONS] SCENE OUT PARTS"
for parts in 0 abc -3 1.5 "" 12345678901; do
    run "$ra" scene.test out/frame.png "$parts"
    check_rc "PARTS '$parts'" 2
    check_contains "PARTS '$parts': message" "$ERR" "PARTS must be a positive integer, got '$parts'"
done
run "$ra" --bogus scene.test out/frame.png 4
check_rc "unknown option" 2
check_contains "unknown option: message" "$ERR" "unknown option '--bogus'"
run "$ra" --pieces
check_rc "--pieces without a value" 2
check_contains "--pieces without a value: message" "$ERR" "--pieces needs a value"
run "$ra" --wait --test-only scene.test out/frame.png 4
check_rc "--wait with --test-only" 2
run "$ra" missing.test out/frame.png 4
check_rc "missing scene" 1
check_contains "missing scene: message" "$ERR" "cannot read scene 'missing.test'"
run "$ra" scene.test nodir/frame.png 4
check_rc "OUT in a missing directory" 1
check_contains "OUT in a missing directory: message" "$ERR" "directory of OUT 'nodir/frame.png'"
run "$ra" scene.test out 4
check_rc "OUT a directory" 1
GLINT=$work/no-glint run "$ra" scene.test out/frame.png 4
check_rc "GLINT missing" 1
check_contains "GLINT missing: message" "$ERR" "glint not found ('$work/no-glint')"
check_eq "nothing submitted after usage errors" "" "$(calls)"
check "no pieces directory made after usage errors" test ! -e out/frame.pieces

## render-array.sh: the two sbatch calls.
reset_calls
run "$ra" --sbatch=--partition=render --sbatch --time=5 scene.test out/frame.png 4 --spp 16 -q
check_rc "submit" 0
check_eq "submit: prints both job ids" \
    "array job 100: 4 pieces of $work/scene.test into $work/out/frame.pieces
merge job 101: $work/out/frame.png once every piece has succeeded" "$OUT"
check_eq "array sbatch arguments" "$(lines --parsable --array=0-3 --job-name=glint-piece \
    "--output=$work/out/frame.pieces/slurm-%A_%a.out" --partition=render --time=5 \
    "$contrib/glint-piece.sbatch" "$work/scene.test" "$work/out/frame.pieces" 4 --spp 16 -q)" \
    "$(call_args sbatch 1)"
check_eq "merge sbatch arguments" "$(lines --parsable --dependency=afterok:100 \
    --kill-on-invalid-dep=yes --job-name=glint-merge \
    "--output=$work/out/frame.pieces/slurm-merge-%j.out" --partition=render --time=5 \
    "$contrib/glint-merge.sbatch" "$work/out/frame.png" "$work/out/frame.pieces" 4)" \
    "$(call_args sbatch 2)"
check_contains "GLINT given to the jobs as an absolute path" "$(calls)" "GLINT=$work/bin/recorder"
check "pieces directory made" test -d out/frame.pieces

reset_calls
run "$ra" --pieces=elsewhere -- scene.test out/frame.exr 1
check_rc "--pieces DIR and --" 0
check_contains "--pieces DIR" "$(call_args sbatch 1)" "$work/elsewhere"$'\n'1
check_contains "one piece: array 0-0" "$(call_args sbatch 1)" "--array=0-0"

reset_calls
FAIL_SCRIPT=glint-merge.sbatch run "$ra" scene.test out/frame.png 3
check_rc "merge job refused" 1
check_contains "merge job refused: message" "$ERR" "job array 100 cancelled"
check_eq "merge job refused: the array is cancelled" "100" "$(call_args scancel 1)"

reset_calls
FAIL_SCRIPT=glint-piece.sbatch run "$ra" scene.test out/frame.png 3
check_rc "job array refused" 1
check_eq "job array refused: no merge job" "" "$(call_args sbatch 2)"

reset_calls
run "$ra" --test-only scene.test out/t.png 2 -q
check_rc "--test-only" 0
check_contains "--test-only: the array" "$(call_args sbatch 1)" "--test-only"$'\n'--array=0-1
check_contains "--test-only: the merge" "$(call_args sbatch 2)" "--test-only"$'\n'--job-name=glint-merge
check "--test-only makes no pieces directory" test ! -e out/t.pieces

## glint-piece.sbatch: the glint command of task K.
piece=$contrib/glint-piece.sbatch
reset_calls
run "$piece" scene.test pieces 4
check_rc "piece outside a job array" 2
check_contains "piece outside a job array: message" "$ERR" "not a job array task"
SLURM_ARRAY_TASK_ID=4 run "$piece" scene.test pieces 4
check_rc "array task 4 of 4 pieces" 2
check_contains "array task 4 of 4: message" "$ERR" "array task 4 is not a piece of 4"
SLURM_ARRAY_TASK_ID=0 run "$piece" scene.test pieces x
check_rc "piece with PARTS x" 2
SLURM_ARRAY_TASK_ID=0 run "$piece" scene.test
check_rc "piece with too few arguments" 2
check_eq "no glint run for a bad piece" "" "$(calls)"
SLURM_ARRAY_TASK_ID=2 run "$piece" scene.test pieces 4 --spp 8
check_rc "piece 2 of 4" 0
check_eq "piece 2 of 4: glint arguments" \
    "$(lines scene.test --part 2/4 -o pieces/piece-0002.exr --spp 8)" "$(call_args glint 1)"
SLURM_ARRAY_TASK_ID=13 SLURM_CPUS_PER_TASK=3 run "$piece" scene.test pieces 16
check_eq "piece with --cpus-per-task 3" \
    "$(lines scene.test --part 13/16 --threads 3 -o pieces/piece-0013.exr)" "$(call_args glint 2)"
SLURM_ARRAY_TASK_ID=0 SLURM_CPUS_PER_TASK=3 run "$piece" scene.test pieces 1 -t 1
check_eq "the user's --threads wins" "$(lines scene.test --part 0/1 -o pieces/piece-0000.exr -t 1)" \
    "$(call_args glint 3)"

## glint-merge.sbatch: names missing pieces, else merges all of them in order.
merge=$contrib/glint-merge.sbatch
reset_calls
mkdir pieces
touch pieces/piece-0000.exr pieces/piece-0002.exr
run "$merge" out/m.png pieces 4
check_rc "merge with pieces missing" 1
check_contains "merge with pieces missing: message" "$ERR" "2 of 4 pieces missing in pieces: 1 3"
touch pieces/piece-0001.exr pieces/piece-0003.exr
run "$merge" out/m.png pieces 4
check_rc "merge" 0
check_eq "merge: glint arguments" "$(lines merge -o out/m.png pieces/piece-0000.exr \
    pieces/piece-0001.exr pieces/piece-0002.exr pieces/piece-0003.exr)" "$(call_args glint 1)"
run "$merge" out/m.png pieces
check_rc "merge with too few arguments" 2

## glint-mpi.sbatch: the launcher commands.
mpi=$contrib/glint-mpi.sbatch
reset_calls
run "$mpi" scene.test -o out/mpi.png
check_rc "mpi by mpirun" 0
check_eq "mpi by mpirun: arguments" "$(lines glint-mpi scene.test -o out/mpi.png)" \
    "$(call_args mpirun 1)"
SLURM_CPUS_PER_TASK=8 run "$mpi" scene.test -o out/mpi.png
check_eq "mpi by mpirun, 8 cpus per task" "$(lines --map-by slot:PE=8 glint-mpi \
    scene.test -o out/mpi.png --threads 8)" "$(call_args mpirun 2)"
GLINT_MPI_LAUNCHER=srun SLURM_CPUS_PER_TASK=8 run "$mpi" scene.test -o out/mpi.png -t 2
check_eq "mpi by srun" "$(lines --mpi=pmix --cpus-per-task=8 glint-mpi scene.test \
    -o out/mpi.png -t 2)" "$(call_args srun 1)"
GLINT_MPI_LAUNCHER=pmi2 run "$mpi" scene.test
check_rc "mpi by an unknown launcher" 2
run "$mpi"
check_rc "mpi without a scene" 2

## render-frames.sh: usage errors exit 2 and say what is wrong, before anything is submitted.
rf=$contrib/render-frames.sh
reset_calls
run "$rf"
check_rc "frames: no arguments" 2
check_contains "frames: no arguments: message" "$ERR" "expected SCENE OUT FRAMES"
run "$rf" --help
check_rc "frames: --help" 0
check_contains "frames: --help prints the usage" "$OUT" \
    "Usage: render-frames.sh [OPTIONS] SCENE OUT FRAMES [GLINT_OPTION...]"
for frames in 1-3 3 a:b 1:2:3:4 "" 1:2:-1; do
    run "$rf" scene.test 'out/f_%04d.png' "$frames"
    check_rc "FRAMES '$frames'" 2
    check_contains "FRAMES '$frames': message" "$ERR" "FRAMES expected A:B or A:B:STEP"
done
bad_frames=("3:1" "the last frame comes before the first in '3:1'"
    "1:3:0" "the step must be at least 1 in '1:3:0'"
    "0:10000001" "frames must be -10000000 to 10000000")
for ((i = 0; i < ${#bad_frames[@]}; i += 2)); do
    run "$rf" scene.test 'out/f_%04d.png' "${bad_frames[i]}"
    check_rc "FRAMES '${bad_frames[i]}'" 2
    check_contains "FRAMES '${bad_frames[i]}': message" "$ERR" "${bad_frames[i + 1]}"
done
run "$rf" scene.test out/f.png 0:9
check_rc "OUT without a frame number" 2
check_contains "OUT without a frame number: message" "$ERR" \
    "it needs a frame number in its name, as out_%04d.png or out_####.png, got 'out/f.png'"
run "$rf" --tasks 11 scene.test 'out/f_%04d.png' 0:9
check_rc "more tasks than frames" 2
check_contains "more tasks than frames: message" "$ERR" \
    "--tasks 11: the sequence 0:9:1 has 10 frames, so at most 10 tasks"
for tasks in 0 x -1; do
    run "$rf" --tasks "$tasks" scene.test 'out/f_%04d.png' 0:9
    check_rc "--tasks '$tasks'" 2
done
run "$rf" --parts 0 scene.test 'out/f_%04d.png' 0:9
check_rc "--parts 0" 2
run "$rf" --parts 2 --tasks 2 scene.test 'out/f_%04d.png' 0:9
check_rc "--parts with --tasks" 2
check_contains "--parts with --tasks: message" "$ERR" "with --parts every task renders one piece"
run "$rf" --pieces p scene.test 'out/f_%04d.png' 0:9
check_rc "--pieces without --parts" 2
run "$rf" --wait --test-only scene.test 'out/f_%04d.png' 0:9
check_rc "frames: --wait with --test-only" 2
run "$rf" --frames 0:9 scene.test 'out/f_%04d.png' 0:9
check_rc "frames: unknown option" 2
check_contains "frames: unknown option: message" "$ERR" "unknown option '--frames'"
run "$rf" missing.test 'out/f_%04d.png' 0:9
check_rc "frames: missing scene" 1
run "$rf" scene.test 'nodir/f_%04d.png' 0:9
check_rc "frames: OUT in a missing directory" 1
check_eq "frames: nothing submitted after usage errors" "" "$(calls)"

## render-frames.sh by frames: one array, task K of N with its share (glint-frames.sbatch).
reset_calls
run "$rf" --tasks 4 --sbatch=--partition=render scene.test 'out/f_%04d.png' 0:99 --spp 2 -q
check_rc "frames: submit" 0
check_eq "frames: prints the array job" \
    "array job 100: 100 frames (0:99:1) of $work/scene.test in 4 tasks (contiguous), into $work/out/f_%04d.png" \
    "$OUT"
check_eq "frames: array sbatch arguments" "$(lines --parsable --array=0-3 --job-name=glint-frames \
    "--output=$work/out/f.logs/slurm-%A_%a.out" --partition=render \
    "$contrib/glint-frames.sbatch" "$work/scene.test" "$work/out/f_%04d.png" 0:99:1 4 contiguous \
    --spp 2 -q)" "$(call_args sbatch 1)"
check_eq "frames: one sbatch call" "" "$(call_args sbatch 2)"
check "frames: logs directory made" test -d out/f.logs
reset_calls
run "$rf" --strided --logs=elsewhere scene.test 'out/####.exr' -5:20:5
check_rc "frames: --strided, one task per frame" 0
check_contains "frames: --strided, 6 tasks" "$(call_args sbatch 1)" \
    "--array=0-5"$'\n'--job-name=glint-frames$'\n'"--output=$work/elsewhere/slurm-%A_%a.out"
check_contains "frames: --strided, split" "$(call_args sbatch 1)" \
    "$work/out/####.exr"$'\n'-5:20:5$'\n'6$'\n'strided
reset_calls
run "$rf" --test-only scene.test 'out/t%d.png' 1:2
check_rc "frames: --test-only" 0
check_contains "frames: --test-only: the array" "$(call_args sbatch 1)" "--test-only"$'\n'--array=0-1
check_eq "frames: --test-only: one call" "" "$(call_args sbatch 2)"
check "frames: --test-only makes no logs directory" test ! -e out/t.logs

## render-frames.sh by pieces of frames: frames x parts tasks, a merge job per frame after its
## pieces (glint-frame-piece.sbatch, glint-merge.sbatch).
reset_calls
run "$rf" --parts 2 scene.test 'out/p_%03d.png' 10:20:5 --spp 4
check_rc "pieces of frames: submit" 0
check_eq "pieces of frames: prints the jobs" \
    "array job 100: 3 frames (10:20:5) of $work/scene.test in 2 pieces each, 6 tasks, into $work/out/p.pieces
merge jobs 101 102 103: one per frame, into $work/out/p_%03d.png once its pieces have succeeded" "$OUT"
check_eq "pieces of frames: array sbatch arguments" "$(lines --parsable --array=0-5 \
    --job-name=glint-frame-piece "--output=$work/out/p.pieces/slurm-%A_%a.out" \
    "$contrib/glint-frame-piece.sbatch" "$work/scene.test" "$work/out/p.pieces" 10:20:5 2 \
    --spp 4)" "$(call_args sbatch 1)"
for i in 0 1 2; do
    frame=$((10 + 5 * i))
    check_eq "pieces of frames: merge job of frame $frame" "$(lines --parsable \
        "--dependency=afterok:100_$((2 * i)):100_$((2 * i + 1))" --kill-on-invalid-dep=yes \
        --job-name=glint-merge "--output=$work/out/p.pieces/slurm-merge-%j.out" \
        "$contrib/glint-merge.sbatch" "$work/out/p_0$frame.png" "$work/out/p.pieces/frame-00$frame" 2)" \
        "$(call_args sbatch $((i + 2)))"
done
reset_calls
FAIL_SCRIPT=glint-merge.sbatch FAIL_AT=2 run "$rf" --parts 3 scene.test 'out/p_%d.png' 0:2
check_rc "pieces of frames: a merge job refused" 1
check_contains "pieces of frames: a merge job refused: message" "$ERR" \
    "the merge job of frame 1; job array 100 and the 1 merge jobs before it cancelled"
check_eq "pieces of frames: a merge job refused: what is cancelled" "$(lines 100 101)" \
    "$(call_args scancel 1)"
reset_calls
run "$rf" --test-only --parts 2 scene.test 'out/p_#.png' 0:3
check_rc "pieces of frames: --test-only" 0
check_contains "pieces of frames: --test-only: the array" "$(call_args sbatch 1)" \
    "--test-only"$'\n'--array=0-7
check_contains "pieces of frames: --test-only: the first merge" "$(call_args sbatch 2)" \
    "$work/out/p_0.png"$'\n'"$work/out/p.pieces/frame-0000"$'\n'2
check_eq "pieces of frames: --test-only: two calls" "" "$(call_args sbatch 3)"

## render-frames.sh --wait: waits for the queue to empty, then names the frames not written.
reset_calls
ON_SQUEUE="touch out/w_0001.png out/w_0003.png" run "$rf" --wait scene.test 'out/w_%04d.png' 1:4
check_rc "--wait, frames missing" 1
check_contains "--wait, frames missing: message" "$ERR" "2 of 4 frames not written: 2 4"
check_contains "--wait, frames missing: logs" "$ERR" "$work/out/w.logs/slurm-100_T.out for task T"
check_contains "--wait polls squeue" "$(calls)" "== squeue"
reset_calls
ON_SQUEUE="touch out/w_0001.png out/w_0002.png out/w_0003.png out/w_0004.png" \
    run "$rf" --wait scene.test 'out/w_%04d.png' 1:4
check_rc "--wait, every frame" 0
check_contains "--wait, every frame: message" "$OUT" "all 4 frames written"
reset_calls
mkdir -p out/v.pieces/frame-0007
ON_SQUEUE="touch out/v.pieces/frame-0007/piece-0000.exr out/v_6.png" \
    run "$rf" --wait --parts 2 scene.test 'out/v_%d.png' 6:7
check_rc "--wait, pieces missing" 1
check_contains "--wait, pieces missing: frame 7" "$ERR" "1 of 2 frames not written: 7"
check_contains "--wait, pieces missing: which" "$ERR" "frame 7: pieces 1 (tasks 2 to 3)"

## glint-frames.sbatch: the glint command of task K, its share of the frames.
gf=$contrib/glint-frames.sbatch
reset_calls
run "$gf" scene.test 'f_%04d.png' 0:9 4 contiguous
check_rc "frames task outside a job array" 2
SLURM_ARRAY_TASK_ID=4 run "$gf" scene.test 'f_%04d.png' 0:9 4 contiguous
check_rc "frames task 4 of 4" 2
SLURM_ARRAY_TASK_ID=3 run "$gf" scene.test 'f_%04d.png' 0:2 4 contiguous
check_rc "frames task without a frame" 2
check_contains "frames task without a frame: message" "$ERR" "0:2 has 3 frames"
SLURM_ARRAY_TASK_ID=0 run "$gf" scene.test 'f_%04d.png' 0:9 4 sideways
check_rc "frames task, unknown split" 2
SLURM_ARRAY_TASK_ID=0 run "$gf" scene.test 'f_%04d.png' 9:0 4 contiguous
check_rc "frames task, frames backwards" 2
check_eq "no glint run for a bad frames task" "" "$(calls)"
# 10 frames in 4 tasks: 2, 3, 2 and 3 frames; strided: 0 4 8, 1 5 9, 2 6, 3 7.
shares=("0:1:1" "2:4:1" "5:6:1" "7:9:1")
strides=("0:9:4" "1:9:4" "2:9:4" "3:9:4")
for task in 0 1 2 3; do
    reset_calls
    SLURM_ARRAY_TASK_ID=$task run "$gf" scene.test 'f_%04d.png' 0:9 4 contiguous --spp 2
    check_eq "frames task $task of 4, contiguous" \
        "$(lines scene.test --frames "${shares[task]}" -o 'f_%04d.png' --spp 2)" "$(call_args glint 1)"
    SLURM_ARRAY_TASK_ID=$task run "$gf" scene.test 'f_%04d.png' 0:9 4 strided
    check_eq "frames task $task of 4, strided" \
        "$(lines scene.test --frames "${strides[task]}" -o 'f_%04d.png')" "$(call_args glint 2)"
done
reset_calls
SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=3 run "$gf" scene.test 'f_%04d.png' -10:90:10 3 contiguous
check_eq "frames task with a step and --cpus-per-task" \
    "$(lines scene.test --frames 20:50:10 --threads 3 -o 'f_%04d.png')" "$(call_args glint 1)"
check_contains "frames task: says its share" "$OUT" "frames 20:50:10 (4) -> f_%04d.png"

## glint-frame-piece.sbatch: the glint command of task T: a piece of a frame.
gp=$contrib/glint-frame-piece.sbatch
reset_calls
SLURM_ARRAY_TASK_ID=6 run "$gp" scene.test fp 10:20:5 2
check_rc "frame piece task 6 of 3 x 2" 2
check_contains "frame piece task 6 of 3 x 2: message" "$ERR" "not one of the 3 x 2 pieces"
SLURM_ARRAY_TASK_ID=0 run "$gp" scene.test fp 10:20:5 0
check_rc "frame piece, PARTS 0" 2
check_eq "no glint run for a bad frame piece" "" "$(calls)"
SLURM_ARRAY_TASK_ID=5 SLURM_CPUS_PER_TASK=2 run "$gp" scene.test fp 10:20:5 2 --spp 4
check_rc "frame piece task 5" 0
check_eq "frame piece task 5: frame 20, piece 1/2" "$(lines scene.test --frame 20 --part 1/2 \
    --threads 2 -o fp/frame-0020/piece-0001.exr --spp 4)" "$(call_args glint 1)"
check "frame piece: the frame's directory made" test -d fp/frame-0020
SLURM_ARRAY_TASK_ID=0 run "$gp" scene.test fp -3:3:3 3
check_eq "frame piece task 0: frame -3" "$(lines scene.test --frame -3 --part 0/3 \
    -o fp/frame--003/piece-0000.exr)" "$(call_args glint 2)"

finish
