#!/bin/sh
# Glint's Blender add-on against Cycles on the same .blend files (issue 38, docs/blender.md).
#
#   bench/blender/run.sh [BUILD_DIR [OUT_DIR [REF_SPP [THREADS]]]]
#
# For each scene of scenes.py (and two with Lambert materials only): the .blend file; both engines at REF_SPP (default 1024) samples,
# compared (mean ratio, largest block difference, compare.py); then both at 16 and 64 samples,
# timed, with relMSE against their own REF_SPP image: the efficiency 1 / (relMSE x seconds) and
# Glint's over Cycles'. Needs blender, the add-on built (make build: BUILD_DIR/blender), NumPy.
set -eu
build=${1:-build}
out=${2:-/tmp/glint-blender-bench}
ref=${3:-1024}
threads=${4:-2}
here=$(cd "$(dirname "$0")" && pwd)
export GLINT_BLENDER_DIR=$(cd "$build" && pwd)/blender
mkdir -p "$out"
render() {  # scene engine spp tag -> seconds
    blender -b "$out/$1.blend" --python "$here/render.py" -- "$2" "$3" "$out/$1-$4.exr" \
        "$threads" 2>&1 | sed -n 's/^seconds //p'
}
# name:flags; -diffuse: every material a Diffuse BSDF (scenes.py --diffuse), where both
# engines' models agree (Lambert).
for entry in cornell materials lights cornell-diffuse:--diffuse lights-diffuse:--diffuse; do
    scene=${entry%%:*}
    flags=$(echo "$entry" | sed -n 's/^[^:]*://p')
    blender -b --factory-startup --python "$here/scenes.py" -- "${scene%-diffuse}" \
        "$out/$scene.blend" $flags >/dev/null 2>&1
    tc=$(render "$scene" CYCLES "$ref" cycles-ref)
    tg=$(render "$scene" GLINT "$ref" glint-ref)
    echo "$scene: converged ($ref spp; Cycles ${tc} s, Glint ${tg} s):" \
        "$(/usr/bin/python3 "$here/compare.py" "$out/$scene-glint-ref.npy" "$out/$scene-cycles-ref.npy")"
    for spp in 16 64; do
        tc=$(render "$scene" CYCLES "$spp" cycles-$spp)
        tg=$(render "$scene" GLINT "$spp" glint-$spp)
        ec=$(/usr/bin/python3 "$here/compare.py" "$out/$scene-cycles-$spp.npy" "$out/$scene-cycles-ref.npy" | sed 's/.*relmse //')
        eg=$(/usr/bin/python3 "$here/compare.py" "$out/$scene-glint-$spp.npy" "$out/$scene-glint-ref.npy" | sed 's/.*relmse //')
        echo "$scene: $spp spp: Cycles ${tc} s relMSE $ec, Glint ${tg} s relMSE $eg," \
            "efficiency ratio $(echo "$ec * $tc / ($eg * $tg)" | bc -l | cut -c1-5)"
    done
done
