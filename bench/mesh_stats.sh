#!/usr/bin/env bash
# Loading and rendering a 1M-triangle model with no scene file (`glint model.obj --integrator
# whitted`, or .glb, .ply, .stl): medians over RUNS runs of parse (file to MeshData to scene),
# BVH build, render and peak memory.
# Usage: bench/mesh_stats.sh BUILD_DIR [RUNS] [THREADS] [obj|glb|draco|meshopt|ply|stl]
# The model (bench/gen_mesh.cpp: a rippled trefoil-knot tube, 1,048,576 triangles with vertex
# normals; about 80 MB of OBJ text, a 25 MB binary glTF, a 26 MB binary PLY or a 52 MB binary STL
# without normals) is written to $GLINT_BENCH_TMP (default /tmp/glint-bench) once and reused; it
# is never part of the repository. `draco` and `meshopt` compress the .glb with Debian's tools,
# as a user would: draco_transcoder (package draco; its defaults: 11-bit positions, 8-bit
# normals, compression level 7) and gltfpack -c (package gltfpack; its defaults: 14-bit
# positions, 8-bit normals, EXT_meshopt_compression).
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [THREADS] [obj|glb|draco|meshopt|ply|stl]" >&2
    exit 2
fi
build=$1
runs=${2:-5}
threads=${3:-2}
format=${4:-obj}
case $format in
    obj | glb | draco | meshopt | ply | stl) ;;
    *) echo "$0: format must be obj, glb, draco, meshopt, ply or stl" >&2 && exit 2 ;;
esac
tmp=${GLINT_BENCH_TMP:-/tmp/glint-bench}
mkdir -p "$tmp"
ext=$format
case $format in draco | meshopt) ext=glb ;; esac
source=$tmp/trefoil-1m.$ext
if [ ! -f "$source" ]; then
    start=$(date +%s.%N)
    "$build/bench/glint_gen_mesh" "$source"
    echo "(generated in $(echo "$(date +%s.%N) - $start" | bc) s)"
fi
model=$source
if [ "$format" = draco ] || [ "$format" = meshopt ]; then
    model=$tmp/trefoil-1m-$format.glb
    if [ ! -f "$model" ]; then
        start=$(date +%s.%N)
        if [ "$format" = draco ]; then
            draco_transcoder -i "$source" -o "$model" >/dev/null
        else
            gltfpack -i "$source" -o "$model" -c >/dev/null
        fi
        echo "(compressed in $(echo "$(date +%s.%N) - $start" | bc) s)"
    fi
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
