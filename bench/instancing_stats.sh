#!/usr/bin/env bash
# Instancing: 100 copies of a 102,400-triangle model, stored once (one mesh file placed 100
# times: instances of one shared mesh over a two-level BVH) against stored 100 times (100
# names for the same file, so that each is read and placed as plain triangles), and one copy
# alone. Medians over RUNS runs of parse, BVH build, render, whole command and peak memory.
# Usage: bench/instancing_stats.sh BUILD_DIR [RUNS] [THREADS]
# The model (bench/gen_mesh.cpp, 400 x 128 cells) and the scenes are written to
# $GLINT_BENCH_TMP (default /tmp/glint-bench); the 100 names are symbolic links.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [THREADS]" >&2
    exit 2
fi
build=$1
runs=${2:-3}
threads=${3:-2}
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/measure.sh
. "$here/measure.sh"
tmp=${GLINT_BENCH_TMP:-/tmp/glint-bench}/instancing
mkdir -p "$tmp"
[ -f "$tmp/knot.obj" ] || "$build/bench/glint_gen_mesh" --segments 400 --sides 128 "$tmp/knot.obj"

# A 10 x 10 grid of knots (each about 7 units across) seen from above and in front.
scene() {  # scene FILE NAME_OF_COPY_I...
    local file=$1 i
    {
        echo "size 640 480"
        echo "camera 36 55 -45 36 0 36 0 1 0 45"
        echo "directional 0.3 1 -0.4 0.8 0.8 0.8"
        echo "point 36 40 36 0.5 0.5 0.5"
        echo "diffuse 0.6 0.5 0.3"
        echo "specular 0.2 0.2 0.2"
        echo "shininess 30"
        for ((i = 0; i < ${2:-100}; i++)); do
            echo "pushTransform"
            echo "translate $((i % 10 * 8)) 0 $((i / 10 * 8))"
            echo "rotate 1 0 0 90"
            echo "mesh $(name "$i")"
            echo "popTransform"
        done
    } >"$file"
}
name() { echo knot.obj; }
scene "$tmp/instanced.test" 100
scene "$tmp/one.test" 1
for ((i = 0; i < 100; i++)); do ln -sf knot.obj "$tmp/copy$i.obj"; done
name() { echo "copy$1.obj"; }
scene "$tmp/copies.test" 100

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-22s ' case
glint_header
echo
for case in one instanced copies; do
    glint_runs "$runs" "$out/$case" "$build/glint" -q --stats -t "$threads" "$tmp/$case.test" \
        -o "$out/$case.png"
    printf '%-22s ' "$case"
    glint_medians "$out/$case"
    echo
done
for case in one instanced copies; do
    echo "$case:"
    grep -E '^(Scene|Instances|BVH)' "$out/$case.stats" | sed 's/^/  /'
done
echo "(medians of $runs runs, $threads threads, 640x480; one: 1 copy; instanced: 100 placements" \
    "of one file; copies: 100 files with the same content)"
