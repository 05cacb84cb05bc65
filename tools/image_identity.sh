#!/usr/bin/env bash
# Renders a fixed set of scenes with fixed seeds and prints one line per output file: its
# SHA-256 and name. Run it with two builds (before and after a change that must not change what
# users see) and diff the lists: equal lines are byte-identical images.
#
#   tools/image_identity.sh build/glint /tmp/after > after.txt
#   diff before.txt after.txt
#
# The set: the course's scenes (Whitted, bit-exact with the course), the repository's scenes
# (path tracer, area lights, media, depth of field, motion blur), the light pass's caustics, the
# denoiser's benchmark scenes with render passes, and glTF models in the model mode (denoised,
# adaptive at a fixed cap, so no time budget) with layered materials (sheen, clearcoat,
# iridescence, transmission, volume, dispersion, anisotropy). Float outputs (.exr, .pfm) show
# differences below what an 8-bit image would. Models and course scenes come from ../shared
# beside the repository when it is there; the rest are the repository's own.
set -euo pipefail
glint=${1:?usage: image_identity.sh GLINT_BINARY OUT_DIR}
out=${2:?usage: image_identity.sh GLINT_BINARY OUT_DIR}
root=$(cd "$(dirname "$0")/.." && pwd)
shared=$root/../shared
mkdir -p "$out"
run() {  # NAME ARGS...: renders into $out/NAME.*
    local name=$1
    shift
    "$glint" -q -t 2 "$@" 2>"$out/log.txt" || { cat "$out/log.txt" >&2; echo "FAILED $name" >&2; exit 1; }
}

# The course (Whitted, bit-exact).
if [ -d "$shared/scenes/cse167x" ]; then
    for s in "$shared"/scenes/cse167x/scene*.test; do
        n=$(basename "$s" .test)
        run "$n" "$s" -o "$out/course-$n.png"
    done
fi
# The repository's scenes, as they ask and path traced with floats out.
for s in demo antialias arealight cornell dof glass media shapes; do
    run "$s" "$root/scenes/$s.test" --spp 16 --seed 7 -o "$out/scene-$s.png"
    run "$s" "$root/scenes/$s.test" --spp 16 --seed 7 --integrator path -o "$out/path-$s.exr"
done
run spinning "$root/scenes/spinning.test" --frame 3 --shutter -0.25:0.25 --spp 16 \
    -o "$out/spinning-blur.exr"
# Caustics (the light pass), the path tracer's media, an environment map.
run ball "$root/bench/caustics/ball.test" --spp 16 -o "$out/caustics-ball.exr"
run ball-off "$root/bench/caustics/ball.test" --spp 16 --caustics off -o "$out/caustics-off.exr"
run fogsss "$root/bench/media/fogsss.test" --spp 8 --size 160x120 -o "$out/media-fogsss.exr"
run studio "$root/scenes/glass.test" --spp 8 --integrator path --environment studio \
    -o "$out/environment-studio.exr"
# The denoiser's scenes: passes, adaptive sampling, denoised.
for s in glass lamps room; do
    run "$s" "$root/bench/denoise/$s.test" --spp 16 --size 160x120 --aov all \
        -o "$out/denoise-$s-raw.exr"
    run "$s" "$root/bench/denoise/$s.test" --spp 16 --size 160x120 --denoise \
        -o "$out/denoise-$s.png"
    run "$s" "$root/bench/denoise/$s.test" --spp 32 --noise-threshold 0.05 --size 160x120 \
        --denoise -o "$out/adaptive-$s.exr"
done
# Models in the model mode: the studio, a shadow catcher, the denoiser, adaptive to a cap.
models=()
[ -d "$shared/real-world/gltf" ] && models+=(
    "$shared/real-world/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf"
    "$shared/real-world/gltf/WaterBottle/glTF/WaterBottle.gltf")
if [ -d "$shared/real-world/gltf-ext" ]; then
    for m in SheenChair ClearCoatCarPaint IridescenceLamp TransmissionTest DispersionTest \
        AnisotropyBarnLamp CompareVolume GlassVaseFlowers EmissiveStrengthTest; do
        f=$(ls "$shared/real-world/gltf-ext/$m/glTF/"*.gltf 2>/dev/null | head -1)
        [ -n "$f" ] && models+=("$f")
    done
fi
for f in "${models[@]}"; do
    n=$(basename "$f" .gltf)
    run "$n" "$f" --size 160x120 --spp 32 --noise-threshold 0.02 -o "$out/model-$n.png"
    run "$n" "$f" --size 160x120 --spp 16 --no-denoise -o "$out/model-$n-raw.exr"
done
cd "$out"
rm -f log.txt
sha256sum -- * | sort -k2
