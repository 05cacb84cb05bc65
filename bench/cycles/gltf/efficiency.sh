#!/usr/bin/env bash
# Efficiency against Blender Cycles (issue 22): each renderer against its own long reference,
# at equal samples, on one of this folder's assets. For Glint and for Cycles: a reference at
# REF_SPP (rendered once, kept in OUT/ref), then RUNS renders at SPP with other seeds,
# interleaved so that both meet the same machine load; each renderer's own time (Glint: BVH
# build and render from --stats; Cycles: bpy.ops.render.render, which includes its scene sync
# and BVH build), median of the runs; the errors of the last run against the renderer's own
# reference (bench/denoise/relmse.py --all: relMSE, relMSE without the worst 0.1% of pixels,
# mean absolute relative error, and the pixels off by more than 4x counted apart); efficiency
# 1 / (error x time), and Glint's over Cycles'. Then the two references against each other
# (imgdiff --blocks 16).
# Usage: bench/cycles/gltf/efficiency.sh BUILD OUT ASSET [SPP] [REF_SPP] [RUNS]
#   e.g. bench/cycles/gltf/efficiency.sh build /tmp/eff lamps 64 2048 3
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?build dir}" && pwd)
mkdir -p "${2:?output dir}"
out=$(cd "$2" && pwd)
asset=${3:?asset (a .test beside this script)}
spp=${4:-64} ref=${5:-2048} runs=${6:-3}
command -v blender >/dev/null ||
    { echo "efficiency.sh: needs Blender (apt-get install blender python3-numpy)" >&2; exit 1; }
mkdir -p "$out/assets" "$out/ref" "$out/runs"
python3 "$here/make_assets.py" "$out/assets" >/dev/null
cp "$here/$asset.test" "$out/assets/"
scene=$out/assets/$asset.test
split=$build/bench/glint_aov_split
relmse=$here/../../denoise/relmse.py

glint() {  # SPP SEED OUT.exr -> prints build+render seconds
    "$build/glint" "$scene" --spp "$1" --seed "$2" -t 2 --stats -o "$3" 2>&1 |
        awk '/^Time/ { for (i = 1; i <= NF; ++i) { if ($i == "build") b = $(i + 1); if ($i == "render") r = $(i + 1) } print b + r }'
}
cycles() {  # SPP SEED OUT.exr -> prints render seconds
    blender -b --factory-startup --python "$here/gltf_cycles.py" -- --scene "$scene" \
        --out "$3" --spp "$1" --threads 2 --seed "$2" 2>&1 |
        sed -n 's/^CYCLES_RESULT.* render_s=\([0-9.]*\).*/\1/p'
}
pfm() { "$split" "$1" "${1%.exr}" >/dev/null; echo "${1%.exr}.pfm"; }

g_ref=$out/ref/glint-$asset-${ref}spp.exr c_ref=$out/ref/cycles-$asset-${ref}spp.exr
[ -f "$g_ref" ] || { echo "glint reference: $(glint "$ref" 1000 "$g_ref") s"; }
[ -f "$c_ref" ] || { echo "cycles reference: $(cycles "$ref" 1000 "$c_ref") s"; }
g_times=() c_times=()
for ((k = 0; k < runs; ++k)); do
    g_times+=("$(glint "$spp" "$k" "$out/runs/glint-$asset.exr")")
    c_times+=("$(cycles "$spp" "$k" "$out/runs/cycles-$asset.exr")")
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
g_t=$(median "${g_times[@]}") c_t=$(median "${c_times[@]}")
g_err=$(python3 "$relmse" "$(pfm "$out/runs/glint-$asset.exr")" "$(pfm "$g_ref")" --all)
c_err=$(python3 "$relmse" "$(pfm "$out/runs/cycles-$asset.exr")" "$(pfm "$c_ref")" --all)
echo "$asset at $spp spp, 256x256, 2 threads; each against its own $ref-spp reference"
echo "glint  time ${g_t} s (runs: ${g_times[*]})  $g_err"
echo "cycles time ${c_t} s (runs: ${c_times[*]})  $c_err"
field() { awk -v k="$1" '{ for (i = 1; i < NF; ++i) if ($i == k) print $(i + 1) }' <<<"$2"; }
for k in relMSE relMSE-trim MARE; do
    awk -v k="$k" -v ge="$(field "$k" "$g_err")" -v ce="$(field "$k" "$c_err")" \
        -v gt="$g_t" -v ct="$c_t" 'BEGIN {
            printf "efficiency by %s: glint %.4g, cycles %.4g: %.2fx\n", k, 1 / (ge * gt),
                   1 / (ce * ct), (ce * ct) / (ge * gt) }'
done
echo "per-sample noise (relMSE-trim), glint over cycles: $(awk -v g="$(field relMSE-trim "$g_err")" -v c="$(field relMSE-trim "$c_err")" 'BEGIN { printf "%.2f", g / c }')"
echo "references against each other:"
"$build/imgdiff" --blocks 16 "$g_ref" "$c_ref" | sed 's/^/  /'
