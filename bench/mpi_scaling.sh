#!/usr/bin/env bash
# The figures behind glint-mpi's scaling model (docs/scale-out.md, "MPI"), then the model:
#   1. the path-traced Cornell box at 3840x2160 in 16-pixel tiles at SPP_A and SPP_B samples
#      per pixel (default 2 and 8) on two ranks of one thread each, with --timings: every tile's
#      render time, scene load and BVH build times, bytes sent, rank 0's MPI thread CPU time;
#   2. load and build of a larger scene (the course's scene7, 150,000 lines) on two ranks;
#   3. bench/mpi_model.py on (1): the speedup at 4, 16 and 64 nodes for 1024 spp.
# Usage: bench/mpi_scaling.sh BUILD_DIR [SPP_A] [SPP_B] [MODEL_OPTIONS...]
# The timings files stay in $GLINT_BENCH_TMP (default /tmp/glint-bench): run bench/mpi_model.py
# on them again with other options (--threads, --tiles, --startup, ...).
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [SPP_A] [SPP_B] [MODEL_OPTIONS...]" >&2
    exit 2
fi
build=$(cd "$1" && pwd)
spp_a=${2:-2}
spp_b=${3:-8}
shift $(($# < 3 ? $# : 3))
here=$(cd "$(dirname "$0")" && pwd)
tmp=${GLINT_BENCH_TMP:-/tmp/glint-bench}
mkdir -p "$tmp"

mpirun=(mpirun --oversubscribe --bind-to none --mca pml ob1 --mca btl self,vader)
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)

for spp in "$spp_a" "$spp_b"; do
    echo "== cornell 3840x2160, $spp spp, 16-pixel tiles, 2 ranks x 1 thread"
    "${mpirun[@]}" -np 2 "$build/glint-mpi" "$here/../scenes/cornell.test" --integrator path \
        --size 3840x2160 --spp "$spp" --tile 16 -t 1 -q --stats -o "$tmp/cornell-4k.exr" \
        --timings "$tmp/mpi-4k-$spp.json" | grep -E '^(Time|MPI|Tiles|Messages|Coordinator)'
done
echo "== scene7 (the course's), load and build on 2 ranks"
"${mpirun[@]}" -np 2 "$build/glint-mpi" "$here/../tests/data/cse167x/scene7.test" --size 32x32 \
    -t 1 -q --stats -o "$tmp/scene7.png" | grep -E '^(Scene|Slowest)'
echo
"$here/mpi_model.py" "$tmp/mpi-4k-$spp_a.json" "$tmp/mpi-4k-$spp_b.json" "$@"
