#!/bin/sh
# Glint beside Khronos' glTF Render Fidelity images: each model rendered from the scenario's
# orbit camera (--camera orbit:..., --fov), at the thumbnails' size, through the same ACES
# tone mapper (--tonemap aces), then put beside the Cycles thumbnail and one more renderer's
# (STELLAR, V-Ray, Dassault's Enterprise PBR, three-gpu-pathtracer or the glTF Sample Viewer,
# the first there is; the Sample Viewer's screenshot in the model's folder where Khronos has no
# thumbnail). The lighting,
# lightroom_14b.hdr, is not available here: Glint lights with its studio environment, so
# shapes, materials and framing compare, exact light does not (docs/correctness.md).
#   bench/fidelity/run.sh [--docs DIR] BUILD OUT [MODEL...]
# Renders are kept in OUT and reused; delete them to render anew.
set -eu
DOCS=
if [ "${1:-}" = "--docs" ]; then DOCS=$2; shift 2; fi
BUILD=$1
OUT=$2
shift 2
MODELS=${*:-ClearCoatTest SheenChair ToyCar SpecularTest IridescenceLamp AnisotropyBarnLamp \
DispersionTest GlassVaseFlowers GlassHurricaneCandleHolder TransmissionTest AttenuationTest}
HERE=$(cd "$(dirname "$0")" && pwd)
ASSETS=${GLINT_ASSETS:-$HERE/../../../shared/real-world/gltf-ext}
TSV=$ASSETS/render-fidelity-cameras.tsv
mkdir -p "$OUT"

# A column of the cameras table, by its header name, for one model.
field() {
    awk -F'\t' -v m="$1" -v f="$2" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
        $1 == m { print $c[f]; exit }' "$TSV"
}

for model in $MODELS; do
    file=$(field "$model" local_file)
    [ -n "$file" ] || { echo "run.sh: $model is not in $TSV" >&2; exit 1; }
    orbit=$(field "$model" theta_deg),$(field "$model" phi_deg),$(field "$model" radius_m)
    orbit=$orbit,$(field "$model" target_x),$(field "$model" target_y),$(field "$model" target_z)
    # The thumbnails' size: 512 wide, as tall as the scenario's aspect ratio makes it.
    w=512
    h=$(awk -v a="$(field "$model" width_css)" -v b="$(field "$model" height_css)" \
        'BEGIN { printf "%d", 512 * b / a + 0.5 }')
    glint=$OUT/glint-$model.png
    if [ ! -f "$glint" ]; then
        echo "== $model: --camera orbit:$orbit --fov $(field "$model" vfov_deg) --size ${w}x$h"
        "$BUILD/glint" "$ASSETS/$model/$file" --camera "orbit:$orbit" \
            --fov "$(field "$model" vfov_deg)" --size "${w}x$h" --tonemap aces --ground none \
            --spp 1024 --noise-threshold 0.01 --time 20 -t 2 -o "$glint"
    fi
    thumbs=$ASSETS/$model/fidelity-thumbnails
    panels="$glint"
    cycles=$thumbs/blender-cycles-golden.thumb.webp
    if [ -f "$cycles" ]; then panels="$panels $cycles"; fi
    other=
    for r in stellar vray dspbr-pt three-gpu-pathtracer gltf-sample-viewer; do
        if [ -f "$thumbs/$r-golden.thumb.webp" ]; then other=$thumbs/$r-golden.thumb.webp; break; fi
    done
    if [ -z "$other" ]; then
        other=$(ls "$ASSETS/$model/screenshot/"screenshot.* 2>/dev/null | head -1)
    fi
    [ -z "$other" ] || panels="$panels $other"
    echo "$model: $(echo "$panels" | tr ' ' '\n' | sed 's|.*/||' | tr '\n' ' ')" \
        >"$OUT/panels-$model.txt"
    # shellcheck disable=SC2086 # the panels are words
    blender -b --factory-startup --python "$HERE/compose.py" -- \
        --out "$OUT/fidelity-$model.png" --height 256 $panels 2>&1 | grep "compose.py"
    [ -z "$DOCS" ] || cp "$OUT/fidelity-$model.png" "$DOCS/"
done
cat "$OUT"/panels-*.txt
