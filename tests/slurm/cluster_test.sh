#!/bin/bash
# contrib/slurm/ on a real Slurm: a private single-node cluster on localhost
# (tests/slurm/local_slurm.sh) runs the job array of pieces and the dependent merge job through
# render-array.sh, and the MPI recipe glint-mpi.sbatch, and the results are compared with a
# single-machine render, byte for byte.
#
#   cluster_test.sh SOURCE_DIR GLINT
#
# While glint has no --part and merge (issue 13), the array runs a stand-in piece renderer
# (standin_glint.sh: every task renders the whole frame with the real glint, the "merge" checks
# that all pieces are the same bytes); that proves the scripts and Slurm's part: the array's
# tasks, K/N, the dependency, the failure path. The same script renders with glint's own pieces
# as soon as `glint merge --help` answers, and with glint's MPI mode once `glint --help` names
# --mpi. Exit code 77 (CTest: skipped) without slurm-wlm and munge, or when not root.
set -uo pipefail
source_dir=$(readlink -f "${1:?usage: cluster_test.sh SOURCE_DIR GLINT}")
glint=$(readlink -f "${2:?usage: cluster_test.sh SOURCE_DIR GLINT}")
here=$source_dir/tests/slurm
contrib=$source_dir/contrib/slurm
# shellcheck source=tests/slurm/assert.sh
. "$here/assert.sh"
# shellcheck source=tests/slurm/local_slurm.sh
. "$here/local_slurm.sh"

# shellcheck source=tests/slurm/cluster_harness.sh
. "$here/cluster_harness.sh"
cluster_harness cluster_test "$glint" 75 60
job_id() { sed -n "s/^$1 job \([0-9]*\):.*/\1/p" <<<"$OUT"; }
jobcomp() { grep "^JobId=$1 " "$work/slurm/log/jobcomp.txt" 2>/dev/null; }
array_task() { grep " ArrayJobId=$1 ArrayTaskId=$2 " "$work/slurm/log/jobcomp.txt" 2>/dev/null; }

# Whether glint has --part and merge (a merge help of its own, not glint's), and --mpi. The help
# is read whole before grep sees it: `glint --help | grep -q` can fail under pipefail when grep
# stops reading early.
help=$("$glint" --help 2>&1)
merge_help=$("$glint" merge --help 2>&1) && [ "$merge_help" != "$help" ] &&
    grep -q -- '--part' <<<"$help" && pieces_on=1 || pieces_on=0
# glint-mpi is built beside glint when CMake finds MPI.
glint_mpi=$(dirname "$glint")/glint-mpi
[ -x "$glint_mpi" ] && mpi_on=1 || mpi_on=0

## The cluster.
t0=$(now)
mkdir slurm
if ! local_slurm_start "$work/slurm"; then
    echo "cluster_test: error: the private Slurm did not start" >&2
    exit 1
fi
start_time=$(seconds "$t0" "$(now)")
echo "cluster_test: Slurm up in $start_time s (SLURM_CONF=$SLURM_CONF)"

## sbatch --test-only: Slurm accepts the array, the merge job and the MPI recipe; submits none.
scene=$source_dir/scenes/shapes.test
opts=(--size 64x48 -q)
run env GLINT="$glint" "$contrib/render-array.sh" --test-only "$scene" frame.png 4 "${opts[@]}"
check_rc "render-array.sh --test-only" 0
check_contains "--test-only: the array would start" "$ERR" "to start at"
check_eq "--test-only: both jobs would start" 2 "$(grep -c "to start at" <<<"$ERR")"
run env GLINT="$glint" "$contrib/render-array.sh" --test-only --sbatch=--partition=nosuch "$scene" frame.png 4
check_rc "--test-only in a partition that does not exist" 1
check_contains "--test-only, no such partition: Slurm says why" "$ERR" "invalid partition"
run timeout 20 sbatch --test-only -n 2 "$contrib/glint-mpi.sbatch" "$scene" -o mpi.png
check_rc "MPI recipe --test-only" 0
check_contains "MPI recipe --test-only: 2 processors" "$ERR" "using 2 processors"
check_eq "--test-only submitted nothing" "" "$(timeout 10 squeue -h -o %i)"
check "--test-only made no pieces directory" test ! -e frame.pieces

## The single-machine renders to compare with: a course scene (Whitted), and with glint's own
## pieces a path-traced one with many samples per pixel.
"$glint" "$scene" "${opts[@]}" -o ref.png || check "single-machine render" false
path_scene=$source_dir/scenes/cornell.test
path_opts=(--integrator path --spp 16 --size 64x64 --srgb -q)
if [ "$pieces_on" = 1 ]; then
    "$glint" "$path_scene" "${path_opts[@]}" -o ref-path.png ||
        check "single-machine render, path traced" false
fi

## Everything at once (the cluster has 4 CPUs): the harness, a failing piece, the MPI recipe
## by both launchers, and glint's own pieces and MPI mode where glint has them.
t1=$(now)
mkdir harness failing mpirun srun pieces pieces-path mpi
printf '#!/bin/bash\nexec "%s" --mpi "$@"\n' "$here/standin_glint.sh" >"$work/standin_glint_mpi"
chmod +x "$work/standin_glint_mpi"
standin=(env "GLINT=$here/standin_glint.sh" "GLINT_MPI=$work/standin_glint_mpi" "STANDIN_GLINT=$glint")
bg harness "${standin[@]}" STANDIN_LOG="$work/harness.log" \
    "$contrib/render-array.sh" --wait "$scene" harness/frame.png 4 "${opts[@]}"
bg failing "${standin[@]}" STANDIN_LOG="$work/failing.log" STANDIN_FAIL_PART=2 \
    "$contrib/render-array.sh" --wait "$scene" failing/frame.png 4 "${opts[@]}"
# srun --mpi=pmix: Slurm's pmix plugin loads libpmix.so, which Debian ships in libpmix-dev only.
launchers=()
if command -v mpirun >/dev/null; then launchers+=(mpirun); fi
if dpkg-query -W -f='${Status}' libpmix-dev 2>/dev/null | grep -q 'ok installed'; then
    launchers+=(srun)
fi
for launcher in "${launchers[@]}"; do
    bg "$launcher" "${standin[@]}" STANDIN_LOG="$work/$launcher.log" \
        GLINT_MPI_LAUNCHER="$launcher" sbatch --wait -n 2 -o "$launcher/slurm-%j.out" \
        "$contrib/glint-mpi.sbatch" "$scene" -o "$launcher/frame.png" "${opts[@]}"
done
if [ "$pieces_on" = 1 ]; then
    bg pieces env GLINT="$glint" "$contrib/render-array.sh" --wait "$scene" pieces/frame.png 4 \
        "${opts[@]}"
    bg pieces-path env GLINT="$glint" "$contrib/render-array.sh" --wait "$path_scene" \
        pieces-path/frame.png 4 "${path_opts[@]}"
fi
if [ "$mpi_on" = 1 ]; then
    bg mpi env GLINT_MPI="$glint_mpi" sbatch --wait -n 2 -o mpi/slurm-%j.out \
        "$contrib/glint-mpi.sbatch" "$scene" -o mpi/frame.png "${opts[@]}"
fi

## The harness: 4 tasks, piece K/4 by task K of one array, merged after all of them.
collect harness
check_rc "harness: render-array.sh --wait" 0
array=$(job_id array) merge=$(job_id merge)
check_contains "harness: completed" "$OUT" "merge job $merge completed: $work/harness/frame.png"
check "harness: merged image equals the single-machine render" cmp harness/frame.png ref.png
for part in 0 1 2 3; do
    check_eq "harness: piece $part/4 rendered once, by task $part of array $array" 1 \
        "$(grep -c "^piece part=$part/4 job=$array task=$part options=$scene --size 64x48 -q$" \
            harness.log)"
    check "harness: piece $part file" test -f "$(printf 'harness/frame.pieces/piece-%04d.exr' "$part")"
    check "harness: task $part log" test -f "harness/frame.pieces/slurm-${array}_$part.out"
    check_contains "harness: task $part completed" "$(array_task "$array" "$part")" \
        "JobState=COMPLETED"
done
check_eq "harness: 4 pieces then one merge, in that order" "piece piece piece piece merge" \
    "$(cut -d' ' -f1 harness.log | paste -sd' ')"
check_contains "harness: the merge job merged 4 pieces" "$(tail -n 1 harness.log)" \
    "merge job=$merge pieces=4 out=$work/harness/frame.png"
check_contains "harness: merge job completed" "$(jobcomp "$merge")" "JobState=COMPLETED"
harness_time=$(cat harness.time)

## A failing piece: the merge job never runs, no image, and the wrapper says which piece.
collect failing
check_rc "failing piece: render-array.sh --wait" 1
array=$(job_id array) merge=$(job_id merge)
check_contains "failing piece: named" "$ERR" "merge job $merge ended CANCELLED: pieces not rendered: 2"
check "failing piece: no image" test ! -e failing/frame.png
check_contains "failing piece: task 2 failed" "$(array_task "$array" 2)" "JobState=FAILED"
check_contains "failing piece: merge job cancelled" "$(jobcomp "$merge")" "JobState=CANCELLED"
check_eq "failing piece: no merge ran" 0 "$(grep -c '^merge' failing.log)"

## The MPI recipe: one job, 2 ranks, by mpirun (Open MPI reads the allocation) and srun --mpi=pmix.
for launcher in "${launchers[@]}"; do
    collect "$launcher"
    check_rc "MPI recipe by $launcher: sbatch --wait" 0
    job=$(sed -n 's/^Submitted batch job \([0-9]*\)$/\1/p' <<<"$OUT")
    if [ "$launcher" = mpirun ]; then by="ompi=yes"; else by="ompi= pmix=yes"; fi
    for rank in 0 1; do
        check_contains "MPI recipe by $launcher: rank $rank of 2 in job $job" \
            "$(cat "$launcher/frame.png.rank-$rank" 2>/dev/null)" \
            "rank=$rank size=2 $by"
        check_contains "MPI recipe by $launcher: rank $rank job" \
            "$(cat "$launcher/frame.png.rank-$rank" 2>/dev/null)" "job=$job options=$scene"
    done
done
[[ " ${launchers[*]} " == *" mpirun "* ]] ||
    echo "cluster_test: no mpirun (openmpi-bin): the MPI recipe by mpirun was not run"
[[ " ${launchers[*]} " == *" srun "* ]] ||
    echo "cluster_test: no libpmix-dev: the MPI recipe by srun --mpi=pmix was not run"

## glint's own pieces and MPI mode, byte-identical to the single-machine render.
if [ "$pieces_on" = 1 ]; then
    collect pieces
    check_rc "glint pieces: render-array.sh --wait" 0
    check "glint pieces: merged image equals the single-machine render" cmp pieces/frame.png ref.png
    check_eq "glint pieces: 4 EXR pieces" 4 "$(find pieces/frame.pieces -name 'piece-*.exr' | wc -l)"
    collect pieces-path
    check_rc "glint pieces, path traced: render-array.sh --wait" 0
    check "glint pieces, path traced: merged image equals the single-machine render" \
        cmp pieces-path/frame.png ref-path.png
else
    echo "cluster_test: glint has no --part and merge yet: the job array ran the stand-in piece" \
        "renderer only (harness part); glint's own pieces are not tested"
fi
if [ "$mpi_on" = 1 ]; then
    collect mpi
    check_rc "glint MPI mode under Slurm: sbatch --wait" 0
    check "glint MPI mode: image equals the single-machine render" cmp mpi/frame.png ref.png
else
    echo "cluster_test: no glint-mpi beside glint (MPI not found): the MPI recipe ran the stand-in only"
fi
jobs_time=$(seconds "$t1" "$(now)")

finished=1
trap - EXIT
cluster_cleanup
total=$(seconds "$t0" "$(now)")
echo "cluster_test: times: Slurm start $start_time s; 4-task array and merge (--wait)" \
    "$harness_time s; all jobs $jobs_time s; stop $stop_time s; total $total s"
finish
