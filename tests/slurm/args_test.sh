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
# the script named in $FAIL_SCRIPT.
mkdir bin
cat >bin/recorder <<'EOF'
#!/bin/bash
name=$(basename "$0")
{ echo "== $name"; printf '%s\n' "$@"; echo "GLINT=${GLINT:-}"; } >>"$CALLS"
if [ "$name" = sbatch ]; then
    for arg in "$@"; do
        [ -n "${FAIL_SCRIPT:-}" ] && [[ $arg == *"$FAIL_SCRIPT" ]] && { echo "sbatch: error: no" >&2; exit 1; }
    done
    id=$(($(cat "$CALLS.id" 2>/dev/null || echo 99) + 1))
    echo "$id" >"$CALLS.id"
    echo "$id"
fi
exit 0
EOF
chmod +x bin/recorder
for tool in sbatch scancel mpirun srun glint glint-mpi; do ln -s recorder "bin/$tool"; done
export CALLS=$work/calls PATH=$work/bin:$PATH
echo "size 8 6" >scene.test
mkdir out

calls() { cat "$CALLS" 2>/dev/null; }
reset_calls() { rm -f "$CALLS" "$CALLS.id"; }
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

finish
