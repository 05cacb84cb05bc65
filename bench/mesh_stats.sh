#!/usr/bin/env bash
# Loading and rendering a 1M-triangle model with no scene file (`glint model.obj --integrator
# whitted`, or `glint model.glb ...`): medians over RUNS runs of parse (file to MeshData to
# scene), BVH build, render and peak memory.
# Usage: bench/mesh_stats.sh BUILD_DIR [RUNS] [THREADS] [obj|glb]
# The model (bench/gen_mesh.cpp: a rippled trefoil-knot tube, 1,048,576 triangles with vertex
# normals; about 80 MB of OBJ text, or a 25 MB binary glTF) is written to $GLINT_BENCH_TMP
# (default /tmp/glint-bench) once and reused; it is never part of the repository.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [THREADS] [obj|glb]" >&2
    exit 2
fi
build=$1
runs=${2:-5}
threads=${3:-2}
format=${4:-obj}
case $format in obj | glb) ;; *) echo "$0: format must be obj or glb" >&2 && exit 2 ;; esac
tmp=${GLINT_BENCH_TMP:-/tmp/glint-bench}
mkdir -p "$tmp"
model=$tmp/trefoil-1m.$format
if [ ! -f "$model" ]; then
    start=$(date +%s.%N)
    "$build/bench/glint_gen_mesh" "$model"
    echo "(generated in $(echo "$(date +%s.%N) - $start" | bc) s)"
fi
ls -l "$model" | awk '{printf "model: %s, %.1f MB\n", $NF, $5 / 1e6}'

here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/measure.sh
. "$here/measure.sh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# The classic look (--integrator whitted: one sample per pixel, the course's integrator), as
# before the model mode's studio: this measures loading; bench/model_mode.sh measures the studio.
glint_runs "$runs" "$out/runs" "$build/glint" -q --stats -t "$threads" "$model" \
    --integrator whitted -o "$out/img.png"
grep -E '^(Scene|BVH)' "$out/runs.stats"
glint_header
echo
glint_medians "$out/runs"
echo
echo "(medians of $runs runs, $threads threads, 640x480; parse = $format read, checked and placed)"
