#!/usr/bin/env bash
# The model mode's defaults, two glint programs in turn (docs/clean-images.md, "A model's
# defaults"): for each of models.sh's five Khronos models, RUNS rounds of OLD then NEW at their
# defaults (`glint MODEL -o OUT.png`), and a Markdown row of the median wall times, their ratio,
# and what NEW's adaptive sampler and denoiser reported. Alternating them puts the machine's
# slow and quiet moments on both.
# Usage: bench/denoise/models_ab.sh OLD_GLINT NEW_GLINT [RUNS]
set -euo pipefail
old=${1:?old glint}
new=${2:?new glint}
runs=${3:-3}
here=$(cd "$(dirname "$0")" && pwd)
ext=$here/../../../shared/real-world/gltf-ext
base=$here/../../../shared/real-world/gltf
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median() { printf '%s\n' "$@" | sort -n | sed -n "$((($# + 1) / 2))p"; }
seconds() { local s=$EPOCHREALTIME; "$@"; echo "$EPOCHREALTIME - $s" | bc; }
echo "| model | OLD | NEW | ratio | NEW's samples per pixel (mean, most) | NEW's denoiser |"
echo "|---|---|---|---|---|---|"
for m in GlassVaseFlowers IridescenceLamp ToyCar SheenChair DamagedHelmet; do
    f=$(ls "$ext/$m"/glTF/*.gltf "$base/$m"/glTF-Binary/*.glb 2>/dev/null | head -1 || true)
    to=() tn=()
    for ((i = 0; i < runs; i++)); do
        to+=("$(seconds "$old" "$f" -q -o "$tmp/old.png" 2>/dev/null)")
        tn+=("$(seconds "$new" "$f" -o "$tmp/new.png" 2>"$tmp/new.log")")
    done
    mo=$(median "${to[@]}") mn=$(median "${tn[@]}")
    spp=$(sed -n 's/.*: \([0-9]*\) samples per pixel on average (most \([0-9]*\) .*/\1, \2/p' "$tmp/new.log")
    dn=$(sed -n 's/glint: denoised in \([0-9.]* s\).*/\1/p' "$tmp/new.log")
    printf '| %s | %.2f s | %.2f s | %.2f | %s | %s |\n' "$m" "$mo" "$mn" "$(echo "$mn / $mo" | bc -l)" "$spp" "$dn"
done
