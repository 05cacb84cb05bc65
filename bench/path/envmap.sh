#!/usr/bin/env bash
# The path tracer's cost on a 1M-triangle model (bench/gen_mesh.cpp) lit only by an
# equirectangular environment map with a sun (rendered from sky.test): medians of RUNS runs of
# parse, BVH build and render at SPP samples per pixel, rays per path and Mrays/s.
# Usage: bench/path/envmap.sh BUILD_DIR [RUNS] [THREADS] [SPP]
# GEN_MESH: the mesh generator binary (default BUILD_DIR/bench/glint_gen_mesh).
set -euo pipefail
build=$1
runs=${2:-3}
threads=${3:-2}
spp=${4:-16}
here=$(cd "$(dirname "$0")" && pwd)
tmp=${GLINT_BENCH_TMP:-/tmp/glint-bench}
mkdir -p "$tmp"
gen=${GEN_MESH:-$build/bench/glint_gen_mesh}
[ -f "$tmp/trefoil-1m.obj" ] || "$gen" "$tmp/trefoil-1m.obj"
"$build/glint" "$here/sky.test" -q -t "$threads" -o "$tmp/sky.exr"
cp "$here/envmap.test" "$tmp/envmap.test"
for i in $(seq "$runs"); do
    "$build/glint" "$tmp/envmap.test" -q --stats -t "$threads" --spp "$spp" -o "$tmp/envmap-$i.png" 2>&1 |
        awk '/^Time/ {gsub(",", ""); print $3, $6, $9} /^Rays/ {print "rays", $2, $8}'
done | awk -v spp="$spp" '
    NF == 3 && $1 != "rays" { parse[++n] = $1; build[n] = $2; render[n] = $3 }
    $1 == "rays" { camera = $2; total = $3 }
    function median(a, k,   i, j, t) {
        for (i = 1; i <= k; ++i) for (j = i + 1; j <= k; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
        return k % 2 ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
    }
    END {
        r = median(render, n)
        printf "parse %.2f s, build %.2f s, render %.2f s (medians of %d)\n", median(parse, n), median(build, n), r, n
        printf "%d paths, %.2f rays per path, %.2f Mrays/s, %.3f Mpaths/s\n", camera, total / camera, total / r / 1e6, camera / r / 1e6
    }'
