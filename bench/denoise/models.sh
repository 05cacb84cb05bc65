#!/usr/bin/env bash
# The model mode's defaults on five Khronos sample models (docs/clean-images.md, "Model mode"):
# the wall time of `glint MODEL -o OUT.png` (load, build, adaptive sampling, denoising, write;
# median of RUNS runs) and what the adaptive sampler chose, and the images: OUT_DIR/NAME.png at
# the defaults and OUT_DIR/NAME_raw.png, the same time budget without the denoiser.
# Usage: bench/denoise/models.sh GLINT OUT_DIR [RUNS]
set -euo pipefail
glint=${1:?glint binary}
out=${2:?output dir}
runs=${3:-3}
here=$(cd "$(dirname "$0")" && pwd)
ext=$here/../../../shared/real-world/gltf-ext
base=$here/../../../shared/real-world/gltf
mkdir -p "$out"
echo "| model | wall time (median of $runs) | samples per pixel (mean, most) | pixels converged | denoise |"
echo "|---|---|---|---|---|"
for m in GlassVaseFlowers IridescenceLamp ToyCar SheenChair DamagedHelmet; do
    f=$(ls "$ext/$m"/glTF/*.gltf "$base/$m"/glTF-Binary/*.glb 2>/dev/null | head -1 || true)
    times=()
    for ((i = 0; i < runs; i++)); do
        start=$(date +%s.%N)
        "$glint" "$f" -o "$out/$m.png" 2> "$out/$m.log"
        times+=("$(echo "$(date +%s.%N) - $start" | bc)")
    done
    median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(((runs + 1) / 2))p")
    "$glint" "$f" --no-denoise -o "$out/${m}_raw.png" 2>/dev/null
    spp=$(sed -n 's/.*: \([0-9]*\) samples per pixel on average (most \([0-9]*\) .*/\1, \2/p' "$out/$m.log")
    conv=$(sed -n 's/.*, \([0-9]*%\) of pixels below.*/\1/p' "$out/$m.log")
    dn=$(sed -n 's/glint: denoised in \([0-9.]* s\).*/\1/p' "$out/$m.log")
    printf '| %s | %.2f s | %s | %s | %s |\n' "$m" "$median" "$spp" "$conv" "$dn"
done
