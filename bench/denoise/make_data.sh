#!/usr/bin/env bash
# Renders the denoising benchmark's inputs (docs/clean-images.md, "Benchmark"): each scene at
# 4, 16, 64, 128 and 512 samples per pixel with every render pass (glint --aov all --no-denoise), and
# a 4096-spp reference, then splits each EXR into PFM files for bench/denoise/run.sh:
#   OUT/NAME_SPP.pfm, .albedo.pfm, .normal.pfm, .depth.pfm, .variance.pfm; OUT/NAME_ref.pfm
# Scenes: the three course-format scenes beside this script, two Khronos sample models from
# ../shared/real-world/gltf and five from ../shared/real-world/gltf-ext (glass and flowers, a
# toy car, a velvet chair, a cloth, a lamp) in Glint's model mode (the studio), and the glass ball
# of bench/caustics that focuses a small lamp onto the floor (with the caustic light pass), all at
# 320x240.
# Usage: bench/denoise/make_data.sh BUILD_DIR OUT_DIR [REF_SPP [NAME...]]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?build dir}
out=${2:?output dir}
ref=${3:-4096}
shift $(($# < 3 ? $# : 3))
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(glass room lamps helmet bottle vase toycar chair cloth lamp caustic)
glint=$build/glint
split=$build/bench/glint_aov_split
models=$here/../../../shared/real-world/gltf
ext=$here/../../../shared/real-world/gltf-ext
mkdir -p "$out"
declare -A input=(
    [glass]="$here/glass.test"
    [room]="$here/room.test"
    [lamps]="$here/lamps.test"
    [helmet]="$models/DamagedHelmet/glTF-Binary/DamagedHelmet.glb"
    [bottle]="$models/WaterBottle/glTF/WaterBottle.gltf"
    [vase]="$ext/GlassVaseFlowers/glTF/GlassVaseFlowers.gltf"
    [toycar]="$ext/ToyCar/glTF/ToyCar.gltf"
    [chair]="$ext/SheenChair/glTF/SheenChair.gltf"
    [cloth]="$ext/SheenCloth/glTF/SheenCloth.gltf"
    [lamp]="$ext/IridescenceLamp/glTF/IridescenceLamp.gltf"
    [caustic]="$here/../caustics/ball.test"
)
for name in "${names[@]}"; do
    scene=${input[$name]}
    [ -f "$scene" ] || { echo "make_data: $scene is missing" >&2; exit 1; }
    for spp in 4 16 64 128 512 ref; do
        n=$spp; [ "$spp" = ref ] && n=$ref
        [ -f "$out/${name}_$spp.pfm" ] && continue
        "$glint" "$scene" --size 320x240 --spp "$n" --no-denoise --aov all -q \
            -o "$out/${name}_$spp.exr"
        "$split" "$out/${name}_$spp.exr" "$out/${name}_$spp"
        echo "make_data: $name at $n spp"
    done
done
