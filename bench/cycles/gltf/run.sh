#!/usr/bin/env bash
# glTF metallic-roughness materials in Glint's path tracer against Blender Cycles (issue 12,
# "Against Cycles"; bench/cycles/gltf/README.md explains the set-up). For each asset
# (make_assets.py writes them: textured metal, dielectrics, a normal map, an emissive texture)
# it renders the Glint scene (ASSET.test) and the same scene in Cycles through Blender's glTF
# importer (gltf_cycles.py), both at SPP samples per pixel, and compares them with
# `imgdiff --ssim` (SSIM of the displayed sRGB luma; relative difference of the luminance
# means; mean absolute luminance difference relative to the mean) and `imgdiff --blocks 16`.
# Beside each, the noise floor: Glint against Glint with another seed at the same spp.
# Side-by-side PNGs (Glint | Cycles | difference: red where Glint is brighter, blue where
# darker, full at 25% of the mean luminance) go to OUT_DIR/side-ASSET.png. For normaltilt (four
# patches, one 32x32 block each) it prints each patch's mean luminance in both (block_means.py),
# and Glint's under the same sky without its sun.
# Cycles renders are kept (OUT_DIR/cycles-ASSET-SPPspp-seed0.exr): delete them to render anew.
#
# Usage: bench/cycles/gltf/run.sh [OPTIONS] BUILD_DIR [OUT_DIR]
#   BUILD_DIR  holds glint and imgdiff (make build)
#   OUT_DIR    default: cycles-gltf-out beside the repository
# Options (defaults in brackets):
#   --spp N [1024]  --cycles-spp N [SPP]  --threads N [2]
#   --assets "LIST" [metal dielectric normalmap normaltilt emissive]
#   --docs DIR     also copy the side-by-side PNGs there as PREFIXASSET.png (at half size
#                  where the PNG is over 300 KB)
#   --docs-prefix P [gltf-cycles-]
#   --tests DIR    where ASSET.test are [this folder]; default OUT_DIR: cycles-NAME-out beside
#                  the repository, NAME the folder's name
#   --khronos DIR  Khronos' glTF models, linked as OUT_DIR/assets/khronos for the scenes that
#                  name khronos/... [../shared/real-world/gltf-ext beside the repository]
# A scene that names smoke.vdb gets it from BUILD_DIR/tools/glint_make_smoke_vdb; a line
# `# cycles-args: ARGS` in a scene passes ARGS to gltf_cycles.py.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../../.." && pwd)

usage() {
    sed -n '/^# Usage:/,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
    exit 2
}
spp=1024 cycles_spp= threads=2 assets="metal dielectric normalmap normaltilt emissive" docs=
docs_prefix=gltf-cycles- tests=$here khronos=$repo/../shared/real-world/gltf-ext
positional=()
while [ $# -gt 0 ]; do
    case $1 in
        --spp) spp=${2:?}; shift 2 ;;
        --cycles-spp) cycles_spp=${2:?}; shift 2 ;;
        --threads) threads=${2:?}; shift 2 ;;
        --assets) assets=${2:?}; shift 2 ;;
        --docs) docs=${2:?}; shift 2 ;;
        --docs-prefix) docs_prefix=${2:?}; shift 2 ;;
        --tests) tests=$(cd "${2:?}" && pwd); shift 2 ;;
        --khronos) khronos=${2:?}; shift 2 ;;
        -h | --help) usage ;;
        -*) echo "run.sh: unknown option $1" >&2; usage ;;
        *) positional+=("$1"); shift ;;
    esac
done
[ ${#positional[@]} -ge 1 ] && [ ${#positional[@]} -le 2 ] || usage
cycles_spp=${cycles_spp:-$spp}
for n in "$spp" "$cycles_spp" "$threads"; do
    [[ $n =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: '$n' is not a positive integer" >&2; exit 2; }
done
for a in $assets; do
    [ -f "$tests/$a.test" ] || { echo "run.sh: no asset '$a' ($tests/$a.test)" >&2; exit 2; }
done
build=$(cd "${positional[0]}" && pwd) || usage
out=${positional[1]:-$repo/../cycles-$(basename "$tests")-out}
mkdir -p "$out/assets" "$out/logs"
out=$(cd "$out" && pwd)
glint=$build/glint
imgdiff=$build/imgdiff
command -v blender >/dev/null || {
    echo "run.sh: blender not found (make bench installs it)" >&2
    exit 1
}
for x in "$glint" "$imgdiff"; do
    [ -x "$x" ] || { echo "run.sh: $x not found: build $build first" >&2; exit 1; }
done

echo "$(basename "$tests")/: Glint's path tracer against Blender Cycles, $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) hardware threads;" \
    "1-minute load average at start: $(cut -d' ' -f1 /proc/loadavg)"
echo "Cycles: $(blender --version 2>/dev/null | head -1), CPU, $threads threads, $cycles_spp spp;" \
    "Glint: $("$glint" --version), $spp spp"
echo "Output: $out"

python3 "$here/make_assets.py" "$out/assets"
scenes=()
for a in $assets; do cp "$tests/$a.test" "$out/assets/"; scenes+=("$out/assets/$a.test"); done
if grep -qs 'khronos/' "${scenes[@]}"; then
    [ -d "$khronos" ] || { echo "run.sh: no Khronos models at $khronos (--khronos)" >&2; exit 1; }
    ln -sfn "$(cd "$khronos" && pwd)" "$out/assets/khronos"
fi
if grep -qs 'smoke\.vdb' "${scenes[@]}" && [ ! -f "$out/assets/smoke.vdb" ]; then
    "$build/tools/glint_make_smoke_vdb" "$out/assets/smoke.vdb" >/dev/null
fi

# glint_render ASSET SEED OUT.exr -> "render_s cpu_s"
glint_render() {
    local log=$out/logs/glint-$1-seed$2.log
    if ! /usr/bin/time -o "$log.cpu" -f '%U %S' "$glint" "$out/assets/$1.test" --spp "$spp" \
        -t "$threads" --seed "$2" --stats -o "$3" >"$log" 2>&1; then
        echo "run.sh: glint failed; $log:" >&2
        cat "$log" >&2
        exit 1
    fi
    local cpu
    cpu=$(awk '{print $1 + $2}' "$log.cpu") && rm -f "$log.cpu"
    awk -v cpu="$cpu" '/^Time/ {for (i = 1; i < NF; i++) if ($i == "render") print $(i + 1), cpu}' "$log"
}

# cycles_render ASSET OUT.exr -> "render_s cpu_s"
cycles_render() {
    local log=$out/logs/cycles-$1.log
    local extra
    read -ra extra < <(sed -n 's/^# cycles-args: //p' "$out/assets/$1.test") || true
    if ! blender -b --factory-startup --python "$here/gltf_cycles.py" -- \
        --scene "$out/assets/$1.test" --out "$2" --spp "$cycles_spp" --threads "$threads" \
        --seed 0 "${extra[@]}" >"$log" 2>&1; then
        echo "run.sh: Blender failed; $log:" >&2
        grep -v '^Fra:' "$log" >&2
        exit 1
    fi
    sed -n 's/.*render_s=\([0-9.]*\) cpu_s=\([0-9.]*\).*/\1 \2/p' "$log"
}

field() { awk -v k="$1" -v f="$2" '$1 == k {for (i = 2; i <= NF; i++) if (index($i, f "=") == 1) print substr($i, length(f) + 2)}'; }

summary=$out/logs/summary.txt
: >"$summary"
for a in $assets; do
    echo
    echo "== $a =="
    g=$out/glint-$a-${spp}spp-seed0.exr g1=$out/glint-$a-${spp}spp-seed1.exr
    c=$out/cycles-$a-${cycles_spp}spp-seed0.exr
    read -r tg cg < <(glint_render "$a" 0 "$g")
    echo "  Glint: $tg s render ($cg CPU s)"
    glint_render "$a" 1 "$g1" >/dev/null
    if [ -f "$c" ]; then
        echo "  Cycles: $c (kept from an earlier run)"
        tc=$(sed -n 's/.*render_s=\([0-9.]*\).*/\1/p' "$out/logs/cycles-$a.log" 2>/dev/null || true)
        cc=$(sed -n 's/.*cpu_s=\([0-9.]*\).*/\1/p' "$out/logs/cycles-$a.log" 2>/dev/null || true)
    else
        read -r tc cc < <(cycles_render "$a" "$c")
        echo "  Cycles: $tc s render ($cc CPU s)"
        { grep -E '^  |^gltf_cycles.py: (medium|fog|--sheen)' "$out/logs/cycles-$a.log" |
            sed 's/^/  cycles: /' | head -40; } || true
    fi
    "$imgdiff" --preview "$out/glint-$a.ppm" "$g"
    "$imgdiff" --preview "$out/cycles-$a.ppm" "$c"
    cmp=$("$imgdiff" --ssim "$g" "$c" --diff "$out/diff-$a.ppm")
    noise=$("$imgdiff" --ssim "$g" "$g1")
    blocks=$("$imgdiff" --blocks 16 "$g" "$c")
    echo "$cmp" | sed 's/^/  /'
    echo "  block_rel (16x16, luminance): $(echo "$blocks" | field block_rel lum)"
    echo "  noise floor, Glint seed 0 against seed 1: ssim $(echo "$noise" | field ssim mean)," \
        "mae_rel $(echo "$noise" | field lum mae_rel)"
    python3 "$here/side_by_side.py" "$out/side-$a.png" "$out/glint-$a.ppm" "$out/cycles-$a.ppm" \
        "$out/diff-$a.ppm"
    if [ "$a" = normaltilt ]; then
        sed 's/sky_low\.hdr/sky_low_nosun.hdr/' "$out/assets/normaltilt.test" \
            >"$out/assets/normaltilt_nosun.test"
        glint_render normaltilt_nosun 0 "$out/glint-normaltilt_nosun-${spp}spp-seed0.exr" >/dev/null
        echo "  patches (flat; mapped towards the sun; mapped away; tilted towards it), mean"
        echo "  luminance of each block's central 16x16, Glint (a) and Cycles (b):"
        blender -b --factory-startup --python "$here/block_means.py" -- "$g" "$c" 32 2>&1 |
            grep '^BLOCK' | sed 's/^/    /'
        echo "  Glint with the sun (a) and without it (b):"
        blender -b --factory-startup --python "$here/block_means.py" -- "$g" \
            "$out/glint-normaltilt_nosun-${spp}spp-seed0.exr" 32 2>&1 | grep '^BLOCK' | sed 's/^/    /'
    fi
    if [ -n "$docs" ]; then
        if [ "$(stat -c %s "$out/side-$a.png")" -gt 307200 ]; then
            # A noisy render compresses badly: the docs get it at half size beyond 300 KB.
            python3 "$here/side_by_side.py" --half "$docs/$docs_prefix$a.png" "$out/glint-$a.ppm" \
                "$out/cycles-$a.ppm" "$out/diff-$a.ppm"
        else
            cp "$out/side-$a.png" "$docs/$docs_prefix$a.png"
        fi
    fi
    printf '%-11s %7.4f %7.4f %9.4f %8.4f %8.4f %9.4f %8s %8s %8s %8s\n' "$a" \
        "$(echo "$cmp" | field ssim mean)" "$(echo "$noise" | field ssim mean)" \
        "$(echo "$cmp" | field lum mean_rel)" "$(echo "$cmp" | field lum mae_rel)" \
        "$(echo "$noise" | field lum mae_rel)" "$(echo "$blocks" | field block_rel lum)" \
        "${tg:-?}" "${cg:-?}" "${tc:-?}" "${cc:-?}" >>"$summary"
done

echo
echo "==== Summary: Glint $spp spp against Cycles $cycles_spp spp, $threads threads (sizes: the scenes') ===="
printf '%-11s %7s %7s %9s %8s %8s %9s %8s %8s %8s %8s\n' asset ssim ssim_gg mean_rel mae_rel \
    mae_gg block_rel glint_s glint_cpu cycles_s cyc_cpu
cat "$summary"
echo
echo "ssim: mean SSIM of the sRGB luma (11x11 Gaussian windows), Glint against Cycles; ssim_gg:"
echo "  Glint against Glint at another seed (noise alone). mean_rel: relative difference of the"
echo "  luminance means; mae_rel: mean |Y_glint - Y_cycles| over the Cycles mean (mae_gg: Glint"
echo "  against Glint); block_rel: largest relative difference of 16x16 block means of luminance."
echo "  glint_s, cycles_s: each renderer's own render time (wall clock: Glint's 'render' of"
echo "  --stats, Cycles' bpy.ops.render.render); glint_cpu, cyc_cpu: CPU seconds of the process"
echo "  (Glint: all of it; Cycles: over the render), all threads: less disturbed by other jobs."
echo "Side by side (Glint | Cycles | difference): $out/side-*.png"
