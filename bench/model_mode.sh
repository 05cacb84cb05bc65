#!/usr/bin/env bash
# The model mode at its default quality (`glint MODEL`: the path tracer at 64 samples per pixel
# in the studio environment, with a ground shadow, 640x480): medians over RUNS runs of parse,
# BVH build, render, whole command and peak memory, for two generated models:
#   - knot-15k.obj: a rippled trefoil-knot tube of 15,360 triangles with vertex normals and
#     texture coordinates, textured (bench/model_texture.py) and glossy (Ks 0.25, Ns 200);
#   - trefoil-1m.glb: the same surface at 1,048,576 triangles, binary glTF, no material (the
#     light grey default), as bench/mesh_stats.sh uses it.
# Usage: bench/model_mode.sh BUILD_DIR [RUNS] [THREADS] [GLINT_OPTIONS...]
# BUILD_DIR needs bench/glint_gen_mesh (-DGLINT_BUILD_BENCH=ON). The models and the last run's
# images go to $GLINT_BENCH_TMP (default /tmp/glint-bench); the models are written once and
# reused, and never committed.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [THREADS] [GLINT_OPTIONS...]" >&2
    exit 2
fi
build=$1
runs=${2:-3}
threads=${3:-2}
shift $(($# < 3 ? $# : 3))
here=$(cd "$(dirname "$0")" && pwd)
tmp=${GLINT_BENCH_TMP:-/tmp/glint-bench}
mkdir -p "$tmp"

knot=$tmp/knot-15k.obj
if [ ! -f "$knot" ]; then
    "$build/bench/glint_gen_mesh" --segments 96 --sides 80 --uv "$tmp/knot-15k-raw.obj"
    { echo "mtllib knot-15k.mtl"; echo "usemtl knot"; cat "$tmp/knot-15k-raw.obj"; } >"$knot"
    rm "$tmp/knot-15k-raw.obj"
    printf 'newmtl knot\nKd 1 1 1\nKs 0.25 0.25 0.25\nNs 200\nmap_Kd knot-15k.png\n' \
        >"$tmp/knot-15k.mtl"
    python3 "$here/model_texture.py" "$tmp/knot-15k.png"
fi
big=$tmp/trefoil-1m.glb
[ -f "$big" ] || "$build/bench/glint_gen_mesh" "$big"

# shellcheck source=bench/measure.sh
. "$here/measure.sh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for model in "$knot" "$big"; do
    echo "== $(basename "$model") $*"
    glint_runs "$runs" "$out/runs" "$build/glint" -q --stats -t "$threads" "$model" \
        -o "$tmp/$(basename "$model" | tr . -)-render.png" "$@"
    grep -E '^(Scene|Rays)' "$out/runs.stats"
    glint_header
    echo
    glint_medians "$out/runs"
    echo
    echo "CPU time (user + system), median: $(glint_cpu_median "$out/runs") s"
    rm "$out/runs"
done
echo "(medians of $runs runs, $threads threads; the last images: $tmp/*-render.png)"
