#!/usr/bin/env bash
# The full benchmark of issue 3 (what `make bench` runs), on a build configured with
# -DGLINT_BUILD_BENCH=ON:
#   1. BVH build and traversal against Intel Embree (bench/glint_traversal_bench, when built);
#   2. whole renders against POV-Ray 3.7 (bench/render_compare.sh);
#   3. --stats medians for the official course scenes (bench/course_stats.sh);
#   4. loading and rendering a generated 1M-triangle OBJ model (bench/mesh_stats.sh);
#   5. 100 copies of a model, instanced and stored (bench/instancing_stats.sh);
#   6. the path tracer against Blender Cycles on the Cornell box (bench/cycles/run.sh; its long
#      Cycles reference is rendered once and kept in ../cycles-out beside the repository);
#   7. reading 1M-triangle PLY and STL files with Glint's readers and with Assimp
#      (bench/mesh_load_stats.sh).
#   8. the model mode at its default quality, a 15k-triangle textured model and a 1M-triangle
#      one (bench/model_mode.sh).
# Usage: bench/run.sh BUILD_DIR
set -euo pipefail

if [ $# -ne 1 ]; then
    echo "usage: $0 BUILD_DIR" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "$1" && pwd)

header() { printf '\n==== %s ====\n\n' "$*"; }

model=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
cores=$(lscpu | awk -F: '/^Core\(s\) per socket/ {c = $2} /^Socket\(s\)/ {s = $2}
                         END {if (c && s) print c * s}')
echo "Glint benchmark, $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "Machine: ${model:-unknown CPU}, ${cores:-?} cores, $(nproc) hardware threads;" \
    "$("$build/glint" --version 2>/dev/null || echo 'glint ?'), build $build"

header "1. BVH build and traversal: Glint vs Embree"
if [ -x "$build/bench/glint_traversal_bench" ]; then
    "$build/bench/glint_traversal_bench"
else
    echo "(skipped: $build/bench/glint_traversal_bench was not built; it needs libembree-dev)"
fi

header "2. Whole renders: Glint vs POV-Ray"
"$here/render_compare.sh" "$build"

header "3. Course scenes: glint --stats"
"$here/course_stats.sh" "$build/glint" 7 2

header "4. A 1M-triangle OBJ model: glint model.obj"
"$here/mesh_stats.sh" "$build" 5 2

header "5. Instancing: 100 copies of a 102,400-triangle model"
"$here/instancing_stats.sh" "$build" 3 2

header "6. Path tracing: Glint vs Blender Cycles, the Cornell box"
if command -v blender >/dev/null; then
    "$here/cycles/run.sh" "$build" || echo "(bench/cycles/run.sh failed: exit $?)"
else
    echo "(skipped: blender is not installed; make bench installs it)"
fi

header "7. PLY and STL: Glint's readers vs Assimp, 1M triangles"
"$here/mesh_load_stats.sh" "$build" 5

header "8. The model mode at its default quality: glint knot-15k.obj, glint trefoil-1m.glb"
"$here/model_mode.sh" "$build" 3 2
