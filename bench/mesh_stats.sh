#!/usr/bin/env bash
# Loading and rendering a 1M-triangle model with no scene file (`glint model.obj`, .glb, .ply
# or .stl): medians over RUNS runs of parse (file to MeshData to scene), BVH build,
# render and peak memory.
# Usage: bench/mesh_stats.sh BUILD_DIR [RUNS] [THREADS] [obj|glb|ply|stl]
# The model (bench/gen_mesh.cpp: a rippled trefoil-knot tube, 1,048,576 triangles with vertex
# normals; about 80 MB of OBJ text, a 25 MB binary glTF, a 26 MB binary PLY or a 52 MB binary STL
# without normals) is written to $GLINT_BENCH_TMP
# (default /tmp/glint-bench) once and reused; it is never part of the repository.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [THREADS] [obj|glb|ply|stl]" >&2
    exit 2
fi
build=$1
runs=${2:-5}
threads=${3:-2}
format=${4:-obj}
case $format in obj | glb | ply | stl) ;; *) echo "$0: format must be obj, glb, ply or stl" >&2 && exit 2 ;; esac
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
glint_runs "$runs" "$out/runs" "$build/glint" -q --stats -t "$threads" "$model" -o "$out/img.png"
grep -E '^(Scene|BVH)' "$out/runs.stats"
glint_header
echo
glint_medians "$out/runs"
echo
echo "(medians of $runs runs, $threads threads, 640x480; parse = $format read, checked and placed)"
