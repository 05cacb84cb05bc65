#!/usr/bin/env bash
# The model mode's defaults beside a converged reference (docs/clean-images.md, "A model's
# defaults"): for each of the five Khronos models of models.sh,
#   OUT/NAME_ref.{exr,pfm,png}  the reference: REF_SPP samples per pixel, no denoiser (kept if
#                               there: it takes long, about 20 minutes at 640x480 on 2 cores)
#   OUT/NAME.{exr,pfm,png}      glint MODEL at its defaults (adaptive sampling, the denoiser)
#   OUT/NAME_raw.{pfm,png}      the same without the denoiser
# all at SIZE, the PNGs as the model mode shows them (PBR Neutral, sRGB); then prints the
# relMSE of the default and the raw image against the reference (relmse.py --all: with the
# 0.1% worst pixels left out too, and the count of pixels off by more than 4x: speckles).
# Usage: bench/denoise/models_reference.sh BUILD_DIR OUT_DIR [REF_SPP] [SIZE] [MODEL...]
#        (BUILD_DIR configured with GLINT_BUILD_BENCH=ON; defaults 4096 and 640x480)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?build dir}
out=${2:?output dir}
ref=${3:-4096}
size=${4:-640x480}
shift $(($# < 4 ? $# : 4))
models=("$@")
[ ${#models[@]} -gt 0 ] || models=(GlassVaseFlowers IridescenceLamp ToyCar SheenChair DamagedHelmet)
glint=$build/glint
split=$build/bench/glint_aov_split
ext=$here/../../../shared/real-world/gltf-ext
base=$here/../../../shared/real-world/gltf
mkdir -p "$out"
echo "| model | size | default: relMSE | trimmed | pixels off 4x | raw: relMSE | trimmed | pixels off 4x |"
echo "|---|---|---|---|---|---|---|---|"
for m in "${models[@]}"; do
    f=$(ls "$ext/$m"/glTF/*.gltf "$base/$m"/glTF-Binary/*.glb 2>/dev/null | head -1 || true)
    [ -f "$f" ] || { echo "models_reference: no model $m" >&2; exit 1; }
    if [ ! -f "$out/${m}_ref.pfm" ]; then
        "$glint" "$f" --size "$size" --spp "$ref" --no-denoise -q -o "$out/${m}_ref.exr" 2>/dev/null
        "$split" "$out/${m}_ref.exr" "$out/${m}_ref"
    fi
    "$glint" "$f" --size "$size" -q -o "$out/$m.exr" 2>/dev/null
    "$split" "$out/$m.exr" "$out/$m"
    "$glint" "$f" --size "$size" --no-denoise -q -o "$out/${m}_raw.exr" 2>/dev/null
    "$split" "$out/${m}_raw.exr" "$out/${m}_raw"
    errors() {
        python3 "$here/relmse.py" "$1" "$out/${m}_ref.pfm" --all |
            awk '{printf "%s | %s | %s", $2, $4, $8}'
    }
    echo "| $m | $size | $(errors "$out/$m.pfm") | $(errors "$out/${m}_raw.pfm") |"
done
