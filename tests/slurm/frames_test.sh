#!/bin/bash
# Sequences on a real Slurm (issue 24, "The farm"): the 100 frames of an animated glTF file
# (tests/data/gltf/animated.gltf) rendered by a job array of contrib/slurm/render-frames.sh, by
# frames (contiguous runs, and strided), by pieces of frames with a merge job per frame, and by
# glint-mpi on a Slurm allocation (glint-mpi.sbatch --frames); every frame is compared with
# glint's single-process render of the same frame, byte for byte. A piece that fails leaves
# its frame unwritten, and the other frames written.
#
#   frames_test.sh SOURCE_DIR GLINT
#
# The private cluster is tests/slurm/local_slurm.sh's (4 CPUs on localhost). Exit code 77
# (CTest: skipped) without slurm-wlm and munge, or when not root, as cluster_test.sh; the MPI part
# runs when glint-mpi is built beside glint and mpirun (openmpi-bin) is there.
set -uo pipefail
source_dir=$(readlink -f "${1:?usage: frames_test.sh SOURCE_DIR GLINT}")
glint=$(readlink -f "${2:?usage: frames_test.sh SOURCE_DIR GLINT}")
here=$source_dir/tests/slurm
contrib=$source_dir/contrib/slurm
# shellcheck source=tests/slurm/assert.sh
. "$here/assert.sh"
# shellcheck source=tests/slurm/local_slurm.sh
. "$here/local_slurm.sh"

# shellcheck source=tests/slurm/cluster_harness.sh
. "$here/cluster_harness.sh"
cluster_harness frames_test "$glint" 100 80
job_id() { sed -n "s/^$1 jobs\{0,1\} \([0-9]*\).*/\1/p" <<<"$OUT"; }
jobcomp() { grep "^JobId=$1 " "$work/slurm/log/jobcomp.txt" 2>/dev/null; }
# same DIR A:B[:STEP] [REF]: how many frames of the range in DIR (f_NNNN.png) are byte for byte
# the single-process frame (in REF, by default ref), of how many.
same() {
    local dir=$1 ref=${3:-ref} first last step n equal=0 total=0 name
    IFS=: read -r first last step <<<"$2"
    for ((n = first; n <= last; n += ${step:-1})); do
        name=$(printf 'f_%04d.png' "$n")
        total=$((total + 1))
        cmp -s "$ref/$name" "$dir/$name" && equal=$((equal + 1))
    done
    echo "$equal of $total"
}

scene=$source_dir/tests/data/gltf/animated.gltf
opts=(--size 32x24 --spp 2 -t 1 -q)
# Pieces are never denoised (glint merge adds their sums): a model's frames by pieces are
# compared without the denoiser that its whole frames have by default.
raw_opts=("${opts[@]}" --no-denoise)

## The single-process frames: one glint, the sequence of 100 frames; and 4 of them raw.
t0=$(now)
mkdir ref raw
"$glint" "$scene" --frames 0:99 -o 'ref/f_%04d.png' "${opts[@]}" ||
    check "single-process sequence" false
ref_time=$(seconds "$t0" "$(now)")
"$glint" "$scene" --frames 0:99:33 -o 'raw/f_%04d.png' "${raw_opts[@]}" ||
    check "single-process sequence, raw" false
check_eq "single-process sequence: 100 frames" 100 "$(find ref -name 'f_*.png' | wc -l)"
check_eq "the frames differ from each other" 100 "$(md5sum ref/f_*.png | cut -d' ' -f1 | sort -u | wc -l)"

## The cluster.
t1=$(now)
mkdir slurm
if ! local_slurm_start "$work/slurm"; then
    echo "frames_test: error: the private Slurm did not start" >&2
    exit 1
fi
echo "frames_test: Slurm up in $(seconds "$t1" "$(now)") s (SLURM_CONF=$SLURM_CONF)"

## Everything at once (the cluster has 4 CPUs).
t2=$(now)
mkdir frames strided pieces failing mpi
# A glint that fails for piece 1 of frame 33, as a node that dies would.
printf '#!/bin/bash\n[[ " $* " == *" --frame 33 --part 1/2 "* ]] && { echo "failing as asked" >&2; exit 1; }\nexec "%s" "$@"\n' \
    "$glint" >failing_glint
chmod +x failing_glint
bg frames env GLINT="$glint" "$contrib/render-frames.sh" --wait --tasks 4 "$scene" \
    'frames/f_%04d.png' 0:99 "${opts[@]}"
bg strided env GLINT="$glint" "$contrib/render-frames.sh" --wait --tasks 3 --strided "$scene" \
    'strided/f_####.png' 0:99:9 "${opts[@]}"
bg pieces env GLINT="$glint" "$contrib/render-frames.sh" --wait --parts 2 "$scene" \
    'pieces/f_%04d.png' 0:99:33 "${raw_opts[@]}"
bg failing env GLINT="$work/failing_glint" "$contrib/render-frames.sh" --wait --parts 2 "$scene" \
    'failing/f_%04d.png' 0:66:33 "${raw_opts[@]}"
glint_mpi=$(dirname "$glint")/glint-mpi
mpi_on=0
if [ -x "$glint_mpi" ] && command -v mpirun >/dev/null; then
    mpi_on=1
    bg mpi env GLINT_MPI="$glint_mpi" sbatch --wait -n 2 -o mpi/slurm-%j.out \
        "$contrib/glint-mpi.sbatch" "$scene" --frames 0:99 -o 'mpi/f_%04d.png' "${opts[@]}"
fi

## By frames: 4 tasks of 25 consecutive frames, each task one glint --frames.
collect frames
check_rc "by frames: render-frames.sh --wait" 0
check_contains "by frames: all written" "$OUT" "all 100 frames written"
check_eq "by frames: every frame equals the single-process frame" "100 of 100" "$(same frames 0:99)"
array=$(job_id array)
for task in 0 1 2 3; do
    check_contains "by frames: task $task rendered its 25 frames" \
        "$(cat "frames/f.logs/slurm-${array}_$task.out" 2>/dev/null)" \
        "task $task on $(hostname): frames $((25 * task)):$((25 * task + 24)):1 (25)"
done

## Strided: 12 frames (0, 9, ... 99) in 3 tasks of every third.
collect strided
check_rc "strided: render-frames.sh --wait" 0
check_eq "strided: every frame equals the single-process frame" "12 of 12" "$(same strided 0:99:9)"
array=$(job_id array)
check_contains "strided: task 1 rendered frames 9, 36, 63, 90" \
    "$(cat "strided/f.logs/slurm-${array}_1.out" 2>/dev/null)" "frames 9:99:27 (4)"

## By pieces of frames: frames 0, 33, 66, 99 in 2 pieces each, a merge job per frame.
collect pieces
check_rc "pieces of frames: render-frames.sh --wait" 0
check_eq "pieces of frames: every merged frame equals the single-process frame" "4 of 4" \
    "$(same pieces 0:99:33 raw)"
check_eq "pieces of frames: 8 pieces" 8 "$(find pieces/f.pieces -name 'piece-*.exr' | wc -l)"
check_eq "pieces of frames: 4 merge jobs" 4 \
    "$(sed -n 's/^merge jobs \([0-9 ]*\):.*/\1/p' <<<"$OUT" | wc -w)"

## A failing piece: its frame's merge job is cancelled, the other frames are written.
collect failing
check_rc "failing piece: render-frames.sh --wait" 1
check_contains "failing piece: the frame named" "$ERR" "1 of 3 frames not written: 33"
check_contains "failing piece: the piece named" "$ERR" "frame 33: pieces 1 (tasks 2 to 3)"
check "failing piece: no frame 33" test ! -e failing/f_0033.png
check_eq "failing piece: frames 0 and 66 written" "2 of 2" "$(same failing 0:66:66 raw)"
merge33=$(sed -n 's/^merge jobs [0-9]* \([0-9]*\) .*/\1/p' <<<"$OUT")
check_contains "failing piece: frame 33's merge job cancelled" "$(jobcomp "$merge33")" \
    "JobState=CANCELLED"

## glint-mpi: the 100 frames in one job of 2 ranks, started once.
if [ "$mpi_on" = 1 ]; then
    collect mpi
    check_rc "glint-mpi under Slurm: sbatch --wait" 0
    check_eq "glint-mpi: every frame equals the single-process frame" "100 of 100" \
        "$(same mpi 0:99)"
    check_eq "glint-mpi: one job" 1 "$(find mpi -name 'slurm-*.out' | wc -l)"
else
    echo "frames_test: no glint-mpi beside glint, or no mpirun: the MPI sequence was not run"
fi
jobs_time=$(seconds "$t2" "$(now)")

finished=1
trap - EXIT
cluster_cleanup
echo "frames_test: times: single-process sequence $ref_time s; every job $jobs_time s;" \
    "total $(seconds "$t0" "$(now)") s"
finish
