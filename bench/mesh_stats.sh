#!/usr/bin/env bash
# Loading and rendering a 1M-triangle model with no scene file (`glint model.obj`, or
# `glint model.glb`): medians over RUNS runs of parse (file to MeshData to scene), BVH build,
# render and peak memory.
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

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
: >"$out/runs"
for ((i = 0; i < runs; i++)); do
    /usr/bin/time -v "$build/glint" -q --stats -t "$threads" "$model" -o "$out/img.png" \
        >"$out/stats" 2>"$out/time"
    rss=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$out/time")
    wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$out/time" |
        awk -F: '{print (NF == 3 ? $1 * 3600 + $2 * 60 + $3 : $1 * 60 + $2)}')
    awk -v rss="$rss" -v wall="$wall" '
        /^Time/ {parse=$3; build=$6; render=$9; write=$12}
        END {print parse, build, render, write, wall, rss / 1024}' "$out/stats" >>"$out/runs"
done
grep -E '^(Scene|BVH)' "$out/stats"
printf '%9s %9s %9s %9s %9s %12s\n' parse_s build_s render_s write_s total_s peak_RSS_MiB
row=""
for col in 1 2 3 4 5 6; do row="$row $(cut -d' ' -f$col "$out/runs" | median)"; done
# shellcheck disable=SC2086
printf '%9.3f %9.3f %9.3f %9.3f %9.2f %12.0f\n' $row
echo "(medians of $runs runs, $threads threads, 640x480; parse = $format read, checked and placed)"
