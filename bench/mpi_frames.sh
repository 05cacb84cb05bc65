#!/usr/bin/env bash
# A sequence through glint-mpi (docs/scale-out.md, "Sequences: glint-mpi --frames"): 10 frames of
# tests/data/gltf/animated.gltf rendered by
#   glint --frames 0:9 -t 2                            one process (the plain render)
#   mpirun -np 2 glint-mpi --frames 0:9 -t 1           one job: mpirun's start paid once
#   10 x mpirun -np 2 glint-mpi --frame N -t 1         a job per frame: paid ten times
# in RUNS rounds, each running every command once, so that the load of a shared machine falls
# on all of them alike (round r starts with command r mod 3). Prints the median wall time of
# each, its ratio to the one job, and the cost per frame of a job's start. Every frame is
# checked to be glint's, byte for byte.
# Usage: bench/mpi_frames.sh BUILD_DIR [RUNS] [GLINT_OPTIONS...]   (default: --size 64x48 --spp 4)
# BUILD_DIR needs glint and glint-mpi (Open MPI found). Needs python3.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [GLINT_OPTIONS...]" >&2
    exit 2
fi
build=$(cd "$1" && pwd)
runs=${2:-5}
shift $(($# < 2 ? $# : 2))
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$here/../tests/data/gltf" && pwd)/animated.gltf
if [ $# -gt 0 ]; then opts=(-q "$@"); else opts=(-q --size 64x48 --spp 4); fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# One machine: shared memory only; as root if need be; no binding (two ranks of one thread).
mpirun=(mpirun --bind-to none --mca pml ob1 --mca btl "self,vader")
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)

cd "$out"
now() { date +%s.%N; }
plain() { "$build/glint" "$scene" --frames 0:9 -t 2 -o "plain_%04d.png" "${opts[@]}"; }
one_job() {
    "${mpirun[@]}" -np 2 "$build/glint-mpi" "$scene" --frames 0:9 -t 1 -o "job_%04d.png" \
        "${opts[@]}"
}
job_per_frame() {
    local n
    for n in 0 1 2 3 4 5 6 7 8 9; do
        "${mpirun[@]}" -np 2 "$build/glint-mpi" "$scene" --frame "$n" -t 1 \
            -o "$(printf 'each_%04d.png' "$n")" "${opts[@]}"
    done
}
commands=(plain one_job job_per_frame)
one_job  # warm the caches once
for ((r = 0; r < runs; r++)); do
    for ((j = 0; j < 3; j++)); do
        c=${commands[(j + r) % 3]}
        t0=$(now)
        "$c"
        echo "$c $(awk -v a="$t0" -v b="$(now)" 'BEGIN { print b - a }')" >>times.txt
    done
done
for n in 0 1 2 3 4 5 6 7 8 9; do
    f=$(printf '%04d.png' "$n")
    if ! cmp "plain_$f" "job_$f" || ! cmp "plain_$f" "each_$f"; then
        echo "$0: frame $n differs from glint's" >&2
        exit 1
    fi
done

python3 - "$runs" "${opts[*]}" <<'EOF'
import statistics, sys
runs, opts = int(sys.argv[1]), sys.argv[2]
t = {}
for line in open("times.txt"):
    name, s = line.split()
    t.setdefault(name, []).append(float(s))
med = {k: statistics.median(v) for k, v in t.items()}
names = {"plain": "glint --frames 0:9 -t 2",
         "one_job": "mpirun -np 2 glint-mpi --frames 0:9 -t 1",
         "job_per_frame": "10 x mpirun -np 2 glint-mpi --frame N -t 1"}
print(f"10 frames of animated.gltf, {opts}, median of {runs} rounds:")
print("| command | wall (s), median | range | vs one job |")
print("|---|---|---|---|")
for k in ("plain", "one_job", "job_per_frame"):
    print(f"| `{names[k]}` | {med[k]:.2f} | {min(t[k]):.2f} to {max(t[k]):.2f} "
          f"| {med[k] / med['one_job']:.2f}x |")
print(f"start paid per frame: {(med['job_per_frame'] - med['one_job']) / 9:.3f} s "
      "(the difference over the 9 starts saved)")
EOF
