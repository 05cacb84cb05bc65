#!/usr/bin/env bash
# Reading a 1M-triangle PLY and STL (binary and ASCII) with Glint's own readers and with Assimp:
# the median seconds of RUNS reads in one process, and the peak resident memory of one read in a
# process of its own (docs/performance.md, "PLY and STL: Glint's reader or Assimp").
# Usage: bench/mesh_load_stats.sh BUILD_DIR [RUNS]
# BUILD_DIR is a build with -DGLINT_BUILD_BENCH=ON (and libassimp-dev installed for Assimp). The
# models (bench/gen_mesh.cpp: the rippled trefoil-knot tube, 1,048,576 triangles with vertex
# normals; STL without) are written to $GLINT_BENCH_TMP (default /tmp/glint-bench) once and
# reused; they are never part of the repository.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS]" >&2
    exit 2
fi
build=$1
runs=${2:-5}
tmp=${GLINT_BENCH_TMP:-/tmp/glint-bench}
mkdir -p "$tmp"
gen() {
    local file=$tmp/$1
    shift
    [ -f "$file" ] || "$build/bench/glint_gen_mesh" "$@" "$file" >/dev/null
}
gen trefoil-1m.ply
gen trefoil-1m-ascii.ply --ascii
gen trefoil-1m-be.ply --big-endian
gen trefoil-1m.stl
gen trefoil-1m-ascii.stl --ascii

here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/measure.sh
. "$here/measure.sh"
printf '%-22s %9s %-7s %10s %10s %s\n' file MB loader median_s peak_MiB faces
for name in trefoil-1m.ply trefoil-1m-be.ply trefoil-1m-ascii.ply trefoil-1m.stl \
    trefoil-1m-ascii.stl; do
    file=$tmp/$name
    mb=$(stat -c %s "$file" | awk '{printf "%.1f", $1 / 1e6}')
    for loader in glint assimp; do
        if ! out=$("$build/bench/glint_mesh_load_bench" "$loader" "$file" "$runs" 2>&1); then
            printf '%-22s %9s %-7s %s\n' "$name" "$mb" "$loader" "failed: $(echo "$out" | tail -n 1)"
            continue
        fi
        median_s=$(echo "$out" | awk '{print $3}' | median)
        faces=$(echo "$out" | tail -n 1 | awk '{print $5}')
        peak=$(/usr/bin/time -v "$build/bench/glint_mesh_load_bench" "$loader" "$file" 1 2>&1 \
            >/dev/null | awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}')
        printf '%-22s %9s %-7s %10.3f %10s %s\n' "$name" "$mb" "$loader" "$median_s" "$peak" "$faces"
    done
done
echo "(median of $runs reads in one process; peak resident memory of one read in its own process)"
