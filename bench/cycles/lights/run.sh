#!/usr/bin/env bash
# Glint's punctual lights against Cycles (README.md): bench/cycles/lights/run.sh BUILD_DIR OUT_DIR
# [OLD_GLINT]. Writes the scenes, renders each converged in both (1024 spp), then the
# coincident coloured lights at 16 spp in both (and in OLD_GLINT, a build from before a change),
# and prints compare.py's figures and each render's seconds.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?usage: run.sh BUILD_DIR OUT_DIR [OLD_GLINT]}
out=${2:?usage: run.sh BUILD_DIR OUT_DIR [OLD_GLINT]}
old=${3:-}
glint=$build/glint
size=(160 120)
mkdir -p "$out"
out=$(cd "$out" && pwd)
/usr/bin/python3 "$here/make_lights.py" "$out"
render_glint() {  # GLINT SCENE SPP SEED OUT
    "$1" "$out/$2.gltf" --size "${size[0]}x${size[1]}" --spp "$3" --seed "$4" -t 2 \
        --environment none --ground none --exposure 0 --no-denoise --max-bounces 8 \
        --stats -q -o "$5" | sed -n 's/^Time.*render \([0-9.]*\) s.*/glint: rendered in \1 s/p'
}
render_cycles() {  # SCENE SPP SEED OUT [diffuse]
    blender -b --factory-startup --python "$here/cycles_lights.py" -- "$out/$1.gltf" "$4" "$2" \
        "$3" "${size[0]}" "${size[1]}" 8 2 ${5:-} 2>&1 | grep '^cycles:'
}
for scene in rgb white spot spot-hard; do
    echo "== $scene, converged (1024 spp)"
    render_cycles $scene 1024 1 "$out/cycles-$scene-ref.pfm"
    render_cycles $scene 1024 2 "$out/cycles-$scene-diffuse.pfm" diffuse
    render_glint "$glint" $scene 1024 1 "$out/glint-$scene-ref.pfm"
    /usr/bin/python3 "$here/compare.py" "$out/cycles-$scene-ref.pfm" \
        "$out/glint-$scene-ref.pfm" "$out/cycles-$scene-diffuse.pfm"
    /usr/bin/python3 "$here/compare.py" "$out/cycles-$scene-diffuse.pfm" "$out/glint-$scene-ref.pfm"
done
echo "== rgb and white at 16 spp, each against its own renderer's 1024-spp image"
for scene in rgb white; do
    render_cycles $scene 16 3 "$out/cycles-$scene-16.pfm"
    render_glint "$glint" $scene 16 3 "$out/glint-$scene-16.pfm"
    /usr/bin/python3 "$here/compare.py" "$out/cycles-$scene-ref.pfm" "$out/cycles-$scene-16.pfm"
    /usr/bin/python3 "$here/compare.py" "$out/glint-$scene-ref.pfm" "$out/glint-$scene-16.pfm"
    if [ -n "$old" ]; then
        render_glint "$old" $scene 1024 1 "$out/old-$scene-ref.pfm"
        render_glint "$old" $scene 16 3 "$out/old-$scene-16.pfm"
        /usr/bin/python3 "$here/compare.py" "$out/old-$scene-ref.pfm" "$out/old-$scene-16.pfm"
    fi
done
